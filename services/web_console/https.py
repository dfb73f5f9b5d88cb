"""The console over HTTPS: which certificate it serves, and a renewed one taken without a restart.

With the station's TLS directory (TELEROBOT_TLS_DIR) holding the console's own certificate and
key, `web_console.pem` and `web_console.key` (a server certificate of the station's CA whose
names are those browsers reach the console by), the console serves HTTPS, and may then listen
beyond loopback: browsers sign in with bearer tokens, which the DecisionServer checks. Without
them it serves HTTP, on loopback unless --allow-plaintext-network.

This module imports nothing heavy: the launcher asks it how to reach the console.
"""

from __future__ import annotations

import logging
import os
import ssl
from pathlib import Path

log = logging.getLogger("web_console")

CERTIFICATE_NAME = "web_console"
ALPN = ["http/1.1"]  # uvicorn's h11 speaks HTTP/1.1 only


def certificate_files(tls_dir: str | os.PathLike | None) -> tuple[Path, Path] | None:
    """The console's certificate and key in `tls_dir`, or None when it has not both."""
    if not tls_dir:
        return None
    directory = Path(tls_dir)
    files = directory / f"{CERTIFICATE_NAME}.pem", directory / f"{CERTIFICATE_NAME}.key"
    return files if all(path.is_file() for path in files) else None


def issue_command(tls_dir: str | os.PathLike) -> str:
    """The command that issues the console's certificate (with every other, keeping the CA)
    from the development CA in `tls_dir`."""
    return (f"python -m services.security.pki --dir {tls_dir} --host <each name or address "
            "browsers use>")


class RenewingCertificate:
    """The TLS context the console serves, which takes a renewed certificate from the next
    connection on, as the station's gRPC servers do.

    OpenSSL asks `_on_hello` at every handshake's ClientHello (with a server name or without:
    a browser sends none for an IP address). It compares the two files' stat with the last
    loaded pair's; when they changed, it loads them into a new context and serves that one
    from then on. A pair that does not load (a key and certificate that do not match yet: a
    renewal half done) is not taken: the last good one serves on, and the next handshake tries
    again. Open connections keep theirs."""

    def __init__(self, certificate: Path, key: Path):
        self.files = (certificate, key)
        self._stamp = self._stat()
        self.context = self._context()  # the one the server was given; it also serves first
        self.context.sni_callback = self._on_hello
        self._serving = self.context
        self._refused: tuple | None = None

    def _context(self) -> ssl.SSLContext:
        context = ssl.SSLContext(ssl.PROTOCOL_TLS_SERVER)
        context.minimum_version = ssl.TLSVersion.TLSv1_2
        context.set_alpn_protocols(ALPN)
        context.load_cert_chain(*self.files)  # ssl.SSLError, OSError: not taken
        return context

    def _stat(self) -> tuple:
        try:
            stats = [path.stat() for path in self.files]
        except OSError:
            return ()
        return tuple((s.st_ino, s.st_size, s.st_mtime_ns) for s in stats)

    def current(self) -> ssl.SSLContext:
        """The context for a new connection: a renewed pair once it loads, else the last."""
        stamp = self._stat()
        if stamp and stamp != self._stamp:
            try:
                context = self._context()
            except (OSError, ssl.SSLError, ValueError) as exc:
                if stamp != self._refused:
                    log.warning("the console's certificate files changed but do not load (%s);"
                                " serving the previous certificate", exc)
                    self._refused = stamp
                return self._serving
            self._stamp, self._serving = stamp, context
            log.info("serving the renewed certificate %s", self.files[0])
        return self._serving

    def _on_hello(self, connection: ssl.SSLObject, _server_name, _context) -> None:
        try:
            serving = self.current()
            if connection.context is not serving:
                connection.context = serving
        except Exception:  # never fail a handshake for this: the last context serves
            log.exception("choosing the console's certificate failed")
