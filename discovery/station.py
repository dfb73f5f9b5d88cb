"""What a slave station says about itself on the network, and how an operator picks one.

Pure: no zeroconf, no grpc, no sockets. The advertisement (advertise.py) turns a station's
settings into a DNS-SD service instance of SERVICE_TYPE with the TXT properties below; the
browser (browse.py) turns what it hears back into `Station`s; `pick` chooses one.

TXT properties (DNS-SD keys, all strings):
- ``txtvers``: this layout's version, 1.
- ``contract``: the gRPC package the station serves (``telerobot.v1``); a client refuses a
  station that speaks another.
- ``tls``: ``1`` when its ports require TLS (mutual TLS on the main port), ``0`` for plaintext.
- ``token_port``: the DecisionServer's bearer-token port (TLS without client certificates),
  absent when it has none.
- ``station``: the station's name, which is also the instance name unless DNS-SD had to
  rename the instance because another station on the network holds that name.
- ``host``: the host name of the machine the station runs on.
"""

from __future__ import annotations

import ipaddress
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass

from telerobot.v1 import decision_server_pb2

SERVICE_TYPE = "_telerobot._tcp.local."
# The contract's package, from the generated code: one source of truth with the protos.
CONTRACT = decision_server_pb2.DESCRIPTOR.package
TXT_VERSION = "1"
# DNS-SD instance names are at most 63 bytes (RFC 6763 4.1.1).
MAX_NAME_BYTES = 63


class DiscoveryError(Exception):
    """No station, several where one was wanted, or one that cannot be used; the message
    says which stations were found and what to do."""


@dataclass(frozen=True)
class Station:
    """A slave station found on the network."""

    name: str  # the DNS-SD instance name: what `pick` matches and `list` shows
    addresses: tuple[str, ...]  # where its DecisionServer listens, IPv4 first
    port: int  # the DecisionServer's port
    tls: bool
    contract: str
    token_port: int | None = None
    host: str = ""

    @property
    def address(self) -> str:
        """host:port of its first address (IPv6 in brackets), for a channel."""
        if not self.addresses:
            raise DiscoveryError(f"station {self.name!r} announced no address")
        return join_host_port(self.addresses[0], self.port)

    def describe(self) -> str:
        """One line: name, addresses:port, TLS, contract, token port."""
        where = ", ".join(join_host_port(a, self.port) for a in self.addresses) or "no address"
        parts = [self.name, where, "TLS" if self.tls else "plaintext", self.contract]
        if self.token_port is not None:
            parts.append(f"tokens on port {self.token_port}")
        return "  ".join(parts)


def txt_properties(station_name: str, tls: bool, token_port: int | None,
                   host: str) -> dict[str, str]:
    """The TXT properties of a station's advertisement (see the module's docstring)."""
    properties = {"txtvers": TXT_VERSION, "contract": CONTRACT, "tls": "1" if tls else "0",
                  "station": station_name, "host": host}
    if token_port is not None:
        properties["token_port"] = str(token_port)
    return properties


def station_from_record(instance: str, addresses: Iterable[str], port: int,
                        properties: Mapping[str, str | None]) -> Station:
    """A Station from a resolved service: its instance label (without the service type),
    addresses, port and decoded TXT properties. A property that is missing or malformed
    reads as unknown (contract "") or off, never as an error: any host can advertise."""
    token = properties.get("token_port") or ""
    ordered = sorted(set(addresses), key=lambda a: (ipaddress.ip_address(a).version, a))
    return Station(
        name=instance,
        addresses=tuple(ordered),
        port=port,
        tls=properties.get("tls") == "1",
        contract=properties.get("contract") or "",
        token_port=int(token) if token.isdigit() and 0 < int(token) < 65536 else None,
        host=properties.get("host") or "",
    )


def pick(stations: Sequence[Station], name: str | None = None) -> Station:
    """The station called `name`, or the only station there is when `name` is None.
    DiscoveryError when there is none, when several match, or when the one found speaks
    another contract than this code's."""
    if not stations:
        raise DiscoveryError(
            f"no slave station found ({SERVICE_TYPE} on the local network): is one running "
            "with --advertise (or on a non-loopback address), on this network segment, with "
            "UDP port 5353 open?")
    found = "; ".join(sorted(s.describe() for s in stations))
    if name is None:
        usable = [s for s in stations if s.contract == CONTRACT]
        if len(usable) > 1:
            names = ", ".join(sorted(repr(s.name) for s in usable))
            raise DiscoveryError(f"{len(usable)} slave stations found ({names}): name the one "
                                 f"to use. Found: {found}")
        if not usable:
            raise DiscoveryError(f"no slave station speaks {CONTRACT}. Found: {found}")
        return usable[0]
    matches = [s for s in stations if s.name == name]
    if not matches:
        raise DiscoveryError(f"no slave station called {name!r}. Found: {found}")
    if len(matches) > 1:  # two responders answering for one name
        raise DiscoveryError(f"{len(matches)} slave stations answer as {name!r}: "
                             f"{'; '.join(s.describe() for s in matches)}")
    chosen = matches[0]
    if chosen.contract != CONTRACT:
        speaks = chosen.contract or "no known contract"
        raise DiscoveryError(f"slave station {name!r} speaks {speaks}, this operator station "
                             f"{CONTRACT}")
    return chosen


def default_station_name(host_name: str, port: int) -> str:
    """The station's name unless one is given: the host's short name and the port (the port
    tells apart two stations on one host)."""
    short = host_name.split(".", 1)[0] or "telerobot"
    return f"{short}:{port}"


def check_station_name(name: str) -> str:
    """`name` if DNS-SD can carry it as an instance name; DiscoveryError saying why not."""
    if not name or len(name.encode()) > MAX_NAME_BYTES:
        raise DiscoveryError(f"a station name is 1 to {MAX_NAME_BYTES} bytes: {name!r}")
    if "." in name:  # zeroconf splits the full service name at dots
        raise DiscoveryError(f"a station name has no dots: {name!r}")
    if any(ord(c) < 0x20 or ord(c) == 0x7f for c in name):
        raise DiscoveryError(f"a station name has no control characters: {name!r}")
    return name


def is_loopback(address: str) -> bool:
    """Whether an IP address is a loopback one (127.0.0.0/8, ::1)."""
    return ipaddress.ip_address(address).is_loopback


def should_advertise(addresses: Sequence[str], mode: str) -> bool:
    """Whether to advertise a station listening on `addresses` (IPs) when asked with `mode`:
    "1" always, "0" never, "auto" when it listens on at least one non-loopback address.

    mDNS on loopback is meaningless to other hosts: they could not reach a loopback address
    even if they heard of it, so "auto" keeps a development station on loopback quiet.
    """
    if mode == "1":
        return bool(addresses)
    if mode == "0":
        return False
    if mode != "auto":
        raise DiscoveryError(f"advertise mode is 1, 0 or auto, not {mode!r}")
    return any(not is_loopback(a) for a in addresses)


def join_host_port(host: str, port: int) -> str:
    """host:port, with an IPv6 address in brackets."""
    return f"[{host}]:{port}" if ":" in host else f"{host}:{port}"


def split_host_port(address: str) -> tuple[str, int]:
    """(host, port) from host:port or [v6]:port."""
    host, sep, port = address.rpartition(":")
    if not sep or not port.isdigit():
        raise DiscoveryError(f"expected host:port, not {address!r}")
    return host.strip("[]"), int(port)
