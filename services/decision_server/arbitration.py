"""Who may command the arm: the Parma paper's concurrency control, as leases.

EXCLUSIVE control is a write lock: one holder. COLLABORATIVE control is a read lock shared by
the members of one group. A request that conflicts waits in a fair FIFO queue (no one overtakes
a waiter) or fails at once, as the caller chooses. Every lock is a lease: it expires unless
its holder renews it or uses it (each authorized call renews it), so a crashed operator never
blocks the arm for longer than one lease. No gRPC here.

A group admits only whom its members invite: its first holder starts it and gets a join secret
(Lease.group_secret, random, the same for every member), and anyone joining the group while it
holds control must present it, or is refused with PermissionDeniedError (BAD_GROUP_SECRET). The
group, and its secret, end when its last member's lease does; the next first holder of that
name starts a new group with a new secret. The servicer never puts the secret in a ControlState.

A lease belongs to the identity that took it. When the server authenticates its callers (TLS),
the holder is the caller's identity (services.security.caller), not the request's operator_id,
and a lease id presented by anyone else is refused with PermissionDeniedError; only an admin may
release another's lease. Without authentication (plaintext on loopback) the holder is the
operator_id the client gives, as in the papers.

Time comes from a Clock (services/runtime/clock.py): lease deadlines, wait deadlines and the
reaper's period are all on its monotonic scale. A lease is valid up to its deadline and gone
after it: every call sweeps expired leases before it looks, and a reaper sweeps when nobody
calls, so waiters are promoted and `on_change` told. `on_change` is always called with the
manager's lock released (it may take locks of its own and call back in).
"""

from __future__ import annotations

import enum
import hmac
import secrets
import threading
import uuid
from collections import deque
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field

from services.runtime.clock import SYSTEM_CLOCK, Clock
from services.security.caller import Caller, current_caller
from services.security.roles import Role
from wire.errors import (
    AbortedError,
    DeadlineExceededError,
    FailedPreconditionError,
    InvalidArgumentError,
    NotFoundError,
    PermissionDeniedError,
    ResourceExhaustedError,
    RpcCancelledError,
)

DEFAULT_LEASE_S = 10.0  # outlives a short cut: see sessions.RESUME_WINDOW_S
MIN_LEASE_S, MAX_LEASE_S = 0.1, 60.0
MAX_WAIT_S = 3600.0
# Waiting callers at once, and each operator waits once: a waiting call holds a server thread,
# so a flood of waits must not take them all.
MAX_WAITERS = 16
REAPER_PERIOD_S = 0.05  # expired leases are noticed this fast even when nobody calls


class ControlMode(enum.Enum):
    EXCLUSIVE = 1
    COLLABORATIVE = 2


@dataclass
class Lease:
    lease_id: str
    operator_id: str
    mode: ControlMode
    group: str
    duration_s: float
    expires_at: float  # on the LockManager's clock.monotonic() scale
    identity: str | None = None  # the authenticated holder; None when nobody is authenticated
    # COLLABORATIVE: the group's join secret, the same for every member; "" for EXCLUSIVE.
    group_secret: str = field(default="", repr=False)


@dataclass
class _Waiter:
    operator_id: str
    mode: ControlMode
    group: str
    duration_s: float
    deadline: float  # clock.monotonic()
    identity: str | None = None
    group_secret: str = field(default="", repr=False)  # the one it presented
    granted: Lease | None = None
    refusal: PermissionDeniedError | None = None  # its turn came, but its group refused it
    abandoned: bool = False  # the caller went away while it waited
    ready: threading.Event = field(default_factory=threading.Event)


@dataclass(frozen=True)
class ControlView:
    """Holders and waiters, first in line first."""

    mode: ControlMode | None
    holders: tuple[Lease, ...]
    waiters: tuple[tuple[str, ControlMode, str, float], ...]  # operator, mode, group, deadline
    # (the waiters' deadlines and the holders' expires_at are on the manager's clock.monotonic())


