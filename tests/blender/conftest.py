"""The `blender` marker (tests that need Blender or the bpy module, skipped without them), and
fixtures shared by the tests that replace Blender with small fake executables."""

from __future__ import annotations

import os
import stat
import subprocess
import sys
import textwrap
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

ROOT = Path(__file__).resolve().parents[2]

#: What every fake Blender starts with: it answers `--version` like Blender `version` and
#: otherwise reads the job (the last argument), with helpers to report and to write images.
FAKE_HEADER = """
import json, os, signal, sys, time
if sys.argv[1:] == ["--version"]:
    print("Blender {version}\\n\\tbuild date: 2024")
    sys.exit(0)
job = json.load(open(sys.argv[-1]))

def emit(event, **data):
    print("MATLOOM-JSON " + json.dumps(dict(event=event, **data)), flush=True)

def write_png(path, size, rgba=(90, 120, 200, 255)):
    import png  # pypng: a plain PNG, as Blender writes it (no MatLoom Software chunk)
    rows = [list(rgba) * size for _ in range(size)]
    with open(path, "wb") as handle:
        png.Writer(size, size, greyscale=False, alpha=True).write(handle, rows)

def render_all():
    emit("start", blender="{version}")
    for k, view in enumerate(job["renders"]):
        size = job["layouts"][view["layout"]]["resolution"]
        total = len(job["renders"])
        emit("render_start", layout=view["layout"], view=view["view"], index=k, total=total)
        write_png(view["output"], size)
        emit("render", layout=view["layout"], view=view["view"], index=k,
             total=total, seconds=0.01, output=view["output"])
    for key in ("save_blend", "save_material"):
        if job.get(key):
            with open(job[key], "wb") as handle:
                handle.write(b"BLENDER-v500 fake")
            emit("saved", path=job[key], kind=key)
"""

#: A fake Blender that works: renders every view as a flat-colour PNG.
WORKS = "render_all()\nemit('done', seconds=0.01)\n"


def pytest_configure(config: pytest.Config) -> None:
    config.addinivalue_line(
        "markers", "blender: needs Blender 4.2+ or the bpy module (make blender-venv)"
    )


@pytest.fixture(scope="session")
def blender() -> Any:
    """The real Blender (or bpy Python) the command would use; skips the test without one."""
    from matloom.blender.runner import BlenderError, find_blender

    try:
        return find_blender()
    except BlenderError as err:
        pytest.skip(f"no Blender or bpy here ({err})")


@pytest.fixture
def fake_blender(tmp_path: Path) -> Callable[..., Path]:
    """``fake_blender(body, name="blender", version="4.2.3")``: an executable Python script
    standing in for Blender (a name starting with "python" stands in for a bpy Python);
    ``header=False`` leaves out :data:`FAKE_HEADER` (a program that is not Blender at all)."""

    def make(
        body: str = WORKS, name: str = "blender", version: str = "4.2.3", header: bool = True
    ) -> Path:
        folder = tmp_path / "fakes"
        folder.mkdir(exist_ok=True)
        path = folder / name
        header_text = FAKE_HEADER.replace("{version}", version) if header else "\n"
        path.write_text(f"#!{sys.executable}\n" + header_text + textwrap.dedent(body))
        path.chmod(path.stat().st_mode | stat.S_IXUSR)
        return path

    return make


def cli_env() -> dict[str, str]:
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    for var in ("MATLOOM_BLENDER", "MATLOOM_BLENDER_PYTHON"):
        env.pop(var, None)
    return env


@pytest.fixture
def cli_environment() -> dict[str, str]:
    """The environment of a ``python -m matloom`` subprocess, without any Blender set."""
    return cli_env()


@pytest.fixture
def matloom_cli() -> Callable[..., subprocess.CompletedProcess[str]]:
    """``matloom_cli(*args)``: run ``python -m matloom`` with no Blender in the environment."""

    def run(*args: str) -> subprocess.CompletedProcess[str]:
        return subprocess.run(
            [sys.executable, "-m", "matloom", *args],
            capture_output=True,
            text=True,
            env=cli_env(),
            timeout=300,
        )

    return run


@pytest.fixture
def one_line_error() -> Callable[[subprocess.CompletedProcess[str]], str]:
    """The single ``Error:`` line of a failed command (no traceback)."""

    def check(res: subprocess.CompletedProcess[str]) -> str:
        assert res.returncode != 0, res.stderr
        assert "Traceback" not in res.stderr, res.stderr
        errors = [line for line in res.stderr.splitlines() if line.startswith("Error:")]
        assert len(errors) == 1, res.stderr
        return errors[0]

    return check
