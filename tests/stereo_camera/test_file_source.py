"""Recorded stereo video (written here with cv2.VideoWriter, MJPG in .avi) replayed through the
service, side by side or as two files, with and without a calibration file."""

from __future__ import annotations

import json

import cv2
import grpc
import numpy as np
import pytest

from services.stereo_camera.calibration import load_calibration, parse_calibration
from services.stereo_camera.client import decode_pair
from services.stereo_camera.pattern import pattern_image, read_tick
from services.stereo_camera.source import LEFT, RIGHT
from services.stereo_camera.video import FILE, VideoSource
from telerobot.v1 import stereo_camera_pb2 as pb
from tests.stereo_camera.conftest import psnr

W, H = 160, 120
FRAMES = 10
PNG = pb.IMAGE_ENCODING_PNG


def _record(path, images, fps=50.0):
    height, width = images[0].shape[:2]
    writer = cv2.VideoWriter(str(path), cv2.VideoWriter_fourcc(*"MJPG"), fps, (width, height))
    assert writer.isOpened()
    for image in images:
        writer.write(cv2.cvtColor(image, cv2.COLOR_RGB2BGR))
    writer.release()
    return str(path)


@pytest.fixture
def side_by_side(tmp_path):
    frames = [np.hstack([pattern_image(i, LEFT, W, H), pattern_image(i, RIGHT, W, H)])
              for i in range(FRAMES)]
    return _record(tmp_path / "stereo_sbs.avi", frames)


@pytest.fixture
def two_files(tmp_path):
    return tuple(_record(tmp_path / f"{eye}.avi",
                         [pattern_image(i, eye, W, H) for i in range(FRAMES)])
                 for eye in (LEFT, RIGHT))


CALIBRATION = {
    "width_px": 2 * W, "height_px": 2 * H,  # calibrated at twice the recorded size
    "left": {"fx_px": 400.0, "fy_px": 410.0, "cx_px": 159.5, "cy_px": 119.5,
             "distortion": [0.01, -0.02, 0.0, 0.0, 0.001],
             "position_m": [1.0, 0.0, 0.5], "rotation": [0, 0, -1, 1, 0, 0, 0, -1, 0]},
    "right": {"fx_px": 400.0, "fy_px": 410.0, "cx_px": 159.5, "cy_px": 119.5,
              "position_m": [1.0, 0.1, 0.5], "rotation": [0, 0, -1, 1, 0, 0, 0, -1, 0]},
}


def _replayed_frame_indices(messages):
    """(sequence, frame index) of each pair, after checking both eyes against the recording."""
    header = messages[0].header
    seen = []
    for message in messages[1:]:
        pair = message.pair
        left, right = decode_pair(header, pair)
        index = read_tick(left)
        assert index is not None and read_tick(right) == index  # one recorded instant
        assert psnr(left, pattern_image(index, LEFT, W, H)) > 30
        assert psnr(right, pattern_image(index, RIGHT, W, H)) > 30
        seen.append((pair.sequence, index))
    return seen


def test_a_side_by_side_recording_replays_in_order_and_loops(serve, side_by_side):
    camera = serve(VideoSource(FILE, side_by_side, side_by_side=True))
    messages = camera.stream(FRAMES + 4, encoding=PNG)
    header = messages[0].header
    assert (header.width_px, header.height_px) == (W, H)
    assert header.source == f"file:{side_by_side} (side by side)"
    assert header.left.fx_px == 0 and not header.left.projection and header.baseline_m == 0
    seen = _replayed_frame_indices(messages)
    first_sequence, first_index = seen[0]
    for sequence, index in seen:  # one frame per capture tick, wrapping at the end
        assert index == (first_index + sequence - first_sequence) % FRAMES
    assert seen[-1][0] - first_sequence >= FRAMES  # so it went round
    assert all(message.pair.eye_skew.ToNanoseconds() == 0 for message in messages[1:])


