"""The console's video as an operator across a long link sees it: H.264 with receipts, decoded
by WebCodecs in headless Chromium, through the impairment link (183 ms round trip) in front of
the console, from a pattern camera (640x480 per eye, 30 fps) behind a DecisionServer.

How fast and how fresh is measured by `make bench ONLY=video` (its console cells), not here: a
shared 2-core machine times nothing reliably."""

from __future__ import annotations

import pytest

from services.impairment.link import LinkProfile
from services.impairment.proxy import ImpairmentProxy
from services.runtime import children
from tests.conftest import wait_for
from tests.processes import start_service
from tests.web_console.test_browser import open_console

pytestmark = [pytest.mark.e2e, pytest.mark.slow]

ONE_WAY_S = 0.0915  # each way: a 183 ms round trip
FRAMES = 60  # shown after the first, for the stream to count as flowing


@pytest.fixture(scope="module")
def video_console(video_station):
    """A console in front of the pattern camera's DecisionServer; its address."""
    console = start_service("web_console", "--decision-server", video_station.decision_address)
    yield console.address
    children.stop_all([console])


def video_stats(page) -> dict:
    return page.evaluate("""() => ({codec: videoStats.codec, decoder: videoStats.decoder,
        fallback: videoStats.fallbackReason, errors: videoStats.decodeErrors,
        frames: videoStats.frames, receipts: videoStats.receipts,
        bySocket: videoStats.receiptsBySocket,
        ages: videoStats.samples.map((s) => s.receivedAgeMs)})""")


def test_h264_video_through_a_183_ms_link(browser, video_console):
    link = LinkProfile(delay_s=ONE_WAY_S)
    with ImpairmentProxy("127.0.0.1:0", video_console, up=link, down=link,
                         report=lambda line: None) as proxy:
        page = open_console(browser, f"http://{proxy.address}/")
        first = wait_for(lambda: video_stats(page)["frames"], timeout_s=30,
                         what="a first frame shown")
        stats = wait_for(lambda: (s := video_stats(page))["frames"] >= first + FRAMES and s,
                         timeout_s=60, what=f"{FRAMES} more frames shown")
        shown = page.locator("#video-stats")
        figures = {key: shown.get_attribute(f"data-{key}")
                   for key in ("codec", "decoder", "fps", "age-p95", "kbit-per-s",
                               "render-scale")}
        streamed, shown_px = page.evaluate("""() => {
            const eye = document.getElementById("left-eye");
            return [eye.width, eye.clientWidth * devicePixelRatio]; }""")
    assert stats["decoder"] == "webcodecs" and stats["codec"].startswith("h264"), stats["fallback"]
    assert stats["errors"] == 0
    assert figures["decoder"] == "webcodecs" and float(figures["fps"]) > 0, figures
    assert float(figures["kbit-per-s"]) > 0, figures
    assert float(figures["render-scale"]) == 1.0, figures  # the test card is drawn whole
    # The page asks for the pixels its canvas shows, no more: the source is 640 wide.
    assert 0 < streamed <= min(640, shown_px), (streamed, shown_px)
    # Every pair came through the link: none arrived younger than its one-way delay.
    assert min(stats["ages"]) >= ONE_WAY_S * 1e3, min(stats["ages"])
    # A receipt per pair, on the receipts socket (bar the first few, sent while it opened).
    assert stats["receipts"] >= stats["frames"] - 1, stats
    assert stats["bySocket"] >= stats["receipts"] - 10, stats
    assert page.errors == []


def test_without_webcodecs_the_page_polls_jpeg_snapshots(browser, video_console):
    """An insecure context has no VideoDecoder: the page shows snapshots instead."""
    page = browser.new_page()
    page.add_init_script("delete window.VideoDecoder")
    page.goto(f"http://{video_console}/")
    wait_for(lambda: page.evaluate("() => window.videoStats.frames") >= 10, timeout_s=30,
             what=lambda: f"snapshots shown; the page's video: {video_stats(page)}")
    stats = page.evaluate("() => ({codec: videoStats.codec, decoder: videoStats.decoder, "
                          "fallback: videoStats.fallbackReason})")
    assert stats["codec"] == "jpeg" and stats["decoder"] == "snapshots", stats
    assert "VideoDecoder" in stats["fallback"], stats
    assert int(page.locator("#left-eye").get_attribute("data-sequence")) > 0


# Closes the decoder on every 20th frame it is given, as a decoder that fails would be.
FAILING_DECODER = """(() => {
  const decode = VideoDecoder.prototype.decode;
  let given = 0;
  VideoDecoder.prototype.decode = function (chunk) {
    if (++given % 20 === 0) { this.close(); return; }
    return decode.call(this, chunk);
  };
})()"""


def test_a_failing_decoder_asks_for_key_frames_then_falls_back(browser, video_console):
    """A decode error: a receipt asks for a key frame and the video resumes from it; the third
    error within 30 s: JPEG snapshots for good."""
    page = browser.new_page()
    page.add_init_script(FAILING_DECODER)
    page.goto(f"http://{video_console}/")

    def stats():
        return page.evaluate("() => ({frames: videoStats.frames, errors: videoStats.decodeErrors,"
                             " keyframes: videoStats.keyframeRequests, decoder: videoStats.decoder,"
                             " fallback: videoStats.fallbackReason})")

    failed = wait_for(lambda: (s := stats())["errors"] >= 1 and s, timeout_s=30,
                      what=lambda: f"the first decode error; the page's video: {stats()}")
    resumed = wait_for(lambda: (s := stats())["frames"] > failed["frames"] + 5 and s,
                       timeout_s=30, what=lambda: f"frames after the first decode error; {stats()}")
    assert resumed["keyframes"] >= 1, resumed
    done = wait_for(lambda: (s := stats())["decoder"] == "snapshots" and s, timeout_s=30,
                    what=lambda: f"the fallback to snapshots; {stats()}")
    assert done["errors"] == 3 and "failed 3 times" in done["fallback"], done
    frames = done["frames"]
    wait_for(lambda: stats()["frames"] > frames + 5, timeout_s=30,
             what=lambda: f"snapshots shown; {stats()}")
