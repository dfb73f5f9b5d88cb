"""wire.foxglove: our messages as Foxglove's schemas, checked against real
Pinocchio forward kinematics and the real MuJoCo cameras' calibration."""

from __future__ import annotations

import cv2
import mujoco
import numpy as np
import pinocchio as pin
import pytest
from foxglove_schemas_protobuf.FrameTransforms_pb2 import FrameTransforms

from domain.robot_model import puma560 as p
from domain.robot_model.kinematics import ArmKinematics
from domain.robot_model.loader import load_mujoco_model
from services.stereo_camera.calibration import mujoco_stereo
from telerobot.v1 import stereo_camera_pb2 as sc_pb
from telerobot.v1 import types_pb2
from wire import convert
from wire import foxglove as fx

T0 = 1_700_000_000_123_456_789


def se3(transform) -> pin.SE3:
    q = transform.rotation
    rotation = pin.Quaternion(q.w, q.x, q.y, q.z).toRotationMatrix()
    t = transform.translation
    return pin.SE3(rotation, np.array([t.x, t.y, t.z]))


def world_poses(message: FrameTransforms) -> dict[str, pin.SE3]:
    """Every child frame's pose in `base`, by composing the tree's parent chain."""
    by_child = {t.child_frame_id: t for t in message.transforms}
    assert len(by_child) == len(message.transforms), "a frame with two parents"

    def pose(frame: str) -> pin.SE3:
        if frame == fx.BASE_FRAME:
            return pin.SE3.Identity()
        transform = by_child[frame]
        return pose(transform.parent_frame_id) * se3(transform)

    return {frame: pose(frame) for frame in by_child}


def configurations(kinematics: ArmKinematics, count: int = 6) -> list[np.ndarray]:
    rng = np.random.default_rng(17)
    lower, upper = kinematics.lower_limits, kinematics.upper_limits
    return [kinematics.home_q, np.zeros(6)] + [rng.uniform(lower, upper) for _ in range(count)]


def stereo_header(width: int = 64, height: int = 48) -> sc_pb.StereoHeader:
    """The simulation's own calibration of both eyes (MuJoCo's cameras in scene.xml)."""
    model = load_mujoco_model()
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    left = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_CAMERA, "left_eye")
    right = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_CAMERA, "right_eye")
    calibration = mujoco_stereo(model, data, left, right, width, height)
    left_proto, right_proto = calibration.eye_protos()
    return sc_pb.StereoHeader(width_px=width, height_px=height,
                              encoding=sc_pb.IMAGE_ENCODING_JPEG, left=left_proto,
                              right=right_proto, baseline_m=calibration.baseline_m)


def test_the_frames_compose_to_pinocchio_forward_kinematics():
    kinematics = ArmKinematics()
    arm = fx.ArmTransforms(ArmKinematics())
    for q in configurations(kinematics):
        message = arm.transforms(q, T0)
        assert {t.timestamp.ToNanoseconds() for t in message.transforms} == {T0}
        poses = world_poses(message)
        assert set(poses) == {*arm.link_frames, fx.FLANGE_FRAME, fx.TOOL_FRAME}
        expected = {name: kinematics.frame_pose(q, name) for name in arm.link_frames}
        expected[fx.FLANGE_FRAME] = kinematics.flange_pose(q)
        expected[fx.TOOL_FRAME] = kinematics.tool_pose(q)
        for frame, pose in poses.items():
            assert np.allclose(pose.homogeneous, expected[frame].homogeneous, atol=1e-9), frame
    # A parent chain: each link hangs from the one before it.
    parents = {t.child_frame_id: t.parent_frame_id for t in message.transforms}
    assert parents["link1"] == fx.BASE_FRAME and parents["link6"] == "link5"
    assert parents[fx.TOOL_FRAME] == fx.FLANGE_FRAME
    # The tool offset is the one the arm reports: the tool point is 0.1 m out along the flange's z.
    assert np.allclose(kinematics.flange_T_tool.translation, [0, 0, 0.1])


def test_a_robot_states_frames_use_its_own_tool_frame_and_sample_time():
    kinematics = ArmKinematics()
    arm = fx.ArmTransforms()
    q = configurations(kinematics)[3]
    flange = kinematics.flange_pose(q)
    flange_T_tool = pin.SE3(pin.rpy.rpyToMatrix(0.1, -0.2, 0.3), np.array([0.01, 0.02, 0.15]))
    state = types_pb2.RobotState(sequence=4, sample_time=convert.timestamp(T0),
                                 joint_positions_rad=q.tolist(),
                                 joint_velocities_rad_per_s=[0.1] * 6,
                                 flange_pose=convert.pose_to_proto(flange),
                                 tool_pose=convert.pose_to_proto(flange * flange_T_tool))
    poses = world_poses(arm.state_transforms(state))
    assert np.allclose(poses[fx.TOOL_FRAME].homogeneous, (flange * flange_T_tool).homogeneous,
                       atol=1e-9)
    assert arm.state_transforms(state).transforms[0].timestamp.ToNanoseconds() == T0
    with pytest.raises(ValueError, match="6 joint positions"):
        arm.transforms([0.0] * 5, T0)


