"""DecisionServer.Teleoperate for browsers: a WebSocket whose binary messages are
TeleoperateRequest (browser to station) and TeleoperateResponse (station to browser), each one
protobuf message, forwarded as they are on one gRPC stream.

The stream lives exactly as long as the socket: a tab that closes, reloads or loses its link
ends the socket, the gateway cancels the stream, and the DecisionServer's watchdog holds the
arm (a stream that ends is a hold, as for any client). A tab that stays open but goes quiet
(hidden, frozen) trips the watchdog by its timeout. When the DecisionServer ends the stream,
the socket closes with 1000 for OK, or 4000 + the gRPC status code (4009 FAILED_PRECONDITION,
4010 ABORTED: the lock was lost, ...) and the status message as its reason.
"""

from __future__ import annotations

import asyncio
import contextlib
import logging

import grpc

from services.web_console.bridge import Upstream
from services.web_console.sockets import (
    CLOSE_NORMAL,
    CLOSE_TOO_BIG,
    CLOSE_UNSUPPORTED_DATA,
    accept,
    close_code,
    reason,
)

log = logging.getLogger(__name__)

PATH = "/ws/teleoperate"
METHOD = "/telerobot.v1.DecisionServer/Teleoperate"
SUBPROTOCOL = "telerobot.v1.teleoperate"  # the lease rides in the init message
MAX_MESSAGE_BYTES = 64 * 1024
# A session the browser ended itself has this long to end at the DecisionServer, then it is
# cancelled.
CLEAN_END_TIMEOUT_S = 2.0


async def serve(scope, receive, send, upstream: Upstream) -> None:
    """One browser's Teleoperate session, an ASGI websocket scope."""
    metadata = await accept(scope, receive, send, upstream, SUBPROTOCOL)
    if metadata is None:
        return
    call = upstream.channel.stream_stream(METHOD)(metadata=metadata)
    peer = scope.get("client")

    async def browser_to_station() -> tuple[int, str] | None:
        """Until the browser leaves (None) or breaks the rules (the close to send). A browser
        that ends the session itself (close code 1000) half-closes the stream, so the
        DecisionServer sees a clean end; any other departure cancels it (a broken link)."""
        while True:
            message = await receive()
            if message["type"] == "websocket.disconnect":
                if message.get("code") == CLOSE_NORMAL:
                    with contextlib.suppress(grpc.aio.AioRpcError, asyncio.InvalidStateError,
                                             TimeoutError):  # then cancelled, as a broken link
                        await call.done_writing()
                        await asyncio.wait_for(asyncio.shield(outbound), CLEAN_END_TIMEOUT_S)
                return None
            data = message.get("bytes")
            if data is None:
                return (CLOSE_UNSUPPORTED_DATA,
                        "send binary TeleoperateRequest messages, not text")
            if len(data) > MAX_MESSAGE_BYTES:
                return CLOSE_TOO_BIG, f"a message is at most {MAX_MESSAGE_BYTES} bytes"
            try:
                await call.write(data)
            except (grpc.aio.AioRpcError, asyncio.InvalidStateError):
                # The stream ended under the write: close as station_to_browser reports it.
                return await asyncio.shield(outbound)

    async def station_to_browser() -> tuple[int, str]:
        try:
            async for response in call:
                await send({"type": "websocket.send", "bytes": response})
        except grpc.aio.AioRpcError as error:
            return close_code(error.code()), error.details() or ""
        return CLOSE_NORMAL, "the station ended the session"

    inbound = asyncio.ensure_future(browser_to_station())
    outbound = asyncio.ensure_future(station_to_browser())
    try:
        done, _ = await asyncio.wait({inbound, outbound}, return_when=asyncio.FIRST_COMPLETED)
        if inbound in done:
            close = inbound.result()
            call.cancel()  # the stream ends now: the DecisionServer holds the arm
            outbound.cancel()
            if close is not None:
                await send({"type": "websocket.close", "code": close[0],
                            "reason": reason(close[1])})
            log.info("teleoperate from %s ended by the browser%s", peer,
                     f" ({close[1]})" if close else "")
        else:
            code, why = outbound.result()
            inbound.cancel()
            with contextlib.suppress(Exception):  # the browser may be gone already
                await send({"type": "websocket.close", "code": code, "reason": reason(why)})
            log.info("teleoperate from %s ended by the station: %d %s", peer, code, why)
    finally:
        call.cancel()
        for task in (inbound, outbound):
            task.cancel()
