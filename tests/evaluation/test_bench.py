"""`matloom bench` end to end: 20 prompts x 2 systems (the library and a scripted model on
127.0.0.1, through a profile of a temporary config file), the inline executor, scoring through a
metric registered here, results.csv / summary.json / report.html; resume, an interrupted cell,
and the one-line errors."""

from __future__ import annotations

import csv
import importlib.util
import json
import re
import sys
from collections.abc import Iterator, Sequence
from pathlib import Path
from typing import Any

import pytest
from click.testing import CliRunner

pytest.importorskip("scipy", reason="needs the bench extra (pip install 'matloom[bench]')")
pytest.importorskip("matplotlib", reason="needs the bench extra (pip install 'matloom[bench]')")

from matloom.author.prompts.system import FEW_SHOT_EXAMPLES  # noqa: E402
from matloom.cli.main import cli  # noqa: E402
from matloom.evaluation.metrics.base import (  # noqa: E402
    MetricUnavailableError,
    Sample,
    register_metric,
)

PROMPTS = Path(__file__).parents[1] / "data" / "prompts-dev.json"
CALLS: list[int] = []  # samples scored by the tiny metric, per call
LAYOUTS_SEEN: list[set[str]] = []  # the image layouts of each sample scored


class TinyMetric:
    """Mean brightness of the quick preview and the program's line count."""

    name = "tinytest"
    layouts = ("quick",)

    def score(self, samples: Sequence[Sample]) -> list[dict[str, float]]:
        import numpy as np
        from PIL import Image

        CALLS.append(len(samples))
        out = []
        for s in samples:
            LAYOUTS_SEEN.append(set(s.images))
            with Image.open(s.images["quick"]) as img:
                bright = float(np.asarray(img.convert("L")).mean()) / 2.55
            out.append({"tiny.bright": bright, "tiny.lines": float(len(s.program.splitlines()))})
        return out


def _unavailable(name: str, options: Any) -> Any:
    raise MetricUnavailableError("tinyweights: no weights here; put them in ~/weights")


register_metric("tinytest", lambda name, options: TinyMetric())
register_metric("tinyweights", _unavailable)
OPTIONS_SEEN: list[Any] = []


def _with_options(name: str, options: Any) -> TinyMetric:
    OPTIONS_SEEN.append(dict(options))
    return TinyMetric()


register_metric("tinyopts", _with_options)


def _reply(body: dict[str, Any]) -> str:
    first = body["messages"][0]["content"]
    text = first if isinstance(first, str) else " ".join(p.get("text", "") for p in first)
    if "critic" in text:
        return json.dumps({"match_score": 55, "differences": [], "suggestions": []})
    turns = sum(m["role"] == "assistant" for m in body["messages"])
    program = FEW_SHOT_EXAMPLES[turns % len(FEW_SHOT_EXAMPLES)].program()
    return f"<material>\n{program}\n</material>"


@pytest.fixture
def server(chat_module: Any) -> Iterator[Any]:
    with chat_module.ChatServer(_reply) as srv:
        yield srv


@pytest.fixture
def setup(
    tmp_path: Path, server: Any, monkeypatch: pytest.MonkeyPatch, scripted_config: Any
) -> dict[str, Any]:
    monkeypatch.setenv("MATLOOM_API_KEY", "test-key")
    monkeypatch.setenv("MATLOOM_CONFIG", str(tmp_path / "no-such.toml"))
    monkeypatch.delenv("OPENAI_API_KEY", raising=False)
    monkeypatch.chdir(tmp_path)
    config = scripted_config(tmp_path / "bench.toml", server.base_url)
    data = json.loads(PROMPTS.read_text(encoding="utf-8"))
    prompts = tmp_path / "prompts20.json"
    prompts.write_text(json.dumps({"prompts": data["prompts"][:20]}), encoding="utf-8")
    return {"config": config, "prompts": prompts, "out": tmp_path / "bench", "server": server}


def _bench(s: dict[str, Any], *extra: str) -> Any:
    args = [
        "bench", str(s["prompts"]), "--system", "lib=library",
        "--system", "llm=tiny+profile:scripted", "--config", str(s["config"]),
        "--runs", "2", "--size", "32", "--layouts", "quick", "--metric", "tinytest",
        "--resamples", "500", "--quiet", "-o", str(s["out"]), *extra,
    ]  # fmt: skip
    return CliRunner().invoke(cli, args)


def _rows(out: Path) -> list[dict[str, str]]:
    with (out / "results.csv").open(encoding="utf-8") as fh:
        return list(csv.DictReader(fh))


