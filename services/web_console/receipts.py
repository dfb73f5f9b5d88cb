"""StereoCamera.ReportReceipt for browsers: a WebSocket whose binary messages are
ReportReceiptRequest, each forwarded to the DecisionServer as one ReportReceipt call, at once and
without waiting for the previous one.

Why not the Connect endpoint the bridge serves for it: a stream with receipts wants one receipt
per pair as the pair arrives (30 a second), each reaching the sender about half a round trip
later, since the sender times the path by them. Over HTTP/1.1 a browser opens at most six
connections to a host, and the page's server streams (state, force, events, video) hold four:
receipts then wait in the browser's queue for one of the other two, one round trip each, and
the sender reads that wait as a full path (measured through a 183 ms round trip: receipts took
470 ms, p95 1.3 s, and the stream fell to 11 pairs/s at the lowest bitrate). One WebSocket
carries them all, in order, with no connection to wait for.

Nothing comes back: a receipt is fire and forget (the pair says the sender's target). A receipt
for a stream that has ended (NOT_FOUND) is dropped; a refusal that every later receipt would
get too (no token, a role too low) closes the socket with 4000 + the gRPC code, as
/ws/teleoperate does, and the page reports its receipts over Connect instead.
"""

from __future__ import annotations

import asyncio
import logging

import grpc
from google.protobuf.message import DecodeError

from services.web_console.bridge import Upstream
from services.web_console.sockets import (
    CLOSE_TOO_BIG,
    CLOSE_UNSUPPORTED_DATA,
    accept,
    close_code,
    reason,
)
from telerobot.v1 import stereo_camera_pb2 as pb

log = logging.getLogger(__name__)

PATH = "/ws/receipts"
METHOD = "/telerobot.v1.StereoCamera/ReportReceipt"
SUBPROTOCOL = "telerobot.v1.receipts"
MAX_MESSAGE_BYTES = 1024  # a receipt is under 60 bytes
TIMEOUT_S = 5.0  # each ReportReceipt call's deadline
# Receipts forwarded and not yet answered; more waits (the socket then stops being read, and
# the browser's sends back up): the DecisionServer answers one in about a millisecond.
MAX_IN_FLIGHT = 16
# Errors every later receipt on this socket would get as well: the socket closes.
_FATAL = (grpc.StatusCode.UNAUTHENTICATED, grpc.StatusCode.PERMISSION_DENIED,
          grpc.StatusCode.UNIMPLEMENTED)


async def serve(scope, receive, send, upstream: Upstream) -> None:
    """One browser's receipts, an ASGI websocket scope."""
    metadata = await accept(scope, receive, send, upstream, SUBPROTOCOL)
    if metadata is None:
        return
    call = upstream.stereo_channel.unary_unary(
        METHOD, request_serializer=pb.ReportReceiptRequest.SerializeToString,
        response_deserializer=pb.ReportReceiptResponse.FromString)
    room = asyncio.Semaphore(MAX_IN_FLIGHT)
    fatal: asyncio.Future[tuple[int, str]] = asyncio.get_running_loop().create_future()
    pending: set[asyncio.Task] = set()

    async def forward(request: pb.ReportReceiptRequest) -> None:
        try:
            await call(request, metadata=metadata, timeout=TIMEOUT_S)
        except grpc.aio.AioRpcError as error:
            if error.code() in _FATAL and not fatal.done():
                fatal.set_result((close_code(error.code()), error.details() or ""))
            else:  # NOT_FOUND: the stream ended; others: this receipt is lost, the next counts
                log.debug("receipt for %s: %s %s", request.stream_id, error.code().name,
                          error.details())
        finally:
            room.release()

    async def browser() -> tuple[int, str] | None:
        while True:
            message = await receive()
            if message["type"] == "websocket.disconnect":
                return None
            data = message.get("bytes")
            if data is None:
                return CLOSE_UNSUPPORTED_DATA, "send binary ReportReceiptRequest messages"
            if len(data) > MAX_MESSAGE_BYTES:
                return CLOSE_TOO_BIG, f"a receipt is at most {MAX_MESSAGE_BYTES} bytes"
            try:
                request = pb.ReportReceiptRequest.FromString(data)
            except DecodeError:
                return CLOSE_UNSUPPORTED_DATA, "not a ReportReceiptRequest"
            await room.acquire()
            task = asyncio.ensure_future(forward(request))
            pending.add(task)
            task.add_done_callback(pending.discard)

    reading = asyncio.ensure_future(browser())
    try:
        await asyncio.wait({reading, fatal}, return_when=asyncio.FIRST_COMPLETED)
        close = fatal.result() if fatal.done() else reading.result()
        if close is not None:
            await send({"type": "websocket.close", "code": close[0],
                        "reason": reason(close[1])})
    finally:
        reading.cancel()
        for task in pending:
            task.cancel()
