"""force_<rate> and observers_<n>: wrench samples from the sensor to the operator.

The sensor samples every 1 ms (its default TimerValue); a subscriber asks for every Nth sample
with StreamWrench's per-subscriber `decimation` (1 for 1 kHz; 8 for the papers' ~120 Hz, i.e.
125 Hz), one sample per message (batch_size 1). A sample's `sample_time` is the world's servo
step time (time.time_ns() in the world process); latency is time.time_ns() when the client has
the decoded message, minus that. It so includes the sensor thread's phase against the world's
step (0 to 1 ms: both run 1 kHz loops, unsynchronized), for the project and the baselines alike
(the baselines run the same ForceSensorCore).

`dropped` is what the server's per-subscriber queue dropped (`dropped_count`) plus gaps in the
kept samples' sequence numbers. A sampler that is late skips the tick (it takes no sample), so
that shows as a delivered rate under the offered one, not as drops.

With `mcap_path` (force_1000_mcap, recording.py) the subscriber writes every sample it
receives into an MCAP file, as `make teleop --mcap` does, before it takes the latency
timestamp: the recording's cost is in the latency, and the file must hold every sample.

`subscriber_cpu_us_per_sample`: the subscriber process's own CPU (time.process_time: user +
system, every thread, gRPC's included) over the measured window, per sample received: the
p50 includes waiting (for the sample, for the core), the CPU is what receiving, and
recording, cost. Closing the MCAP file after the window is not in it.
"""

from __future__ import annotations

import os
import threading
import time
from collections.abc import Callable, Iterator
from pathlib import Path

import grpc

from bench import framing
from bench.cpu import CpuWindow
from bench.stats import interarrival, summary
from telerobot.v1 import force_sensor_pb2, force_sensor_pb2_grpc

SENSOR_RATE_HZ = 1000.0
WARMUP_S = 0.3
POLL_MS = 100


def _grpc_messages(address: str, decimation: int, timeout_s: float, stop: threading.Event
                   ) -> Iterator[force_sensor_pb2.StreamWrenchResponse]:
    # A channel of its own (and its own connection): observers are separate clients.
    channel = grpc.insecure_channel(address, options=[("grpc.use_local_subchannel_pool", 1)])
    stub = force_sensor_pb2_grpc.ForceSensorStub(channel)
    stream = stub.StreamWrench(
        force_sensor_pb2.StreamWrenchRequest(decimation=decimation, batch_size=1),
        timeout=timeout_s)
    try:
        for message in stream:
            yield message
            if stop.is_set():
                return
    except grpc.RpcError as error:
        if error.code() not in (grpc.StatusCode.CANCELLED, grpc.StatusCode.DEADLINE_EXCEEDED):
            raise
    finally:
        stream.cancel()
        channel.close()


def _zmq_messages(address: str, decimation: int, timeout_s: float, stop: threading.Event
                  ) -> Iterator[force_sensor_pb2.StreamWrenchResponse]:
    import zmq

    context = zmq.Context()
    socket = context.socket(zmq.SUB)
    socket.setsockopt(zmq.LINGER, 0)
    socket.connect(f"tcp://{address}")
    socket.subscribe(f"d{decimation}|".encode())
    deadline = time.monotonic() + timeout_s
    try:
        while not stop.is_set() and time.monotonic() < deadline:
            if socket.poll(POLL_MS):
                _, payload = socket.recv_multipart()
                yield force_sensor_pb2.StreamWrenchResponse.FromString(payload)
    finally:
        socket.close()
        context.term()


def _tcp_messages(address: str, decimation: int, timeout_s: float, stop: threading.Event
                  ) -> Iterator[force_sensor_pb2.StreamWrenchResponse]:
    sock = framing.connect(address)
    sock.settimeout(POLL_MS / 1000)
    sock.sendall(framing.MODE_FORCE + framing.DECIMATION.pack(decimation))
    deadline = time.monotonic() + timeout_s
    try:
        while not stop.is_set() and time.monotonic() < deadline:
            try:
                payload = framing.recv_frame(sock)
            except TimeoutError:
                continue
            yield force_sensor_pb2.StreamWrenchResponse.FromString(payload)
    finally:
        sock.close()


STREAMS: dict[str, Callable] = {"grpc": _grpc_messages, "zmq": _zmq_messages,
                                "tcp": _tcp_messages}
TRANSPORT_NAMES = {"grpc": "grpc-stream", "zmq": "zmq-pubsub", "tcp": "tcp-struct"}


def sequence_gaps(last: int | None, sequence: int, decimation: int) -> int:
    """Samples missing between a subscriber's sample `last` and the next one, `sequence`
    (every `decimation`-th sample is the subscriber's)."""
    if last is None or sequence - last <= decimation:
        return 0
    return (sequence - last) // decimation - 1