def test_bench_end_to_end_resume_and_new_metric(setup: dict[str, Any]) -> None:
    CALLS.clear()
    result = _bench(setup)
    assert result.exit_code == 0, result.output
    out = setup["out"]
    rows = _rows(out)
    # 20 prompts x 2 systems x 2 runs x 2 values of the one metric
    assert len(rows) == 20 * 2 * 2 * 2
    assert {r["system"] for r in rows} == {"lib", "llm"}
    assert {r["seed"] for r in rows} == {"42", "123"}
    assert {r["source"] for r in rows} >= {"GenProc"}
    assert all(r["value"] for r in rows)
    requests = len(setup["server"].state.requests)
    assert requests >= 40  # one generation per model cell at least
    summary = json.loads((out / "summary.json").read_text(encoding="utf-8"))
    assert summary["cells"] == {"total": 80, "done": 80, "missing": 0}
    assert [(c["a"], c["b"]) for c in summary["contrasts"]] == [("lib", "llm")] * 2
    assert summary["holm_family"] <= 2 and set(summary["by_source"]) >= {"GenProc"}
    page = (out / "report.html").read_text(encoding="utf-8")
    assert "<img" in page and "data:image/png;base64," in page and "tiny.bright" in page
    cell = json.loads(next((out / "cells").glob("*/run")).parent.joinpath("cell.json").read_text())
    assert cell["author"] == "model" and cell["prompt_tokens"] > 0 and cell["model_calls"] >= 1
    assert sum(CALLS) == 80

    # a rerun (resume) authors nothing and scores nothing again
    CALLS.clear()
    result = _bench(setup, "--resume")
    assert result.exit_code == 0, result.output
    assert len(setup["server"].state.requests) == requests
    assert CALLS == []
    assert _rows(out) == rows

    # resume with nothing but the folder; an unavailable metric is one line and skipped
    result = CliRunner().invoke(
        cli,
        ["bench", "--resume", "--config", str(setup["config"]), "-o", str(out),
         "--metric", "tinyweights", "--layouts", "quick", "--size", "32", "--quiet"],
    )  # fmt: skip
    assert result.exit_code == 0, result.output
    assert "metric tinyweights skipped: tinyweights: no weights here" in result.output
    assert len(setup["server"].state.requests) == requests
    assert len(_rows(out)) == len(rows)  # the cached scores are still reported


def test_interrupted_cell_is_redone(setup: dict[str, Any]) -> None:
    data = json.loads(setup["prompts"].read_text(encoding="utf-8"))
    setup["prompts"].write_text(json.dumps({"prompts": data["prompts"][:2]}), encoding="utf-8")
    args = ["--system", "lib=library", "--runs", "1"]
    result = CliRunner().invoke(
        cli,
        ["bench", str(setup["prompts"]), *args, "--size", "32", "--layouts", "quick",
         "--metric", "tinytest", "--quiet", "-o", str(setup["out"])],
    )  # fmt: skip
    assert result.exit_code == 0, result.output
    cells = setup["out"] / "cells"
    victim = sorted(p for p in cells.iterdir() if p.is_dir() and not p.name.startswith("."))[0]
    # a killed run leaves its stage folder, never a half cell
    stage = cells / f".stage-{victim.name}-deadbeef"
    victim.rename(stage)
    (stage / "program.mat").write_text("partial", encoding="utf-8")
    result = CliRunner().invoke(
        cli,
        ["bench", str(setup["prompts"]), *args, "--size", "32", "--layouts", "quick",
         "--metric", "tinytest", "--quiet", "-o", str(setup["out"])],
    )  # fmt: skip
    assert result.exit_code == 0, result.output
    assert victim.is_dir() and not stage.exists()
    assert (victim / "program.mat").read_text(encoding="utf-8") != "partial"
    assert len(_rows(setup["out"])) == 2 * 2


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["--system", "x=nonsense+profile:scripted"], "unknown settings preset"),
        (["--system", "x=profile:nobody"], "unknown model profile 'nobody'"),
        (["--system", "x"], "give NAME=SPEC"),
        (["--system", "lib=library", "--metric", "no_such_metric"], "unknown metric"),
        (["--system", "lib=library", "--runs", "4"], "--runs 4 needs 4 seeds"),
        (["--system", "l=library", "--metric-option", "nosuch.k=1"], "unknown metric nosuch"),
        (["--system", "l=library", "--metric-option", "tinyopts"], "give FAMILY.KEY=VALUE"),
        (["--system", "a=library", "--system", "b=library", "--contrast", "a-c"], "--contrast"),
    ],
)
def test_one_line_errors(setup: dict[str, Any], args: list[str], message: str) -> None:
    result = CliRunner().invoke(
        cli, ["bench", str(setup["prompts"]), "--config", str(setup["config"]), *args,
              "-o", str(setup["out"])],
    )  # fmt: skip
    assert result.exit_code != 0
    assert message in result.output
    assert "Traceback" not in result.output and len(result.output.strip().splitlines()) == 1
    assert not (setup["out"] / "cells").exists()


def test_missing_prompts_file_and_foreign_folder(setup: dict[str, Any], tmp_path: Path) -> None:
    result = CliRunner().invoke(
        cli, ["bench", str(tmp_path / "nope.json"), "--system", "l=library", "-o", "o"]
    )
    assert result.exit_code != 0 and "nope.json does not exist" in result.output
    assert len(result.output.strip().splitlines()) == 1
    foreign = tmp_path / "mine"
    foreign.mkdir()
    (foreign / "notes.txt").write_text("mine", encoding="utf-8")
    result = CliRunner().invoke(
        cli, ["bench", str(setup["prompts"]), "--system", "l=library", "-o", str(foreign)]
    )
    assert result.exit_code != 0 and "not empty and holds no bench" in result.output
    assert sorted(p.name for p in foreign.iterdir()) == ["notes.txt"]


