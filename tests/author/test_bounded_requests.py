"""Each model request is bounded, and a malformed answer is a bad reply, not a crash.

Through a real HTTP server on 127.0.0.1 and the ``openai`` SDK:

- the reply-size cap stops the *reading* of a huge reply (the server counts the bytes it
  managed to send before the client hung up);
- ``timeout_s`` is a total deadline per attempt, whatever the server trickles (headers, body,
  or an event stream nobody asked for);
- a malformed HTTP-200 body is retried and then recorded as a bad answer, for the generator and
  the critic, and never ends the run.
"""

from __future__ import annotations

import json
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

from author.chat_server import ChatServer, Fault, completion
from author.test_generate_e2e import generate
from author.test_openai_adapter import settings
from matloom.author.llm import ChatMessage, ModelError, ModelTimeoutError, get_model
from matloom.author.records import validate_record_file

#: A huge reply: far more than the client may read, and more than the socket buffers hold.
HUGE_CHARS = 64_000_000
#: How long the server side of a test may take to notice the client hung up.
SERVER_NOTICE_S = 10.0


def eventually(check: Callable[[], bool]) -> None:
    """Wait (bounded) for the server thread to record what it saw."""
    end = time.monotonic() + SERVER_NOTICE_S
    while not check() and time.monotonic() < end:
        time.sleep(0.02)
    assert check()


def ask(model: Any, **kw: Any) -> Any:
    return model.complete([ChatMessage("user", "x")], **kw)


@pytest.fixture
def echo_server():
    with ChatServer(lambda body: "fine") as srv:
        yield srv


# --------------------------------------------------------------------------- reply size (5)


def test_a_huge_reply_is_not_read_past_its_byte_budget(echo_server: ChatServer) -> None:
    echo_server.inject(Fault(huge_chars=HUGE_CHARS))
    reply = ask(get_model(settings(echo_server, max_retries=0)), max_reply_chars=1_000)
    assert reply.cut_at_bytes is not None and reply.cut_at_bytes < 1_000_000
    assert reply.text.startswith("aaaa") and len(reply.text) <= 2_000
    eventually(lambda: bool(echo_server.state.sent))
    ((sent, finished),) = echo_server.state.sent
    assert not finished and sent < HUGE_CHARS // 2


def test_generate_stops_reading_a_huge_reply_and_asks_again(
    server: ChatServer, tmp_path: Path
) -> None:
    server.inject(Fault(huge_chars=HUGE_CHARS))
    result = generate(
        server, tmp_path / "run", "--rounds", "0", "--variants", "0", "--max-reply-chars", "50000"
    )
    assert result.exit_code == 0, result.stderr
    eventually(lambda: bool(server.state.sent))
    ((sent, finished),) = server.state.sent
    assert not finished and sent < HUGE_CHARS // 2  # the client hung up early
    refused, accepted = validate_record_file(tmp_path / "run" / "record.json").turns[0].attempts
    assert (refused.outcome, accepted.outcome) == ("too_large", "accepted")
    assert "not read further" in refused.error and "50,000 characters" in refused.error
    assert refused.reply.startswith("aaaa") and len(refused.reply) < 5_000


# --------------------------------------------------------------------------- deadline (6)


def test_a_trickled_body_times_out_at_the_deadline_on_every_attempt(
    echo_server: ChatServer,
) -> None:
    echo_server.inject(*[Fault(trickle_s=0.25)] * 2)
    model = get_model(settings(echo_server, timeout_s=1.0, max_retries=1))
    with pytest.raises(ModelTimeoutError, match="timed out 2 time"):
        ask(model)
    # Both connections were dropped by the client, not read to the server's end.
    eventually(lambda: len(echo_server.state.trickled) == 2)
    assert echo_server.state.trickled == [True, True]


@pytest.mark.parametrize("what", ["headers", "events"])
def test_trickled_headers_or_an_unrequested_event_stream_time_out(
    echo_server: ChatServer, what: str
) -> None:
    echo_server.inject(Fault(trickle_s=0.25, trickle=what))
    model = get_model(settings(echo_server, timeout_s=1.0, max_retries=0))
    with pytest.raises(ModelTimeoutError, match="timed out 1 time"):
        ask(model)


# --------------------------------------------------------------------------- malformed (9)


def _body(**changes: Any) -> bytes:
    data = completion("fine", "m")
    data.update(changes)
    return json.dumps(data).encode()


