"""Edits by a model, against the scripted Chat Completions server on 127.0.0.1: the answer is
applied, checked and held to its channels; a leak or a bad answer goes back for repair."""

from __future__ import annotations

import json
from collections import deque
from pathlib import Path
from typing import Any

import pytest
from click.testing import CliRunner

from author.chat_server import ChatServer
from author.conftest import text_of
from matloom.author.config import ModelSettings
from matloom.author.edit import EditError, edit
from matloom.author.llm.providers import get_model
from matloom.cli.main import cli

TILES = (
    Path(__file__).resolve().parents[2] / "matloom/examples/black_ceramic_tiles.mat"
).read_text()

#: glazeRipple feeds basecolor and height: changing it while claiming basecolor leaks
LEAKING = json.dumps(
    {"assign": {"define:glazeRipple.fBm.base_freq": 20}, "channels": ["basecolor"], "note": "bluer"}
)
GOOD = json.dumps(
    {"assign": {"layer:2.basecolor.base": [30, 60, 160]}, "channels": ["basecolor"], "note": "blue"}
)


class Replies:
    def __init__(self, *replies: str) -> None:
        self.replies = deque(replies)

    def __call__(self, body: dict[str, Any]) -> str:
        return self.replies.popleft()


def _model(server: ChatServer) -> Any:
    return get_model(
        ModelSettings(model="edit-model", base_url=server.base_url, max_retries=0, timeout_s=20)
    )


def test_good_answer_is_applied_and_local() -> None:
    with ChatServer(Replies(f"Here it is:\n```json\n{GOOD}\n```")) as server:
        result = edit(TILES, "blue glaze", _model(server), size=32)
        first = server.requests[0]
    assert (
        "(30 + (glazeRipple * 6)), (60 + (glazeRipple * 6)), (160 + (glazeRipple * 6))"
        in result.program
    )
    assert result.report.mode == "model" and result.report.ok and result.report.turns == 0
    assert result.report.locality.changed == ("basecolor",)
    prompt = text_of(first["messages"][1])
    assert "<request>blue glaze</request>" in prompt
    assert "layer:2.basecolor.base" in prompt and "define:tileMask.Bricks.mortar" in prompt


def test_leaking_answer_is_sent_back_and_retried() -> None:
    with ChatServer(Replies(LEAKING, GOOD)) as server:
        result = edit(TILES, "blue glaze", _model(server), repair_turns=2, size=32)
        requests = list(server.requests)
    assert len(requests) == 2
    repair = text_of(requests[1]["messages"][-1])
    assert "leaks" in repair and "height" in repair
    assert result.report.ok and result.report.turns == 1
    assert result.report.attempts and "height changed on" in result.report.attempts[0]
    assert "base_freq=7" in result.program  # the leaking change is not kept


def test_leak_after_the_last_turn_is_reported() -> None:
    with ChatServer(Replies(LEAKING, LEAKING)) as server:
        result = edit(TILES, "blue glaze", _model(server), repair_turns=1, size=32)
    assert not result.report.ok
    assert "height" in result.report.locality.leaks
    assert result.report.to_json()["ok"] is False


def test_bad_answers_get_diagnostics_then_fail() -> None:
    bad_program = json.dumps(
        {
            "replace": {"define:glazeGrain": "Define(glazeGrain, fBm(octaves=0))"},
            "channels": ["roughness"],
        }
    )
    seeds = json.dumps({"assign": {"define:glazeGrain.fBm.seed": 5}, "channels": ["roughness"]})
    with ChatServer(Replies("no json here", bad_program, seeds)) as server:
        with pytest.raises(EditError, match="seeds"):
            edit(TILES, "rougher glaze", _model(server), repair_turns=2, size=32)
        requests = list(server.requests)
    assert len(requests) == 3
    assert "JSON" in text_of(requests[1]["messages"][-1])
    assert "does not check" in text_of(requests[2]["messages"][-1])


def test_cli_edit_with_model(tmp_path: Path) -> None:
    src = tmp_path / "tiles.mat"
    src.write_text(TILES)
    with ChatServer(Replies(LEAKING, GOOD)) as server:
        res = CliRunner().invoke(
            cli,
            [
                "edit",
                str(src),
                "blue glaze",
                "--model",
                "edit-model",
                "--base-url",
                server.base_url,
                "--max-retries",
                "0",
                "--size",
                "32",
                "--json",
            ],  # fmt: skip
        )
    assert res.exit_code == 0, res.output
    record = json.loads(res.stdout)
    assert record["mode"] == "model" and record["repair_turns"] == 1
    assert record["locality"]["leaks"] == []
    out = tmp_path / "tiles.edited.mat"
    assert "(30 + (glazeRipple * 6))" in out.read_text()
    assert src.read_text() == TILES  # the input is never overwritten
