"""The options an RPC declares in the protos (its lane, its least role), by method path."""

from __future__ import annotations

from google.protobuf import descriptor_pool
from google.protobuf.descriptor_pb2 import MethodOptions


def method_options(method_path: str) -> MethodOptions | None:
    """The options of "/pkg.Service/Method" from the loaded protos; None for a method they do
    not define (the runtime's own services, or an unknown method)."""
    service, _, method = method_path.lstrip("/").partition("/")
    try:
        return descriptor_pool.Default().FindMethodByName(f"{service}.{method}").GetOptions()
    except KeyError:
        return None
