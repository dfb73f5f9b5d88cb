"""docs/foxglove_layout.json: it parses, its panels are the ones the README promises, and every
topic and message path it names is one a make teleop --mcap recording holds, down to the field
(resolved against the channel's protobuf schema)."""

from __future__ import annotations

import json
import re

import pytest

from clients.teleop import mcap_log
from telerobot.v1 import decision_server_pb2, stereo_camera_pb2, types_pb2
from tests.processes import REPO
from wire import foxglove as fox

LAYOUT = REPO / "docs" / "foxglove_layout.json"
# Every topic a recording holds, with its message class.
RECORDED = {
    **fox.FOXGLOVE_TOPICS,
    mcap_log.COMMAND: decision_server_pb2.MasterCommand,
    mcap_log.HEARTBEAT: decision_server_pb2.Heartbeat,
    mcap_log.ACK: decision_server_pb2.CommandAck,
    mcap_log.TOOL_POSE: types_pb2.Pose,
    mcap_log.WRENCH: types_pb2.Wrench,
    mcap_log.STEREO_HEADER: stereo_camera_pb2.StereoHeader,
    mcap_log.STEREO_PAIR: stereo_camera_pb2.StereoPair,
    mcap_log.EVENTS: decision_server_pb2.StreamEventsResponse,
    mcap_log.ROBOT_STATE: types_pb2.RobotState,
}
_STEP = re.compile(r"\.(\w+)|\[(\d+)\]")


def resolve(path: str):
    """The protobuf field a message path ("/topic.field[0].field") names; KeyError if none."""
    topic = re.match(r"/[\w/]+", path).group(0)
    descriptor, field = RECORDED[topic].DESCRIPTOR, None
    rest = path[len(topic):]
    while rest:
        step = _STEP.match(rest)
        if step is None:
            raise KeyError(f"{path}: cannot read {rest!r}")
        rest = rest[step.end():]
        if step.group(1):
            field = descriptor.fields_by_name[step.group(1)]
            descriptor = field.message_type
        elif field is None or not field.is_repeated:
            raise KeyError(f"{path}: an index on a field that is not repeated")
    return field


def strings(value):
    if isinstance(value, dict):
        for item in value.values():
            yield from strings(item)
    elif isinstance(value, list):
        for item in value:
            yield from strings(item)
    elif isinstance(value, str):
        yield value


def panels(tree) -> list[str]:
    if isinstance(tree, str):
        return [tree]
    return panels(tree["first"]) + panels(tree["second"])


def test_the_layout_parses_and_every_panel_is_configured():
    layout = json.loads(LAYOUT.read_text())
    assert sorted(panels(layout["layout"])) == sorted(layout["configById"])
    kinds = sorted(panel.split("!")[0] for panel in layout["configById"])
    assert kinds == ["3D", "Image", "Plot", "Plot", "RawMessages"]


def test_every_topic_it_names_is_recorded_down_to_the_field():
    layout = json.loads(LAYOUT.read_text())
    named = [s for s in strings(layout) if s.startswith("/")]
    named += [key for config in layout["configById"].values()
              for key in config.get("topics", {})]
    assert named
    for path in named:
        topic = re.match(r"/[\w/]+", path).group(0)
        assert topic in RECORDED, path
        resolve(path)
    plotted = [p["value"] for config in layout["configById"].values()
               for p in config.get("paths", [])]
    assert {"/robot/wrench.force_n.z", "/joint_states.joints[5].position"} <= set(plotted)
    for path in plotted:  # a plot needs numbers
        assert resolve(path).cpp_type == resolve(path).CPPTYPE_DOUBLE, path


def test_the_panels_watch_the_right_topics():
    config = json.loads(LAYOUT.read_text())["configById"]
    assert config["3D!arm"]["followTf"] == fox.BASE_FRAME
    assert config["3D!arm"]["topics"][fox.TF]["visible"]
    assert config["3D!arm"]["topics"][fox.FORCE_ARROW]["visible"]
    # One panel for the cameras: the side-by-side H.264 video (an H.264 session's recording has
    # no per-eye images, and the live view then opens one camera stream, not two).
    assert config["Image!stereo"]["imageMode"] == {"imageTopic": fox.STEREO_VIDEO,
                                                   "annotations": {}}
    assert config["RawMessages!events"]["topicPath"] == mcap_log.EVENTS


def test_a_wrong_path_is_caught():
    with pytest.raises(KeyError):
        resolve("/robot/wrench.force.z")
    with pytest.raises(KeyError):
        resolve("/robot/wrench[0]")
    assert set(RECORDED) == {*mcap_log.CHANNELS, *mcap_log.FOXGLOVE_CHANNELS}
