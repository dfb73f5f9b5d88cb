"""Protobuf adapters: the StereoCamera and ProxyRobot contracts' messages to the AR domain.

Messages only, no channel (nothing here imports grpc): the caller owns the stubs and streams,
and passes what they return.

- `projections_from_header(header)`: the stream header's per-eye 3x4 projection as perspective
  CameraProjections (the camera's own calibration; an alternative to identifying it, and the
  ground truth the tests identify against).
- `RobotModelFeed`: keeps a RobotModel in step with the ProxyRobot: builds each
  MoveCartesianIncrementalRequest while predicting it, acknowledges the reply's target, and
  corrects on moved events and on state samples taken at rest.
"""

from __future__ import annotations

from collections.abc import Iterable

import numpy as np

from clients.ar.identification import CameraProjection, ProjectionKind
from clients.ar.model import Frame, RobotModel, make_pose
from telerobot.v1 import proxy_robot_pb2, stereo_camera_pb2, types_pb2
from wire import convert

_FRAMES = {
    Frame.BASE: types_pb2.REFERENCE_FRAME_BASE,
    Frame.TOOL: types_pb2.REFERENCE_FRAME_TOOL,
    Frame.WRIST: types_pb2.REFERENCE_FRAME_WRIST,
}
_AT_REST = (types_pb2.ROBOT_STATUS_READY,)


def pose_matrix(pose: types_pb2.Pose) -> np.ndarray:
    """A Pose message as a 4x4 matrix (an empty rotation is the identity)."""
    return make_pose(convert.rotation_value(pose.rotation),
                     convert.vector3_value(pose.position_m))


def pose_message(pose) -> types_pb2.Pose:
    pose = np.asarray(pose, float)
    x, y, z = pose[:3, 3].tolist()
    return types_pb2.Pose(position_m=types_pb2.Vector3(x=x, y=y, z=z),
                          rotation=types_pb2.Matrix3(row_major=pose[:3, :3].reshape(9).tolist()))


def projection_from_calibration(eye: stereo_camera_pb2.CameraCalibration) -> CameraProjection:
    """One eye's header projection; ValueError when the camera's pose is unknown."""
    if len(eye.projection) != 12:
        raise ValueError("the stream header has no projection for this eye (an uncalibrated "
                         "camera): identify it from reference points instead")
    matrix = np.array(eye.projection, float).reshape(3, 4)
    matrix = matrix / np.linalg.norm(matrix[2, :3])  # w = depth in metres, as identified ones
    return CameraProjection(ProjectionKind.PERSPECTIVE, matrix)


def projections_from_header(
        header: stereo_camera_pb2.StereoHeader) -> tuple[CameraProjection, CameraProjection]:
    """(left, right) projections carried by a StereoCamera stream header."""
    return projection_from_calibration(header.left), projection_from_calibration(header.right)


class RobotModelFeed:
    """Feeds a RobotModel from ProxyRobot messages.

        feed = RobotModelFeed(model)
        request, command_id = feed.request(delta_m, frame=Frame.BASE)
        try:
            feed.on_reply(command_id, stub.MoveCartesianIncremental(request, metadata=...))
        except grpc.RpcError:
            feed.on_refused(command_id)
        for event in stub.StreamRobotEvents(...):   # on another thread
            feed.on_event(event)
    """

    def __init__(self, model: RobotModel):
        self.model = model

    def request(self, delta_position_m, delta_rotation=None, frame: Frame | str = Frame.BASE
                ) -> tuple[proxy_robot_pb2.MoveCartesianIncrementalRequest, int]:
        """The request for this increment, predicted by the model; and its command id."""
        frame = Frame(frame)
        command_id = self.model.command(delta_position_m, delta_rotation, frame)
        x, y, z = (float(v) for v in np.asarray(delta_position_m, float).reshape(3))
        request = proxy_robot_pb2.MoveCartesianIncrementalRequest(
            delta_position_m=types_pb2.Vector3(x=x, y=y, z=z), frame=_FRAMES[frame])
        if delta_rotation is not None:
            request.delta_rotation.row_major.extend(
                np.asarray(delta_rotation, float).reshape(9).tolist())
        return request, command_id

    def on_reply(self, command_id: int,
                 reply: proxy_robot_pb2.MoveCartesianIncrementalResponse) -> None:
        """The accepted target of command `command_id`."""
        self.model.acknowledge(command_id, pose_matrix(reply.target_tool_pose))

    def on_refused(self, command_id: int) -> None:
        """The move failed (any gRPC error): the arm will not go there."""
        self.model.reject(command_id)

    def on_event(self, event: proxy_robot_pb2.StreamRobotEventsResponse) -> bool:
        """A StreamRobotEvents message: moved events correct the model, as do data-received
        samples at rest. True when the model was corrected."""
        kind = event.WhichOneof("event")
        if kind == "moved":
            return self.on_moved(event.moved)
        if kind == "data_received":
            return self.on_state(event.data_received.state)
        return False

    def on_moved(self, moved: proxy_robot_pb2.MovedEvent) -> bool:
        if moved.HasField("tool_pose"):
            self.model.correct(pose_matrix(moved.tool_pose))
        else:
            self.model.correct_joints(moved.joint_positions_rad)
        return True

    def on_state(self, state: types_pb2.RobotState) -> bool:
        """A state sample corrects the model only when the arm is at rest (READY): a sample of
        a moving arm is behind the command, and the model is ahead of it."""
        if state.status not in _AT_REST or not state.HasField("tool_pose"):
            return False
        self.model.correct(pose_matrix(state.tool_pose))
        return True

    def follow(self, events: Iterable[proxy_robot_pb2.StreamRobotEventsResponse]) -> int:
        """Consume an event stream until it ends; returns how many corrections it made."""
        return sum(self.on_event(event) for event in events)
