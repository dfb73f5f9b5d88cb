"""Discovery: slave stations advertise themselves on the local network (zeroconf: DNS-SD over
multicast DNS, service type `_telerobot._tcp`), and operator stations list and pick them.

- station.py: what an advertisement says (TXT properties), `Station`, `pick`; pure.
- interfaces.py: the addresses a server bound to a host listens on.
- advertise.py: the advertisement (the launcher's `advertised(...)`).
- browse.py: `browse`, `discovered_address`, the `Browser` that keeps listening.
- ``python -m discovery list | watch | address [NAME] | advertise``.
"""

from discovery.browse import Browser, browse, discovered_address
from discovery.station import CONTRACT, SERVICE_TYPE, DiscoveryError, Station, pick

__all__ = ["CONTRACT", "SERVICE_TYPE", "Browser", "DiscoveryError", "Station", "browse",
           "discovered_address", "pick"]
