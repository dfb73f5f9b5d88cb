"""wire.stereo: decoding a pair's images; raw frames need only numpy."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from services.stereo_camera.encoding import encode_image
from telerobot.v1 import stereo_camera_pb2 as pb
from wire.stereo import LOW_LATENCY_OPTIONS, decode_image, decode_pair

ROOT = Path(__file__).resolve().parents[2]
WIDTH, HEIGHT = 8, 6


def image(seed: int = 0) -> np.ndarray:
    return np.random.default_rng(seed).integers(0, 256, (HEIGHT, WIDTH, 3), dtype=np.uint8)


def test_raw_and_png_decode_exactly_and_jpeg_closely():
    rgb = image()
    for encoding in (pb.IMAGE_ENCODING_RAW_RGB8, pb.IMAGE_ENCODING_PNG):
        decoded = decode_image(encode_image(rgb, encoding), encoding, WIDTH, HEIGHT)
        np.testing.assert_array_equal(decoded, rgb)
    smooth = np.full((HEIGHT, WIDTH, 3), (200, 40, 90), dtype=np.uint8)  # RGB order kept
    jpeg = decode_image(encode_image(smooth, pb.IMAGE_ENCODING_JPEG, 95),
                        pb.IMAGE_ENCODING_JPEG, WIDTH, HEIGHT)
    assert np.abs(jpeg.astype(int) - smooth).max() <= 4


def test_decode_pair_uses_the_header():
    header = pb.StereoHeader(width_px=WIDTH, height_px=HEIGHT,
                             encoding=pb.IMAGE_ENCODING_RAW_RGB8)
    pair = pb.StereoPair(left_image=image(1).tobytes(), right_image=image(2).tobytes())
    left, right = decode_pair(header, pair)
    np.testing.assert_array_equal(left, image(1))
    np.testing.assert_array_equal(right, image(2))


@pytest.mark.parametrize(("data", "encoding", "match"), [
    (b"\0" * 10, pb.IMAGE_ENCODING_RAW_RGB8, "raw 8x6 image has 144 bytes"),
    (b"not an image", pb.IMAGE_ENCODING_JPEG, "decoded nothing"),
])
def test_bad_bytes_are_a_value_error(data, encoding, match):
    with pytest.raises(ValueError, match=match):
        decode_image(data, encoding, WIDTH, HEIGHT)


def test_an_image_of_the_wrong_size_is_a_value_error():
    png = encode_image(image(), pb.IMAGE_ENCODING_PNG)
    with pytest.raises(ValueError, match="expected a 6x8 image, decoded 8x6"):
        decode_image(png, pb.IMAGE_ENCODING_PNG, HEIGHT, WIDTH)


@pytest.mark.e2e
def test_raw_frames_do_not_load_opencv():
    code = ("import sys; from wire.stereo import decode_image; "
            "decode_image(bytes(12), 1, 2, 2); print('cv2' in sys.modules)")
    assert pb.IMAGE_ENCODING_RAW_RGB8 == 1
    result = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True,
                            text=True, timeout=60)
    assert result.returncode == 0, result.stderr
    assert result.stdout.split() == ["False"]


def test_low_latency_options_turn_off_window_growth():
    assert dict(LOW_LATENCY_OPTIONS)["grpc.http2.bdp_probe"] == 0
