"""A real HTTP server on 127.0.0.1 speaking the Chat Completions protocol with scripted replies.

``POST /v1/chat/completions`` takes the JSON request and answers with a JSON completion whose
content comes from a responder function. Faults can be queued to hit the next requests: an HTTP
status (429, 500, ..., optionally with the request headers echoed in the error body), a delay
(to trigger client timeouts), a dropped connection, a hang that blocks until
:meth:`ChatServer.release` (to kill a client mid-run), an HTTP-200 body given verbatim (malformed
replies), a reply trickled a few bytes at a time (headers, body, or an unrequested event
stream), or a huge reply streamed until the client stops reading (the bytes the server managed
to send are counted in :attr:`ServerState.sent`).
"""

from __future__ import annotations

import json
import threading
import time
from collections import deque
from collections.abc import Callable
from dataclasses import dataclass, field
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from typing import Any

Responder = Callable[[dict[str, Any]], str]


@dataclass
class Fault:
    """What to do instead of (or before) answering one request."""

    status: int | None = None
    #: With ``status``: quote the request's headers (Authorization included) in the error body,
    #: as careless servers do.
    echo_headers: bool = False
    delay: float = 0.0
    drop: bool = False
    hang: bool = False
    #: Answer HTTP 200 with exactly these bytes as the body (a malformed reply).
    body: bytes | None = None
    content_type: str = "application/json"
    #: Send the answer one byte at a time, this many seconds apart ...
    trickle_s: float = 0.0
    #: ... for at most this long, then close the connection (bounds the test's server side).
    trickle_for_s: float = 8.0
    #: What is trickled: "body" (headers at once), "headers" (the status line and headers too)
    #: or "events" (an unrequested text/event-stream of chunks that never ends).
    trickle: str = "body"
    #: Stream a valid completion whose content is this many characters of "a", until the
    #: client stops reading.
    huge_chars: int = 0


@dataclass
class ServerState:
    responder: Responder
    requests: list[dict[str, Any]] = field(default_factory=list)
    headers: list[dict[str, str]] = field(default_factory=list)
    faults: deque[Fault] = field(default_factory=deque)
    hang_event: threading.Event = field(default_factory=threading.Event)
    hung: threading.Event = field(default_factory=threading.Event)
    lock: threading.Lock = field(default_factory=threading.Lock)
    #: Bytes of the body sent per ``huge_chars`` answer, and whether the client read it all.
    sent: list[tuple[int, bool]] = field(default_factory=list)
    #: Per trickled answer: True when the client hung up before the server was done.
    trickled: list[bool] = field(default_factory=list)


def completion(text: str, model: str) -> dict[str, Any]:
    """A Chat Completions response body."""
    return {
        "id": "chatcmpl-test",
        "object": "chat.completion",
        "created": int(time.time()),
        "model": model,
        "choices": [
            {"index": 0, "finish_reason": "stop", "message": {"role": "assistant", "content": text}}
        ],
        "usage": {"prompt_tokens": 10, "completion_tokens": 10, "total_tokens": 20},
    }