def test_without_scipy_one_line(setup: dict[str, Any], monkeypatch: pytest.MonkeyPatch) -> None:
    import importlib.util

    real = importlib.util.find_spec
    monkeypatch.setattr(
        importlib.util, "find_spec", lambda name, *a: None if name == "scipy" else real(name, *a)
    )
    result = CliRunner().invoke(
        cli, ["bench", str(setup["prompts"]), "--system", "l=library", "-o", "o"]
    )
    assert result.exit_code != 0
    assert re.search(r"needs scipy: pip install 'matloom\[bench\]'", result.output)


def _fake_blender(tmp_path: Path) -> Path:
    """A stand-in Blender executable: the Blender tests' fake that renders flat-colour PNGs."""
    import stat

    path = Path(__file__).resolve().parents[1] / "blender" / "conftest.py"
    spec = importlib.util.spec_from_file_location("bench_blender_fakes", path)
    assert spec is not None and spec.loader is not None
    fakes = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(fakes)
    exe = tmp_path / "blender"
    header = fakes.FAKE_HEADER.replace("{version}", "4.2.3")
    exe.write_text(f"#!{sys.executable}\n{header}\n{fakes.WORKS}", encoding="utf-8")
    exe.chmod(exe.stat().st_mode | stat.S_IXUSR)
    return exe


def test_blender_layouts_render_per_cell_and_reach_the_metrics(
    setup: dict[str, Any], tmp_path: Path
) -> None:
    data = json.loads(setup["prompts"].read_text(encoding="utf-8"))
    setup["prompts"].write_text(json.dumps({"prompts": data["prompts"][:2]}), encoding="utf-8")
    CALLS.clear()
    args = [
        "bench", str(setup["prompts"]), "--system", "lib=library", "--runs", "1",
        "--size", "32", "--blender-size", "16", "--blender", str(_fake_blender(tmp_path)),
        "--metric", "tinytest", "--quiet", "-o", str(setup["out"]),
    ]  # fmt: skip
    result = CliRunner().invoke(cli, args)
    assert result.exit_code == 0, result.output
    assert "skipped" not in result.output
    renders = sorted(p.name.split(".")[1] for p in (setup["out"] / "renders").iterdir())
    assert renders == ["flat16", "flat16", "staged16", "staged16"]
    assert all(len(s) == 3 for s in LAYOUTS_SEEN[-2:])  # quick, flat and staged reached it
    # other Cycles samples are other renders; the cells themselves are not authored again
    result = CliRunner().invoke(cli, [*args, "--blender-samples", "3"])
    assert result.exit_code == 0, result.output
    renders = sorted(p.name.split(".")[1] for p in (setup["out"] / "renders").iterdir())
    assert (
        renders
        == ["flat16", "flat16", "flat16s3", "flat16s3"] + ["staged16"] * 2 + ["staged16s3"] * 2
    )


def test_without_blender_the_layouts_are_skipped_once(
    setup: dict[str, Any], tmp_path: Path
) -> None:
    data = json.loads(setup["prompts"].read_text(encoding="utf-8"))
    setup["prompts"].write_text(json.dumps({"prompts": data["prompts"][:2]}), encoding="utf-8")
    args = [
        "bench", str(setup["prompts"]), "--system", "lib=library", "--runs", "1",
        "--size", "32", "--blender", str(tmp_path / "no-blender"), "--metric", "tinytest",
        "--quiet", "-o", str(setup["out"]),
    ]  # fmt: skip
    result = CliRunner().invoke(cli, args)
    assert result.exit_code == 0, result.output
    assert result.output.count("Blender layouts flat, staged skipped:") == 1
    OPTIONS_SEEN.clear()
    args[args.index("tinytest")] = "tinyopts"
    result = CliRunner().invoke(cli, [*args, "--metric-option", "tinyopts.profile=judge"])
    assert result.exit_code == 0, result.output
    assert OPTIONS_SEEN == [{"profile": "judge"}]
    assert not (setup["out"] / "renders").exists()


def test_cell_tasks_pickle_for_dask(tmp_path: Path) -> None:
    """Dask ships tasks to worker processes: the task function is importable by name and its
    arguments pickle; the unpickled task authors the same cell."""
    import pickle

    from matloom.evaluation.bench_cells import CellSpec, author_cell
    from matloom.evaluation.executor import Task

    spec = CellSpec("red brick wall", "lib", "library", 42, 32, "test")
    task = Task("k1", author_cell, (str(tmp_path), "k1", spec))
    back = pickle.loads(pickle.dumps(task))
    assert back.fn is author_cell and back.args[2] == spec
    summary = back.fn(*back.args)
    assert summary["seed"] == 42 and (tmp_path / "k1" / "preview.png").is_file()
