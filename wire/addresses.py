"""Where each service listens: its default port, or ``TELEROBOT_<SERVICE>_ADDRESS``.

Each service listens on loopback by default. The variable (for example
TELEROBOT_PROXY_ROBOT_ADDRESS=0.0.0.0:50052) or a service's ``--address`` flag changes it; the
launcher and the clients read the same variables, so they always agree on where a service is.
"""

from __future__ import annotations

import ipaddress
import os

DEFAULT_HOST = "127.0.0.1"
# The operator's one address is the DecisionServer's; the others are the slave station's inside.
DEFAULT_PORTS = {
    "world": 50050,  # the simulated hardware; serves only health, its link is shared memory
    "decision_server": 50051,
    "proxy_robot": 50052,
    "force_sensor": 50053,
    "stereo_camera": 50054,
    "emergency_stop": 50055,  # the emergency-stop band: ProxyRobot.EmergencyStop past the driver
    "web_console": 50080,  # HTTP: the browser console's page, Connect and WebSocket (#18)
    "foxglove": 8765,  # WebSocket: the live view for Foxglove or Lichtblick (Foxglove's port)
    "zenoh_router": 7447,  # Zenoh: observers subscribe through it (Zenoh's own port)
}


def env_name(service: str, setting: str) -> str:
    """Environment variable for a service's setting: ("proxy_robot", "address") ->
    TELEROBOT_PROXY_ROBOT_ADDRESS."""
    return f"TELEROBOT_{service.upper()}_{setting.upper()}"


def address_for(service: str) -> str:
    """host:port where `service` listens, from its environment variable or the default."""
    if service not in DEFAULT_PORTS:
        raise KeyError(f"unknown service {service!r}; known: {', '.join(DEFAULT_PORTS)}")
    default = f"{DEFAULT_HOST}:{DEFAULT_PORTS[service]}"
    return os.environ.get(env_name(service, "address"), default)


def is_loopback(address: str) -> bool:
    """Whether host:port names a loopback host (127.0.0.0/8, ::1, localhost)."""
    host = address.rsplit(":", 1)[0].strip("[]")
    if host == "localhost":
        return True
    try:
        return ipaddress.ip_address(host).is_loopback
    except ValueError:
        return False  # a name, "0.0.0.0" parses; "" or a hostname may reach any interface
