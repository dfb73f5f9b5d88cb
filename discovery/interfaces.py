"""Which IP addresses a server bound to a host accepts connections on.

A gRPC server bound to 0.0.0.0 listens on every IPv4 address of the host, one bound to ``::``
on every address (IPv4 too, dual stack), one bound to an address or a name only there. The
advertisement names these addresses, so that what a browser learns is where the station
really listens. IPv6 link-local addresses are left out: they mean nothing without the
interface they belong to, which another host cannot know.
"""

from __future__ import annotations

import ipaddress
import socket

import ifaddr

WILDCARD_V4 = "0.0.0.0"
WILDCARD_V6 = "::"


def host_addresses() -> list[str]:
    """Every IPv4 and IPv6 address of this host (of its network namespace), link-local IPv6
    left out."""
    found = []
    for adapter in ifaddr.get_adapters():
        for ip in adapter.ips:
            address = ip.ip if isinstance(ip.ip, str) else ip.ip[0]  # IPv6 is (addr, flow, scope)
            if ipaddress.ip_address(address).is_link_local and ":" in address:
                continue
            found.append(address)
    return _unique(found)


def listen_addresses(host: str) -> list[str]:
    """The IP addresses a server bound to `host` (an address, a wildcard or a name) is
    reachable at; empty when a name does not resolve."""
    host = host.strip("[]")
    if host in ("", WILDCARD_V4):
        return [a for a in host_addresses() if ipaddress.ip_address(a).version == 4]
    if host == WILDCARD_V6:
        return host_addresses()
    try:
        return [str(ipaddress.ip_address(host))]
    except ValueError:
        pass
    try:
        infos = socket.getaddrinfo(host, None, proto=socket.IPPROTO_TCP)
    except socket.gaierror:
        return []
    return _unique([info[4][0] for info in infos])


def _unique(addresses: list[str]) -> list[str]:
    return list(dict.fromkeys(addresses))