def test_joint_states_name_the_models_joints():
    arm = fx.ArmTransforms()
    state = types_pb2.RobotState(sample_time=convert.timestamp(T0),
                                 joint_positions_rad=[0.1, 0.2, 0.3, 0.4, 0.5, 0.6],
                                 joint_velocities_rad_per_s=[1, 2, 3, 4, 5, 6])
    message = fx.joint_states(state)
    assert tuple(j.name for j in message.joints) == arm.joint_names == (
        "joint1", "joint2", "joint3", "joint4", "joint5", "joint6")
    assert [j.position for j in message.joints] == pytest.approx([0.1, 0.2, 0.3, 0.4, 0.5, 0.6])
    assert [j.velocity for j in message.joints] == [1, 2, 3, 4, 5, 6]
    assert message.timestamp.ToNanoseconds() == T0
    no_rates = fx.joint_states(types_pb2.RobotState(joint_positions_rad=[0.0] * 6))
    assert not any(j.HasField("velocity") for j in no_rates.joints)
    with pytest.raises(ValueError, match="6 joint positions"):
        fx.joint_states(types_pb2.RobotState(joint_positions_rad=[0.0] * 3))


@pytest.mark.parametrize("force", [(0, 0, -12.5), (3, 0, 0), (-5, 0, 0), (0, -40, 0),
                                   (1.5, -2, 7)])
def test_the_force_arrow_points_along_the_force_and_scales_with_it(force):
    wrench = types_pb2.Wrench(force_n=types_pb2.Vector3(x=force[0], y=force[1], z=force[2]),
                              torque_nm=types_pb2.Vector3(x=9.0))
    update = fx.force_arrow(wrench, T0)
    (entity,) = update.entities
    assert entity.frame_id == fx.TOOL_FRAME and entity.id == fx.FORCE_ARROW_ENTITY
    assert entity.timestamp.ToNanoseconds() == T0
    (arrow,) = entity.arrows
    o = arrow.pose.orientation
    direction = pin.Quaternion(o.w, o.x, o.y, o.z).toRotationMatrix()[:, 0]  # the arrow's +x
    magnitude = np.linalg.norm(force)
    assert np.allclose(direction, np.array(force) / magnitude, atol=1e-9)
    assert arrow.shaft_length + arrow.head_length == pytest.approx(
        fx.FORCE_ARROW_M_PER_N * magnitude)
    assert 0 < arrow.head_length < arrow.shaft_length + arrow.head_length


def test_a_zero_force_clears_the_arrow_and_a_nan_is_refused():
    (entity,) = fx.force_arrow(types_pb2.Wrench(), T0, frame_id="flange").entities
    assert entity.frame_id == "flange" and not entity.arrows
    with pytest.raises(ValueError, match="not finite"):
        fx.force_arrow(types_pb2.Wrench(force_n=types_pb2.Vector3(x=float("nan"))), T0)


def test_images_pass_through_as_they_came():
    left = cv2.imencode(".jpg", np.full((48, 64, 3), 40, np.uint8))[1].tobytes()
    right = cv2.imencode(".png", np.full((48, 64, 3), 90, np.uint8))[1].tobytes()
    pair = sc_pb.StereoPair(sequence=3, left_capture_time=convert.timestamp(T0),
                            right_capture_time=convert.timestamp(T0 + 1000),
                            left_image=left, right_image=right)
    left_image, right_image = fx.camera_images(pair)
    assert left_image.data == left and right_image.data == right
    assert (left_image.format, right_image.format) == ("jpeg", "png")
    assert (left_image.frame_id, right_image.frame_id) == (fx.LEFT_CAMERA_FRAME,
                                                           fx.RIGHT_CAMERA_FRAME)
    assert left_image.timestamp.ToNanoseconds() == T0
    assert right_image.timestamp.ToNanoseconds() == T0 + 1000
    raw = sc_pb.StereoPair(left_image=bytes(64 * 48 * 3), right_image=bytes(64 * 48 * 3))
    with pytest.raises(ValueError, match="JPEG"):
        fx.camera_images(raw)


