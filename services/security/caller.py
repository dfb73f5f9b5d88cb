"""Who the current call speaks for, as the runtime authenticated it.

The runtime sets it around each handler (services.runtime.auth); domain code reads it where a
decision depends on the identity (a lease belongs to the identity that took it). None means the
server authenticates nobody (plaintext on loopback, for development) or the code runs outside a
call (a session's own threads act for the identity that opened the session).
"""

from __future__ import annotations

import contextlib
import contextvars
from collections.abc import Iterator
from dataclasses import dataclass

from services.security.roles import Role


@dataclass(frozen=True)
class Caller:
    identity: str
    role: Role


_current: contextvars.ContextVar[Caller | None] = contextvars.ContextVar("caller", default=None)


def current_caller() -> Caller | None:
    return _current.get()


@contextlib.contextmanager
def acting_as(caller: Caller | None) -> Iterator[None]:
    token = _current.set(caller)
    try:
        yield
    finally:
        _current.reset(token)
