"""A user-space impairment link (this kernel has no netem): a TCP proxy that delays, jitters,
throttles, stalls and cuts the bytes between a client and its target, the same way or not up
and down, repeatably from a seed. `python -m services.impairment --help` runs it by hand."""

from services.impairment.link import LinkProfile, LinkSchedule
from services.impairment.proxy import CUT_MODES, ImpairmentProxy, ProxyStats

__all__ = ["CUT_MODES", "ImpairmentProxy", "LinkProfile", "LinkSchedule", "ProxyStats"]