MALFORMED = {
    "not_json": b"<html>502 Bad Gateway</html>",
    "empty_body": b"",
    "choices_null_entry": _body(choices=[None]),
    "choices_null_entry_after_a_good_one": _body(choices=[None, {"message": {"content": "x"}}]),
    "choices_a_string": _body(choices="fine"),
    "content_a_number": _body(choices=[{"index": 0, "message": {"content": 5}}]),
    "content_part_a_string": _body(choices=[{"index": 0, "message": {"content": ["fine"]}}]),
    "nested_too_deep": b"[" * 200_000,
}


@pytest.mark.parametrize("body", MALFORMED.values(), ids=MALFORMED.keys())
def test_a_malformed_reply_is_retried(echo_server: ChatServer, body: bytes) -> None:
    echo_server.inject(Fault(body=body))
    reply = ask(get_model(settings(echo_server)))
    assert (reply.text, reply.attempts) == ("fine", 2)


@pytest.mark.parametrize(
    ("body", "reason"),
    [
        (b"<html>oops</html>", "the reply is not JSON (17 bytes starting '<html>oops</html>')"),
        (
            json.dumps({"error": {"message": "overloaded"}}).encode(),
            "the server answered HTTP 200 with an error: overloaded",
        ),
    ],
    ids=["not_json", "error_with_200"],
)
def test_persistent_malformed_replies_are_a_bad_reply_error(
    echo_server: ChatServer, body: bytes, reason: str
) -> None:
    echo_server.inject(*[Fault(body=body)] * 4)
    with pytest.raises(ModelError) as failure:
        ask(get_model(settings(echo_server)))
    assert type(failure.value).__name__ == "BadReplyError"
    assert str(failure.value).endswith(f"4 unusable replies in a row; the last: {reason}")
    assert len(echo_server.requests) == 4


def test_a_key_echoed_in_a_malformed_body_is_redacted_before_it_is_quoted(
    echo_server: ChatServer,
) -> None:
    # A guard on the quoting of bad replies (new with it): the key is redacted, then the quote
    # clipped, so even a key that straddles the clip is never shown in part.
    echo_server.inject(*[Fault(body=b"x" * 228 + b" Authorization: Bearer test-key")] * 4)
    with pytest.raises(ModelError) as failure:
        ask(get_model(settings(echo_server)))
    assert "test-key" not in str(failure.value) and "test-k" not in str(failure.value)


def test_unreadable_usage_is_left_out_and_the_answer_kept(echo_server: ChatServer) -> None:
    usage = {"prompt_tokens": "lots", "completion_tokens": 7, "total_tokens": -1}
    echo_server.inject(Fault(body=_body(usage=usage)))
    reply = ask(get_model(settings(echo_server)))
    assert (reply.text, reply.attempts, reply.usage) == ("fine", 1, {"completion_tokens": 7})


def test_content_parts_are_read_as_their_joined_text(echo_server: ChatServer) -> None:
    parts = [
        {"type": "text", "text": "<material>\nMaterial("},
        {"type": "image_url", "image_url": {"url": "data:,"}},
        {"type": "text", "text": "Layer(1))\n</material>"},
    ]
    echo_server.inject(Fault(body=_body(choices=[{"index": 0, "message": {"content": parts}}])))
    reply = ask(get_model(settings(echo_server)))
    assert reply.text == "<material>\nMaterial(Layer(1))\n</material>" and reply.attempts == 1


def test_malformed_critic_replies_fail_the_critique_not_the_run(
    server: ChatServer, tmp_path: Path
) -> None:
    # The generator's first request is answered; then every critic attempt (4 calls of 4
    # requests each: the adapter's retries, then the critic's) gets a malformed body.
    server.inject(Fault(), *[Fault(body=_body(choices=[None]))] * 16)
    result = generate(server, tmp_path / "run", "--rounds", "1")
    assert result.exit_code == 0, result.stderr
    record = validate_record_file(tmp_path / "run" / "record.json")
    assert record.status == "finished" and record.final is not None
    (critique,) = record.critiques
    assert not critique.ok and critique.attempts == 4
    assert "`choices[0]` is null or missing, not an object" in critique.error
    assert record.stop_reason.startswith("critique of P0 failed")


def test_a_malformed_generator_reply_is_recorded_and_asked_again(
    server: ChatServer, tmp_path: Path
) -> None:
    server.inject(*[Fault(body=b"not json at all")] * 4)
    result = generate(server, tmp_path / "run", "--rounds", "0", "--variants", "0")
    assert result.exit_code == 0, result.stderr
    bad, accepted = validate_record_file(tmp_path / "run" / "record.json").turns[0].attempts
    assert (bad.outcome, accepted.outcome) == ("bad_reply", "accepted")
    assert "4 unusable replies in a row; the last: the reply is not JSON" in bad.error
