"""Serve the studio: bind the socket (127.0.0.1, port 0 = any free one), build the app for
that exact address, print the URL with its token, open the browser, run uvicorn until Ctrl-C.

The socket is bound before the app is made, so the Host/Origin checks know the real port; the
engine session is made here (backend settings from the environment, the numba kernels
compiled in the background on first use as the CLI does) and is the process's default session
while the server runs, so every engine call of the studio shares its lock.
"""

from __future__ import annotations

import socket
import sys
import threading
import webbrowser
from collections.abc import Callable
from dataclasses import dataclass

from matloom.studio.workspace import Workspace

LOOPBACK = ("127.0.0.1", "localhost", "::1")


@dataclass(frozen=True)
class Address:
    host: str
    port: int

    @property
    def url_host(self) -> str:
        return f"[{self.host}]" if ":" in self.host else self.host

    def url(self, token: str) -> str:
        return f"http://{self.url_host}:{self.port}/?token={token}"


def bind(host: str, port: int) -> socket.socket:
    """A listening TCP socket on ``host:port`` (``port`` 0: a free port); OSError when taken."""
    family = socket.AF_INET6 if ":" in host else socket.AF_INET
    sock = socket.socket(family, socket.SOCK_STREAM)
    sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
    try:
        sock.bind((host, port))
        sock.listen(128)
    except OSError:
        sock.close()
        raise
    sock.set_inheritable(True)
    return sock


def serve(
    workspace: Workspace,
    *,
    host: str = "127.0.0.1",
    port: int = 0,
    open_browser: bool = True,
    say: Callable[[str], None] = lambda line: print(line, file=sys.stderr),
    fragment: str = "",
) -> None:
    """Run the studio on ``workspace`` until interrupted (see the module docstring)."""
    import uvicorn

    from matloom.engine.session import Session, use_session
    from matloom.runtime.cold_start import background_compile
    from matloom.studio.app import create_app
    from matloom.studio.security import new_token

    sock = bind(host, port)
    address = Address(host, sock.getsockname()[1])
    token = new_token()
    session = Session.from_env(cold_start=background_compile())
    app = create_app(workspace, token, port=address.port, host=host, session=session, warm=True)
    if host not in LOOPBACK:
        say(
            f"warning: serving on {host}: anyone who can reach {host} and has the URL (with "
            "its token) can use the studio"
        )
    url = address.url(token) + (f"#{fragment}" if fragment else "")
    say(
        f"workspace: {workspace.root}"
        + (f" (opened {workspace.opened})" if workspace.opened else "")
    )
    say(f"MatLoom studio at {url}")
    say("press Ctrl-C to stop")
    config = uvicorn.Config(app, log_level="warning", lifespan="on", access_log=False)
    server = uvicorn.Server(config)
    if open_browser:
        threading.Timer(0.5, _open, args=(url,)).start()
    try:
        with use_session(session):
            server.run(sockets=[sock])
    except KeyboardInterrupt:  # uvicorn stops on Ctrl-C, then passes the signal on
        pass
    finally:
        sock.close()
    say("studio stopped")


def _open(url: str) -> None:
    try:
        webbrowser.open(url)
    except Exception:  # noqa: BLE001 - no browser: the printed URL is enough
        pass