def measure_stream(transport: str, address: str, decimation: int, duration_s: float,
                   on_first: Callable[[], None] | None = None,
                   mcap_path: str | None = None,
                   watch_pids: dict[str, int] | None = None) -> dict:
    """Receive the wrench stream for WARMUP_S + duration_s; the scenario's summary.
    `mcap_path`: record every sample there (recording.WrenchRecorder), the result's
    `recording` says what the file holds. `watch_pids`: the result's `cpu` says how busy the
    machine was over the measured window and what each of these processes, and this
    subscriber ("operator"), took of it (bench/cpu.py)."""
    recorder = None
    if mcap_path is not None:
        from bench.recording import WrenchRecorder  # the MCAP writer: only when recording

        recorder = WrenchRecorder(Path(mcap_path))
    stop = threading.Event()
    latencies, arrivals = [], []
    server_dropped = gaps = 0
    first_dropped = None
    last_sequence = None
    window_start = window_end = None
    cpu_start = cpu_end = 0.0
    started = time.monotonic()
    timeout_s = WARMUP_S + duration_s + 10.0
    for message in STREAMS[transport](address, decimation, timeout_s, stop):
        if recorder is not None:
            recorder.write(message)
        now_ns = time.time_ns()
        now = time.monotonic()
        if on_first is not None:
            on_first()
            on_first = None
        if now - started < WARMUP_S:
            continue
        if window_start is None:
            window_start = now
            first_dropped = message.dropped_count
            cpu_start = time.process_time()
            if watch_pids is not None:
                cpu_window = CpuWindow({**watch_pids, "operator": os.getpid()})
        for sample in message.samples:
            latencies.append((now_ns - sample.sample_time.ToNanoseconds()) / 1e6)
            gaps += sequence_gaps(last_sequence, sample.sequence, decimation)
            last_sequence = sample.sequence
        arrivals.append(now_ns)
        server_dropped = message.dropped_count - (first_dropped or 0)
        window_end = now
        cpu_end = time.process_time()
        if now - window_start >= duration_s:
            stop.set()
            break
    if window_start is None:
        raise RuntimeError(f"no wrench samples arrived over {transport} from {address}")
    elapsed = max(window_end - window_start, 1e-9)
    rate = SENSOR_RATE_HZ / decimation
    # The first message opens the window: count the ones after it over the time they took.
    result = summary(latencies, rate, len(latencies) - 1, elapsed, server_dropped + gaps,
                     transport=TRANSPORT_NAMES[transport], decimation=decimation,
                     duration_s=round(elapsed, 3), server_dropped=server_dropped,
                     sequence_gaps=gaps, **interarrival(arrivals, 1000.0 / rate))
    if len(latencies) > 1:  # the window opens after the first message's CPU
        result["subscriber_cpu_us_per_sample"] = round(
            1e6 * (cpu_end - cpu_start) / (len(latencies) - 1), 2)
    if watch_pids is not None:
        result["cpu"] = cpu_window.stop()
    if recorder is not None:
        result["recording"] = recorder.close()
    result["latencies_ms"] = [round(v, 4) for v in latencies]
    return result


def observe(address: str, count: int, decimation: int, max_s: float,
            ready: Callable[[], None], stop: threading.Event) -> dict:
    """`count` observers, one thread and one connection each, streaming until `stop` (or
    max_s); calls ready() once every one has its first sample. Counts per observer, and what
    each lost after ready(): the server's drops for it (`dropped_count`) and the gaps in its
    samples' sequence numbers."""
    counts = [0] * count
    first = [threading.Event() for _ in range(count)]
    errors: list[str] = []
    marked = threading.Event()  # ready() was called: losses count from here
    dropped_at_mark: list[int | None] = [None] * count
    dropped, gaps = [0] * count, [0] * count

    def run(index: int):
        last = None
        try:
            for message in _grpc_messages(address, decimation, max_s, stop):
                counts[index] += len(message.samples)
                first[index].set()
                if not marked.is_set():
                    last = message.samples[-1].sequence if message.samples else last
                    continue
                if dropped_at_mark[index] is None:
                    dropped_at_mark[index] = message.dropped_count
                dropped[index] = message.dropped_count - dropped_at_mark[index]
                for sample in message.samples:
                    gaps[index] += sequence_gaps(last, sample.sequence, decimation)
                    last = sample.sequence
        except Exception as error:  # reported with the result, not raised from a thread
            errors.append(f"observer {index}: {error}")
            first[index].set()

    threads = [threading.Thread(target=run, args=(i,), name=f"observer-{i}", daemon=True)
               for i in range(count)]
    started = time.monotonic()
    for thread in threads:
        thread.start()
    for event in first:
        event.wait(max(0.0, max_s - (time.monotonic() - started)))
    ready()
    marks = list(counts)
    mark_time = time.monotonic()
    marked.set()
    stop.wait(max(0.0, max_s - (mark_time - started)))
    elapsed = time.monotonic() - mark_time
    delivered = [c - m for c, m in zip(counts, marks, strict=True)]
    stop.set()
    for thread in threads:
        thread.join(2.0)
    total = sum(delivered)
    return {"observers": count, "observer_rate_hz": SENSOR_RATE_HZ / decimation,
            "observer_delivered_hz_mean": round(total / elapsed / count, 2) if count else None,
            "observer_delivered_hz_min": (round(min(delivered) / elapsed, 2) if count
                                          else None),
            "observer_samples": total, "observer_duration_s": round(elapsed, 3),
            "observer_server_dropped": sum(dropped), "observer_sequence_gaps": sum(gaps),
            "errors": errors[:5]}
