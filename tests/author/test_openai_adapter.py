"""The OpenAI-compatible adapter against a real local HTTP server (no client patching)."""

from __future__ import annotations

import base64
import socket
import time

import pytest

from author.chat_server import ChatServer, Fault
from author.conftest import image_parts
from matloom.author.config import ModelSettings
from matloom.author.llm import (
    ChatMessage,
    ImageInput,
    ModelError,
    ModelTimeoutError,
    ModelUnavailableError,
    get_model,
    provider_names,
)


def settings(server: ChatServer, **kw: object) -> ModelSettings:
    base = {
        "model": "test-model",
        "base_url": server.base_url,
        "max_retries": 2,
        "backoff_s": 0.01,
        "timeout_s": 10.0,
    }
    return ModelSettings(**{**base, **kw})


def ask(model, text: str = "hello", images: tuple = ()) -> str:
    return model.complete([ChatMessage("system", "sys"), ChatMessage("user", text, images)]).text


@pytest.fixture
def echo_server():
    with ChatServer(lambda body: f"echo {len(body['messages'])}") as srv:
        yield srv


def test_openai_is_a_registered_provider() -> None:
    assert {"openai", "scripted"} <= set(provider_names())


def test_round_trip_and_request_options(echo_server: ChatServer) -> None:
    model = get_model(
        settings(
            echo_server,
            temperature=0.3,
            reasoning_effort="low",
            extra_body={"reasoning": {"enabled": True}},
        )
    )
    assert ask(model) == "echo 2"
    body = echo_server.requests[-1]
    assert body["model"] == "test-model" and body["temperature"] == 0.3
    assert body["reasoning_effort"] == "low" and body["reasoning"] == {"enabled": True}
    assert body["messages"][0] == {"role": "system", "content": "sys"}
    assert echo_server.state.headers[-1]["authorization"] == "Bearer test-key"


def test_unset_options_are_not_sent(echo_server: ChatServer) -> None:
    ask(get_model(settings(echo_server)))
    body = echo_server.requests[-1]
    assert "temperature" not in body and "reasoning_effort" not in body


def test_api_key_from_profile_variable(echo_server: ChatServer, monkeypatch) -> None:
    monkeypatch.setenv("MY_PROVIDER_KEY", "k-123")
    ask(get_model(settings(echo_server, api_key_env="MY_PROVIDER_KEY")))
    assert echo_server.state.headers[-1]["authorization"] == "Bearer k-123"


def test_images_become_data_url_parts(echo_server: ChatServer) -> None:
    jpeg = b"\xff\xd8fake-jpeg"
    ask(get_model(settings(echo_server)), "look", (ImageInput(jpeg, "image/jpeg"),))
    user = echo_server.requests[-1]["messages"][1]
    assert user["content"][0] == {"type": "text", "text": "look"}
    (part,) = image_parts(user)
    assert part["image_url"]["url"] == "data:image/jpeg;base64," + base64.b64encode(jpeg).decode()


def test_429_then_success_is_retried(echo_server: ChatServer) -> None:
    echo_server.inject(Fault(status=429))
    reply = get_model(settings(echo_server)).complete([ChatMessage("user", "x")])
    assert reply.text == "echo 1" and reply.attempts == 2
    assert len(echo_server.requests) == 2


def test_500_and_dropped_connection_are_retried(echo_server: ChatServer) -> None:
    echo_server.inject(Fault(status=500), Fault(drop=True))
    reply = get_model(settings(echo_server)).complete([ChatMessage("user", "x")])
    assert reply.attempts == 3


def test_persistent_5xx_gives_a_clean_error(echo_server: ChatServer) -> None:
    echo_server.inject(*[Fault(status=503)] * 3)
    with pytest.raises(ModelError, match="HTTP 503 after 3 attempt"):
        ask(get_model(settings(echo_server)))


def test_auth_error_is_not_retried(echo_server: ChatServer) -> None:
    echo_server.inject(Fault(status=401))
    with pytest.raises(ModelError, match="MATLOOM_API_KEY"):
        ask(get_model(settings(echo_server)))
    assert len(echo_server.requests) == 1


def test_timeout_is_retried_then_reported(echo_server: ChatServer) -> None:
    echo_server.inject(Fault(delay=1.5), Fault(delay=1.5))
    model = get_model(settings(echo_server, timeout_s=0.3, max_retries=1))
    with pytest.raises(ModelTimeoutError, match="timed out 2 time"):
        ask(model)


def test_timeout_then_success(echo_server: ChatServer) -> None:
    echo_server.inject(Fault(delay=1.5))
    reply = get_model(settings(echo_server, timeout_s=0.3)).complete([ChatMessage("user", "x")])
    assert reply.text == "echo 1" and reply.attempts == 2


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def test_connection_refused_is_a_clean_error() -> None:
    s = ModelSettings(
        model="m", base_url=f"http://127.0.0.1:{_free_port()}/v1", max_retries=1, backoff_s=0.01
    )
    start = time.perf_counter()
    with pytest.raises(ModelUnavailableError, match="cannot connect to http://127.0.0.1"):
        ask(get_model(s))
    assert time.perf_counter() - start < 30  # no minute-long hang (a sanity bound, not a benchmark)


def test_empty_replies_are_retried() -> None:
    replies = iter(["", "  ", "finally"])
    with ChatServer(lambda body: next(replies)) as srv:
        reply = get_model(settings(srv)).complete([ChatMessage("user", "x")])
    assert reply.text == "finally" and reply.attempts == 3


def test_accepts_images_flag() -> None:
    assert ModelSettings(model="gpt-5.6-luna").accepts_images
    assert not ModelSettings(model="deepseek-v4-flash").accepts_images
    assert not ModelSettings(model="z-ai/glm-5.2").accepts_images
    assert not ModelSettings(model="gpt-5.6-luna", images=False).accepts_images
    assert ModelSettings(model="glm-5.2", images=True).accepts_images
