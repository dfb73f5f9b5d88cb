"""Servicers for contracts whose domain a later issue builds: every RPC answers UNIMPLEMENTED
with a message that says what is missing, so nothing pretends to work."""

from __future__ import annotations

import inspect

from services.runtime.errors import Unimplemented


def unimplemented_servicer(servicer_base: type, note: str) -> object:
    """An instance of a generated `*Servicer` base whose every RPC raises Unimplemented(note)."""

    def make(method_name: str):
        def method(self, request, context):
            raise Unimplemented(f"{servicer_base.__name__.removesuffix('Servicer')}.{method_name}"
                                f" is not built yet: {note}", reason="NOT_BUILT")
        return method

    rpc_names = [
        name for name, _ in inspect.getmembers(servicer_base, inspect.isfunction)
        if not name.startswith("_")
    ]
    cls = type(f"Unimplemented{servicer_base.__name__}", (servicer_base,),
               {name: make(name) for name in rpc_names})
    return cls()
