"""python -m services.force_sensor: the ForceSensor service process."""

from services.runtime.placeholder import PlaceholderService
from services.runtime.process import run_service
from services.runtime.server import binding
from services.runtime.unimplemented import unimplemented_servicer
from telerobot.v1 import force_sensor_pb2_grpc


def build(_args):
    servicer = unimplemented_servicer(
        force_sensor_pb2_grpc.ForceSensorServicer,
        "wrench sampling and streaming come with the ForceSensor issue",
    )
    return PlaceholderService([binding(force_sensor_pb2_grpc, "ForceSensor", servicer)])


if __name__ == "__main__":
    raise SystemExit(run_service("force_sensor", "ForceSensor: the wrist F/T sensor.", build))
