"""Every entry point checks size, work and memory before allocating (issue "Reliability" #7):
``matloom.preview`` (tiled too), ``matloom.render.api.stats``, seed sweeps, ``matloom.evaluate``;
and a bad memory budget or a limit is one line from the CLI, never a traceback (#2)."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import matloom
from matloom.engine import evaluate as evaluate_module
from matloom.engine.limits import MEMORY_ENV, LimitError
from matloom.engine.schedules import sweep
from matloom.render import api
from matloom.render.preview import ShadeParams

REPO = Path(__file__).resolve().parents[2]
PROGRAM = "Define(n, fBm(seed=3))\nMaterial(Layer(1).basecolor((n * 200), 90, 40).height(n))\n"


@pytest.fixture
def no_grid(monkeypatch: pytest.MonkeyPatch) -> None:
    """Fail if an evaluation gets as far as building its sample grid."""

    def refuse(*args: object) -> None:
        raise AssertionError("the request was not checked before any work")

    monkeypatch.setattr(evaluate_module, "sample_axes", refuse)


@pytest.mark.usefixtures("no_grid")
def test_tiled_preview_past_the_resolution_is_refused() -> None:
    with pytest.raises(LimitError, match="8x8 tiled preview"):
        matloom.preview(PROGRAM, 4096, tile=8)


@pytest.mark.usefixtures("no_grid")
def test_tiled_preview_memory_counts_the_tiled_image(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv(MEMORY_ENV, "256")
    with pytest.raises(LimitError, match="4x4 tiled preview of 2048x2048 needs about"):
        matloom.preview(PROGRAM, 2048, tile=4)


@pytest.mark.usefixtures("no_grid")
@pytest.mark.parametrize(
    "call",
    [
        lambda: matloom.preview(PROGRAM, 100_000),
        lambda: matloom.preview(PROGRAM, width=8, height=0),
        lambda: api.stats(PROGRAM, grid=100_000),
        lambda: api.stats_text(PROGRAM, grid=0),
        lambda: matloom.evaluate(PROGRAM, 100_000, 8),
    ],
    ids=["preview", "preview-height", "stats", "stats-text", "evaluate"],
)
def test_sizes_are_checked_by_every_entry_point(call) -> None:  # noqa: ANN001
    with pytest.raises(LimitError):
        call()


def test_sweep_size_is_checked_before_any_work(monkeypatch: pytest.MonkeyPatch) -> None:
    def refuse(*args: object) -> None:
        raise AssertionError("the sweep was not checked before any work")

    monkeypatch.setattr(sweep, "KernelRenderer", refuse)
    monkeypatch.setattr(sweep, "ExactRenderer", refuse)
    shading = ShadeParams.of()
    with pytest.raises(LimitError, match="maximum resolution"):
        sweep.run_sweep(PROGRAM, variants=2, shading=shading, size=100_000)
    monkeypatch.setenv(MEMORY_ENV, "1")
    with pytest.raises(LimitError, match="sweeping at 1024x1024 needs about"):
        sweep.run_sweep(PROGRAM, variants=2, shading=shading, size=1024)


def test_sweep_results_do_not_depend_on_the_chunk(monkeypatch: pytest.MonkeyPatch) -> None:
    """A budget that shrinks the chunk (down to one candidate) changes no preview."""
    pytest.importorskip("numba")
    shading = ShadeParams.of()
    full = sweep.run_sweep(PROGRAM, variants=5, shading=shading, size=32, keep=6)
    monkeypatch.setattr(sweep, "check_sweep", lambda *args: 1)
    single = sweep.run_sweep(PROGRAM, variants=5, shading=shading, size=32, keep=6)
    assert [i for i, _ in full.top_images] == [i for i, _ in single.top_images]
    for (_, a), (_, b) in zip(full.top_images, single.top_images, strict=True):
        np.testing.assert_array_equal(a, b)


# ---------------------------------------------------------------------------- CLI
def run_cli(tmp_path: Path, env: dict[str, str], *args: str) -> subprocess.CompletedProcess[str]:
    program = tmp_path / "p.mat"
    program.write_text(PROGRAM, encoding="utf-8")
    full_env = {**os.environ, "PYTHONPATH": str(REPO), "MATLOOM_BACKEND": "numpy", **env}
    return subprocess.run(
        [sys.executable, "-m", "matloom", *[a.replace("FILE", str(program)) for a in args]],
        capture_output=True,
        text=True,
        env=full_env,
        cwd=tmp_path,
        timeout=120,
    )


def assert_one_line(result: subprocess.CompletedProcess[str], *words: str) -> None:
    assert result.returncode != 0
    assert "Traceback" not in result.stderr
    lines = [line for line in result.stderr.splitlines() if line.strip()]
    assert len(lines) == 1, result.stderr
    for word in words:
        assert word in lines[0]


@pytest.mark.parametrize("raw", ["abc", "-5", "0", "nan"])
def test_cli_bad_memory_budget_is_one_line(tmp_path: Path, raw: str) -> None:
    result = run_cli(tmp_path, {MEMORY_ENV: raw}, "render", "FILE", "-o", "out", "--size", "8")
    assert_one_line(result, MEMORY_ENV, repr(raw))
    assert not (tmp_path / "out" / "basecolor.png").exists()


def test_cli_preview_over_the_budget_is_one_line(tmp_path: Path) -> None:
    result = run_cli(
        tmp_path,
        {MEMORY_ENV: "64"},
        "preview",
        "FILE",
        "-o",
        "x.png",
        "--size",
        "2048",
        "--tile",
        "4",
    )
    assert_one_line(result, "tiled preview", "MiB", MEMORY_ENV)
    assert not (tmp_path / "x.png").exists()


def test_cli_stats_with_a_bad_budget_is_one_line(tmp_path: Path) -> None:
    assert_one_line(run_cli(tmp_path, {MEMORY_ENV: "abc"}, "stats", "FILE"), MEMORY_ENV)
