"""What the console's WebSockets share: the opening handshake (subprotocol, bearer token) and
how a gRPC status travels in a close frame.

A browser cannot set headers on a WebSocket: its bearer token rides as a second offered
subprotocol, "bearer.<token>" (never echoed back). A socket that ends with a gRPC status
closes with 1000 for OK, or 4000 + the status code, and the status message as its reason.
"""

from __future__ import annotations

import grpc

from services.web_console.bridge import Upstream

TOKEN_SUBPROTOCOL_PREFIX = "bearer."
CLOSE_NORMAL = 1000
CLOSE_UNSUPPORTED_DATA = 1003
CLOSE_POLICY = 1008
CLOSE_TOO_BIG = 1009
CLOSE_GRPC_BASE = 4000  # + the gRPC status code
_MAX_REASON_BYTES = 120  # a close frame's reason holds 123 bytes


def close_code(code: grpc.StatusCode) -> int:
    """The WebSocket close code that reports a gRPC status."""
    return CLOSE_NORMAL if code is grpc.StatusCode.OK else CLOSE_GRPC_BASE + code.value[0]


def reason(text: str) -> str:
    """`text` cut to what a close frame's reason holds (whole characters)."""
    return text.encode()[:_MAX_REASON_BYTES].decode(errors="ignore")


async def accept(scope, receive, send, upstream: Upstream, subprotocol: str
                 ) -> list[tuple[str, str]] | None:
    """Open a browser's socket that offers `subprotocol`: the gRPC metadata its calls carry (its
    bearer token), or None when it was refused and closed (no such subprotocol: before the
    handshake completes, so the browser sees a failed connection; no token where one is
    needed, or a console that refuses every call: UNAUTHENTICATED after it)."""
    message = await receive()
    if message["type"] != "websocket.connect":
        return None
    offered = list(scope.get("subprotocols") or ())
    if subprotocol not in offered:
        await send({"type": "websocket.close", "code": CLOSE_POLICY})
        return None
    tokens = [p[len(TOKEN_SUBPROTOCOL_PREFIX):] for p in offered
              if p.startswith(TOKEN_SUBPROTOCOL_PREFIX)]
    await send({"type": "websocket.accept", "subprotocol": subprotocol})
    refusal = upstream.refusal
    if upstream.needs_token and not tokens:
        # Said here rather than by the DecisionServer: its refusal of a call with no
        # credentials comes before it reads a message, and grpc.aio reports a write racing
        # that refusal as INTERNAL ("Internal error from Core"), not UNAUTHENTICATED.
        refusal = "no bearer token: offer the subprotocol bearer.<token> (the page's token field)"
    if refusal:
        await send({"type": "websocket.close",
                    "code": close_code(grpc.StatusCode.UNAUTHENTICATED),
                    "reason": reason(refusal)})
        return None
    return [("authorization", f"Bearer {tokens[0]}")] if tokens else []


async def refuse(receive, send, code: grpc.StatusCode, why: str) -> None:
    """Open a browser's socket and close it at once with a gRPC status (the page then shows
    why, where a refused handshake would show only a failed connection)."""
    if (await receive())["type"] != "websocket.connect":
        return
    await send({"type": "websocket.accept"})
    await send({"type": "websocket.close", "code": close_code(code), "reason": reason(why)})
