"""Every kind of Blender failure is one clear line and leaves nothing half-written.

Blender is replaced by small fake executables (conftest.py's ``fake_blender``): missing, not
Blender, too old (as an executable and as a bpy module), crashing before and in the middle of a
render, killed after a partial write, printing garbage, writing a garbage image, and a command
stopped by SIGTERM while Blender runs. The real kill of a real render is in
test_blender_render.py.
"""

from __future__ import annotations

import json
import signal
import subprocess
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

from matloom.blender.runner import Blender, BlenderError, check_version, find_blender, run_worker
from matloom.io.outdir import STAGING_PREFIX

ROOT = Path(__file__).resolve().parents[2]
PROGRAM = ROOT / "docs" / "examples" / "01_plank_floor.mat"
Fake = Callable[..., Path]


def _visible(folder: Path) -> list[str]:
    """Every file under ``folder`` except MatLoom's hidden index (nothing else may remain)."""
    return sorted(
        str(p.relative_to(folder))
        for p in folder.rglob("*")
        if p.is_file() and p.name != ".matloom-files.json"
    )


# ------------------------------------------------------------------ finding Blender


def test_missing_blender_says_how_to_get_one(
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
    matloom_cli: Any,
    one_line_error: Any,
) -> None:
    with pytest.raises(BlenderError, match="make blender-venv"):
        find_blender(str(tmp_path / "nowhere" / "blender"))
    monkeypatch.setattr("matloom.blender.runner.project_venvs", lambda: [])
    with pytest.raises(BlenderError, match=r"Blender not found; install Blender 4\.2"):
        find_blender(None, env={"PATH": str(tmp_path)})
    res = matloom_cli(
        "blender", str(PROGRAM), "-o", str(tmp_path / "o"), "--blender", str(tmp_path / "nope")
    )
    line = one_line_error(res)
    assert "Blender not found" in line and "blender.org" in line and "make blender-venv" in line
    assert not (tmp_path / "o").exists()


def test_a_file_that_is_not_executable(tmp_path: Path, one_line_error: Any) -> None:
    plain = tmp_path / "blender"
    plain.write_text("not a program")
    with pytest.raises(BlenderError, match="is not executable"):
        find_blender(str(plain))


def test_discovery_order(tmp_path: Path, fake_blender: Fake) -> None:
    exe = fake_blender()
    python = fake_blender(name="python3.11")
    assert find_blender(str(python)).kind == "bpy"
    assert find_blender(None, env={"MATLOOM_BLENDER": str(exe)}).kind == "blender"
    found = find_blender(None, env={"MATLOOM_BLENDER_PYTHON": str(exe), "PATH": ""})
    assert found.kind == "bpy" and found.origin == "MATLOOM_BLENDER_PYTHON"
    assert find_blender(None, env={"PATH": str(exe.parent)}).path == str(exe)


# ------------------------------------------------------------------ wrong version


def test_wrong_version_and_not_blender(fake_blender: Fake) -> None:
    old = fake_blender(version="3.6.5", name="old")
    with pytest.raises(BlenderError, match=r"Blender 3\.6\.5; MatLoom needs 4\.2"):
        check_version(Blender(str(old), "blender", "test"))
    just_below = fake_blender(version="4.1.1", name="b41")
    with pytest.raises(BlenderError, match=r"Blender 4\.1\.1; MatLoom needs 4\.2"):
        check_version(Blender(str(just_below), "blender", "test"))
    other = fake_blender('print("hello")\n', name="other", header=False)
    with pytest.raises(BlenderError, match="does not look like Blender"):
        check_version(Blender(str(other), "blender", "test"))
    failing = fake_blender("import sys\nsys.exit(9)\n", name="failing", header=False)
    with pytest.raises(BlenderError, match=r"exited with status 9"):
        check_version(Blender(str(failing), "blender", "test"))
    assert check_version(Blender(str(fake_blender()), "blender", "t"))[:2] == (4, 2)
    assert check_version(Blender(str(fake_blender(version="5.0.1", name="b5")), "blender", "t"))


def test_wrong_version_through_the_command(
    tmp_path: Path, fake_blender: Fake, matloom_cli: Any, one_line_error: Any
) -> None:
    old = fake_blender(version="4.1.0")
    res = matloom_cli("blender", str(PROGRAM), "-o", str(tmp_path / "o"), "--blender", str(old))
    line = one_line_error(res)
    assert "Blender 4.1.0; MatLoom needs 4.2 or newer" in line and "blender.org" in line
    assert not (tmp_path / "o").exists()  # refused before anything is written


