"""The DecisionServer's forward of StreamPairs holds no more than its client's transport: through
a 50 ms round trip, the operator's one address delivers pairs as fresh as the camera's own port.
"""

from __future__ import annotations

import pytest

from clients.video_probe import probe
from services.impairment.link import LinkProfile
from services.impairment.proxy import ImpairmentProxy

pytestmark = pytest.mark.e2e

ONE_WAY_S = 0.025


def _through_link(target: str, **probe_args) -> dict:
    link = LinkProfile(delay_s=ONE_WAY_S)
    with ImpairmentProxy("127.0.0.1:0", target, up=link, down=link,
                         report=lambda line: None) as proxy:
        return probe(proxy.address, 8.0, skip_s=2.0, **probe_args)


def test_jpeg_through_the_decision_server_is_as_fresh_as_from_the_camera(video_station):
    """Today's JPEG stream, paced by the transport alone (a small receive window): a forward
    that read ahead of its client would let the age grow by seconds; one that holds nothing
    keeps it near the camera port's own."""
    direct = _through_link(video_station.camera_address, encoding="jpeg", receipts=False)
    forwarded = _through_link(video_station.decision_address, encoding="jpeg", receipts=False)
    assert forwarded["frames"] > 20, forwarded
    # Not growing: the last third no older than the first third plus a frame or two.
    first, _, last = forwarded["age_ms_p95_thirds"]
    assert last <= first + 100, forwarded
    # The forward adds a loopback hop, not a queue.
    assert forwarded["age_ms_p50"] <= direct["age_ms_p50"] + 100, (direct, forwarded)


def test_h264_with_receipts_through_the_decision_server(video_station):
    """The operator's own stream: H.264 paced by receipts that the DecisionServer forwards, at
    the camera's rate and about the link's one-way delay old."""
    result = _through_link(video_station.decision_address)
    assert result["codec"] == "h264"
    assert result["fps"] >= 25, result
    assert result["age_ms_p95"] <= ONE_WAY_S * 1e3 + 80, result
    first, _, last = result["age_ms_p95_thirds"]
    assert last <= first + 20, result
    assert result["target_kbit_per_s"] > 0, result
    assert result["render_scale"] == 1.0, result  # the test card is drawn whole
