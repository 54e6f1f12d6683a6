"""The studio's guard: a pure ASGI middleware in front of every route (docs/studio-api.md).

* **Host** must name the server as the browser reached it -- ``127.0.0.1:PORT``,
  ``localhost:PORT``, ``[::1]:PORT`` or the bound host -- on every request, static files
  included: a page of another site that rebinds its DNS name to 127.0.0.1 sends its own name
  and is refused (DNS rebinding).
* **Origin**, when the browser sends one, must be ``http://`` one of those hosts: no other
  site's page may call the API (cross-site requests).
* **Token**: every ``/api/*`` request carries the session token in ``X-MatLoom-Token`` (or, for
  a ``GET`` -- downloads and ``EventSource`` streams, which cannot set headers -- in the query
  ``?token=``). Compared in constant time.
* **Body cap**: a body over :data:`~matloom.studio.protocol.MAX_BODY` is refused with 413
  before the route runs (the body is read here, at most that many bytes, and handed on).

Refusals are ``{"error": "..."}`` with 403 (or 413); nothing else of the app runs for them.
"""

from __future__ import annotations

import hmac
import json
import secrets
from collections.abc import Awaitable, Callable, MutableMapping
from typing import Any
from urllib.parse import parse_qs

from matloom.studio.protocol import MAX_BODY

Scope = MutableMapping[str, Any]
Message = MutableMapping[str, Any]
Receive = Callable[[], Awaitable[Message]]
Send = Callable[[Message], Awaitable[None]]
ASGIApp = Callable[[Scope, Receive, Send], Awaitable[None]]

#: The header carrying the token on API calls.
TOKEN_HEADER = "x-matloom-token"
#: Names of the loopback interface a browser may use for the server.
LOOPBACK_NAMES = ("127.0.0.1", "localhost", "[::1]")
#: Response headers of every reply: no sniffing, no referrer (the page URL holds the token),
#: not framed by another site.
SAFE_HEADERS: tuple[tuple[bytes, bytes], ...] = (
    (b"x-content-type-options", b"nosniff"),
    (b"referrer-policy", b"no-referrer"),
    (b"x-frame-options", b"DENY"),
)


def new_token() -> str:
    """A fresh session token: 32 random bytes, url-safe base64."""
    return secrets.token_urlsafe(32)


def host_names(host: str) -> tuple[str, ...]:
    """The names a browser may use for a server bound to ``host`` (IPv6 in brackets)."""
    bound = f"[{host}]" if ":" in host and not host.startswith("[") else host
    return tuple(dict.fromkeys((*LOOPBACK_NAMES, bound.lower())))


class Guard:
    """The ASGI middleware (see the module docstring). ``port`` is the port the server listens
    on (known before the app is built: the server binds its socket first)."""

    def __init__(self, app: ASGIApp, *, token: str, host: str, port: int) -> None:
        self.app = app
        self.token = token.encode()
        names = host_names(host)
        self.hosts = frozenset(f"{n}:{port}" for n in names)
        self.origins = frozenset(f"http://{n}:{port}" for n in names)

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] == "websocket":  # the studio has none: refuse every one
            await send({"type": "websocket.close", "code": 1008})
            return
        if scope["type"] != "http":  # lifespan
            await self.app(scope, receive, send)
            return
        headers = _headers(scope)
        problem = self._refusal(scope, headers)
        if problem is not None:
            await _reply(send, 403, problem)
            return
        body = await _read_capped(receive, headers)
        if body is None:
            await _reply(send, 413, f"the request body is over {MAX_BODY:,} bytes")
            return
        await self.app(scope, _replay(body, receive), _with_safe_headers(send))

    def _refusal(self, scope: Scope, headers: dict[str, str]) -> str | None:
        host = headers.get("host", "").lower()
        if host not in self.hosts:
            return f"refused: Host {host or '(none)'!r} is not this studio's address"
        origin = headers.get("origin")
        if origin is not None and origin.lower() not in self.origins:
            return f"refused: requests from {origin!r} are not allowed"
        path = scope.get("path", "")
        if path == "/api" or path.startswith("/api/"):
            given = headers.get(TOKEN_HEADER)
            if given is None and scope.get("method") == "GET":
                query = parse_qs(scope.get("query_string", b"").decode("latin-1"))
                given = (query.get("token") or [None])[0]
            if given is None:
                return "refused: the session token is missing"
            if not hmac.compare_digest(given.encode(), self.token):
                return "refused: wrong session token"
        return None


def _headers(scope: Scope) -> dict[str, str]:
    """The request headers, lower-case names; the first value of each."""
    out: dict[str, str] = {}
    for name, value in scope.get("headers", ()):
        out.setdefault(name.decode("latin-1").lower(), value.decode("latin-1"))
    return out


async def _read_capped(receive: Receive, headers: dict[str, str]) -> bytes | None:
    """The whole body, or None when it is over :data:`MAX_BODY` (announced or sent)."""
    try:
        if int(headers.get("content-length", "0")) > MAX_BODY:
            return None
    except ValueError:
        return None
    chunks: list[bytes] = []
    size = 0
    while True:
        message = await receive()
        if message["type"] == "http.disconnect":
            break
        chunk = message.get("body", b"")
        size += len(chunk)
        if size > MAX_BODY:
            return None
        chunks.append(chunk)
        if not message.get("more_body", False):
            break
    return b"".join(chunks)


def _replay(body: bytes, receive: Receive) -> Receive:
    """A ``receive`` that gives ``body`` once, then waits for the client's disconnect."""
    sent = [False]

    async def replay() -> Message:
        if not sent[0]:
            sent[0] = True
            return {"type": "http.request", "body": body, "more_body": False}
        return await receive()

    return replay


def _with_safe_headers(send: Send) -> Send:
    async def wrapped(message: Message) -> None:
        if message["type"] == "http.response.start":
            present = {name.lower() for name, _ in message.get("headers", [])}
            extra = [(n, v) for n, v in SAFE_HEADERS if n not in present]
            message["headers"] = [*message.get("headers", []), *extra]
        await send(message)

    return wrapped


async def _reply(send: Send, status: int, message: str) -> None:
    body = json.dumps({"error": message}).encode()
    await send(
        {
            "type": "http.response.start",
            "status": status,
            "headers": [
                (b"content-type", b"application/json"),
                (b"content-length", str(len(body)).encode()),
                (b"cache-control", b"no-store"),
                *SAFE_HEADERS,
            ],
        }
    )
    await send({"type": "http.response.body", "body": body})
