"""python -m services.decision_server: the operator's one address.

It serves DecisionServer and, as IDecisionServer inherits IProxyRobot and IForceSensor, the
ProxyRobot and ForceSensor services too; StereoCamera is served here as well so that one address
reaches everything.
"""

from services.runtime.placeholder import PlaceholderService
from services.runtime.process import run_service
from services.runtime.server import binding
from services.runtime.unimplemented import unimplemented_servicer
from telerobot.v1 import (
    decision_server_pb2_grpc,
    force_sensor_pb2_grpc,
    proxy_robot_pb2_grpc,
    stereo_camera_pb2_grpc,
)

_NOTE = "forwarding with supervisory checks comes with the DecisionServer issue"


def build(_args):
    served = [
        binding(module, name, unimplemented_servicer(getattr(module, f"{name}Servicer"), _NOTE))
        for module, name in [
            (decision_server_pb2_grpc, "DecisionServer"),
            (proxy_robot_pb2_grpc, "ProxyRobot"),
            (force_sensor_pb2_grpc, "ForceSensor"),
            (stereo_camera_pb2_grpc, "StereoCamera"),
        ]
    ]
    return PlaceholderService(served)


if __name__ == "__main__":
    raise SystemExit(run_service(
        "decision_server", "DecisionServer: supervisory control and arbitration.", build))
