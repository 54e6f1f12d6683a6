"""`matloom bench` on a real Dask ``LocalCluster`` (2 worker processes): the library and a
scripted model (the authoring tests' Chat Completions server on 127.0.0.1, reached from the
workers) over 4 prompts; every cell once, the same results as the inline executor."""

from __future__ import annotations

import csv
import json
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

pytest.importorskip("distributed", reason="needs the dask extra (make test-dask)")
pytest.importorskip("scipy", reason="needs the bench extra")

from click.testing import CliRunner  # noqa: E402

from matloom.author.prompts.system import FEW_SHOT_EXAMPLES  # noqa: E402
from matloom.cli.main import cli  # noqa: E402

pytestmark = pytest.mark.dask

PROMPTS = Path(__file__).resolve().parents[1] / "data" / "prompts-dev.json"


def _reply(body: dict[str, Any]) -> str:
    text = json.dumps(body["messages"])
    index = sum(ord(c) for c in text[-200:]) % len(FEW_SHOT_EXAMPLES)
    return f"<material>\n{FEW_SHOT_EXAMPLES[index].program()}\n</material>"


@pytest.fixture
def server(chat_module: Any) -> Iterator[Any]:
    with chat_module.ChatServer(_reply) as srv:
        yield srv


def _rows(out: Path) -> list[dict[str, str]]:
    with (out / "results.csv").open(encoding="utf-8") as fh:
        return sorted(csv.DictReader(fh), key=lambda r: json.dumps(r, sort_keys=True))


def test_bench_on_local_cluster_matches_inline(
    tmp_path: Path, server: Any, monkeypatch: pytest.MonkeyPatch, scripted_config: Any
) -> None:
    monkeypatch.setenv("MATLOOM_API_KEY", "test-key")
    monkeypatch.setenv("MATLOOM_CONFIG", str(tmp_path / "no-such.toml"))
    monkeypatch.delenv("OPENAI_API_KEY", raising=False)
    monkeypatch.chdir(tmp_path)
    config = scripted_config(tmp_path / "bench.toml", server.base_url)
    data = json.loads(PROMPTS.read_text(encoding="utf-8"))
    prompts = tmp_path / "prompts4.json"
    prompts.write_text(json.dumps({"prompts": data["prompts"][:4]}), encoding="utf-8")

    def bench(out: Path, *scheduler: str) -> Any:
        args = ["bench", str(prompts), "--system", "lib=library",
                "--system", "llm=tiny+profile:scripted", "--config", str(config),
                "--runs", "2", "--size", "32", "--layouts", "quick", "--metric", "size",
                "--resamples", "200", "--quiet", "-o", str(out), *scheduler]  # fmt: skip
        return CliRunner().invoke(cli, args)

    result = bench(tmp_path / "dask", "--scheduler", "local", "--workers", "2")
    assert result.exit_code == 0, result.output
    cells = [p for p in (tmp_path / "dask" / "cells").iterdir()]
    assert len(cells) == 4 * 2 * 2 and not any(p.name.startswith(".") for p in cells)
    asked = len(server.state.requests)
    assert asked >= 8  # every model cell asked the model, from a worker process
    result = bench(tmp_path / "inline")
    assert result.exit_code == 0, result.output
    dask_rows, inline_rows = _rows(tmp_path / "dask"), _rows(tmp_path / "inline")
    assert len(dask_rows) == len(inline_rows) > 0
    assert dask_rows == inline_rows  # same programs, same scores, whichever executor ran them
    before = len(server.state.requests)
    result = bench(tmp_path / "dask", "--scheduler", "local", "--workers", "2")
    assert result.exit_code == 0, result.output
    assert len(server.state.requests) == before  # a rerun on the cluster authors nothing
    assert _rows(tmp_path / "dask") == dask_rows