class _Handler(BaseHTTPRequestHandler):
    server: _Server

    def log_message(self, format: str, *args: Any) -> None:  # noqa: A002 - silence the log
        pass

    def _send_json(self, status: int, body: dict[str, Any]) -> None:
        data = json.dumps(body).encode()
        try:
            self.send_response(status)
            self.send_header("Content-Type", "application/json")
            self.send_header("Content-Length", str(len(data)))
            self.end_headers()
            self.wfile.write(data)
        except (BrokenPipeError, ConnectionResetError):
            pass

    def do_POST(self) -> None:  # noqa: N802 - http.server naming
        state = self.server.state
        length = int(self.headers.get("Content-Length", 0))
        body = json.loads(self.rfile.read(length) or b"{}")
        if self.path.rstrip("/") != "/v1/chat/completions":
            self._send_json(404, {"error": {"message": f"no route {self.path}"}})
            return
        with state.lock:
            fault = state.faults.popleft() if state.faults else None
            state.requests.append(body)
            state.headers.append({k.lower(): v for k, v in self.headers.items()})
        if fault is not None and self._apply(fault, state):
            return
        try:
            text = state.responder(body)
        except Exception as err:  # noqa: BLE001 - report responder bugs as a 500
            self._send_json(500, {"error": {"message": f"responder failed: {err!r}"}})
            return
        self._send_json(200, completion(text, body.get("model", "?")))

    def _apply(self, fault: Fault, state: ServerState) -> bool:
        """Apply a fault; True when the request is finished (no normal answer)."""
        if fault.hang:
            state.hung.set()
            state.hang_event.wait(60)
            self.close_connection = True
            return True
        if fault.delay:
            time.sleep(fault.delay)
        if fault.drop:
            self.close_connection = True
            self.connection.close()
            return True
        if fault.body is not None:
            self._send_raw(200, fault.body, fault.content_type)
            return True
        if fault.trickle_s:
            state.trickled.append(self._trickle(fault, state))
            self.close_connection = True
            return True
        if fault.huge_chars:
            state.sent.append(self._send_huge(fault.huge_chars))
            self.close_connection = True
            return True
        if fault.status is not None:
            message = f"injected {fault.status}"
            if fault.echo_headers:
                message += f"; request headers: {dict(self.headers.items())}"
            self._send_json(
                fault.status,
                {
                    "error": {
                        "message": message,
                        "type": "test",
                        "code": fault.status,
                    }
                },
            )
            return True
        return False

    def _send_raw(self, status: int, data: bytes, content_type: str) -> None:
        try:
            self.send_response(status)
            self.send_header("Content-Type", content_type)
            self.send_header("Content-Length", str(len(data)))
            self.end_headers()
            self.wfile.write(data)
        except (BrokenPipeError, ConnectionResetError):
            pass

    def _trickle(self, fault: Fault, state: ServerState) -> bool:
        """Send a valid answer (or an endless event stream) a byte at a time; True when the
        client hung up first."""
        body = json.dumps(completion("trickled", "trickle-model")).encode()
        head = (
            f"HTTP/1.1 200 OK\r\nContent-Type: application/json\r\n"
            f"Content-Length: {len(body)}\r\nConnection: close\r\n\r\n"
        ).encode()
        if fault.trickle == "events":
            head = (
                b"HTTP/1.1 200 OK\r\nContent-Type: text/event-stream\r\nConnection: close\r\n\r\n"
            )
            chunk = json.dumps({"choices": [{"index": 0, "delta": {"content": "a"}}]})
            body = f"data: {chunk}\n\n".encode() * 10_000
        slow = head + body if fault.trickle == "headers" else body
        end = time.monotonic() + fault.trickle_for_s
        try:
            if fault.trickle != "headers":
                self.wfile.write(head)
                self.wfile.flush()
            for i in range(len(slow)):
                if time.monotonic() > end:
                    return False
                self.wfile.write(slow[i : i + 1])
                self.wfile.flush()
                time.sleep(fault.trickle_s)
        except (BrokenPipeError, ConnectionResetError):
            return True
        return False

    def _send_huge(self, chars: int) -> tuple[int, bool]:
        """Stream a completion of ``chars`` characters in 64 KiB writes; (bytes of the body
        sent, whether all were sent) -- a client that stops reading makes the writes fail."""
        prefix, suffix = json.dumps(completion("<<CONTENT>>", "huge-model")).split("<<CONTENT>>")
        total = len(prefix) + chars + len(suffix)
        block = b"a" * 65_536
        sent = 0
        try:
            self.send_response(200)
            self.send_header("Content-Type", "application/json")
            self.send_header("Content-Length", str(total))
            self.end_headers()
            self.wfile.write(prefix.encode())
            sent = len(prefix)
            left = chars
            while left > 0:
                piece = block[: min(left, len(block))]
                self.wfile.write(piece)
                sent += len(piece)
                left -= len(piece)
            self.wfile.write(suffix.encode())
            sent += len(suffix)
        except (BrokenPipeError, ConnectionResetError):
            return sent, False
        return sent, True


class _Server(ThreadingHTTPServer):
    daemon_threads = True
    state: ServerState


class ChatServer:
    """Start with ``with ChatServer(responder) as server:``; ``server.base_url`` ends in /v1."""

    def __init__(self, responder: Responder) -> None:
        self._server = _Server(("127.0.0.1", 0), _Handler)
        self._server.state = ServerState(responder=responder)
        self._thread = threading.Thread(
            target=self._server.serve_forever, kwargs={"poll_interval": 0.05}, daemon=True
        )

    @property
    def state(self) -> ServerState:
        return self._server.state

    @property
    def base_url(self) -> str:
        host, port = self._server.server_address[:2]
        return f"http://{host}:{port}/v1"

    @property
    def requests(self) -> list[dict[str, Any]]:
        return self.state.requests

    def inject(self, *faults: Fault) -> None:
        """Queue faults for the next requests, in order."""
        self.state.faults.extend(faults)

    def release(self) -> None:
        """Unblock hung requests."""
        self.state.hang_event.set()

    def __enter__(self) -> ChatServer:
        self._thread.start()
        return self

    def __exit__(self, *exc: object) -> None:
        self.release()
        self._server.shutdown()
        self._server.server_close()
