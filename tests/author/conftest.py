"""Fixtures for the authoring tests: a scripted Chat Completions server and fast settings."""

from __future__ import annotations

import hashlib
import json
import re
from collections import deque
from collections.abc import Callable, Iterator
from typing import Any

import pytest

from author.chat_server import ChatServer
from matloom.author.prompts.system import FEW_SHOT_EXAMPLES

GENERATOR_MARK = "You are an expert technical artist"
CRITIC_MARK = "meticulous material-appearance critic"

#: Small sizes so an end-to-end run takes well under a second of rendering.
FAST_FLAGS = [
    "--critique-size",
    "48",
    "--select-size",
    "48",
    "--sweep-size",
    "32",
    "--export-size",
    "32",
    "--stats-grid",
    "32",
    "--sweep-jobs",
    "1",
]


def text_of(message: dict[str, Any]) -> str:
    """Text of a Chat Completions message (string content or text parts)."""
    content = message.get("content")
    if isinstance(content, str):
        return content
    return "\n".join(p.get("text", "") for p in content or [] if p.get("type") == "text")


def image_parts(message: dict[str, Any]) -> list[dict[str, Any]]:
    content = message.get("content")
    if isinstance(content, str):
        return []
    return [p for p in content or [] if p.get("type") == "image_url"]


def is_critic(body: dict[str, Any]) -> bool:
    return CRITIC_MARK in text_of(body["messages"][0])


def description_of(body: dict[str, Any]) -> str:
    for m in body["messages"]:
        found = re.search(r"<description>(.*?)</description>", text_of(m), re.DOTALL)
        if found:
            return found.group(1)
    return ""


def example_program(k: int, *, strip_seeds: bool = True) -> str:
    """One of the six few-shot programs; without seeds so canonicalisation must add them."""
    program = FEW_SHOT_EXAMPLES[k % len(FEW_SHOT_EXAMPLES)].program()
    return re.sub(r",\s*seed=\d+", "", program) if strip_seeds else program


def default_generator_reply(body: dict[str, Any]) -> str:
    """A valid program chosen by the description and the number of assistant turns so far."""
    digest = int(hashlib.sha256(description_of(body).encode()).hexdigest(), 16)
    turns = sum(m["role"] == "assistant" for m in body["messages"])
    program = example_program(digest + turns)
    return f"I will layer the material.\n<material>\n{program}\n</material>"


def default_critic_reply(body: dict[str, Any]) -> str:
    digest = int(hashlib.sha256(json.dumps(body["messages"][-1]).encode()).hexdigest(), 16)
    return json.dumps(
        {
            "match_score": 30 + digest % 60,
            "differences": ["the colour is too dark"],
            "suggestions": ["raise basecolor of layer 0 by 20"],
        }
    )


class Script:
    """Routes generator and critic requests to queued replies, then to defaults."""

    def __init__(
        self,
        generator: list[str] | None = None,
        critic: list[str] | None = None,
        default_generator: Callable[[dict[str, Any]], str] = default_generator_reply,
        default_critic: Callable[[dict[str, Any]], str] = default_critic_reply,
    ) -> None:
        self.generator = deque(generator or [])
        self.critic = deque(critic or [])
        self.default_generator = default_generator
        self.default_critic = default_critic

    def __call__(self, body: dict[str, Any]) -> str:
        if is_critic(body):
            return self.critic.popleft() if self.critic else self.default_critic(body)
        return self.generator.popleft() if self.generator else self.default_generator(body)


@pytest.fixture
def script() -> Script:
    return Script()


@pytest.fixture
def server(script: Script) -> Iterator[ChatServer]:
    with ChatServer(script) as srv:
        yield srv


@pytest.fixture(autouse=True)
def _clean_env(monkeypatch: pytest.MonkeyPatch, tmp_path: Any) -> None:
    """No user config or real keys leak into the tests."""
    monkeypatch.setenv("MATLOOM_CONFIG", str(tmp_path / "no-such-matloom.toml"))
    monkeypatch.setenv("MATLOOM_API_KEY", "test-key")
    monkeypatch.delenv("OPENAI_API_KEY", raising=False)
    monkeypatch.chdir(tmp_path)


def model_flags(server: ChatServer, model: str = "test-vision-model") -> list[str]:
    return [
        "--model",
        model,
        "--base-url",
        server.base_url,
        "--max-retries",
        "2",
        "--timeout",
        "20",
    ]
