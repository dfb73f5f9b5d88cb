"""Roles and the least role each RPC needs, as declared in the protos (`min_role`).

The ladder is OBSERVER < OPERATOR < STATION < ADMIN; a role may do whatever the roles below it
may. One rule on top of the declarations: the station's inner ports (ProxyRobot, ForceSensor,
StereoCamera, the e-stop band) take commands (operator- and admin-level calls) only from STATION
and ADMIN, so an operator cannot go around the DecisionServer's lock by calling ProxyRobot
directly, and the DecisionServer can forward what it allowed at its door (an admin's tool
frame) as itself.
"""

from __future__ import annotations

import enum
import functools

from telerobot.v1 import options_pb2
from wire.errors import PermissionDeniedError
from wire.options import method_options


class Role(enum.IntEnum):
    OBSERVER = options_pb2.ROLE_OBSERVER
    OPERATOR = options_pb2.ROLE_OPERATOR
    STATION = options_pb2.ROLE_STATION
    ADMIN = options_pb2.ROLE_ADMIN

    @classmethod
    def parse(cls, text: str) -> Role:
        """A role from its name ("operator", "ROLE_OPERATOR"); ValueError naming the choices."""
        name = text.strip().upper().removeprefix("ROLE_")
        try:
            return cls[name]
        except KeyError:
            choices = ", ".join(role.name.lower() for role in cls)
            raise ValueError(f"unknown role {text!r}; one of {choices}") from None

    @property
    def label(self) -> str:
        return self.name.lower()


# The runtime's own services, which carry no `min_role` option. None: open to anyone.
_BUILTIN_ROLES: dict[str, Role | None] = {
    "/grpc.health.v1.Health/Check": None,
    "/grpc.health.v1.Health/Watch": None,
    "/grpc.reflection.v1alpha.ServerReflection/ServerReflectionInfo": Role.OBSERVER,
    "/grpc.reflection.v1.ServerReflection/ServerReflectionInfo": Role.OBSERVER,
}


@functools.lru_cache(maxsize=1024)  # looked up for every call: cached (methods are few)
def declared_role(method_path: str) -> Role | None:
    """The least role an RPC declares ("/pkg.Service/Method"); None for Health, which is open.
    A method that declares none needs ADMIN: a forgotten option fails closed."""
    if method_path in _BUILTIN_ROLES:
        return _BUILTIN_ROLES[method_path]
    options = method_options(method_path)
    value = options.Extensions[options_pb2.min_role] if options is not None else 0
    return Role(value) if value else Role.ADMIN


def required_role(method_path: str, inner_port: bool) -> Role | None:
    """The least role a call needs on this server; None when the method is open to anyone."""
    role = declared_role(method_path)
    if inner_port and role is not None and role >= Role.OPERATOR:
        return Role.STATION  # commands reach the inner ports only through the DecisionServer
    return role


def check_role(role: Role, method_path: str, inner_port: bool) -> None:
    """PermissionDenied naming the role needed when `role` is below what the call needs."""
    needed = required_role(method_path, inner_port)
    if needed is not None and role < needed:
        where = " on the station's inner port (call the DecisionServer)" if (
            inner_port and needed is Role.STATION) else ""
        raise PermissionDeniedError(
            f"{method_path} needs the {needed.label} role{where}; this identity is "
            f"{role.label}", "ROLE_TOO_LOW")
