"""python -m services.stereo_camera: the StereoCamera service process."""

from services.runtime.placeholder import PlaceholderService
from services.runtime.process import run_service
from services.runtime.server import binding
from services.runtime.unimplemented import unimplemented_servicer
from telerobot.v1 import stereo_camera_pb2_grpc


def build(_args):
    servicer = unimplemented_servicer(
        stereo_camera_pb2_grpc.StereoCameraServicer,
        "stereo capture and streaming come with the StereoCamera issue",
    )
    return PlaceholderService([binding(stereo_camera_pb2_grpc, "StereoCamera", servicer)])


if __name__ == "__main__":
    raise SystemExit(
        run_service("stereo_camera", "StereoCamera: synchronized stereo pairs.", build))
