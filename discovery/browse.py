"""Finding slave stations: listening for `_telerobot._tcp` advertisements (mDNS, DNS-SD).

    stations = browse(3.0)                        # every station heard within 3 s
    station = pick(stations, "lab-slave")         # or pick(stations): the only one there is
    address = discovered_address("lab-slave", 3.0)  # host:port, returned once it is heard

A `Browser` keeps listening until closed and calls back on each station that appears,
changes or leaves (`python -m discovery watch`). Browsing asks over IPv4 multicast
(224.0.0.251, UDP 5353) on every interface of this host, as advertisements are sent over IPv4.
"""

from __future__ import annotations

import logging
import queue
import threading
import time
from collections.abc import Callable

from zeroconf import InterfaceChoice, IPVersion, ServiceBrowser, ServiceStateChange, Zeroconf

from discovery.station import (
    SERVICE_TYPE,
    Station,
    pick,
    station_from_record,
)

log = logging.getLogger("discovery")

# How long to wait for one station's records (SRV, TXT, addresses) once its name is heard;
# they usually come in the same answer as the name.
RESOLVE_TIMEOUT_S = 2.0
DEFAULT_TIMEOUT_S = 3.0

# on_change(kind, station): kind is "+" (appeared or changed) or "-" (left).
OnChange = Callable[[str, Station], None]


class Browser:
    """Stations on the network, kept up to date until `close()`: `stations()` now,
    `wait_until(...)` for a condition on them, `on_change` called on a thread of its own.
    `interfaces`: the IPv4 addresses of the interfaces to listen on (default: all)."""

    def __init__(self, on_change: OnChange | None = None,
                 interfaces: list[str] | None = None):
        self._on_change = on_change
        self._known: dict[str, Station] = {}  # full service name -> station
        self._changed = threading.Condition()
        self._names: queue.Queue[tuple[str, str] | None] = queue.Queue()
        self._zeroconf = Zeroconf(interfaces=interfaces or InterfaceChoice.All,
                                  ip_version=IPVersion.V4Only)
        # Names arrive on zeroconf's own thread, which must not block: they are resolved here.
        self._resolver = threading.Thread(target=self._resolve_loop, name="discovery-resolve",
                                          daemon=True)
        self._resolver.start()
        self._browser = ServiceBrowser(self._zeroconf, SERVICE_TYPE,
                                       handlers=[self._on_service_state_change])

    def stations(self) -> list[Station]:
        with self._changed:
            return sorted(self._known.values(), key=lambda s: s.name)

    def wait_until(self, found: Callable[[list[Station]], bool], timeout_s: float) -> bool:
        """Whether found(stations) became true within `timeout_s`."""
        deadline = time.monotonic() + timeout_s
        with self._changed:
            while not found(sorted(self._known.values(), key=lambda s: s.name)):
                left = deadline - time.monotonic()
                if left <= 0:
                    return False
                self._changed.wait(left)
            return True

    def close(self) -> None:
        self._browser.cancel()
        self._names.put(None)
        self._resolver.join(RESOLVE_TIMEOUT_S + 1.0)
        self._zeroconf.close()

    def __enter__(self) -> Browser:
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def _on_service_state_change(self, zeroconf: Zeroconf, service_type: str, name: str,
                                 state_change: ServiceStateChange) -> None:
        kind = "-" if state_change is ServiceStateChange.Removed else "+"
        self._names.put((kind, name))

    def _resolve_loop(self) -> None:
        while (item := self._names.get()) is not None:
            kind, name = item
            if kind == "-":
                with self._changed:
                    station = self._known.pop(name, None)
                    self._changed.notify_all()
            else:
                station = self._resolve(name)
                if station is None:
                    continue
                with self._changed:
                    self._known[name] = station
                    self._changed.notify_all()
            if station is not None and self._on_change is not None:
                self._on_change(kind, station)

    def _resolve(self, name: str) -> Station | None:
        info = self._zeroconf.get_service_info(SERVICE_TYPE, name,
                                               timeout=int(RESOLVE_TIMEOUT_S * 1000))
        if info is None or info.port is None:
            log.warning("heard of %r but could not resolve its address", name)
            return None
        instance = name[: -len(SERVICE_TYPE) - 1] if name.endswith(SERVICE_TYPE) else name
        properties = {k: v for k, v in info.decoded_properties.items() if k is not None}
        return station_from_record(instance, info.parsed_addresses(), info.port, properties)


def browse(timeout_s: float = DEFAULT_TIMEOUT_S, name: str | None = None, *,
           interfaces: list[str] | None = None) -> list[Station]:
    """The stations heard within `timeout_s`; with `name`, returns as soon as the station of
    that name is heard (with whatever else was heard by then). `interfaces` as for Browser."""
    with Browser(interfaces=interfaces) as browser:
        if name is None:
            browser.wait_until(lambda _stations: False, timeout_s)  # listen the whole time
        else:
            browser.wait_until(lambda stations: any(s.name == name for s in stations),
                               timeout_s)
        return browser.stations()


def discovered_address(name: str | None, timeout_s: float = DEFAULT_TIMEOUT_S) -> str:
    """host:port of the DecisionServer of the station called `name` (None: of the only station
    on the network), for a client's channel. DiscoveryError (station.py) when there is none,
    when several answer, or when it speaks another contract."""
    return pick(browse(timeout_s, name), name).address
