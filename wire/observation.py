"""Observation over Zenoh: what the station publishes, under which keys, and how to reach it.

The station publishes each observed stream once into Zenoh (services.observation); routers
carry one copy per link to any number of subscribers. Every payload is a message of the
protos' own, serialized, the same one the service's gRPC stream sends:

    telerobot/<station>/wrench   telerobot.v1.StreamWrenchResponse: every 1 kHz sample, in
                                 batches of WRENCH_BATCH (oldest first)
    telerobot/<station>/state    telerobot.v1.StreamStateResponse: the arm's state, 100 Hz
    telerobot/<station>/events   telerobot.v1.StreamEventsResponse (the DecisionServer's):
                                 control, holds, sessions, dependencies, the arm's events
    telerobot/<station>/status   telerobot.v1.SessionStatus: who holds control and who waits,
                                 the assistance in force, each dependency's state; after each
                                 change and every STATUS_PERIOD_S
    telerobot/<station>/video    telerobot.v1.StreamPairsResponse (the StereoCamera's): both
                                 eyes side by side in H.264 at VIDEO_FPS, a key frame at least
                                 every VIDEO_KEYFRAME_S, each one right after the stream's
                                 header (the calibrations), so that a newcomer can start there

An observer follows DEFAULT_TOPICS unless it names the video too: following the video makes
the station's cameras render.

Commands never travel here: they stay on gRPC, behind the DecisionServer's lock.

Endpoints are Zenoh's: `tcp/HOST:PORT`, plaintext, for loopback only (an endpoint beyond it is
refused, as every other port of the station refuses plaintext beyond loopback), and
`tls/HOST:PORT`, anywhere. Over TLS every link is mutual TLS with the station's PKI
(services.security.pki, `make certs`): each end presents its certificate, and a router
lets only the station's publisher and other routers put into telerobot/** (ACCESS_CONTROL).
"""

from __future__ import annotations

import json
import logging
import os
import re
import sys
import threading
from dataclasses import dataclass
from pathlib import Path

import zenoh

from telerobot.v1 import (
    decision_server_pb2,
    force_sensor_pb2,
    proxy_robot_pb2,
    stereo_camera_pb2,
)
from wire.addresses import address_for, is_loopback

log = logging.getLogger(__name__)

KEY_ROOT = "telerobot"
STATION_ENV = "TELEROBOT_STATION"  # the station's name in its Zenoh keys (default station)
DEFAULT_STATION = "station"
ROUTER_ENV = "TELEROBOT_ZENOH_ROUTER"  # an endpoint to join instead of the station's own router
WRENCH_BATCH = 10  # samples per wrench message: 100 messages a second at the sensor's 1 kHz
STATE_PERIOD_S = 0.01
STATUS_PERIOD_S = 1.0  # the session's status is put at least this often
VIDEO_FPS = 10.0  # the camera's pace on this machine (a stereo pair renders in ~85 ms)
VIDEO_KBIT = 1000  # the bitrate ceiling, kbit/s: 640x480 per eye at 10 fps
VIDEO_KEYFRAME_S = 2.0  # the longest a newcomer waits for a key frame
# The longest a process waits for its session's close (close_session) before it exits anyway.
CLOSE_TIMEOUT_S = 2.0

# topic -> the message type of its payloads
TOPICS = {
    "wrench": force_sensor_pb2.StreamWrenchResponse,
    "state": proxy_robot_pb2.StreamStateResponse,
    "events": decision_server_pb2.StreamEventsResponse,
    "status": decision_server_pb2.SessionStatus,
    "video": stereo_camera_pb2.StreamPairsResponse,
}
DEFAULT_TOPICS = ("wrench", "state", "events", "status")
_STATION_NAME = re.compile(r"[A-Za-z0-9_-]{1,64}")
_ENDPOINT = re.compile(r"(?P<protocol>tcp|tls)/(?P<address>\[[0-9a-fA-F:]+\]:\d+|[^/:\[\]]+:\d+)")
# Who may put into the station's keys over TLS (certificate common names): its publisher, and
# routers relaying it. Anyone with a certificate of the station's CA may subscribe.
PUBLISHERS = ("observation", "zenoh_router")


class BadEndpoint(ValueError):
    """An endpoint this station will not listen on or connect to."""


def station_name(name: str | None = None) -> str:
    """The station's name in its keys: `name`, else $TELEROBOT_STATION, else "station".
    ValueError unless it is 1-64 of A-Z a-z 0-9 _ - (a key expression's chunk, no wildcards)."""
    name = name or os.environ.get(STATION_ENV) or DEFAULT_STATION
    if not _STATION_NAME.fullmatch(name):
        raise ValueError(f"station name {name!r}: use 1-64 of A-Z a-z 0-9 _ -")
    return name