class LockManager:
    """Leases on the control of one arm. `on_change(view, reason)` is told of every change."""

    def __init__(self, on_change: Callable[[ControlView, str], None] | None = None,
                 clock: Clock = SYSTEM_CLOCK):
        self._clock = clock
        self._lock = threading.Lock()
        self._holders: dict[str, Lease] = {}
        self._queue: list[_Waiter] = []
        self._on_change = on_change or (lambda view, reason: None)
        self._closed = threading.Event()
        threading.Thread(target=self._reap, name="lease-reaper", daemon=True).start()

    def close(self) -> None:
        self._closed.set()

    # -- requests ---------------------------------------------------------------------------

    def acquire(self, operator_id: str, mode: ControlMode, group: str = "", wait: bool = False,
                wait_timeout_s: float | None = None, lease_s: float = DEFAULT_LEASE_S,
                on_caller_gone: Callable[[Callable[[], None]], object] | None = None,
                group_secret: str = "") -> Lease:
        """Grant a lease now, or queue for one (wait=True), or fail with AbortedError. An
        authenticated caller holds it as its identity, whatever `operator_id` says. A waiting
        caller that goes away (`on_caller_gone(callback)` registers the callback: gRPC's
        context.add_callback) leaves the queue at once, and a lease granted as it left is
        released. Joining a COLLABORATIVE group that holds control takes its `group_secret`
        (PermissionDeniedError otherwise, at once, or when a waiter's turn comes)."""
        caller = current_caller()
        identity = caller.identity if caller is not None else None
        operator_id = identity or operator_id
        if not operator_id:
            raise InvalidArgumentError("operator_id is required: say who you are",
                                       reason="NO_OPERATOR")
        if not MIN_LEASE_S <= lease_s <= MAX_LEASE_S:
            raise InvalidArgumentError(f"lease must be {MIN_LEASE_S}..{MAX_LEASE_S} s",
                                       reason="BAD_LEASE")
        lease, waiter, holders, refusal = None, None, "", None
        with self._lock:
            expired = self._expire()
            if not self._admitted(mode, group, group_secret):
                refusal = self._not_invited(group, group_secret)
            elif not self._queue and self._compatible(mode, group):
                lease = self._grant(operator_id, mode, group, lease_s, identity)
            elif wait and any(w.operator_id == operator_id for w in self._queue):
                refusal = AbortedError(f"{operator_id} already waits for control: one wait at "
                                       "a time", reason="ALREADY_WAITING")
            elif wait and len(self._queue) >= MAX_WAITERS:
                refusal = ResourceExhaustedError(f"{MAX_WAITERS} callers already wait for "
                                                 "control: try later", reason="QUEUE_FULL")
            elif wait:
                deadline = (self._clock.monotonic()
                            + min(wait_timeout_s or MAX_WAIT_S, MAX_WAIT_S))
                waiter = _Waiter(operator_id, mode, group, lease_s, deadline, identity,
                                 group_secret)
                self._queue.append(waiter)
            else:
                holders = self._describe_holders()
        if lease is not None:
            self._notify([*expired, f"{operator_id} acquired {mode.name} control"])
            return lease
        if refusal is not None:
            self._notify(expired)
            raise refusal
        if waiter is None:
            self._notify(expired)
            raise AbortedError(f"control is held by {holders}; ask with wait=true to queue, or try "
                               "later", reason="CONTROL_HELD")
        self._notify([*expired, f"{operator_id} waits for {mode.name} control"])
        # False: the call already ended, so the callback would never run.
        if on_caller_gone is not None and on_caller_gone(lambda: self._abandon(waiter)) is False:
            self._abandon(waiter)
        if (self._clock.wait_until(waiter.ready, waiter.deadline)
                and waiter.granted and not waiter.abandoned):
            return waiter.granted
        with self._lock:
            if waiter.granted and not waiter.abandoned:  # granted just as the wait timed out
                return waiter.granted
            if waiter in self._queue:
                self._queue.remove(waiter)
            granted = waiter.granted
        if waiter.abandoned:
            if granted is not None:  # granted as the caller left: nobody would renew it
                self.release(granted.lease_id)
            self._notify([f"{operator_id} left the queue"])
            raise RpcCancelledError(f"{operator_id} went away while waiting for control",
                                    reason="CALLER_GONE")
        if waiter.refusal is not None:
            self._notify([f"{operator_id} was not admitted to group '{group}'"])
            raise waiter.refusal
        self._notify([f"{operator_id} gave up waiting"])
        raise DeadlineExceededError(f"control did not come free in time; held by "
                                    f"{self.describe_holders()}", reason="WAIT_TIMEOUT")

    def _abandon(self, waiter: _Waiter) -> None:
        """The waiting caller went away: wake its wait (a finished one ignores this)."""
        with self._lock:
            waiter.abandoned = True
        waiter.ready.set()

    def renew(self, lease_id: str) -> Lease:
        with self._lock:
            expired = self._expire()
            lease = self._holders.get(lease_id)
            refusal = _not_the_holder(lease, current_caller())
            if lease is not None and refusal is None:
                lease.expires_at = self._clock.monotonic() + lease.duration_s
        self._notify(expired)
        if refusal is not None:
            raise refusal
        if lease is None:
            raise NotFoundError("no such lease (it expired or was released): acquire control "
                                "again", reason="NO_LEASE")
        return lease

    def release(self, lease_id: str) -> None:
        with self._lock:
            expired = self._expire()
            lease = self._holders.get(lease_id)
            refusal = _not_the_holder(lease, current_caller(), admin_may=True)
            if lease is not None and refusal is None:
                del self._holders[lease_id]
                self._promote()
        if refusal is not None:
            self._notify(expired)
            raise refusal
        if lease is None:
            self._notify(expired)
            raise NotFoundError("no such lease (it expired or was released)", reason="NO_LEASE")
        self._notify([*expired, f"{lease.operator_id} released control"])

    def require(self, lease_id: str | None) -> Lease:
        """The caller's lease, renewed; FailedPreconditionError naming who holds control if none."""
        with self._lock:
            expired = self._expire()
            lease = self._holders.get(lease_id or "")
            refusal = _not_the_holder(lease, current_caller())
            if lease is not None and refusal is None:
                lease.expires_at = self._clock.monotonic() + lease.duration_s
            holders = self._describe_holders()
        self._notify(expired)
        if refusal is not None:
            raise refusal
        if lease is not None:
            return lease
        hint = "send the lease id from AcquireControl in the telerobot-lease-id metadata key"
        raise FailedPreconditionError(
            f"this call needs the control lock, held by {holders}; {hint}"
            if holders != "nobody" else f"this call needs the control lock: {hint}",
            reason="NO_CONTROL")

    def view(self) -> ControlView:
        with self._lock:
            expired = self._expire()
            view = self._view()
        self._notify(expired)
        return view

    def describe_holders(self) -> str:
        with self._lock:
            expired = self._expire()
            holders = self._describe_holders()
        self._notify(expired)
        return holders

    # -- internals (lock held) --------------------------------------------------------------

    def _compatible(self, mode: ControlMode, group: str) -> bool:
        if not self._holders:
            return True
        return mode == ControlMode.COLLABORATIVE and all(
            h.mode == ControlMode.COLLABORATIVE and h.group == group
            for h in self._holders.values())

    def _group_secret(self) -> str | None:
        """The join secret of the COLLABORATIVE group holding control, or None."""
        lease = next(iter(self._holders.values()), None)
        return lease.group_secret if lease and lease.mode == ControlMode.COLLABORATIVE else None

    def _admitted(self, mode: ControlMode, group: str, presented: str) -> bool:
        """False for a COLLABORATIVE request joining the group that holds control without its
        secret; True otherwise (joining nobody, or a request that conflicts anyway)."""
        secret = self._group_secret()
        joining = mode == ControlMode.COLLABORATIVE and self._compatible(mode, group)
        if secret is None or not joining:
            return True
        return hmac.compare_digest(presented.encode(), secret.encode())

    def _not_invited(self, group: str, presented: str) -> PermissionDeniedError:
        what = "a wrong group_secret" if presented else "no group_secret"
        return PermissionDeniedError(
            f"group '{group}' holds control ({self._describe_holders()}) and this request "
            f"has {what}: joining it takes the group_secret its members got from "
            "AcquireControl; ask one of them for it", reason="BAD_GROUP_SECRET")

    def _grant(self, operator_id: str, mode: ControlMode, group: str, lease_s: float,
               identity: str | None) -> Lease:
        secret = ""
        if mode == ControlMode.COLLABORATIVE:  # the group's, or a new group's
            secret = self._group_secret() or secrets.token_urlsafe(24)
        lease = Lease(uuid.uuid4().hex, operator_id, mode, group, lease_s,
                      self._clock.monotonic() + lease_s, identity, secret)
        self._holders[lease.lease_id] = lease
        return lease

    def _promote(self) -> None:
        """Grant waiters from the head of the queue while they fit; one whose group holds
        control without admitting it leaves the queue refused."""
        while self._queue and self._compatible(self._queue[0].mode, self._queue[0].group):
            waiter = self._queue.pop(0)
            if self._admitted(waiter.mode, waiter.group, waiter.group_secret):
                waiter.granted = self._grant(waiter.operator_id, waiter.mode, waiter.group,
                                             waiter.duration_s, waiter.identity)
            else:
                waiter.refusal = self._not_invited(waiter.group, waiter.group_secret)
            waiter.ready.set()

    def _expire(self) -> list[str]:
        """Drop the leases past their deadline (a lease is valid up to and including it),
        promote the waiters they blocked, and return the reasons to tell `on_change`."""
        now = self._clock.monotonic()
        expired = [lease for lease in self._holders.values() if lease.expires_at < now]
        for lease in expired:
            del self._holders[lease.lease_id]
        if expired:
            self._promote()
        return [f"{lease.operator_id}'s lease expired" for lease in expired]

    def _describe_holders(self) -> str:
        if not self._holders:
            return "nobody"
        leases = list(self._holders.values())
        names = ", ".join(f"'{lease.operator_id}'" for lease in leases)
        if leases[0].mode == ControlMode.EXCLUSIVE:
            return f"{names} (EXCLUSIVE)"
        return f"{names} (COLLABORATIVE, group '{leases[0].group}')"

    def _view(self) -> ControlView:
        holders = tuple(self._holders.values())
        return ControlView(holders[0].mode if holders else None, holders,
                           tuple((w.operator_id, w.mode, w.group, w.deadline)
                                 for w in self._queue))

    # -- notifications (lock NOT held) --------------------------------------------------------

    def _notify(self, reasons: Iterable[str]) -> None:
        """Tell `on_change` of each change, in order, with the view as it is when it is told
        (so the last one told shows the latest state). Leases found expired on the way are
        told after."""
        pending = deque(reasons)
        while pending:
            reason = pending.popleft()
            with self._lock:
                pending.extend(self._expire())
                view = self._view()
            self._on_change(view, reason)

    def _reap(self) -> None:
        while not self._clock.wait(self._closed, REAPER_PERIOD_S):
            with self._lock:
                expired = self._expire()
            self._notify(expired)


def _not_the_holder(lease: Lease | None, caller: Caller | None,
                    admin_may: bool = False) -> PermissionDeniedError | None:
    """The refusal for an authenticated caller presenting another identity's lease; None when
    the caller may use it."""
    if (lease is None or caller is None or lease.identity is None
            or caller.identity == lease.identity or (admin_may and caller.role >= Role.ADMIN)):
        return None
    return PermissionDeniedError(
        f"this lease belongs to {lease.identity!r}, not to {caller.identity!r}: acquire "
        "control as yourself" + (" (an admin may release it)" if admin_may else ""),
        reason="NOT_YOUR_LEASE")
