"""stereo_<source>_<mode>: pairs per second and capture -> decoded latency at 640x480.

The bench runs one StereoCamera service process per source (``--source pattern`` and
``--source sim`` rendering at the live arm pose from the bench's world) and measures each
transfer mode (single: single-buffer serialized; double: double-buffer concurrent) with the
stereo service's own client measurement, services/stereo_camera/measure.py: a gRPC client that
decodes both eyes (JPEG) of every pair and takes capture time (the earlier eye) -> both decoded.

The soak streams for a duration instead of a number of pairs (`run_stereo_for`): the same
client, one stream after another of CHUNK_S each (the measurement takes a count of pairs),
the figures pooled.
"""

from __future__ import annotations

import statistics
import time

from bench.stats import summary

WIDTH_PX, HEIGHT_PX = 640, 480
CHUNK_S = 30.0  # run_stereo_for: one stream of this long at the source's rate, then the next


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


def run_stereo_for(address: str, mode: str, duration_s: float, source_fps: float,
                   chunk_s: float = CHUNK_S) -> dict:
    """run_stereo again and again, each stream about `chunk_s` long (sized by the rate the
    last one got; the first at the source's rate), until `duration_s` has passed. Pooled:
    pairs and gaps summed, fps over the streams' time, p50 the median of the streams' p50s,
    p99 and max the worst stream's; a stream that fails is counted in `errors` (its reason in
    `failures`) and the next one starts."""
    from services.stereo_camera.measure import WARMUP_PAIRS

    deadline = time.monotonic() + duration_s
    chunks: list[dict] = []
    failures: list[str] = []
    errors = 0
    fps = source_fps  # the next stream's size: at the rate the last one got
    while (left := deadline - time.monotonic()) > 1.0:
        pairs = max(WARMUP_PAIRS + 2, int(min(chunk_s, left) * fps))
        try:
            chunks.append(run_stereo(address, mode, pairs, source_fps))
            fps = min(source_fps, max(1.0, chunks[-1]["delivered_hz"] or source_fps))
        except Exception as error:  # a stream that failed: counted, and on to the next
            errors += 1
            if len(failures) < 5:
                failures.append(f"{type(error).__name__}: {str(error)[:200]}")
            time.sleep(1.0)
    pairs = sum(chunk["pairs"] for chunk in chunks)
    seconds = sum(chunk["pairs"] / chunk["delivered_hz"] for chunk in chunks
                  if chunk["delivered_hz"])
    first = chunks[0] if chunks else {}
    result = summary([], source_fps, 0, 1, sum(chunk["dropped"] for chunk in chunks),
                     transport=first.get("transport", "grpc-stream StereoCamera.StreamPairs"),
                     source=first.get("source"), mode=mode, pairs=pairs, streams=len(chunks),
                     errors=errors, failures=failures, width_px=first.get("width_px"),
                     height_px=first.get("height_px"))
    result.update(
        delivered_hz=round(pairs / seconds, 3) if seconds else None,
        p50_ms=(round(statistics.median(c["p50_ms"] for c in chunks), 4) if chunks else None),
        p99_ms=max((c["p99_ms"] for c in chunks), default=None),
        max_ms=max((c["max_ms"] for c in chunks), default=None), samples=pairs)
    return result