def test_two_recordings_replay_as_pairs_with_their_calibration(serve, two_files, tmp_path):
    calibration = tmp_path / "rig.json"
    calibration.write_text(json.dumps(CALIBRATION))
    left, right = two_files
    camera = serve(VideoSource(FILE, left, right, calibration_path=calibration))
    messages = camera.stream(4, encoding=PNG)
    _replayed_frame_indices(messages)
    header = messages[0].header
    assert header.source == f"file:{left}+{right}"
    assert header.left.fx_px == pytest.approx(200.0) and header.left.fy_px == pytest.approx(205)
    assert header.left.cx_px == pytest.approx(79.5) and header.left.cy_px == pytest.approx(59.5)
    assert list(header.left.distortion) == pytest.approx([0.01, -0.02, 0.0, 0.0, 0.001])
    assert header.baseline_m == pytest.approx(0.1)
    assert list(header.right.camera_pose.rotation.row_major) == [0, 0, -1, 1, 0, 0, 0, -1, 0]
    # the left camera looks along -x from (1, 0, 0.5): a point 1 m ahead, on its axis, lands
    # on the principal point
    projection = np.array(header.left.projection).reshape(3, 4)
    u, v, w = projection @ [0.0, 0.0, 0.5, 1.0]
    assert (u / w, v / w) == pytest.approx((79.5, 59.5))
    # a client that asks for half the size gets the intrinsics of half the size
    small = camera.stream(1, encoding=PNG, width_px=W // 2, height_px=H // 2)[0].header
    assert small.left.fx_px == pytest.approx(100.0) and small.left.cx_px == pytest.approx(39.5)


def test_a_recording_that_ends_without_looping_ends_the_stream_unavailable(serve, side_by_side):
    camera = serve(VideoSource(FILE, side_by_side, side_by_side=True, loop=False))
    call = camera.stub.StreamPairs(pb.StreamPairsRequest(encoding=PNG), timeout=20)
    received = 0
    with pytest.raises(grpc.RpcError) as error:
        for message in call:
            received += message.HasField("pair")
    assert error.value.code() is grpc.StatusCode.UNAVAILABLE
    assert "ended" in error.value.details() and side_by_side in error.value.details()
    assert 1 <= received <= FRAMES


def test_a_bad_calibration_file_is_refused_naming_it(tmp_path, side_by_side):
    broken = tmp_path / "broken.json"
    broken.write_text(json.dumps({"left": {"fx_px": 1.0}, "right": {}}))
    with pytest.raises(ValueError, match="broken.json"):
        VideoSource(FILE, side_by_side, side_by_side=True, calibration_path=broken)
    rotated = json.loads(json.dumps(CALIBRATION))
    rotated["left"]["rotation"] = [1, 0, 0, 0, 1, 0, 0, 0, 2]  # not a rotation
    bad_rotation = tmp_path / "bad_rotation.json"
    bad_rotation.write_text(json.dumps(rotated))
    with pytest.raises(ValueError, match="left.rotation"):
        load_calibration(bad_rotation, W, H)


def test_an_explicit_projection_is_kept_and_scaled_with_the_image():
    document = json.loads(json.dumps(CALIBRATION))
    measured = np.arange(12, dtype=float).reshape(3, 4) + 1.0
    document["right"]["projection"] = measured.reshape(12).tolist()
    full = parse_calibration(document, 2 * W, 2 * H)
    assert np.array_equal(full.right.projection, measured)
    point = [0.3, -0.2, 0.1]
    u, v = full.left.project(point)
    half = full.for_size(W, H)
    # resizing by 1/2 maps pixel centres as u' = (u + 0.5) / 2 - 0.5
    assert half.left.project(point) == pytest.approx([(u + 0.5) / 2 - 0.5, (v + 0.5) / 2 - 0.5])
    u, v = full.right.project(point)
    assert half.right.project(point) == pytest.approx([(u + 0.5) / 2 - 0.5, (v + 0.5) / 2 - 0.5])
