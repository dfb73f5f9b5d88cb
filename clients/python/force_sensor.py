"""ForceSensor clients: start and stop sampling, tare, configuration, samples and streams.

Use `ForceSensorClient` on ForceSensor's own port (50053), or on the DecisionServer's (50051)
with a lease (``DecisionClient.sensor``): there StartReading, StopReading, Tare and
SetSensorConfig need the control lock.

Returns: `WrenchSample`, `WrenchBatch`, `TareResult`, `SensorConfig` (``values.py``).
"""

from __future__ import annotations

from clients.python.base import AsyncClient, SyncClient
from clients.python.values import SensorConfig, TareResult, WrenchBatch, WrenchSample
from telerobot.v1 import force_sensor_pb2 as pb
from telerobot.v1 import force_sensor_pb2_grpc
from wire import convert
from wire.convert import vector3_value
from wire.pose import Pose


def _batch(response: pb.StreamWrenchResponse) -> WrenchBatch:
    return WrenchBatch([WrenchSample.from_proto(s) for s in response.samples],
                       response.dropped_count)


class _ForceSensorMethods:
    """The ForceSensor calls; on the async client each returns an awaitable of the same value."""

    SERVICE = "telerobot.v1.ForceSensor"
    ADDRESS_NAME = "force_sensor"
    STUB = force_sensor_pb2_grpc.ForceSensorStub

    def start_reading(self, *, timeout: float | None = None, lane: str | None = None
                      ) -> SensorConfig:
        """Start the sampling thread (a no-op when reading). Returns the configuration."""
        return self._unary("StartReading", pb.StartReadingRequest(),
                           lambda r: SensorConfig.from_proto(r.config), timeout, lane)

    def stop_reading(self, *, timeout: float | None = None, lane: str | None = None) -> int:
        """Stop the sampling thread. Returns the sequence number of the last sample."""
        return self._unary("StopReading", pb.StopReadingRequest(), lambda r: r.last_sequence,
                           timeout, lane)

    def tare(self, duration_s: float = 0.0, *, timeout: float | None = None,
             lane: str | None = None) -> TareResult:
        """Take the reading averaged over `duration_s` (0: the latest sample) as the zero."""
        return self._unary("Tare", pb.TareRequest(duration=convert.duration(duration_s)),
                           lambda r: TareResult(vector3_value(r.bias.force_n),
                                                vector3_value(r.bias.torque_nm), r.sample_count),
                           timeout, lane)

    def get_sensor_config(self, *, timeout: float | None = None, lane: str | None = None
                          ) -> SensorConfig:
        return self._unary("GetSensorConfig", pb.GetSensorConfigRequest(),
                           lambda r: SensorConfig.from_proto(r.config), timeout, lane)

    def set_sensor_config(self, *, period_s: float | None = None,
                          threshold_force_n: float | None = None,
                          threshold_torque_nm: float | None = None,
                          thread_priority: int | None = None,
                          flange_to_tool: Pose | None = None,
                          timeout: float | None = None, lane: str | None = None
                          ) -> SensorConfig:
        """Change the given fields only (the update mask is built from the arguments that are
        not None), all or none. Returns the configuration now in force."""
        config, paths = pb.SensorConfig(), []
        if period_s is not None:
            config.period.CopyFrom(convert.duration(period_s))
            paths.append("period")
        if threshold_force_n is not None:
            config.threshold_force_n = threshold_force_n
            paths.append("threshold_force_n")
        if threshold_torque_nm is not None:
            config.threshold_torque_nm = threshold_torque_nm
            paths.append("threshold_torque_nm")
        if thread_priority is not None:
            config.thread_priority = int(thread_priority)
            paths.append("thread_priority")
        if flange_to_tool is not None:
            config.flange_to_tool.CopyFrom(convert.pose_to_proto(flange_to_tool))
            paths.append("flange_to_tool")
        if not paths:
            raise ValueError("set_sensor_config needs at least one field to change")
        request = pb.SetSensorConfigRequest(config=config)
        request.update_mask.paths.extend(paths)
        return self._unary("SetSensorConfig", request,
                           lambda r: SensorConfig.from_proto(r.config), timeout, lane)

    def get_wrench(self, *, timeout: float | None = None, lane: str | None = None
                   ) -> WrenchSample:
        """The latest sample (FAILED_PRECONDITION before the first one)."""
        return self._unary("GetWrench", pb.GetWrenchRequest(),
                           lambda r: WrenchSample.from_proto(r.sample), timeout, lane)

    def stream_wrench(self, decimation: int = 1, *, threshold_force_n: float = 0.0,
                      threshold_torque_nm: float = 0.0, batch_size: int = 1,
                      queue_capacity: int = 0, timeout: float | None = None,
                      lane: str | None = None):
        """`WrenchBatch`es with this subscriber's own rate (every `decimation`-th sample),
        change filter, batch size and queue, until cancelled."""
        return self._server_stream("StreamWrench", pb.StreamWrenchRequest(
            decimation=decimation, threshold_force_n=threshold_force_n,
            threshold_torque_nm=threshold_torque_nm, batch_size=batch_size,
            queue_capacity=queue_capacity), _batch, timeout, lane)


class ForceSensorClient(_ForceSensorMethods, SyncClient):
    """Blocking ForceSensor client. ``with ForceSensorClient("127.0.0.1:50053") as s: ...``"""


class AsyncForceSensorClient(_ForceSensorMethods, AsyncClient):
    """asyncio ForceSensor client: the same methods, awaited; streams are ``async for``."""
