import datetime

from google.protobuf import duration_pb2 as _duration_pb2
from google.protobuf import timestamp_pb2 as _timestamp_pb2
from telerobot.v1 import options_pb2 as _options_pb2
from telerobot.v1 import types_pb2 as _types_pb2
from google.protobuf.internal import containers as _containers
from google.protobuf.internal import enum_type_wrapper as _enum_type_wrapper
from google.protobuf import descriptor as _descriptor
from google.protobuf import message as _message
from collections.abc import Iterable as _Iterable, Mapping as _Mapping
from typing import ClassVar as _ClassVar, Optional as _Optional, Union as _Union

DESCRIPTOR: _descriptor.FileDescriptor

class ImageEncoding(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    IMAGE_ENCODING_UNSPECIFIED: _ClassVar[ImageEncoding]
    IMAGE_ENCODING_RAW_RGB8: _ClassVar[ImageEncoding]
    IMAGE_ENCODING_JPEG: _ClassVar[ImageEncoding]
    IMAGE_ENCODING_PNG: _ClassVar[ImageEncoding]
    IMAGE_ENCODING_H264: _ClassVar[ImageEncoding]

class TransferMode(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    TRANSFER_MODE_UNSPECIFIED: _ClassVar[TransferMode]
    TRANSFER_MODE_SINGLE_BUFFER_SERIALIZED: _ClassVar[TransferMode]
    TRANSFER_MODE_DOUBLE_BUFFER_CONCURRENT: _ClassVar[TransferMode]
IMAGE_ENCODING_UNSPECIFIED: ImageEncoding
IMAGE_ENCODING_RAW_RGB8: ImageEncoding
IMAGE_ENCODING_JPEG: ImageEncoding
IMAGE_ENCODING_PNG: ImageEncoding
IMAGE_ENCODING_H264: ImageEncoding
TRANSFER_MODE_UNSPECIFIED: TransferMode
TRANSFER_MODE_SINGLE_BUFFER_SERIALIZED: TransferMode
TRANSFER_MODE_DOUBLE_BUFFER_CONCURRENT: TransferMode

class GetStreamInfoRequest(_message.Message):
    __slots__ = ()
    def __init__(self) -> None: ...

class GetStreamInfoResponse(_message.Message):
    __slots__ = ("header",)
    HEADER_FIELD_NUMBER: _ClassVar[int]
    header: StereoHeader
    def __init__(self, header: _Optional[_Union[StereoHeader, _Mapping]] = ...) -> None: ...

class StreamPairsRequest(_message.Message):
    __slots__ = ("encoding", "jpeg_quality", "max_fps", "transfer_mode", "width_px", "height_px", "receipts", "max_kbit_per_s")
    ENCODING_FIELD_NUMBER: _ClassVar[int]
    JPEG_QUALITY_FIELD_NUMBER: _ClassVar[int]
    MAX_FPS_FIELD_NUMBER: _ClassVar[int]
    TRANSFER_MODE_FIELD_NUMBER: _ClassVar[int]
    WIDTH_PX_FIELD_NUMBER: _ClassVar[int]
    HEIGHT_PX_FIELD_NUMBER: _ClassVar[int]
    RECEIPTS_FIELD_NUMBER: _ClassVar[int]
    MAX_KBIT_PER_S_FIELD_NUMBER: _ClassVar[int]
    encoding: ImageEncoding
    jpeg_quality: int
    max_fps: float
    transfer_mode: TransferMode
    width_px: int
    height_px: int
    receipts: bool
    max_kbit_per_s: int
    def __init__(self, encoding: _Optional[_Union[ImageEncoding, str]] = ..., jpeg_quality: _Optional[int] = ..., max_fps: _Optional[float] = ..., transfer_mode: _Optional[_Union[TransferMode, str]] = ..., width_px: _Optional[int] = ..., height_px: _Optional[int] = ..., receipts: _Optional[bool] = ..., max_kbit_per_s: _Optional[int] = ...) -> None: ...

class ReportReceiptRequest(_message.Message):
    __slots__ = ("stream_id", "sequence", "received_bytes", "want_keyframe")
    STREAM_ID_FIELD_NUMBER: _ClassVar[int]
    SEQUENCE_FIELD_NUMBER: _ClassVar[int]
    RECEIVED_BYTES_FIELD_NUMBER: _ClassVar[int]
    WANT_KEYFRAME_FIELD_NUMBER: _ClassVar[int]
    stream_id: str
    sequence: int
    received_bytes: int
    want_keyframe: bool
    def __init__(self, stream_id: _Optional[str] = ..., sequence: _Optional[int] = ..., received_bytes: _Optional[int] = ..., want_keyframe: _Optional[bool] = ...) -> None: ...

class ReportReceiptResponse(_message.Message):
    __slots__ = ("target_kbit_per_s", "window_bytes")
    TARGET_KBIT_PER_S_FIELD_NUMBER: _ClassVar[int]
    WINDOW_BYTES_FIELD_NUMBER: _ClassVar[int]
    target_kbit_per_s: int
    window_bytes: int
    def __init__(self, target_kbit_per_s: _Optional[int] = ..., window_bytes: _Optional[int] = ...) -> None: ...

class StreamPairsResponse(_message.Message):
    __slots__ = ("header", "pair")
    HEADER_FIELD_NUMBER: _ClassVar[int]
    PAIR_FIELD_NUMBER: _ClassVar[int]
    header: StereoHeader
    pair: StereoPair
    def __init__(self, header: _Optional[_Union[StereoHeader, _Mapping]] = ..., pair: _Optional[_Union[StereoPair, _Mapping]] = ...) -> None: ...

class GetSnapshotRequest(_message.Message):
    __slots__ = ("encoding", "jpeg_quality")
    ENCODING_FIELD_NUMBER: _ClassVar[int]
    JPEG_QUALITY_FIELD_NUMBER: _ClassVar[int]
    encoding: ImageEncoding
    jpeg_quality: int
    def __init__(self, encoding: _Optional[_Union[ImageEncoding, str]] = ..., jpeg_quality: _Optional[int] = ...) -> None: ...

class GetSnapshotResponse(_message.Message):
    __slots__ = ("header", "pair")
    HEADER_FIELD_NUMBER: _ClassVar[int]
    PAIR_FIELD_NUMBER: _ClassVar[int]
    header: StereoHeader
    pair: StereoPair
    def __init__(self, header: _Optional[_Union[StereoHeader, _Mapping]] = ..., pair: _Optional[_Union[StereoPair, _Mapping]] = ...) -> None: ...

class StereoHeader(_message.Message):
    __slots__ = ("width_px", "height_px", "encoding", "transfer_mode", "left", "right", "baseline_m", "source", "stream_id")
    WIDTH_PX_FIELD_NUMBER: _ClassVar[int]
    HEIGHT_PX_FIELD_NUMBER: _ClassVar[int]
    ENCODING_FIELD_NUMBER: _ClassVar[int]
    TRANSFER_MODE_FIELD_NUMBER: _ClassVar[int]
    LEFT_FIELD_NUMBER: _ClassVar[int]
    RIGHT_FIELD_NUMBER: _ClassVar[int]
    BASELINE_M_FIELD_NUMBER: _ClassVar[int]
    SOURCE_FIELD_NUMBER: _ClassVar[int]
    STREAM_ID_FIELD_NUMBER: _ClassVar[int]
    width_px: int
    height_px: int
    encoding: ImageEncoding
    transfer_mode: TransferMode
    left: CameraCalibration
    right: CameraCalibration
    baseline_m: float
    source: str
    stream_id: str
    def __init__(self, width_px: _Optional[int] = ..., height_px: _Optional[int] = ..., encoding: _Optional[_Union[ImageEncoding, str]] = ..., transfer_mode: _Optional[_Union[TransferMode, str]] = ..., left: _Optional[_Union[CameraCalibration, _Mapping]] = ..., right: _Optional[_Union[CameraCalibration, _Mapping]] = ..., baseline_m: _Optional[float] = ..., source: _Optional[str] = ..., stream_id: _Optional[str] = ...) -> None: ...

class CameraCalibration(_message.Message):
    __slots__ = ("fx_px", "fy_px", "cx_px", "cy_px", "projection", "camera_pose", "distortion")
    FX_PX_FIELD_NUMBER: _ClassVar[int]
    FY_PX_FIELD_NUMBER: _ClassVar[int]
    CX_PX_FIELD_NUMBER: _ClassVar[int]
    CY_PX_FIELD_NUMBER: _ClassVar[int]
    PROJECTION_FIELD_NUMBER: _ClassVar[int]
    CAMERA_POSE_FIELD_NUMBER: _ClassVar[int]
    DISTORTION_FIELD_NUMBER: _ClassVar[int]
    fx_px: float
    fy_px: float
    cx_px: float
    cy_px: float
    projection: _containers.RepeatedScalarFieldContainer[float]
    camera_pose: _types_pb2.Pose
    distortion: _containers.RepeatedScalarFieldContainer[float]
    def __init__(self, fx_px: _Optional[float] = ..., fy_px: _Optional[float] = ..., cx_px: _Optional[float] = ..., cy_px: _Optional[float] = ..., projection: _Optional[_Iterable[float]] = ..., camera_pose: _Optional[_Union[_types_pb2.Pose, _Mapping]] = ..., distortion: _Optional[_Iterable[float]] = ...) -> None: ...

class StereoPair(_message.Message):
    __slots__ = ("sequence", "left_capture_time", "right_capture_time", "left_image", "right_image", "eye_skew", "video_frame", "keyframe", "target_kbit_per_s", "render_scale")
    SEQUENCE_FIELD_NUMBER: _ClassVar[int]
    LEFT_CAPTURE_TIME_FIELD_NUMBER: _ClassVar[int]
    RIGHT_CAPTURE_TIME_FIELD_NUMBER: _ClassVar[int]
    LEFT_IMAGE_FIELD_NUMBER: _ClassVar[int]
    RIGHT_IMAGE_FIELD_NUMBER: _ClassVar[int]
    EYE_SKEW_FIELD_NUMBER: _ClassVar[int]
    VIDEO_FRAME_FIELD_NUMBER: _ClassVar[int]
    KEYFRAME_FIELD_NUMBER: _ClassVar[int]
    TARGET_KBIT_PER_S_FIELD_NUMBER: _ClassVar[int]
    RENDER_SCALE_FIELD_NUMBER: _ClassVar[int]
    sequence: int
    left_capture_time: _timestamp_pb2.Timestamp
    right_capture_time: _timestamp_pb2.Timestamp
    left_image: bytes
    right_image: bytes
    eye_skew: _duration_pb2.Duration
    video_frame: bytes
    keyframe: bool
    target_kbit_per_s: int
    render_scale: float
    def __init__(self, sequence: _Optional[int] = ..., left_capture_time: _Optional[_Union[datetime.datetime, _timestamp_pb2.Timestamp, _Mapping]] = ..., right_capture_time: _Optional[_Union[datetime.datetime, _timestamp_pb2.Timestamp, _Mapping]] = ..., left_image: _Optional[bytes] = ..., right_image: _Optional[bytes] = ..., eye_skew: _Optional[_Union[datetime.timedelta, _duration_pb2.Duration, _Mapping]] = ..., video_frame: _Optional[bytes] = ..., keyframe: _Optional[bool] = ..., target_kbit_per_s: _Optional[int] = ..., render_scale: _Optional[float] = ...) -> None: ...
