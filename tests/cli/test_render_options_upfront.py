"""Options are validated before any work and end in one line, never a traceback: a physical size
no preset can store (``--unit-m 1e308``: JSON has no infinity), an unknown preset of
``library render``, and an EXR write that fails on a full disk or a file-size limit. A
``--unit-m`` that replaces the program's own ``unit_m`` is said on stderr."""

from __future__ import annotations

import os
import resource
import signal
import subprocess
import sys
from pathlib import Path

import pytest
from click.testing import CliRunner

from matloom.cli.main import cli

ROOT = Path(__file__).resolve().parents[2]
#: A cobblestone: 4 units at 5 cm per unit (20 cm wide).
COBBLE = (
    "View(0, 0, 4, 4, unit_m=0.05)\nMaterial(Layer(1).basecolor(90, 90, 90).height(X() * 0.1))\n"
)
PLAIN = "Material(Layer(1).basecolor(200, 100, 50).roughness(X()))\n"


def _render(tmp_path: Path, program: str, *args: str) -> tuple[int, str, Path]:
    source = tmp_path / "prog.mat"
    source.write_text(program)
    out = tmp_path / "out"
    res = CliRunner().invoke(cli, ["render", str(source), "-o", str(out), "--size", "8", *args])
    assert res.exception is None or isinstance(res.exception, SystemExit), res.exception
    return res.exit_code, res.stderr, out


def _one_line_refusal(code: int, stderr: str, out: Path) -> str:
    assert code == 2 and "Traceback" not in stderr
    (line,) = [x for x in stderr.splitlines() if x.startswith("Error:")]
    assert "rendered" not in stderr  # refused before the evaluation
    assert not out.exists() or not any(out.iterdir())
    return line


@pytest.mark.parametrize("unit_m", ["1e308", "1e-320", "1e10"])
def test_unit_m_without_a_storable_size_is_refused_up_front(tmp_path: Path, unit_m: str) -> None:
    line = _one_line_refusal(*_render(tmp_path, PLAIN, "--preset", "gltf", "--unit-m", unit_m))
    assert "--unit-m" in line and "physical size" in line


def test_program_unit_m_without_a_storable_size_is_refused(tmp_path: Path) -> None:
    program = "View(0, 0, 1e6, 1e6, unit_m=1e300)\n" + PLAIN
    line = _one_line_refusal(*_render(tmp_path, program, "--preset", "mtlx"))
    assert "unit_m" in line and "View" in line


def test_unit_m_replacing_the_programs_is_said_in_one_line(tmp_path: Path) -> None:
    code, stderr, _ = _render(tmp_path, COBBLE, "--unit-m", "1.5")
    assert code == 0
    (note,) = [x for x in stderr.splitlines() if x.startswith("note:")]
    assert "--unit-m 1.5" in note and "unit_m=0.05" in note and "6 m" in note
    for args in (("--unit-m", "0.05"), ()):  # the same value, or none: nothing to say
        code, stderr, _ = _render(tmp_path, COBBLE, *args)
        assert code == 0 and "note:" not in stderr
    code, stderr, _ = _render(tmp_path, PLAIN, "--unit-m", "1.5")  # the program has none
    assert code == 0 and "note:" not in stderr


def test_library_render_refuses_an_unknown_preset_before_evaluating(tmp_path: Path) -> None:
    out = tmp_path / "out"
    res = CliRunner().invoke(
        cli, ["library", "render", "bamboo", "-o", str(out), "--preset", "nope"]
    )
    assert res.exit_code == 2 and isinstance(res.exception, SystemExit)
    assert "'nope' is not one of" in res.stderr and "Traceback" not in res.stderr
    assert not out.exists()


@pytest.mark.skipif(not hasattr(resource, "RLIMIT_FSIZE"), reason="needs POSIX file-size limits")
def test_a_failing_exr_write_ends_in_one_line(tmp_path: Path) -> None:
    """A real failing write: the render runs with a 64 KiB file-size limit (SIGXFSZ ignored,
    so write() fails with EFBIG as it fails with ENOSPC on a full disk) and its EXR maps are
    larger; OpenEXR's own writer raised RuntimeError (a traceback) or truncated silently."""
    source = tmp_path / "noise.mat"
    source.write_text(
        "Material(Layer(1).basecolor(fBm(octaves=4, base_freq=8, to_01=True, seed=1) * 255, 9, 9)"
        ".height(fBm(octaves=4, base_freq=8, to_01=True, seed=3)))\n"
    )
    limit = 64 * 1024

    def limited() -> None:
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
        resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit))

    out = tmp_path / "out"
    res = subprocess.run(
        [sys.executable, "-m", "matloom", "render", str(source), "-o", str(out), "--format",
         "exr", "--size", "256", "--backend", "numpy", "--no-preview"],
        capture_output=True, text=True, preexec_fn=limited, timeout=300,
        env={**os.environ, "PYTHONPATH": str(ROOT)},
    )  # fmt: skip
    assert res.returncode == 1 and "Traceback" not in res.stderr, res.stderr[-3000:]
    (line,) = [x for x in res.stderr.splitlines() if x.startswith("Error:")]
    assert "File too large" in line
    assert not any(out.iterdir())  # nothing half-written is left
