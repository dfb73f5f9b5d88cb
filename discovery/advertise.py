"""A slave station's advertisement: DNS-SD over multicast DNS (zeroconf), `_telerobot._tcp`.

    with advertised("0.0.0.0:50051", tls=True, token_address=None, mode="auto"):
        ...  # operator stations on the network see the station until the block ends

The advertisement names the DecisionServer's port and the addresses it really listens on
(interfaces.listen_addresses), with the TXT properties of station.txt_properties, and is sent
on the IPv4 interfaces of those addresses only, never on others. Leaving the block withdraws it
with mDNS goodbye packets, so browsers drop the station at once, not when its records expire.

A station on loopback is not advertised unless asked ("1"): mDNS on loopback is meaningless
to other hosts, which could not reach a loopback address even if they heard of it. The mode
comes from `--advertise` / `--no-advertise` or TELEROBOT_ADVERTISE (1, 0, auto; default auto:
advertise when the DecisionServer listens on a non-loopback address).

Discovery is a convenience: `advertised` logs a failure to advertise (no multicast-capable
interface, say) and carries on, never stopping the station for it.
"""

from __future__ import annotations

import ipaddress
import logging
import os
import socket
from collections.abc import Iterator
from contextlib import contextmanager

from zeroconf import Error as ZeroconfError
from zeroconf import IPVersion, ServiceInfo, Zeroconf

from discovery.interfaces import listen_addresses
from discovery.station import (
    SERVICE_TYPE,
    DiscoveryError,
    check_station_name,
    default_station_name,
    is_loopback,
    should_advertise,
    split_host_port,
    txt_properties,
)

log = logging.getLogger("discovery")

ADVERTISE_ENV = "TELEROBOT_ADVERTISE"  # 1, 0 or auto
STATION_NAME_ENV = "TELEROBOT_STATION_NAME"
# How long a record may be cached (s): a station that vanished without its goodbye (killed,
# cable pulled) drops out of browsers after this.
RECORD_TTL_S = 120


class Advertisement:
    """One station advertised on the network while open. `start()` registers it (probing
    for a unique name, then announcing), `close()` sends the goodbye."""

    def __init__(self, name: str, addresses: list[str], port: int, tls: bool,
                 token_port: int | None = None, host_name: str | None = None):
        self.requested_name = check_station_name(name)
        self.addresses = addresses
        self.port = port
        host_name = host_name or socket.gethostname()
        # Sent over IPv4 (mDNS on 224.0.0.251) on the interfaces of its IPv4 addresses; its
        # IPv6 addresses travel in AAAA records of the same answers.
        self.interfaces = [a for a in addresses if ipaddress.ip_address(a).version == 4]
        if not self.interfaces:
            raise DiscoveryError(f"advertising needs an IPv4 address to send mDNS from; the "
                                 f"station listens on {', '.join(addresses) or 'nothing'}")
        short = host_name.split(".", 1)[0] or "telerobot"
        self.info = ServiceInfo(
            SERVICE_TYPE, f"{name}.{SERVICE_TYPE}",
            parsed_addresses=addresses, port=port,
            properties=txt_properties(name, tls, token_port, host_name),
            server=f"{short}.local.", host_ttl=RECORD_TTL_S, other_ttl=RECORD_TTL_S)
        self._zeroconf: Zeroconf | None = None

    @property
    def name(self) -> str:
        """The instance name registered: the one asked for, or "<name> (2)" and so on when
        another responder on the network already held it."""
        return self.info.name[: -len(SERVICE_TYPE) - 1]

    def start(self) -> Advertisement:
        self._zeroconf = Zeroconf(interfaces=self.interfaces, ip_version=IPVersion.V4Only)
        try:
            self._zeroconf.register_service(self.info, allow_name_change=True)
        except BaseException:
            self._zeroconf.close()
            self._zeroconf = None
            raise
        return self

    def close(self) -> None:
        if self._zeroconf is None:
            return
        zeroconf, self._zeroconf = self._zeroconf, None
        try:
            zeroconf.unregister_service(self.info)  # the goodbye: TTL 0 for every record
        finally:
            zeroconf.close()

    def __enter__(self) -> Advertisement:
        return self.start()

    def __exit__(self, *exc) -> None:
        self.close()


def plan(decision_address: str, *, tls: bool, token_port: int | None = None,
         mode: str = "auto", name: str | None = None,
         host_name: str | None = None) -> Advertisement | None:
    """The advertisement of a station whose DecisionServer listens on `decision_address`
    (host:port, as its ready line says), or None when `mode` says not to advertise it (see the
    module's docstring). `name` defaults to TELEROBOT_STATION_NAME, then to "<host>:<port>".
    DiscoveryError for a bad name or no address to advertise."""
    host, port = split_host_port(decision_address)
    addresses = listen_addresses(host)
    if not should_advertise(addresses, mode):
        return None
    # Other hosts cannot use a loopback address: name it only when it is all there is.
    reachable = [a for a in addresses if not is_loopback(a)] or addresses
    host_name = host_name or socket.gethostname()
    name = name or os.environ.get(STATION_NAME_ENV) or default_station_name(host_name, port)
    return Advertisement(name, reachable, port, tls, token_port, host_name)


@contextmanager
def advertised(decision_address: str, *, tls: bool, token_address: str | None = None,
               mode: str = "auto", name: str | None = None) -> Iterator[Advertisement | None]:
    """The station advertised for the block's duration (see `plan`), withdrawn when it ends,
    however it ends. Yields None when not advertised: by `mode`, or because advertising failed,
    which is logged and never raised."""
    try:
        token_port = split_host_port(token_address)[1] if token_address else None
        advertisement = plan(decision_address, tls=tls, token_port=token_port, mode=mode,
                             name=name)
        if advertisement is not None:
            advertisement.start()
    except (DiscoveryError, OSError, ZeroconfError) as exc:
        log.warning("not advertising the station on the network: %s", exc)
        yield None
        return
    if advertisement is None:
        if mode == "auto":
            log.info("not advertising the station: its DecisionServer listens on loopback only "
                     "(%s); --advertise or %s=1 to advertise it anyway", decision_address,
                     ADVERTISE_ENV)
        yield None
        return
    log.info("advertising the station as %r (%s) on %s, port %d", advertisement.name,
             SERVICE_TYPE, ", ".join(advertisement.addresses), advertisement.port)
    try:
        yield advertisement
    finally:
        try:
            advertisement.close()
        except (OSError, ZeroconfError) as exc:
            log.warning("withdrawing the station's advertisement: %s", exc)
        else:
            log.info("withdrew the station's advertisement")
