"""Roles come from the protos: every RPC declares one, and the inner ports' rule holds."""

import pytest
from google.protobuf import descriptor_pool

from services.security.roles import Role, check_role, declared_role, required_role
from telerobot.v1 import (  # noqa: F401 - registers the services in the descriptor pool
    decision_server_pb2,
    force_sensor_pb2,
    options_pb2,
    proxy_robot_pb2,
    stereo_camera_pb2,
)
from wire.errors import PermissionDeniedError

SERVICES = ["DecisionServer", "ProxyRobot", "ForceSensor", "StereoCamera"]


def _methods():
    pool = descriptor_pool.Default()
    for service in SERVICES:
        for method in pool.FindServiceByName(f"telerobot.v1.{service}").methods:
            yield f"/telerobot.v1.{service}/{method.name}", method


@pytest.mark.parametrize("path,method", list(_methods()), ids=lambda v: str(v).split("/")[-1])
def test_every_rpc_declares_its_role_and_its_doc_says_it(path, method):
    declared = method.GetOptions().Extensions[options_pb2.min_role]
    assert declared != options_pb2.ROLE_UNSPECIFIED, f"{path} has no (min_role) option"
    assert declared_role(path) == Role(declared)


def test_the_ladder_and_the_examples_of_the_issue():
    assert Role.OBSERVER < Role.OPERATOR < Role.STATION < Role.ADMIN
    assert declared_role("/telerobot.v1.ProxyRobot/EmergencyStop") is Role.OBSERVER
    assert declared_role("/telerobot.v1.ProxyRobot/SetToolFrame") is Role.ADMIN
    assert declared_role("/telerobot.v1.ForceSensor/SetSensorConfig") is Role.ADMIN
    assert declared_role("/telerobot.v1.DecisionServer/DeleteRecording") is Role.ADMIN
    assert declared_role("/telerobot.v1.DecisionServer/Teleoperate") is Role.OPERATOR
    assert declared_role("/telerobot.v1.StereoCamera/StreamPairs") is Role.OBSERVER
    assert declared_role("/grpc.health.v1.Health/Check") is None  # open to all
    assert declared_role("/grpc.reflection.v1alpha.ServerReflection/ServerReflectionInfo") \
        is Role.OBSERVER
    assert declared_role("/telerobot.v1.ProxyRobot/NoSuchMethod") is Role.ADMIN  # fails closed


def test_inner_ports_take_commands_only_from_the_station_and_admins():
    move = "/telerobot.v1.ProxyRobot/MoveJointsIncremental"
    assert required_role(move, inner_port=False) is Role.OPERATOR
    assert required_role(move, inner_port=True) is Role.STATION
    check_role(Role.STATION, move, inner_port=True)
    check_role(Role.ADMIN, move, inner_port=True)
    with pytest.raises(PermissionDeniedError, match="needs the station role.*DecisionServer"):
        check_role(Role.OPERATOR, move, inner_port=True)
    # Reads and stops stay open to observers on every port.
    check_role(Role.OBSERVER, "/telerobot.v1.ProxyRobot/GetState", inner_port=True)
    check_role(Role.OBSERVER, "/telerobot.v1.ProxyRobot/EmergencyStop", inner_port=True)
    # An admin-level RPC: the DecisionServer checked the admin at its door and forwards it as
    # itself; operators still cannot call it there.
    check_role(Role.STATION, "/telerobot.v1.ProxyRobot/SetToolFrame", inner_port=True)
    with pytest.raises(PermissionDeniedError, match="needs the station role"):
        check_role(Role.OPERATOR, "/telerobot.v1.ProxyRobot/SetToolFrame", inner_port=True)
    with pytest.raises(PermissionDeniedError, match="needs the admin role"):
        check_role(Role.STATION, "/telerobot.v1.ProxyRobot/SetToolFrame", inner_port=False)


def test_role_names_parse_both_ways():
    assert Role.parse("operator") is Role.OPERATOR
    assert Role.parse("ROLE_ADMIN") is Role.ADMIN
    with pytest.raises(ValueError, match="one of observer, operator, station, admin"):
        Role.parse("root")
