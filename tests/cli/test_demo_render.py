"""`matloom demo`, `matloom render`, `matloom preview`, `matloom sweep` end to end (subprocess)."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
import uuid
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
TILE = ROOT / "tests" / "data" / "parity" / "tile.mat"


def run(*args: str, cwd: Path | None = None) -> subprocess.CompletedProcess[str]:
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    return subprocess.run(
        [sys.executable, "-m", "matloom", *args],
        capture_output=True,
        text=True,
        env=env,
        cwd=cwd,
        timeout=600,
    )


def test_demo_writes_everything_it_prints(tmp_path):
    out = tmp_path / "demo"
    res = run("demo", "-o", str(out), "--size", "64")
    assert res.returncode == 0, res.stderr
    paths = [
        line.split(None, 1)[1]
        for line in res.stdout.splitlines()
        if line.strip().startswith(("program", "preview", "record"))
    ]
    assert len(paths) >= 2 + 3 * 3
    for p in paths:
        assert Path(p.strip()).exists(), p
    again = run("demo", "-o", str(out), "--size", "64")
    assert again.returncode == 0, again.stderr


def _processes_with(marker: str) -> list[str]:
    """The command lines of live processes whose environment holds ``marker`` (every process
    the demo starts inherits its environment, detached ones too; /proc, Linux only)."""
    found = []
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit() or int(entry.name) == os.getpid():
            continue
        try:
            environ = (entry / "environ").read_bytes()
            cmdline = (entry / "cmdline").read_bytes()
        except OSError:
            continue  # gone meanwhile, or not ours
        if marker.encode() in environ.split(b"\0"):
            found.append(cmdline.replace(b"\0", b" ").decode(errors="replace"))
    return found


#: words of the engine's insides that the demo's messages must not show the user
_JARGON = ("numpy", "numba", "kernel", "compil", "backend")


@pytest.mark.slow
@pytest.mark.numba
@pytest.mark.skipif(not Path("/proc/self/environ").exists(), reason="needs Linux /proc")
def test_a_first_demo_ends_with_nothing_running_and_speaks_plainly(tmp_path):
    """A first demo on a machine (empty compiled-code cache) sets up the fast renderer in the
    background; when the command returns nothing it started may still run, and no message
    talks of kernels or the numpy path. Slow: the set-up needs 20 s of CPU or more."""
    pytest.importorskip("numba")
    marker = f"MATLOOM_DEMO_TEST={uuid.uuid4().hex}"
    key, value = marker.split("=", 1)
    env = {**os.environ, "PYTHONPATH": str(ROOT), "NUMBA_CACHE_DIR": str(tmp_path / "cache")}
    env[key] = value
    env.pop("MATLOOM_BACKGROUND_COMPILE", None)
    cmd = [sys.executable, "-m", "matloom", "demo", "-o", str(tmp_path / "demo"), "--size", "64"]
    try:
        res = subprocess.run(cmd, capture_output=True, text=True, env=env, timeout=900)
        left = _processes_with(marker)
    finally:
        for pid in {int(p.name) for p in Path("/proc").iterdir() if p.name.isdigit()}:
            try:  # never leave the demo's processes behind, even when the test fails
                if marker.encode() in Path(f"/proc/{pid}/environ").read_bytes().split(b"\0"):
                    os.kill(pid, signal.SIGKILL)
            except OSError:
                pass
    assert res.returncode == 0, res.stderr
    assert left == [], left
    said = (res.stdout + res.stderr).lower()
    assert not [w for w in _JARGON if w in said], res.stdout + res.stderr


def test_render_exports_maps_and_manifest(tmp_path):
    out = tmp_path / "maps"
    res = run("render", str(TILE), "-o", str(out), "--size", "48", "--format", "png16")
    assert res.returncode == 0, res.stderr
    manifest = json.loads((out / "material.json").read_text())
    assert manifest["width"] == 48
    for name in (
        "basecolor.png",
        "normal_gl.png",
        "ao.png",
        "height.exr",
        "height16.png",
        "preview.png",
        "material.mat",
    ):
        assert (out / name).exists(), name


def test_render_rejects_unknown_map_and_bad_program(tmp_path):
    res = run("render", str(TILE), "-o", str(tmp_path / "x"), "--maps", "basecolor,shininess")
    assert res.returncode != 0 and "shininess" in res.stderr
    bad = tmp_path / "bad.mat"
    bad.write_text("Material(Layer(1).roughnes(0.5))")
    res = run("render", str(bad), "-o", str(tmp_path / "y"))
    assert res.returncode == 2 and "did you mean" in res.stderr
    assert not (tmp_path / "y").exists()


def test_render_reports_nonfinite_texels(tmp_path):
    prog = tmp_path / "nan.mat"
    prog.write_text(
        "Material(\n  Layer(1)\n    .roughness(Sqrt(X() - 0.5))\n    .height(Log(X() - 0.5))\n)"
    )
    res = run("render", str(prog), "-o", str(tmp_path / "n"), "--size", "16")
    assert res.returncode == 0, res.stderr
    assert "non-finite" in res.stderr


def test_preview_tile_and_sweep_cli(tmp_path):
    png = tmp_path / "p.png"
    res = run(
        "preview", str(TILE), "-o", str(png), "--size", "32", "--tile", "2", "--light", "30,40"
    )
    assert res.returncode == 0, res.stderr
    from PIL import Image

    assert Image.open(png).size == (64, 64)
    res = run("sweep", str(TILE), "-k", "3", "--size", "32", "--json", "-o", str(tmp_path / "s"))
    assert res.returncode == 0, res.stderr
    report = json.loads(res.stdout)
    assert report["candidates"] == 4
    assert (tmp_path / "s" / "best.mat").exists()


def test_a_set_up_that_runs_too_long_is_stopped_with_its_process_group(
    tmp_path, monkeypatch
) -> None:
    # what the demo does after waiting SETUP_WAIT_S: its own background compiler (a session
    # leader, with a helper in its group) is stopped, and its lock released
    from matloom.runtime import warmup

    leader = subprocess.Popen(  # stands in for the compiler and the helper it starts
        [sys.executable, "-c", "import subprocess, sys, time; subprocess.Popen([sys.executable,"
         " '-c', 'import time; time.sleep(120)']); time.sleep(120)"],
        start_new_session=True,
    )  # fmt: skip
    monkeypatch.setattr(warmup, "_children", [leader])
    (tmp_path / warmup.LOCK_NAME).write_text(str(leader.pid), encoding="utf-8")
    try:
        deadline = time.monotonic() + 60
        while len(_group(leader.pid)) < 2 and time.monotonic() < deadline:
            time.sleep(0.05)  # until the helper runs too (a sync, not a timing assertion)
        assert len(_group(leader.pid)) == 2
        warmup.stop_background(tmp_path)
        assert leader.poll() is not None
        deadline = time.monotonic() + 30
        while _group(leader.pid) and time.monotonic() < deadline:
            time.sleep(0.05)  # signal delivery is asynchronous (a sync, not a timing test)
        assert _group(leader.pid) == []
        assert not (tmp_path / warmup.LOCK_NAME).exists()
    finally:
        if leader.poll() is None:
            os.killpg(leader.pid, signal.SIGKILL)


def _group(pgid: int) -> list[int]:
    """The live (not zombie) processes of process group ``pgid``."""
    members = []
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit() and _pgid(int(entry.name)) == pgid:
            try:
                state = (entry / "stat").read_text().rsplit(")", 1)[1].split()[0]
            except (OSError, IndexError):
                continue
            if state != "Z":
                members.append(int(entry.name))
    return members


def _pgid(pid: int) -> int | None:
    try:
        return os.getpgid(pid)
    except OSError:
        return None
