"""Client-side helpers: a channel that keeps the freshest pairs coming, and decoding.

The options and the decoding are the contracts' (``wire.stereo``, shared with
``clients.python``; its docstring says why LOW_LATENCY_OPTIONS keeps a slow reader's pairs
fresh); this adds the channel for the services' own tools and tests.
"""

from __future__ import annotations

from collections.abc import Sequence

import grpc

from wire import tls
from wire.stereo import LOW_LATENCY_OPTIONS, decode_pair

__all__ = ["LOW_LATENCY_OPTIONS", "decode_pair", "open_channel"]


def open_channel(address: str, options: Sequence[tuple[str, object]] = ()) -> grpc.Channel:
    """A channel to a StereoCamera at `address` with LOW_LATENCY_OPTIONS (and any extra
    `options`); TLS as the environment says (wire.tls)."""
    return tls.open_channel(address, [*LOW_LATENCY_OPTIONS, *options])