def test_too_old_bpy_module_is_one_line(
    tmp_path: Path, fake_blender: Fake, matloom_cli: Any, one_line_error: Any
) -> None:
    """A Python whose bpy is too old: the worker itself reports it (as worker.py does)."""
    python = fake_blender(
        "emit('start', blender='4.0.2')\n"
        "emit('error', kind='version', message='Blender 4.0.2 is too old: MatLoom needs 4.2 "
        "or newer')\nsys.exit(4)\n",
        name="python3.11",
    )
    out = tmp_path / "o"
    res = matloom_cli("blender", str(PROGRAM), "-o", str(out), "--blender", str(python))
    assert "Blender 4.0.2 is too old: MatLoom needs 4.2 or newer" in one_line_error(res)
    assert _visible(out) == []


# ------------------------------------------------------------------ crashes and garbage


@pytest.mark.parametrize(
    ("body", "message"),
    [
        ("os.kill(os.getpid(), signal.SIGSEGV)\n", "killed by SIGSEGV"),
        (
            "print('boom: out of memory'); sys.exit(3)\n",
            r"exited with status 3 \(.*\); last output: boom",
        ),
        ("emit('error', message='no GPU memory')\nsys.exit(1)\n", "Blender: no GPU memory"),
        ("sys.exit(0)\n", "exited without finishing the job"),
        (  # garbage on stdout, malformed event lines, then a clean exit
            "sys.stdout.buffer.write(bytes(range(256)) * 4)\n"
            "print('MATLOOM-JSON {not json')\nprint('MATLOOM-JSON [1, 2]')\nsys.exit(0)\n",
            "exited without finishing the job",
        ),
    ],
)
def test_worker_failures_are_one_clear_line(
    tmp_path: Path, fake_blender: Fake, body: str, message: str
) -> None:
    fake = fake_blender(body)
    job = tmp_path / "job.json"
    job.write_text("{}")
    with pytest.raises(BlenderError, match=message) as info:
        run_worker(Blender(str(fake), "blender", "test"), job)
    assert "\n" not in str(info.value)


CRASH_MID_RENDER = """
emit("start", blender="4.2.3")
view = job["renders"][0]
emit("render_start", layout=view["layout"], view=0, index=0, total=1)
head, tail = os.path.split(view["output"])
with open(os.path.join(head, "." + tail + ".tmp-0123456789ab"), "wb") as handle:
    handle.write(b"\\x89PNG\\r\\n\\x1a\\n half an image")
os.kill(os.getpid(), signal.SIGSEGV)
"""


@pytest.mark.parametrize("target", ["folder", "out.png"])
def test_crash_mid_render_leaves_nothing(
    tmp_path: Path, fake_blender: Fake, matloom_cli: Any, one_line_error: Any, target: str
) -> None:
    out = tmp_path / "out"
    out.mkdir()
    (out / "notes.txt").write_text("mine")
    dest = out if target == "folder" else out / target
    fake = fake_blender(CRASH_MID_RENDER)
    res = matloom_cli(
        "blender", str(PROGRAM), "-o", str(dest), "--size", "16", "--blender", str(fake)
    )
    assert "killed by SIGSEGV" in one_line_error(res)
    assert _visible(out) == ["notes.txt"]
    assert not [p for p in out.iterdir() if p.name.startswith((STAGING_PREFIX, ".matloom.lock"))]
    assert (out / "notes.txt").read_text() == "mine"


def test_killed_render_leaves_no_half_written_png(
    tmp_path: Path, fake_blender: Fake, matloom_cli: Any, one_line_error: Any
) -> None:
    """A Blender killed after writing part of an image under the final name: nothing appears
    in the output folder, the staging folder is cleaned, the user's file is untouched."""
    fake = fake_blender(
        """
with open(job["renders"][0]["output"], "wb") as handle:
    handle.write(b"\\x89PNG\\r\\n\\x1a\\n half")
os.kill(os.getpid(), signal.SIGKILL)
"""
    )
    out = tmp_path / "out"
    out.mkdir()
    (out / "notes.txt").write_text("mine")
    res = matloom_cli(
        "blender", str(PROGRAM), "-o", str(out), "--size", "16", "--blender", str(fake)
    )
    assert "killed by SIGKILL" in one_line_error(res)
    assert _visible(out) == ["notes.txt"]
    assert not [p for p in out.iterdir() if p.name.startswith(STAGING_PREFIX)]


