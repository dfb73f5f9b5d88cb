"""ForceSensor over gRPC: reads requests, calls ForceSensorCore, converts answers and errors.

StreamWrench never blocks: while it has nothing to send it yields a Wakeup on its subscription's
eventfd, which the server waits for (on grpc.aio, the event loop: no thread per stream). It
yields each message already serialized (bytes; the lane interceptor sends bytes
as they are): a batch's samples are encoded once, by the first stream that needs them, and
every subscriber given the same batch sends those bytes, followed by its own dropped_count.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence

from google.protobuf.timestamp_pb2 import Timestamp

from services.common import se3
from services.force_sensor.core import ForceSensorCore
from services.force_sensor.settings import ThreadPriority
from services.force_sensor.subscribers import StreamOptions, WrenchBatch, WrenchReading
from telerobot.v1 import force_sensor_pb2 as pb
from telerobot.v1 import force_sensor_pb2_grpc, types_pb2
from wire import convert
from wire.errors import InvalidArgumentError, UnavailableError

STREAM_POLL_S = 0.1  # how often an idle stream checks that its client is still there
_MASK_PATHS = {"period", "threshold_force_n", "threshold_torque_nm", "thread_priority",
               "flange_to_tool", "reading"}


def reading_to_proto(reading: WrenchReading) -> pb.WrenchSample:
    """The sample as sent (convert.timestamp and convert.wrench_to_proto, spelled out: 6 us a
    sample instead of 10, on the path of every stream's first copy of it)."""
    fx, fy, fz = reading.force_n.tolist()
    tx, ty, tz = reading.torque_nm.tolist()
    seconds, nanos = divmod(reading.sample_time_ns, 1_000_000_000)
    return pb.WrenchSample(
        sequence=reading.sequence, sample_time=Timestamp(seconds=seconds, nanos=nanos),
        wrench=types_pb2.Wrench(force_n=types_pb2.Vector3(x=fx, y=fy, z=fz),
                                torque_nm=types_pb2.Vector3(x=tx, y=ty, z=tz)))


def encode_samples(readings: Sequence[WrenchReading]) -> bytes:
    """A StreamWrenchResponse carrying `readings` and no dropped_count, serialized."""
    return pb.StreamWrenchResponse(
        samples=[reading_to_proto(r) for r in readings]).SerializeToString()


def encode_dropped(dropped: int) -> bytes:
    """The dropped_count field alone, serialized (nothing for 0, as proto3 leaves it out).
    Appended to encode_samples' bytes it makes the whole message: protobuf writes fields in
    number order, and samples (1) come before dropped_count (2)."""
    return pb.StreamWrenchResponse(dropped_count=dropped).SerializeToString()


def stream_message(batch: WrenchBatch, dropped: int) -> bytes:
    """The serialized StreamWrenchResponse for one subscriber: the batch's shared bytes and
    that subscriber's dropped_count."""
    payload = batch.payload(encode_samples)
    return payload + encode_dropped(dropped) if dropped else payload


def priority_from_proto(value: int) -> ThreadPriority:
    name = pb.SensorThreadPriority.Name(value).removeprefix("SENSOR_THREAD_PRIORITY_")
    return ThreadPriority[name]


class ForceSensorServicer(force_sensor_pb2_grpc.ForceSensorServicer):
    def __init__(self, core: ForceSensorCore):
        self._core = core

    def _config(self) -> pb.SensorConfig:
        settings = self._core.settings
        return pb.SensorConfig(
            period=convert.duration(settings.period_s),
            threshold_force_n=settings.threshold_force_n,
            threshold_torque_nm=settings.threshold_torque_nm,
            thread_priority=pb.SensorThreadPriority.Value(
                f"SENSOR_THREAD_PRIORITY_{settings.thread_priority.name}"),
            reading=self._core.reading,
            flange_to_tool=convert.pose_to_proto(self._core.tool_frame))

    def StartReading(self, request, context):
        self._core.start_reading()
        return pb.StartReadingResponse(config=self._config())

    def StopReading(self, request, context):
        return pb.StopReadingResponse(last_sequence=self._core.stop_reading())

    def Tare(self, request, context):
        bias, count = self._core.tare(convert.seconds(request.duration))
        return pb.TareResponse(bias=convert.wrench_to_proto(bias.force_n, bias.torque_nm),
                               sample_count=count)

    def GetSensorConfig(self, request, context):
        return pb.GetSensorConfigResponse(config=self._config())

    def SetSensorConfig(self, request, context):
        paths = set(request.update_mask.paths) or _MASK_PATHS
        unknown = paths - _MASK_PATHS
        if unknown:
            raise InvalidArgumentError(f"unknown update_mask paths {sorted(unknown)}; use "
                                       f"{sorted(_MASK_PATHS)}", reason="BAD_MASK")
        config, changes = request.config, {}
        if "period" in paths and config.HasField("period"):
            changes["period_s"] = convert.seconds(config.period)
        for name in ("threshold_force_n", "threshold_torque_nm"):
            if name in paths:
                changes[name] = getattr(config, name)
        if "thread_priority" in paths and config.thread_priority:
            if config.thread_priority not in pb.SensorThreadPriority.values():
                raise InvalidArgumentError(f"unknown thread_priority {config.thread_priority}",
                                           reason="BAD_PRIORITY")
            changes["thread_priority"] = priority_from_proto(config.thread_priority)
        tool_frame = None
        if "flange_to_tool" in paths and config.HasField("flange_to_tool"):
            tool_frame = se3.pose_from_proto(config.flange_to_tool, "flange_to_tool")
        # Validate everything before changing anything: all or none.
        settings = dataclasses.replace(self._core.settings, **changes).validated()
        self._core.configure(settings)
        if tool_frame is not None:
            self._core.set_tool_frame(tool_frame)
        return pb.SetSensorConfigResponse(config=self._config())

    def GetWrench(self, request, context):
        return pb.GetWrenchResponse(sample=reading_to_proto(self._core.latest()))

    def StreamWrench(self, request, context):
        options = StreamOptions.from_request(
            request.decimation, request.threshold_force_n, request.threshold_torque_nm,
            request.batch_size, request.queue_capacity)
        with self._core.subscribe(options) as subscription:
            while context.is_active():
                batch = subscription.next_or_arm()
                if batch is not None:
                    yield stream_message(batch, subscription.dropped)
                    continue
                if self._core.failure:
                    raise UnavailableError(f"the sensor stopped: {self._core.failure}; "
                                           "StartReading again, then resubscribe",
                                           reason="SENSOR_DOWN")
                # Waited for by whoever drives the stream (services/common/wakeup.py): on
                # grpc.aio, the event loop, with no thread of its own.
                yield subscription.wakeup(STREAM_POLL_S)
                subscription.disarm()
