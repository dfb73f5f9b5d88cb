"""An H.264 stereo stream as Foxglove's CompressedVideo, and its key frames. Only protobuf: no
kinematics, so that a process that writes video (the recordings' writer) starts light;
wire.foxglove re-exports all of it."""

from __future__ import annotations

from foxglove_schemas_protobuf.CompressedVideo_pb2 import CompressedVideo

from telerobot.v1 import stereo_camera_pb2 as sc_pb

# The side-by-side video's frame id (both eyes in one picture): see wire.foxglove's frames.
STEREO_CAMERA_FRAME = "camera_stereo"


def stereo_video(pair: sc_pb.StereoPair) -> CompressedVideo:
    """An H.264 pair's side-by-side access unit as it came (Annex B, not re-encoded), format
    "h264", stamped with the left eye's capture time, in ``camera_stereo``."""
    if not pair.video_frame:
        raise ValueError("a CompressedVideo needs an H.264 frame; this pair has none (an image "
                         "stream's pair?): ask the camera for IMAGE_ENCODING_H264")
    return CompressedVideo(timestamp=pair.left_capture_time, frame_id=STEREO_CAMERA_FRAME,
                           data=pair.video_frame, format="h264")


_IDR_SLICE = 5  # H.264 NAL unit type of an IDR picture's slice


def h264_is_keyframe(access_unit: bytes) -> bool:
    """Whether an Annex B access unit holds an IDR picture (a decoder may start at it)."""
    start = access_unit.find(b"\x00\x00\x01")
    while 0 <= start < len(access_unit) - 3:
        if access_unit[start + 3] & 0x1F == _IDR_SLICE:
            return True
        start = access_unit.find(b"\x00\x00\x01", start + 3)
    return False
