"""python -m tests.observation.observers_process: N observers in one process, for the
two-router test. Each is a session of its own through --router (mutual TLS as `observer`),
subscribed to the station's wrench. Prints OBSERVING once every one has a message, then after
--seconds one JSON line: per observer, the messages, samples, lost samples and payload bytes,
and the lag p95 over every sample of every observer (received minus taken, one clock)."""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

import numpy as np

from clients.observe import Observer
from wire.observation import ZenohTls, client

READY = "OBSERVING"


def main() -> int:
    parser = argparse.ArgumentParser()
    parser.add_argument("--router", required=True)
    parser.add_argument("--tls-dir", required=True)
    parser.add_argument("--station", required=True)
    parser.add_argument("--count", type=int, required=True)
    parser.add_argument("--seconds", type=float, required=True)
    args = parser.parse_args()
    tls = ZenohTls(Path(args.tls_dir), "observer")
    sessions = [client(args.router, tls) for _ in range(args.count)]
    received_bytes = [0] * args.count

    def counter(index: int):
        def count(_topic: str, message) -> None:
            received_bytes[index] += message.ByteSize()
        return count

    observers = [Observer(session, args.station, ("wrench",), on_message=counter(i))
                 for i, session in enumerate(sessions)]
    deadline = time.monotonic() + 60
    while not all(o.counts["wrench"].messages for o in observers):
        if time.monotonic() > deadline:
            raise SystemExit("not every observer got a message within 60 s")
        time.sleep(0.05)
    print(READY, flush=True)
    time.sleep(args.seconds)
    for session in sessions:
        session.close()
    lags = np.concatenate([o.counts["wrench"].lags_ms for o in observers])
    print(json.dumps({
        "observers": [{"messages": o.counts["wrench"].messages,
                       "samples": o.counts["wrench"].samples, "lost": o.counts["wrench"].lost,
                       "bytes": received_bytes[i]} for i, o in enumerate(observers)],
        "lag_p95_ms": float(np.percentile(lags, 95)),
        "lag_p50_ms": float(np.percentile(lags, 50)), "lag_min_ms": float(lags.min())}), flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