def key(station: str, topic: str) -> str:
    """telerobot/<station>/<topic>"""
    if topic not in TOPICS:
        raise KeyError(f"unknown topic {topic!r}; known: {', '.join(TOPICS)}")
    return f"{KEY_ROOT}/{station}/{topic}"


def topic_of(key_expr: str) -> tuple[str, str] | None:
    """(station, topic) of a published key, or None for a key that is not one of ours."""
    parts = str(key_expr).split("/")
    if len(parts) == 3 and parts[0] == KEY_ROOT and parts[2] in TOPICS:
        return parts[1], parts[2]
    return None


def decode(topic: str, payload: bytes):
    """The message of a payload published on `topic` (google.protobuf DecodeError if bad)."""
    message = TOPICS[topic]()
    message.ParseFromString(payload)
    return message


def endpoint_for(address: str, tls: bool = False) -> str:
    """host:port -> tcp/host:port (tls/host:port)"""
    return f"{'tls' if tls else 'tcp'}/{address}"


def address_of(endpoint: str) -> str:
    """tcp/HOST:PORT or tls/HOST:PORT -> HOST:PORT (BadEndpoint for anything else)."""
    match = _ENDPOINT.fullmatch(endpoint)
    if match is None:
        raise BadEndpoint(f"endpoint {endpoint!r}: expected tcp/HOST:PORT or tls/HOST:PORT")
    return match["address"]


def default_router(tls_dir: str | None = None) -> str:
    """The router to join: $TELEROBOT_ZENOH_ROUTER, else the station's own (its address, over
    TLS when there is a TLS directory)."""
    return os.environ.get(ROUTER_ENV) or endpoint_for(address_for("zenoh_router"),
                                                      tls=bool(tls_dir))


def checked_endpoint(endpoint: str, tls: bool = False) -> str:
    """`endpoint` if it is tcp/HOST:PORT on loopback, or tls/HOST:PORT with `tls` (a TLS
    directory to use); BadEndpoint saying why otherwise."""
    match = _ENDPOINT.fullmatch(endpoint)
    if match is None:
        raise BadEndpoint(f"endpoint {endpoint!r}: expected tcp/HOST:PORT or tls/HOST:PORT")
    if match["protocol"] == "tls" and not tls:
        raise BadEndpoint(f"endpoint {endpoint!r} is TLS: give the station's TLS directory "
                          "(--tls-dir, or TELEROBOT_TLS_DIR)")
    if match["protocol"] == "tcp" and not is_loopback(match["address"]):
        raise BadEndpoint(f"endpoint {endpoint!r} is plaintext beyond loopback, which this "
                          f"station refuses: use tls/{match['address']} with the station's "
                          "TLS directory")
    return endpoint


@dataclass(frozen=True)
class ZenohTls:
    """Mutual TLS from a directory of the station's PKI: its CA, and the certificate of
    `identity` (<identity>.pem / .key), presented both as a client and as a listener."""

    tls_dir: Path
    identity: str

    def files(self) -> dict[str, Path]:
        directory = Path(self.tls_dir)
        files = {"ca": directory / "ca.pem", "cert": directory / f"{self.identity}.pem",
                 "key": directory / f"{self.identity}.key"}
        missing = [str(path) for path in files.values() if not path.exists()]
        if missing:
            raise BadEndpoint(f"TLS needs {', '.join(missing)}: `make certs` issues them")
        return files

    def insert(self, config: zenoh.Config, listens: bool) -> None:
        files = self.files()
        settings = {"root_ca_certificate": files["ca"], "enable_mtls": True,
                    "connect_certificate": files["cert"], "connect_private_key": files["key"]}
        if listens:
            settings |= {"listen_certificate": files["cert"], "listen_private_key": files["key"]}
        for name, value in settings.items():
            config.insert_json5(f"transport/link/tls/{name}",
                                json.dumps(value if isinstance(value, bool) else str(value)))


# A TLS router's rules: anyone with a certificate of the CA subscribes and is delivered to;
# only PUBLISHERS put into the station's keys. Everything else is denied.
ACCESS_CONTROL = {
    "enabled": True,
    "default_permission": "deny",
    "rules": [
        {"id": "subscribe", "permission": "allow", "flows": ["ingress"],
         "messages": ["declare_subscriber"], "key_exprs": [f"{KEY_ROOT}/**"]},
        {"id": "deliver", "permission": "allow", "flows": ["egress"],
         "messages": ["put", "delete", "declare_subscriber"], "key_exprs": [f"{KEY_ROOT}/**"]},
        {"id": "publish", "permission": "allow", "flows": ["ingress"],
         "messages": ["put", "delete"], "key_exprs": [f"{KEY_ROOT}/**"]},
    ],
    "subjects": [{"id": "anyone"},
                 {"id": "publishers", "cert_common_names": list(PUBLISHERS)}],
    "policies": [{"id": "observers", "rules": ["subscribe", "deliver"], "subjects": ["anyone"]},
                 {"id": "station", "rules": ["publish"], "subjects": ["publishers"]}],
}


