"""The console's video as an operator across a long link sees it: H.264 with receipts, decoded
by WebCodecs in headless Chromium, through the impairment link (183 ms round trip) in front of
the console, from a pattern camera (640x480 per eye, 30 fps) behind a DecisionServer."""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np
import pytest

from services.impairment.link import LinkProfile
from services.impairment.proxy import ImpairmentProxy
from services.runtime import children
from tests.conftest import start_service, wait_for
from tests.web_console.test_browser import open_console

pytestmark = [pytest.mark.e2e, pytest.mark.slow]

ONE_WAY_S = 0.0915  # each way: a 183 ms round trip
WARM_UP_S = 2.0  # left out: the stream's start (key frame, the pacer finding the path)
MEASURE_S = 9.0


@pytest.fixture(scope="module")
def video_console(video_station):
    """A console in front of the pattern camera's DecisionServer; its address."""
    console = start_service("web_console", "--decision-server", video_station.decision_address)
    yield console.address
    children.stop_all([console])


def summary(samples: list[dict], skip_s: float) -> dict:
    """As clients/python/video_meter.py's summary: the frames shown after the first `skip_s`,
    their rate, age percentiles, bitrate, and the p95 age of each third (a backlog shows as a
    last third older than the first)."""
    start = samples[0]["shownMs"] + skip_s * 1e3
    kept = [s for s in samples if s["shownMs"] >= start]
    span_s = (kept[-1]["shownMs"] - kept[0]["shownMs"]) / 1e3
    ages = np.array([s["ageMs"] for s in kept])
    return {
        "frames": len(kept), "span_s": round(span_s, 1),
        "fps": round((len(kept) - 1) / span_s, 1),
        "age_ms_p50": round(float(np.percentile(ages, 50)), 1),
        "age_ms_p95": round(float(np.percentile(ages, 95)), 1),
        "age_ms_p95_thirds": [round(float(np.percentile(t, 95)), 1)
                              for t in np.array_split(ages, 3)],
        # Where the age comes from when it is too old: the path (capture to the page's reading
        # it), or the page (its decoder, its drawing).
        "received_age_ms_p95_thirds": [round(float(np.percentile(t, 95)), 1) for t in
                                       np.array_split([s["receivedAgeMs"] for s in kept], 3)],
        "decode_ms_p95": round(float(np.percentile([s["decodeMs"] for s in kept], 95)), 1),
        "draw_ms_p95": round(float(np.percentile([s["drawMs"] for s in kept], 95)), 1),
        "ticks_skipped": kept[-1]["sequence"] - kept[0]["sequence"] - (len(kept) - 1),
        "kbit_per_s": round(sum(s["bytes"] for s in kept[1:]) * 8 / 1e3 / span_s, 1),
        "target_kbit_per_s": kept[-1]["targetKbit"],
    }


def cpu_ticks() -> tuple[int, int]:
    """(busy, total) CPU ticks of the whole machine so far, from /proc/stat."""
    fields = [int(v) for v in Path("/proc/stat").read_text().split("\n")[0].split()[1:]]
    idle = fields[3] + fields[4]  # idle, iowait
    return sum(fields) - idle, sum(fields)


def test_h264_video_through_a_183_ms_link(browser, video_console):
    link = LinkProfile(delay_s=ONE_WAY_S)
    with ImpairmentProxy("127.0.0.1:0", video_console, up=link, down=link,
                         report=lambda line: None) as proxy:
        page = open_console(browser, f"http://{proxy.address}/")
        wait_for(lambda: page.evaluate("() => window.videoStats?.frames ?? 0") > 0,
                 timeout_s=30, what="a first frame shown")
        time.sleep(WARM_UP_S)
        before = cpu_ticks()
        time.sleep(MEASURE_S)
        after = cpu_ticks()
        stats = page.evaluate("""() => ({codec: videoStats.codec, decoder: videoStats.decoder,
            fallback: videoStats.fallbackReason, errors: videoStats.decodeErrors,
            keyframes: videoStats.keyframeRequests, receipts: videoStats.receipts,
            bySocket: videoStats.receiptsBySocket, samples: videoStats.samples})""")
        shown = page.locator("#video-stats")
        figures = {key: shown.get_attribute(f"data-{key}")
                   for key in ("codec", "decoder", "fps", "age-p95", "kbit-per-s")}
    result = summary(stats["samples"], WARM_UP_S)
    # The goals need about three quarters of this 2-core machine (the world's simulation, the
    # camera's x264, Chromium's software decoding and compositing): when other work takes the
    # rest, frames wait for a CPU on every hop. Printed, to tell that from a fault.
    result["machine_busy"] = round((after[0] - before[0]) / max(1, after[1] - before[1]), 2)
    print("video through 183 ms:", result, "page:", figures, "decode errors:", stats["errors"],
          "key frames asked:", stats["keyframes"], "receipts:", stats["receipts"],
          "on the WebSocket:", stats["bySocket"])
    assert stats["decoder"] == "webcodecs" and stats["codec"].startswith("h264"), stats["fallback"]
    assert figures["decoder"] == "webcodecs" and float(figures["fps"]) > 0
    # A receipt per pair, on the receipts socket (bar the first few, sent while it opened).
    assert stats["receipts"] >= result["frames"], stats["receipts"]
    assert stats["bySocket"] >= stats["receipts"] - 10, (stats["receipts"], stats["bySocket"])
    assert result["span_s"] >= MEASURE_S - 1, result
    assert result["fps"] >= 25, result
    assert result["age_ms_p95"] <= ONE_WAY_S * 1e3 + 80, result
    first, _, last = result["age_ms_p95_thirds"]
    assert last <= first + 20, result  # no growing backlog
    assert page.errors == []


def test_without_webcodecs_the_page_polls_jpeg_snapshots(browser, video_console):
    """An insecure context has no VideoDecoder: the page shows snapshots instead."""
    page = browser.new_page()
    page.add_init_script("delete window.VideoDecoder")
    page.goto(f"http://{video_console}/")
    wait_for(lambda: page.evaluate("() => window.videoStats.frames") >= 10, timeout_s=30,
             what="snapshots shown")
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
                      what="the first decode error")
    resumed = wait_for(lambda: (s := stats())["frames"] > failed["frames"] + 5 and s,
                       timeout_s=30, what="frames after the first decode error")
    assert resumed["keyframes"] >= 1, resumed
    done = wait_for(lambda: (s := stats())["decoder"] == "snapshots" and s, timeout_s=30,
                    what="the fallback to snapshots")
    assert done["errors"] == 3 and "failed 3 times" in done["fallback"], done
    frames = done["frames"]
    wait_for(lambda: stats()["frames"] > frames + 5, timeout_s=30, what="snapshots shown")
