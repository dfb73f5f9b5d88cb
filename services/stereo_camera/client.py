"""Client-side helpers: a channel that keeps the freshest pairs coming, and decoding.

The options and the decoding are the contracts' (``wire.stereo``, shared with
``clients.python``; its docstring says why LOW_LATENCY_OPTIONS keeps a slow reader's pairs
fresh); this adds the channel for the services' own tools and tests.
"""

from __future__ import annotations

from collections.abc import Sequence

import grpc

from wire.stereo import LOW_LATENCY_OPTIONS, decode_pair

__all__ = ["LOW_LATENCY_OPTIONS", "decode_pair", "open_channel"]


def open_channel(address: str, options: Sequence[tuple[str, object]] = ()) -> grpc.Channel:
    """An insecure channel to a StereoCamera at `address` with LOW_LATENCY_OPTIONS (and any
    extra `options`)."""
    return grpc.insecure_channel(address, options=[*LOW_LATENCY_OPTIONS, *options])