@pytest.mark.parametrize(
    ("writer", "message"),
    [
        ("open(view['output'], 'wb').write(b'not a png at all')", "unreadable image flat.png"),
        ("open(view['output'], 'wb').write(b'\\x89PNG\\r\\n\\x1a\\n')", "unreadable image"),
        ("write_png(view['output'], 8)", "not the requested 16x16"),
        ("pass", "finished but wrote no image flat.png"),
    ],
)
@pytest.mark.parametrize("target", ["folder", "out.png"])
def test_garbage_image_is_refused(
    tmp_path: Path,
    fake_blender: Fake,
    matloom_cli: Any,
    one_line_error: Any,
    writer: str,
    message: str,
    target: str,
) -> None:
    """Blender says it is done but what it wrote is no image of the asked size."""
    fake = fake_blender(
        f"""
emit("start", blender="4.2.3")
view = job["renders"][0]
{writer}
emit("render", layout="flat", view=0, index=0, total=1, seconds=0.1, output=view["output"])
emit("done", seconds=0.1)
"""
    )
    out = tmp_path / "out"
    dest = out if target == "folder" else out / target
    res = matloom_cli(
        "blender", str(PROGRAM), "-o", str(dest), "--size", "16", "--blender", str(fake)
    )
    assert message in one_line_error(res)
    assert not out.exists() or _visible(out) == []


def test_a_foreign_file_is_never_overwritten(
    tmp_path: Path, fake_blender: Fake, matloom_cli: Any, one_line_error: Any
) -> None:
    out = tmp_path / "out"
    out.mkdir()
    (out / "flat.png").write_bytes(b"an artist's file")
    fake = fake_blender()
    res = matloom_cli(
        "blender", str(PROGRAM), "-o", str(out), "--size", "16", "--blender", str(fake)
    )
    assert "never overwrites" in one_line_error(res)
    assert (out / "flat.png").read_bytes() == b"an artist's file"
    single = matloom_cli(
        "blender", str(PROGRAM), "-o", str(out / "flat.png"), "--size", "16", "--blender", str(fake)
    )
    assert "not written by MatLoom" in one_line_error(single)
    assert (out / "flat.png").read_bytes() == b"an artist's file"


# ------------------------------------------------------------------ stopping the command


def test_sigterm_stops_blender_and_cleans_up(
    tmp_path: Path, fake_blender: Fake, cli_environment: dict[str, str]
) -> None:
    """`kill <matloom>` while two Blenders render (--jobs 2): both are stopped, no staging
    folder stays, no traceback."""
    pids = tmp_path / "pids"
    pids.mkdir()
    fake = fake_blender(
        f"""
open(os.path.join({str(pids)!r}, str(os.getpid())), "w").close()
emit("start", blender="4.2.3")
time.sleep(120)
"""
    )
    out = tmp_path / "out"
    proc = subprocess.Popen(
        [sys.executable, "-m", "matloom", "blender", str(PROGRAM), str(PROGRAM), "-o", str(out)]
        + ["--size", "16", "--jobs", "2", "--blender", str(fake)],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env=cli_environment,
    )
    deadline = time.monotonic() + 120
    while len(list(pids.iterdir())) < 2:
        assert proc.poll() is None and time.monotonic() < deadline, proc.communicate()
        time.sleep(0.1)
    proc.send_signal(signal.SIGTERM)
    _, stderr = proc.communicate(timeout=60)
    assert proc.returncode != 0 and "Traceback" not in stderr, stderr
    for pid in (int(p.name) for p in pids.iterdir()):
        assert not _alive(pid), f"Blender {pid} still runs"
    assert _visible(out) == []
    assert not [p for p in out.iterdir() if p.name.startswith(STAGING_PREFIX)]


def _alive(pid: int) -> bool:
    """True while ``pid`` runs (a zombie of an exited fake counts as gone)."""
    for _ in range(100):
        try:
            with open(f"/proc/{pid}/stat") as handle:
                state = handle.read().rsplit(")", 1)[1].split()[0]
        except FileNotFoundError:
            return False
        if state in ("Z", "X"):
            return False
        time.sleep(0.1)
    return True


def test_worker_events_are_json_lines(tmp_path: Path, fake_blender: Fake) -> None:
    """The runner hands every event to the caller as it arrives."""
    fake = fake_blender(
        "emit('start', blender='4.2.3')\nemit('warning', message='x')\nemit('done', seconds=0)\n"
    )
    job = tmp_path / "job.json"
    job.write_text(json.dumps({"renders": []}))
    seen: list[str] = []
    events = run_worker(Blender(str(fake), "blender", "t"), job, lambda e: seen.append(e["event"]))
    assert seen == ["start", "warning", "done"] == [e["event"] for e in events]
