"""python -m services.proxy_robot: the ProxyRobot service process."""

from services.runtime.placeholder import PlaceholderService
from services.runtime.process import run_service
from services.runtime.server import binding
from services.runtime.unimplemented import unimplemented_servicer
from telerobot.v1 import proxy_robot_pb2_grpc


def build(_args):
    servicer = unimplemented_servicer(
        proxy_robot_pb2_grpc.ProxyRobotServicer,
        "the simulated PUMA 560 and its proxy come with the slave-station issue",
    )
    return PlaceholderService([binding(proxy_robot_pb2_grpc, "ProxyRobot", servicer)])


if __name__ == "__main__":
    raise SystemExit(
        run_service("proxy_robot", "ProxyRobot: the software proxy of the arm.", build))
