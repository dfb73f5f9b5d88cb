"""The emergency-stop band's gRPC face: ProxyRobot.EmergencyStop and nothing else."""

from __future__ import annotations

import logging
import threading
from collections.abc import Callable

from services.world.link import EmergencyStopLink
from telerobot.v1 import proxy_robot_pb2 as pb
from telerobot.v1 import proxy_robot_pb2_grpc, types_pb2
from wire import convert
from wire.addresses import address_for, env_name
from wire.errors import UnavailableError, UnimplementedError

log = logging.getLogger(__name__)


class EmergencyStopServicer(proxy_robot_pb2_grpc.ProxyRobotServicer):
    """Latches the stop through an EmergencyStopLink, opened on first use and opened again
    after it fails (a restarted world is a new segment)."""

    def __init__(self, open_link: Callable[[], EmergencyStopLink]):
        self._open_link = open_link
        self._link: EmergencyStopLink | None = None
        self._lock = threading.Lock()

    def open(self) -> None:
        """Attach now, so the first stop does not pay for it; if the arm is not there yet,
        the first stop attaches (or says UNAVAILABLE)."""
        with self._lock:
            try:
                self._link = self._link or self._open_link()
            except UnavailableError as error:
                log.warning("no arm to stop yet (%s); trying again on the first stop",
                            error.message)

    def EmergencyStop(self, request, context):
        with self._lock:
            try:
                stop_time_ns = self._stop()
            except UnavailableError:
                self._drop_link()
                stop_time_ns = self._stop()  # once more, on a fresh link; else the caller hears
        log.warning("emergency stop latched at the hardware: %s", request.reason or "no reason")
        return pb.EmergencyStopResponse(status=types_pb2.ROBOT_STATUS_ESTOPPED,
                                        stop_time=convert.timestamp(stop_time_ns))

    def stop_now(self) -> None:
        """Latch the stop as an EmergencyStop call arrives (the runtime's on_emergency_call);
        its handler follows, latches again and answers. A link that fails is the handler's to
        report."""
        with self._lock:
            try:
                self._stop()
            except UnavailableError:
                pass

    def _stop(self) -> int:
        if self._link is None:
            self._link = self._open_link()
        return self._link.stop()

    def _drop_link(self) -> None:
        link, self._link = self._link, None
        if link is not None:
            link.close()

    def close(self) -> None:
        with self._lock:
            self._drop_link()


def _refuse(method: str):
    def refuse(self, request, context):
        raise UnimplementedError(
            f"this is the emergency-stop band: it serves only EmergencyStop. Call {method} on "
            f"ProxyRobot ({env_name('proxy_robot', 'address')}, here {address_for('proxy_robot')})",
            reason="EMERGENCY_STOP_ONLY")
    refuse.__name__ = method
    return refuse


for _method in pb.DESCRIPTOR.services_by_name["ProxyRobot"].methods:
    if _method.name != "EmergencyStop":
        setattr(EmergencyStopServicer, _method.name, _refuse(_method.name))
