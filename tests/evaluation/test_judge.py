"""The MLLM judge against the scripted Chat Completions server on 127.0.0.1: the request
(temperature 0, the image, the schema), retries on 429 and on unparseable answers, where the
key goes, and the option errors."""

from __future__ import annotations

import base64
import json
import math
import pickle
from collections import deque
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from matloom.author.llm import ModelError
from matloom.evaluation.metrics.base import MetricUnavailableError, Sample
from matloom.evaluation.metrics.judge import JudgeMetric
from matloom.evaluation.metrics.registry import get_metric
from matloom.io import png

KEY = "sk-judge-secret-0123456789"
GOOD = json.dumps(
    {"match_score": 72, "differences": ["too dark"], "suggestions": ["lighten the base"]}
)


class Replies:
    """Queued answers, then :data:`GOOD`."""

    def __init__(self, *texts: str) -> None:
        self.texts = deque(texts)

    def __call__(self, body: dict[str, Any]) -> str:
        return self.texts.popleft() if self.texts else GOOD


@pytest.fixture(autouse=True)
def _clean_env(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    """No user config and no real keys: only what a test sets."""
    monkeypatch.setenv("MATLOOM_CONFIG", str(tmp_path / "no-such-matloom.toml"))
    monkeypatch.setenv("HOME", str(tmp_path))
    for name in ("MATLOOM_API_KEY", "OPENAI_API_KEY", "OPENAI_BASE_URL"):
        monkeypatch.delenv(name, raising=False)
    monkeypatch.setenv("JUDGE_KEY", KEY)


@pytest.fixture
def replies() -> Replies:
    return Replies()


@pytest.fixture
def server(replies: Replies, chat_module: Any) -> Iterator[Any]:
    with chat_module.ChatServer(replies) as srv:
        yield srv


@pytest.fixture
def image(tmp_path: Path) -> Path:
    path = tmp_path / "preview.png"
    pixels = np.zeros((8, 8, 3), np.uint8)
    pixels[:4] = (200, 40, 30)
    png.save_png(path, pixels)
    return path


def options(server: Any, **extra: Any) -> dict[str, Any]:
    return {
        "model": "judge-vision-model",
        "base_url": server.base_url,
        "api_key_env": "JUDGE_KEY",
        "max_retries": 2,
        "backoff_s": 0.01,
        "timeout_s": 20,
        **extra,
    }


def sample(image: Path, layout: str = "quick", sid: str = "s1") -> Sample:
    return Sample(id=sid, prompt="red brick wall", program="", images={layout: image})


def user_parts(body: dict[str, Any]) -> list[dict[str, Any]]:
    return body["messages"][1]["content"]


def test_request_has_temperature_zero_the_image_and_the_schema(server: Any, image: Path) -> None:
    metric = get_metric("judge", options(server))
    got = metric.score([sample(image)])
    assert got == [{"judge.quick": 72.0, "judge.score": 72.0}]
    (body,) = server.requests
    assert body["temperature"] == 0
    assert body["model"] == "judge-vision-model"
    assert "material-appearance judge" in body["messages"][0]["content"]
    text, picture = user_parts(body)
    assert "<description>red brick wall</description>" in text["text"]
    assert '"match_score"' in text["text"] and '"differences"' in text["text"]
    assert '"edits"' not in text["text"]  # the judge reads no code
    url = picture["image_url"]["url"]
    assert url == "data:image/png;base64," + base64.b64encode(image.read_bytes()).decode()
    reasons = metric.reasons["s1"]["quick"]
    assert reasons["differences"] == ["too dark"] and reasons["suggestions"] == ["lighten the base"]


def test_temperature_is_zero_even_when_the_profile_says_otherwise(
    server: Any, image: Path, tmp_path: Path
) -> None:
    config = tmp_path / "judge.toml"
    config.write_text(
        f'[profiles.j]\nmodel = "judge-vision-model"\nbase_url = "{server.base_url}"\n'
        'api_key_env = "JUDGE_KEY"\ntemperature = 0.8\nbackoff_s = 0.01\n',
        encoding="utf-8",
    )
    metric = get_metric("judge", {"profile": "j", "config": str(config)})
    assert metric.score([sample(image)])[0]["judge.score"] == 72.0
    assert server.requests[0]["temperature"] == 0


def test_a_429_then_success_is_retried(server: Any, image: Path, chat_module: Any) -> None:
    server.inject(chat_module.Fault(status=429))
    got = get_metric("judge", options(server)).score([sample(image)])
    assert got[0]["judge.score"] == 72.0
    assert len(server.requests) == 2


def test_a_garbage_answer_then_a_good_one(replies: Replies, server: Any, image: Path) -> None:
    replies.texts.extend(["I think it looks great!", '{"match_score": 55}'])
    metric = get_metric("judge", options(server))
    got = metric.score([sample(image)])
    assert got[0]["judge.score"] == 55.0
    assert len(server.requests) == 2
    retry = server.requests[1]["messages"]
    assert [m["role"] for m in retry] == ["system", "user", "assistant", "user"]
    assert retry[2]["content"] == "I think it looks great!"
    assert "could not be parsed" in retry[3]["content"]
    assert metric.reasons["s1"]["quick"]["attempts"] == 2


def test_answers_that_never_parse_give_nan_after_the_retries(
    replies: Replies, server: Any, image: Path
) -> None:
    replies.texts.extend(["no"] * 5)
    metric = get_metric("judge", options(server, parse_retries=1))
    got = metric.score([sample(image)])
    assert math.isnan(got[0]["judge.quick"]) and math.isnan(got[0]["judge.score"])
    assert len(server.requests) == 2
    assert "no usable answer" in metric.reasons["s1"]["quick"]["error"]


def test_the_key_goes_only_in_the_authorization_header_to_the_configured_server(
    replies: Replies,
    image: Path,
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
    chat_module: Any,
) -> None:
    chat = chat_module
    with chat.ChatServer(replies) as server, chat.ChatServer(replies) as decoy:
        monkeypatch.setenv("OPENAI_BASE_URL", decoy.base_url)
        monkeypatch.setenv("OPENAI_API_KEY", "sk-other-provider-key")
        server.inject(chat.Fault(status=500, echo_headers=True))
        config = tmp_path / "judge.toml"
        config.write_text(
            f'[profiles.j]\nmodel = "judge-vision-model"\nbase_url = "{server.base_url}"\n'
            'api_key_env = "JUDGE_KEY"\nbackoff_s = 0.01\n',
            encoding="utf-8",
        )
        metric = get_metric("judge", {"profile": "j", "config": str(config)})
        metric.score([sample(image)])
        assert decoy.requests == []
        assert len(server.requests) == 2
        for body, headers in zip(server.requests, server.state.headers, strict=True):
            assert headers["authorization"] == f"Bearer {KEY}"
            others = {k: v for k, v in headers.items() if k != "authorization"}
            assert KEY not in json.dumps(others) and KEY not in json.dumps(body)
            assert "sk-other-provider-key" not in json.dumps(headers)
        assert KEY not in json.dumps(metric.reasons)
        assert KEY not in pickle.dumps(metric).decode("latin-1")


def test_layouts_from_the_name_and_missing_images(server: Any, image: Path, tmp_path: Path) -> None:
    metric = get_metric("judge:flat,staged", options(server))
    assert metric.layouts == ("flat", "staged")
    got = metric.score([sample(image, "flat", "a"), sample(image, "quick", "b")])
    assert got[0] == {"judge.flat": 72.0, "judge.score": 72.0}
    assert set(got[1]) == {"judge.score"} and math.isnan(got[1]["judge.score"])
    assert len(server.requests) == 1
    assert "upright plane" not in server.requests[0]["messages"][0]["content"]
    assert "flat plane seen head-on in a studio" in server.requests[0]["messages"][0]["content"]


def test_each_layout_is_judged_on_its_own(server: Any, image: Path) -> None:
    both = Sample(id="x", prompt="p", program="", images={"flat": image, "staged": image})
    got = get_metric("judge", options(server, layouts=["flat", "staged"])).score([both])
    assert got[0] == {"judge.flat": 72.0, "judge.staged": 72.0, "judge.score": 72.0}
    assert len(server.requests) == 2
    assert all(len(user_parts(b)) == 2 for b in server.requests)  # text + one image each


def test_a_refused_key_raises(server: Any, image: Path, chat_module: Any) -> None:
    server.inject(chat_module.Fault(status=401))
    metric = get_metric("judge", options(server))
    with pytest.raises(ModelError) as err:
        metric.score([sample(image)])
    assert KEY not in str(err.value)


def test_option_errors_are_one_line(server: Any, tmp_path: Path) -> None:
    cases = [
        {},  # no model anywhere
        options(server, images=False),  # a text-only model
        {"profile": "nope", "config": str(tmp_path / "missing.toml")},
        options(server, parse_retries="many"),
        options(server, timeout_s=-1),
    ]
    for case in cases:
        with pytest.raises(MetricUnavailableError) as err:
            get_metric("judge", case)
        assert "\n" not in str(err.value)


def test_the_metric_pickles_without_its_client(server: Any, image: Path) -> None:
    metric = get_metric("judge", options(server))
    copy = pickle.loads(pickle.dumps(metric))
    assert isinstance(copy, JudgeMetric) and copy.settings == metric.settings
    assert copy.score([sample(image)])[0]["judge.score"] == 72.0