@dataclass(frozen=True)
class SessionPlan:
    """A Zenoh session's mode and endpoints (checked): a router listens and may join others;
    a client connects to one router."""

    mode: str  # "router" or "client"
    listen: tuple[str, ...] = ()
    connect: tuple[str, ...] = ()
    tls: ZenohTls | None = None  # mutual TLS (and, for a router, ACCESS_CONTROL)

    def config(self) -> zenoh.Config:
        config = zenoh.Config()
        config.insert_json5("mode", json.dumps(self.mode))
        # Nothing found by multicast: a station joins only the routers it is told of.
        config.insert_json5("scouting/multicast/enabled", "false")
        # Plain TCP, even between processes of one host: with Zenoh's shared memory a router
        # stopped taking clients after about 350, and its segments outlive killed processes.
        config.insert_json5("transport/shared_memory/enabled", "false")
        tls = self.tls is not None
        if self.listen:
            config.insert_json5("listen/endpoints",
                                json.dumps([checked_endpoint(e, tls) for e in self.listen]))
        if self.connect:
            config.insert_json5("connect/endpoints",
                                json.dumps([checked_endpoint(e, tls) for e in self.connect]))
        if self.tls is not None:
            self.tls.insert(config, listens=bool(self.listen))
            if self.mode == "router":
                config.insert_json5("access_control", json.dumps(ACCESS_CONTROL))
        return config

    def open(self) -> zenoh.Session:
        return zenoh.open(self.config())


def client(router: str, tls: ZenohTls | None = None) -> zenoh.Session:
    """A client session through `router` (tcp/HOST:PORT, or tls/HOST:PORT with `tls`)."""
    return SessionPlan("client", connect=(router,), tls=tls).open()


def close_session(session: zenoh.Session, timeout_s: float = CLOSE_TIMEOUT_S) -> None:
    """Close `session`, waiting at most `timeout_s` (and saying so past it). Zenoh's close
    can block about 10 s, then fail, when a link to a `connect` endpoint is slow or lossy
    (eclipse-zenoh/zenoh#2675): longer than a supervisor's grace, so the process would be
    killed. Past the timeout the process goes on to exit, which closes its sockets anyway."""
    closed = threading.Event()

    def close() -> None:
        try:
            session.close()
        except zenoh.ZError as error:  # "close operation timed out"
            log.warning("closing the Zenoh session: %s", error)
        finally:
            closed.set()

    threading.Thread(target=close, name="zenoh-close", daemon=True).start()
    if not closed.wait(timeout_s):
        log.warning("the Zenoh session did not close within %.0f s: exiting without it",
                    timeout_s)


class RouterUnreachable(ConnectionError):
    """A router that did not answer."""


def join_router(router: str, tls_dir: str | None, identity: str) -> zenoh.Session:
    """A client session through `router`, presenting `identity`'s certificate from `tls_dir`
    (none without it): BadEndpoint for an endpoint or TLS directory this station refuses,
    RouterUnreachable when the router does not answer, each saying why."""
    router = checked_endpoint(router, tls=bool(tls_dir))
    tls = tls_from(tls_dir, identity)
    if tls is not None:
        tls.files()  # there, or said so
    try:
        return client(router, tls)
    except zenoh.ZError as error:
        raise RouterUnreachable(f"the router {router} does not answer: {error}") from None


def join_or_exit_code(program: str, router: str, station: str | None, tls_dir: str | None,
                      identity: str) -> tuple[str, zenoh.Session] | int:
    """For a program's main: (the station's name, a session through `router`), or the exit
    code after saying why not on stderr: 2 for a bad station name, endpoint or TLS directory, 1
    for a router that does not answer."""
    try:
        return station_name(station), join_router(router, tls_dir, identity)
    except ValueError as error:  # (BadEndpoint is one)
        print(f"{program}: {error}", file=sys.stderr)
        return 2
    except RouterUnreachable as error:
        print(f"{program}: {error}", file=sys.stderr)
        return 1


def tls_from(tls_dir: str | None, identity: str) -> ZenohTls | None:
    """ZenohTls for `identity` from a TLS directory; None without one."""
    return ZenohTls(Path(tls_dir), identity) if tls_dir else None
