"""A page that DNS re-binds its own name to this host (evil.localhost -> 127.0.0.1) reaches
the console with its own name in Host and, as a same-origin page, a matching Origin: every
route refuses it. In-process: the ASGI app called as uvicorn calls it, upstream never reached."""

from __future__ import annotations

import asyncio
import concurrent.futures

import pytest

from services.web_console import sockets, teleoperate
from services.web_console.app import ConsoleApp
from services.web_console.bridge import Upstream

PORT = 50080
LEASE_CALL = "/telerobot.v1.DecisionServer/AcquireControl"


# An upstream with no channel, whose every call the bridge refuses with this message: a request
# that shows it got as far as the station's side of the console.
REACHED = "reached the bridge"


class NoChannel:
    """A channel no call may use: the refusal above answers first."""

    def __getattr__(self, kind: str):
        def method(path: str, **_):
            def called(*args, **kwargs):
                raise AssertionError(f"{path} was called on the station")
            return called
        return method


def console(allowed_hosts=()) -> ConsoleApp:
    return ConsoleApp(Upstream(NoChannel(), NoChannel(), refusal=REACHED), "none",
                      allowed_hosts)


def call(app, kind: str, path: str, host: str, origin: str | None, method: str = "POST",
         body: bytes = b"{}"):
    """Drive one request through the app; returns the messages it sent."""
    headers = [(b"host", host.encode()), (b"content-type", b"application/json")]
    if origin is not None:
        headers.append((b"origin", origin.encode()))
    scope = {"type": kind, "path": path, "method": method, "headers": headers,
             "query_string": b"", "scheme": "http", "http_version": "1.1",
             "server": ("127.0.0.1", PORT), "client": ("127.0.0.1", 40000), "root_path": "",
             "raw_path": path.encode(), "subprotocols": [teleoperate.SUBPROTOCOL]}
    incoming = ([{"type": "websocket.connect"}] if kind == "websocket"
                else [{"type": "http.request", "body": body, "more_body": False}])
    sent = []

    async def receive():
        return incoming.pop(0) if incoming else {"type": "http.disconnect"}

    async def send(message):
        sent.append(message)

    # A loop of its own, on a thread of its own: a session's Playwright may run one here.
    with concurrent.futures.ThreadPoolExecutor(1) as thread:
        thread.submit(asyncio.run, app(scope, receive, send)).result()
    return sent


def status(sent) -> int:
    return next(m["status"] for m in sent if m["type"] == "http.response.start")


EVIL = f"evil.localhost:{PORT}"


@pytest.mark.parametrize("path,method", [(LEASE_CALL, "POST"), ("/", "GET"),
                                         ("/app.js", "GET")])
def test_a_rebound_name_is_refused_on_every_http_route(path, method):
    sent = call(console(), "http", path, EVIL, f"http://{EVIL}", method)
    assert status(sent) == 403
    assert b"evil.localhost" in sent[-1]["body"] and REACHED.encode() not in sent[-1]["body"]


def test_a_rebound_name_cannot_open_the_teleoperate_socket():
    sent = call(console(), "websocket", teleoperate.PATH, EVIL, f"http://{EVIL}")
    assert sent == [{"type": "websocket.close", "code": sockets.CLOSE_POLICY}]


@pytest.mark.parametrize("host", [f"127.0.0.1:{PORT}", f"localhost:{PORT}", f"[::1]:{PORT}",
                                  f"10.0.0.2:{PORT}"])
def test_an_address_or_localhost_is_served(host):
    assert status(call(console(), "http", "/", host, None, "GET")) == 200


def test_a_name_the_operator_allowed_is_served_and_no_other():
    app = console(["station.lab"])
    assert status(call(app, "http", "/", f"station.lab:{PORT}", None, "GET")) == 200
    assert status(call(app, "http", "/", f"Station.LAB:{PORT}", None, "GET")) == 200
    assert status(call(app, "http", "/", f"evil.lab:{PORT}", None, "GET")) == 403


def test_a_page_of_another_site_cannot_call_the_station():
    """A cross-site page's POST (text/plain passes without a CORS preflight) carries its
    Origin: refused before the station is reached."""
    sent = call(console(), "http", LEASE_CALL, f"127.0.0.1:{PORT}", "http://evil.example")
    assert status(sent) == 403 and REACHED.encode() not in sent[-1]["body"]


@pytest.mark.parametrize("origin", [None, f"http://127.0.0.1:{PORT}"])
def test_a_program_or_the_consoles_own_page_reaches_the_bridge(origin):
    """buf curl and the Node client send no Origin, the console's page its own: the call goes
    on to the bridge (whose upstream here refuses every call, saying so)."""
    sent = call(console(), "http", LEASE_CALL, f"127.0.0.1:{PORT}", origin)
    assert REACHED.encode() in b"".join(m.get("body", b"") for m in sent)
