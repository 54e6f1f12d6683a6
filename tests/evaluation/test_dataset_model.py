"""``matloom dataset --prompts FILE --profile NAME``: a model writes each prompt's program (the
scripted Chat Completions server of the authoring tests on 127.0.0.1), then the samples are built
from those programs."""

from __future__ import annotations

import json
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
from click.testing import CliRunner

from matloom.cli.main import cli

#: Two programs the scripted model answers with, told apart by the prompt's colour word.
PROGRAMS = {
    "red": "Material(Layer(1).basecolor(200, 30, 30).roughness(0.4))",
    "blue": "Material(Layer(1).basecolor(30, 30, 200).roughness(0.7))",
}


def _reply(body: dict[str, Any]) -> str:
    text = json.dumps(body["messages"])
    colour = "red" if "a red plastic" in text else "blue"
    return f"<material>\n{PROGRAMS[colour]}\n</material>"


@pytest.fixture
def server(chat_module: Any) -> Iterator[Any]:
    with chat_module.ChatServer(_reply) as srv:
        yield srv


def test_prompts_written_by_a_model_profile(
    tmp_path: Path, server: Any, monkeypatch: pytest.MonkeyPatch
) -> None:
    config = tmp_path / "matloom.toml"
    config.write_text(
        f'[profiles.scripted]\nmodel = "scripted-model"\nbase_url = "{server.base_url}"\n'
        "max_retries = 0\ntimeout_s = 20\n",
        encoding="utf-8",
    )
    monkeypatch.setenv("MATLOOM_CONFIG", str(config))
    monkeypatch.setenv("MATLOOM_API_KEY", "test-key")
    monkeypatch.delenv("OPENAI_API_KEY", raising=False)
    monkeypatch.chdir(tmp_path)
    prompts = tmp_path / "prompts.json"
    prompts.write_text(json.dumps(["a red plastic", "a blue plastic"]), encoding="utf-8")
    out = tmp_path / "ds"
    args = ["dataset", "--prompts", str(prompts), "--profile", "scripted", "--size", "16",
            "--scheduler", "inline", "-o", str(out)]  # fmt: skip
    res = CliRunner().invoke(cli, args)
    assert res.exit_code == 0, res.output
    rows = [json.loads(line) for line in (out / "metadata.jsonl").read_text().splitlines()]
    assert sorted(r["prompt"] for r in rows) == ["a blue plastic", "a red plastic"]
    for row in rows:
        program = (out / row["path"] / "material.mat").read_text(encoding="utf-8")
        expected = "(200, 30, 30)" if "red" in row["prompt"] else "(30, 30, 200)"
        assert f"basecolor{expected}" in program
    assert server.requests, "the model was asked"
