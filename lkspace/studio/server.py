"""Serving the studio: a socket bound before uvicorn starts (so port 0 names its real port), the URL printed.

uvicorn stops on Ctrl-C or SIGTERM after answering what is in flight (at most 2 s), then
re-raises the signal: the command line turns it into exit status 130 (143), as for every
command.  The workers are stopped as the shutdown begins, so a request waiting for one
(a relaxation, an export) is answered at once and the studio exits within a second.  uvicorn logs only critical events: every endpoint answers its own errors as
JSON, and a measurement cut short by Ctrl-C is no error worth a traceback.
"""

from __future__ import annotations

import socket
import threading
from collections.abc import Callable

from ..errors import UsageError
from .app import Studio, create_app

LOCAL = "127.0.0.1"


def bind(host: str, port: int) -> socket.socket:
    """Return a listening TCP socket on ``host:port`` (port 0: a free one)."""
    family = socket.AF_INET6 if ":" in host else socket.AF_INET
    sock = socket.socket(family, socket.SOCK_STREAM)
    sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
    try:
        sock.bind((host, port))
    except OSError as exc:
        sock.close()
        raise UsageError(f"cannot listen on {host}:{port}: {exc.strerror or exc}") from None
    sock.listen(128)
    sock.set_inheritable(True)
    return sock


def url_of(sock: socket.socket) -> str:
    """Return the http URL of a bound socket (a wildcard host shown as 127.0.0.1)."""
    host, port = sock.getsockname()[:2]
    if host in ("0.0.0.0", "::"):
        host = LOCAL
    return f"http://[{host}]:{port}/" if ":" in host else f"http://{host}:{port}/"


def serve(studio: Studio, host: str = LOCAL, port: int = 8765, on_ready: Callable[[str], None] | None = None) -> None:
    """Serve ``studio`` until interrupted; ``on_ready(url)`` is called once the server listens."""
    import uvicorn

    sock = bind(host, port)
    url = url_of(sock)
    config = uvicorn.Config(create_app(studio), log_level="critical", lifespan="off", timeout_graceful_shutdown=2)
    server = uvicorn.Server(config)
    if on_ready is not None:

        def announce() -> None:
            while not server.started and not server.should_exit:
                threading.Event().wait(0.02)
            if server.started:
                on_ready(url)

        threading.Thread(target=announce, daemon=True).start()

    def stop_workers() -> None:
        while not server.should_exit:
            threading.Event().wait(0.05)
        studio.jobs.shutdown()

    threading.Thread(target=stop_workers, daemon=True).start()
    try:
        server.run(sockets=[sock])
    finally:
        studio.jobs.shutdown()
        sock.close()


def start_in_thread(studio: Studio, host: str = LOCAL, port: int = 0) -> tuple[str, Callable[[], None]]:
    """Serve ``studio`` from a background thread (tests, benchmarks); return ``(url, stop)``."""
    import uvicorn

    sock = bind(host, port)
    config = uvicorn.Config(create_app(studio), log_level="critical", lifespan="off", timeout_graceful_shutdown=1)
    server = uvicorn.Server(config)
    thread = threading.Thread(target=server.run, kwargs={"sockets": [sock]}, name="studio", daemon=True)
    thread.start()
    while not server.started:
        if not thread.is_alive():
            raise RuntimeError("the studio server did not start")
        threading.Event().wait(0.02)

    def stop() -> None:
        server.should_exit = True
        thread.join(timeout=5)
        studio.jobs.shutdown()
        sock.close()

    return url_of(sock), stop
