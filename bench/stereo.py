"""stereo_<source>_<mode>: pairs per second and capture -> decoded latency at 640x480.

The bench runs one StereoCamera service process per source (``--source pattern`` and
``--source sim`` rendering at the live arm pose from the bench's world) and measures each
transfer mode (single: single-buffer serialized; double: double-buffer concurrent) with the
stereo service's own client measurement, services/stereo_camera/measure.py: a gRPC client that
decodes both eyes (JPEG) of every pair and takes capture time (the earlier eye) -> both decoded.
"""

from __future__ import annotations

from bench.stats import summary

WIDTH_PX, HEIGHT_PX = 640, 480


def available() -> str | None:
    """None when the stereo measurement can run here; otherwise why not."""
    try:
        from services.stereo_camera import measure  # noqa: F401
    except Exception as error:  # the stereo service is another helper's, maybe unfinished
        return f"services.stereo_camera.measure does not import: {error}"
    return None


def run_stereo(address: str, mode: str, pairs: int, source_fps: float) -> dict:
    from services.stereo_camera.measure import measure_address

    measured = measure_address(address, mode, pairs=pairs, width_px=WIDTH_PX,
                               height_px=HEIGHT_PX, timeout_s=120.0)
    latency = measured.latency
    result = summary([], source_fps, 0, 1, measured.sequence_gaps,
                     transport=f"grpc-stream StereoCamera.StreamPairs ({measured.encoding})",
                     source=measured.source, mode=mode, pairs=measured.pairs,
                     width_px=measured.width_px, height_px=measured.height_px,
                     mean_eye_skew_ms=round(measured.mean_eye_skew_ms, 3),
                     mean_pair_bytes=round(measured.mean_pair_bytes))
    result.update(delivered_hz=round(measured.fps, 3), p50_ms=round(latency.p50_ms, 4),
                  p99_ms=round(latency.p99_ms, 4), max_ms=round(latency.max_ms, 4),
                  samples=latency.samples)
    return result