def test_calibrations_and_camera_frames_reproduce_our_projection():
    header = stereo_header()
    calibrations = fx.camera_calibrations(header, T0)
    arm = fx.ArmTransforms()
    arm.set_cameras(header)
    poses = world_poses(arm.transforms(np.zeros(6), T0))
    kinematics = ArmKinematics()
    points = [kinematics.tool_pose(q).translation for q in configurations(kinematics)]
    for calibration, eye, frame in zip(calibrations, (header.left, header.right),
                                       (fx.LEFT_CAMERA_FRAME, fx.RIGHT_CAMERA_FRAME),
                                       strict=True):
        assert calibration.frame_id == frame
        assert (calibration.width, calibration.height) == (64, 48)
        assert calibration.timestamp.ToNanoseconds() == T0
        k = np.array(calibration.K).reshape(3, 3)
        assert k == pytest.approx(np.array([[eye.fx_px, 0, eye.cx_px], [0, eye.fy_px, eye.cy_px],
                                            [0, 0, 1]]))
        projection = np.array(calibration.P).reshape(3, 4)
        assert np.allclose(projection[:, :3], k) and not projection[:, 3].any()
        assert calibration.distortion_model == "plumb_bob" and list(calibration.D) == [0.0] * 5
        # Foxglove's P applied in the eye's /tf frame is our base-frame projection.
        camera_T_base = poses[frame].inverse().homogeneous[:3, :]
        ours = np.array(eye.projection).reshape(3, 4)
        assert np.allclose(projection[:, :3] @ camera_T_base, ours, atol=1e-9)
        for point in points:  # and it puts the tool where ours does, in pixels
            u, v, w = projection[:, :3] @ (poses[frame].inverse() * point)
            x, y, z = ours @ np.append(point, 1.0)
            assert (u / w, v / w) == pytest.approx((x / z, y / z))
    # The eyes are the scene's cameras, the baseline apart.
    apart = poses[fx.RIGHT_CAMERA_FRAME].translation - poses[fx.LEFT_CAMERA_FRAME].translation
    assert np.linalg.norm(apart) == pytest.approx(header.baseline_m)
    model = load_mujoco_model()
    camera = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_CAMERA, "left_eye")
    assert np.allclose(poses[fx.LEFT_CAMERA_FRAME].translation, model.cam_pos[camera])


def test_an_eye_without_a_pose_has_no_frame_and_an_uncalibrated_eye_says_so():
    header = sc_pb.StereoHeader(width_px=32, height_px=24,
                                left=sc_pb.CameraCalibration(fx_px=40, fy_px=40, cx_px=15.5,
                                                             cy_px=11.5,
                                                             distortion=[0.1, 0.01, 0, 0]))
    assert fx.camera_transforms(header, T0) == []
    left, right = fx.camera_calibrations(header, T0)
    assert list(left.D) == [0.1, 0.01, 0, 0, 0] and left.distortion_model == "plumb_bob"
    assert right.K[0] == 0.0  # Foxglove: uncalibrated
    header.left.distortion.extend([0.0] * 6)
    with pytest.raises(ValueError, match="at most 8"):
        fx.camera_calibrations(header, T0)


def test_every_topic_has_its_foxglove_schema():
    assert fx.FOXGLOVE_TOPICS[fx.TF].DESCRIPTOR.full_name == "foxglove.FrameTransforms"
    assert fx.FOXGLOVE_TOPICS[fx.FORCE_ARROW].DESCRIPTOR.full_name == "foxglove.SceneUpdate"
    assert {fx.FOXGLOVE_TOPICS[t].DESCRIPTOR.full_name for t in (fx.LEFT_IMAGE, fx.RIGHT_IMAGE)
            } == {"foxglove.CompressedImage"}
    assert fx.FOXGLOVE_TOPICS[fx.STEREO_VIDEO].DESCRIPTOR.full_name == "foxglove.CompressedVideo"
    assert len(fx.FOXGLOVE_TOPICS) == 8
    assert p.FLANGE_SITE == fx.FLANGE_FRAME


def test_an_h264_pair_is_one_compressed_video_frame_and_key_frames_are_told_apart():
    from services.stereo_camera.h264 import H264Encoder
    from services.stereo_camera.pattern import pattern_image
    from services.stereo_camera.source import LEFT, RIGHT

    encoder = H264Encoder(64, 48, fps=10, kbit_per_s=300)
    units = [encoder.encode(pattern_image(i, LEFT, 64, 48), pattern_image(i, RIGHT, 64, 48),
                            keyframe=i == 2) for i in range(3)]
    assert [key for _, key in units] == [True, False, True]
    assert [fx.h264_is_keyframe(data) for data, _ in units] == [True, False, True]
    pair = sc_pb.StereoPair(video_frame=units[1][0], left_capture_time=convert.timestamp(T0),
                            right_capture_time=convert.timestamp(T0 + 5))
    video = fx.stereo_video(pair)
    assert (video.format, video.frame_id) == ("h264", fx.STEREO_CAMERA_FRAME)
    assert video.data == units[1][0] and video.timestamp.ToNanoseconds() == T0
    assert not fx.h264_is_keyframe(b"") and not fx.h264_is_keyframe(b"\x00\x00\x01")
    with pytest.raises(ValueError, match="IMAGE_ENCODING_H264"):
        fx.stereo_video(sc_pb.StereoPair(left_image=b"\xff\xd8\xff"))
