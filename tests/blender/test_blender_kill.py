"""A real Blender killed in the middle of a render (bpy-marked; skipped without Blender).

The render is made large (768 px, 4096 samples) so that it is certainly still running when the
test kills it, a moment after the worker reported ``render_start``; the test then checks the
process was still alive, so it never passes by a render that finished first.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from matloom.blender import tempdirs
from matloom.blender.runner import Blender
from matloom.io.outdir import STAGING_PREFIX, OutputFolder

pytestmark = pytest.mark.blender

ROOT = Path(__file__).resolve().parents[2]
PLANK = ROOT / "docs" / "examples" / "01_plank_floor.mat"


def _start(blender: Blender, out: Path, tmpdir: Path | None = None) -> subprocess.Popen[str]:
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    if tmpdir is not None:
        env["TMPDIR"] = str(tmpdir)
    flag = "MATLOOM_BLENDER_PYTHON" if blender.kind == "bpy" else "MATLOOM_BLENDER"
    env[flag] = blender.path
    return subprocess.Popen(
        [sys.executable, "-m", "matloom", "blender", str(PLANK), "-o", str(out)]
        + ["--size", "768", "--samples", "4096", "--displacement", "off", "--device", "cpu"],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env=env,
    )


def _wait_for_render(proc: subprocess.Popen[str]) -> None:
    """Read progress lines until the render has started, then give Cycles a moment."""
    assert proc.stderr is not None
    for line in proc.stderr:
        if "rendering" in line:
            time.sleep(1.5)
            return
    pytest.fail(f"the render never started: {proc.wait()}")


def _children(pid: int) -> list[int]:
    """The Blender worker processes of ``pid`` (not, e.g., a background kernel compiler)."""
    found = []
    for task in Path(f"/proc/{pid}/task").iterdir():
        text = (task / "children").read_text()
        found += [int(p) for p in text.split()]
    return [p for p in found if b"worker.py" in Path(f"/proc/{p}/cmdline").read_bytes()]


def _gone(pid: int, seconds: float = 20.0) -> bool:
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        try:
            state = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
        except FileNotFoundError:
            return True
        if state in ("Z", "X"):
            return True
        time.sleep(0.1)
    return False


def _leftovers(out: Path) -> list[str]:
    """Everything under ``out`` except MatLoom's hidden index and lock."""
    return sorted(
        str(p.relative_to(out))
        for p in out.rglob("*")
        if p.name not in (".matloom-files.json", ".matloom.lock")
    )


@pytest.mark.skipif(not Path("/proc/self/task").is_dir(), reason="needs Linux /proc")
def test_blender_killed_mid_render(blender: Blender, tmp_path: Path) -> None:
    """SIGKILL to Blender itself: one error line, no PNG under the final name, no temp file."""
    out = tmp_path / "out"
    proc = _start(blender, out)
    _wait_for_render(proc)
    (worker,) = _children(proc.pid)
    assert proc.poll() is None and not _gone(worker, 0)  # still rendering when killed
    os.kill(worker, signal.SIGKILL)
    _, stderr = proc.communicate(timeout=120)
    assert proc.returncode == 1
    assert "Traceback" not in stderr
    errors = [line for line in stderr.splitlines() if line.startswith("Error:")]
    assert len(errors) == 1 and "killed by SIGKILL" in errors[0], stderr
    assert _leftovers(out) == []  # no flat.png, no .flat.png.tmp-*, no staging folder


@pytest.mark.skipif(not Path("/proc/self/task").is_dir(), reason="needs Linux /proc")
def test_matloom_killed_mid_render(blender: Blender, tmp_path: Path) -> None:
    """SIGKILL to MatLoom: Blender ends too (it watches its parent), nothing appears under the
    final name, and the next MatLoom run in the folder removes the staging it left; the next
    `matloom blender` run removes its temporary folders (issue 22, defect 17)."""
    out = tmp_path / "out"
    tmp = tmp_path / "tmp"
    tmp.mkdir()
    proc = _start(blender, out, tmp)
    _wait_for_render(proc)
    (worker,) = _children(proc.pid)
    assert proc.poll() is None and not _gone(worker, 0)
    proc.kill()
    proc.communicate(timeout=60)
    assert _gone(worker), "Blender rendered on after MatLoom was killed"
    assert not (out / "flat.png").exists()
    assert all(name.startswith(STAGING_PREFIX) for name in _leftovers(out))
    with OutputFolder(out):
        pass  # any MatLoom command opening the folder cleans what a killed run left
    assert _leftovers(out) == []
    leaked = sorted(tmp.glob(f"{tempdirs.PREFIX}*"))
    assert leaked, "the killed run had a temporary folder (the program's maps, the job)"
    assert sorted(tempdirs.clean_stale(tmp)) == leaked  # what the next run does first
    assert list(tmp.iterdir()) == []
