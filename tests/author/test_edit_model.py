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


BRICK = (Path(__file__).resolve().parents[2] / "matloom/examples/weathered_brick.mat").read_text()


def _seeds(text: str) -> dict[str, object]:
    from matloom.author.edit.apply import all_params, parse_program

    return {p.address: p.value for p in all_params(parse_program(text)) if p.kind == "seed"}


def test_answer_may_add_lines_with_new_seeds() -> None:
    added = json.dumps(
        {
            "add": [
                "Define(mossN, fBm(octaves=4, base_freq=3, to_01=True, seed=4242))",
                "Define(moss, Threshold(((mossN - 0.55) * 8), below_at=0, above_at=1))",
                "Layer(moss).basecolor(70, 100, 40).roughness(0.95)",
            ],
            "channels": ["basecolor", "roughness", "metallic", "height"],
            "note": "moss in clumps",
        }
    )
    with ChatServer(Replies(added)) as server:
        result = edit(BRICK, "add moss", _model(server), size=32)
    assert result.report.ok and result.report.turns == 0
    assert "Layer(moss)" in result.program and "seed=4242" in result.program
    old, new = _seeds(BRICK), _seeds(result.program)
    assert all(new[a] == v for a, v in old.items()) and len(new) == len(old) + 1
    assert {c.label for c in result.report.changes} >= {"added Define", "added layer"}


def test_answer_may_name_a_library_overlay() -> None:
    answer = json.dumps({"overlay": [{"name": "mossy", "amount": 0.6}], "note": "moss"})
    unknown = json.dumps({"overlay": [{"name": "lichenous"}]})
    with ChatServer(Replies(unknown, answer)) as server:
        result = edit(BRICK, "add moss", _model(server), size=32)
        requests = list(server.requests)
    assert "no library overlay 'lichenous'" in text_of(requests[1]["messages"][-1])
    assert "mossy" in text_of(requests[0]["messages"][1])  # the prompt lists the overlays
    assert result.report.ok and result.report.turns == 1
    assert "Define(cover, 0.6)" in result.program
    assert "basecolor" in result.report.plan["channels"]  # the overlay's channels are added


def test_answer_too_small_to_see_is_sent_back() -> None:
    tiny = json.dumps({"assign": {"layer:2.roughness.base": 0.045}, "channels": ["roughness"]})
    visible = json.dumps({"assign": {"layer:2.roughness.base": 0.5}, "channels": ["roughness"]})
    with ChatServer(Replies(tiny, visible)) as server:
        result = edit(TILES, "rougher glaze", _model(server), repair_turns=2, size=32)
        requests = list(server.requests)
    assert len(requests) == 2
    assert "too small to see" in text_of(requests[1]["messages"][-1])
    assert result.report.turns == 1 and "(0.5 + (glazeGrain * 0.05))" in result.program
    # after the last turn a small change is kept rather than nothing
    with ChatServer(Replies(tiny)) as server:
        kept = edit(TILES, "rougher glaze", _model(server), repair_turns=0, size=32)
    assert "(0.045 + (glazeGrain * 0.05))" in kept.program


def test_prompt_lists_layers_labels_and_affects() -> None:
    from matloom.author.edit.model import SYSTEM, prompt

    text = prompt(TILES, "wider grout")
    assert "<layers>\nlayer:1: coverage everywhere; writes basecolor, roughness, height" in text
    assert "layer:2: coverage tileMask;" in text
    assert "define:tileMask.Bricks.mortar = 0.02 (size units" in text and "affects " in text
    assert "CLEARLY VISIBLE" in SYSTEM and '"overlay"' in SYSTEM and '"add"' in SYSTEM
