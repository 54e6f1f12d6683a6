"""One bounded Chat Completions request: a total deadline and a byte budget.

The ``openai`` SDK's timeout bounds each socket operation, not the request: a server sending a
byte every two seconds (of the headers, the body, or an event stream nobody asked for) keeps a
request alive for as long as it likes, and the SDK reads the whole body before anything checks
its size. So each attempt runs the SDK's raw streaming call
(``chat.completions.with_streaming_response.create``) in a worker thread and

- waits for it at most ``timeout_s`` of wall clock, from sending to the last byte; at the
  deadline the caller gets :class:`DeadlineExceededError` at once, the worker is told to stop
  and the connection's socket is shut down so the worker ends too;
- reads the body in chunks and stops after :func:`reply_byte_budget` bytes, closing the
  connection: the rest of an oversized reply is never received.

Each request asks for ``Connection: close``, so every attempt opens its own connection and its
socket is known (through the HTTP library's documented ``trace`` request extension) to be shut
down at the deadline; a model call takes seconds, so the lost connection reuse costs nothing.
"""

from __future__ import annotations

import socket
import threading
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from matloom.author.config import DEFAULT_MAX_REPLY_CHARS

#: A character of a JSON string takes at most 12 bytes on the wire (an escaped surrogate pair,
#: ``\\ud83d\\ude00``), so a reply of N characters has a body of at most 12 N bytes ...
MAX_BYTES_PER_CHAR = 12
#: ... plus the envelope (id, model, usage, a reasoning summary).
ENVELOPE_BYTES = 64 * 1024


class DeadlineExceededError(Exception):
    """An attempt ran past its total deadline (the caller treats it as a timeout)."""


def reply_byte_budget(max_reply_chars: int | None) -> int:
    """Most body bytes read for a reply capped at ``max_reply_chars`` characters."""
    chars = DEFAULT_MAX_REPLY_CHARS if max_reply_chars is None else max_reply_chars
    return MAX_BYTES_PER_CHAR * chars + ENVELOPE_BYTES


@dataclass(frozen=True)
class RawReply:
    """The body of an HTTP-200 answer, whole or (``cut``) its first ``budget`` bytes."""

    body: bytes
    cut: bool


@dataclass
class _Attempt:
    """One request in flight: its worker's outcome and the sockets to shut at the deadline."""

    budget: int
    done: threading.Event = field(default_factory=threading.Event)
    cancelled: threading.Event = field(default_factory=threading.Event)
    reply: RawReply | None = None
    error: BaseException | None = None
    sockets: list[socket.socket] = field(default_factory=list)
    lock: threading.Lock = field(default_factory=threading.Lock)

    def trace(self, event: str, info: dict[str, Any]) -> None:
        """``trace`` extension callback: remember each socket the request opens."""
        if event not in ("connection.connect_tcp.complete", "connection.start_tls.complete"):
            return
        stream = info.get("return_value")
        sock = stream.get_extra_info("socket") if stream is not None else None
        if not isinstance(sock, socket.socket):
            return
        with self.lock:
            self.sockets.append(sock)
        if self.cancelled.is_set():
            _shut(sock)

    def cancel(self) -> None:
        """Stop the worker: it returns at its next chunk, and a blocked read fails now."""
        self.cancelled.set()
        with self.lock:
            sockets = list(self.sockets)
        for sock in sockets:
            _shut(sock)


def _shut(sock: socket.socket) -> None:
    try:
        sock.shutdown(socket.SHUT_RDWR)
    except OSError:  # already closed by the worker: nothing left to stop
        pass


_current = threading.local()


def attach_trace(request: Any) -> None:
    """httpx ``request`` event hook: let the attempt running in this thread see its sockets."""
    attempt = getattr(_current, "attempt", None)
    if attempt is not None:
        request.extensions = {**request.extensions, "trace": attempt.trace}


def bounded_request(
    send: Callable[[], Any], *, timeout_s: float, budget: int, name: str = "matloom-llm-request"
) -> RawReply:
    """Run ``send()`` (a context manager over the SDK's raw streaming response) in a worker and
    return its body, within ``timeout_s`` seconds and ``budget`` bytes.

    Raises :class:`DeadlineExceededError` at the deadline, or whatever the SDK raised.
    """
    attempt = _Attempt(budget=budget)
    worker = threading.Thread(target=_read, args=(send, attempt), name=name, daemon=True)
    worker.start()
    try:
        finished = attempt.done.wait(timeout_s)
    except BaseException:  # Ctrl-C while waiting: leave no connection behind
        attempt.cancel()
        raise
    if not finished:
        attempt.cancel()
        raise DeadlineExceededError(f"no complete reply within {timeout_s:g} s")
    if attempt.error is not None:
        raise attempt.error
    assert attempt.reply is not None
    return attempt.reply


def _read(send: Callable[[], Any], attempt: _Attempt) -> None:
    """Worker body: send, then read the body chunk by chunk up to the budget."""
    _current.attempt = attempt
    try:
        with send() as response:
            attempt.reply = _read_body(response, attempt)
    except BaseException as err:  # noqa: BLE001 - handed to the waiting caller
        attempt.error = err
    finally:
        _current.attempt = None
        attempt.done.set()


def _read_body(response: Any, attempt: _Attempt) -> RawReply | None:
    chunks: list[bytes] = []
    size = 0
    for chunk in response.iter_bytes():
        if attempt.cancelled.is_set():
            return None
        chunks.append(chunk)
        size += len(chunk)
        if size > attempt.budget:
            return RawReply(b"".join(chunks)[: attempt.budget], cut=True)
    return RawReply(b"".join(chunks), cut=False)
