"""Find Blender and run the worker in it as a separate process (``bpy`` is never imported here).

Blender is, in this order: ``--blender PATH`` (a Blender executable, or a Python with the ``bpy``
module when its name starts with ``python``), ``$MATLOOM_BLENDER`` (the same),
``$MATLOOM_BLENDER_PYTHON`` (a Python with ``bpy``), ``blender`` on PATH, or the project's
``.venv-blender/bin/python`` (``make blender-venv``: bpy 5.0.x for Python 3.11). Every failure
(missing executable, wrong version, crash, non-zero exit, kill) is a :class:`BlenderError`
whose message is one line and says how to get Blender.
"""

from __future__ import annotations

import json
import os
import re
import shutil
import signal
import subprocess
import threading
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from matloom.blender.layouts import MIN_BLENDER

PREFIX = "MATLOOM-JSON "
WORKER = Path(__file__).with_name("worker.py")
VENV_NAME = ".venv-blender"
HOW_TO_GET = (
    "install Blender 4.2 or newer (https://www.blender.org/download/) and pass --blender PATH "
    "or set MATLOOM_BLENDER, or run `make blender-venv` (the bpy 5.0 module for Python 3.11)"
)
_VERSION = re.compile(r"Blender\s+(\d+)\.(\d+)(?:\.(\d+))?")
#: Blender processes running now (``--jobs N``): :func:`stop_all` ends them on Ctrl-C.
_RUNNING: set[subprocess.Popen[str]] = set()
_RUNNING_LOCK = threading.Lock()
#: Set by :func:`stop_all`: no new Blender starts once the command is being stopped.
_STOPPING = threading.Event()


class BlenderError(Exception):
    """Blender is missing or failed; the message is one line for the user."""


@dataclass(frozen=True)
class Blender:
    """A way to run the worker: a Blender executable or a Python with ``bpy``."""

    path: str
    kind: str  # "blender" or "bpy"
    origin: str  # where it was found (for messages)

    def command(self, job: Path) -> list[str]:
        if self.kind == "bpy":
            return [self.path, str(WORKER), str(job)]
        return [
            self.path,
            "-b",
            "--factory-startup",
            "--python-exit-code",
            "1",
            "--python",
            str(WORKER),
            "--",
            str(job),
        ]


def _kind_of(path: str) -> str:
    return "bpy" if Path(path).name.startswith("python") else "blender"


def _resolve(path: str, origin: str) -> Blender:
    found = shutil.which(path) if os.sep not in path else path
    if not found or not os.path.isfile(found):
        raise BlenderError(f"Blender not found at {path} ({origin}); {HOW_TO_GET}")
    if not os.access(found, os.X_OK):
        raise BlenderError(f"{found} ({origin}) is not executable; {HOW_TO_GET}")
    return Blender(found, _kind_of(found), origin)


def project_venvs() -> list[Path]:
    """Candidate ``.venv-blender`` folders: the current folder and the source checkout."""
    roots = [Path.cwd(), Path(__file__).resolve().parents[2]]
    return [root / VENV_NAME / "bin" / "python" for root in dict.fromkeys(roots)]


def find_blender(explicit: str | None = None, env: dict[str, str] | None = None) -> Blender:
    """The Blender to use (see the module docstring); :class:`BlenderError` when there is none."""
    env = dict(os.environ) if env is None else env
    if explicit:
        return _resolve(explicit, "--blender")
    if env.get("MATLOOM_BLENDER"):
        return _resolve(env["MATLOOM_BLENDER"], "MATLOOM_BLENDER")
    if env.get("MATLOOM_BLENDER_PYTHON"):
        found = _resolve(env["MATLOOM_BLENDER_PYTHON"], "MATLOOM_BLENDER_PYTHON")
        return Blender(found.path, "bpy", found.origin)
    on_path = shutil.which("blender", path=env.get("PATH"))
    if on_path:
        return Blender(on_path, "blender", "PATH")
    for python in project_venvs():
        if python.is_file():
            return Blender(str(python), "bpy", str(python.parents[1]))
    raise BlenderError(f"Blender not found; {HOW_TO_GET}")


def check_version(blender: Blender, timeout: float = 60.0) -> tuple[int, ...]:
    """Run ``blender --version`` (executables only); refuse anything that is not Blender 4.2+."""
    if blender.kind == "bpy":
        return ()  # the worker checks bpy.app.version itself and reports a clear error
    try:
        done = subprocess.run(
            [blender.path, "--version"],
            capture_output=True,
            text=True,
            errors="replace",
            timeout=timeout,
            stdin=subprocess.DEVNULL,
        )
    except OSError as err:
        raise BlenderError(
            f"cannot run {blender.path}: {err.strerror or err}; {HOW_TO_GET}"
        ) from None
    except subprocess.TimeoutExpired:
        raise BlenderError(f"{blender.path} --version did not answer in {timeout:.0f} s") from None
    match = _VERSION.search(done.stdout + "\n" + done.stderr)
    if done.returncode != 0 or match is None:
        raise BlenderError(
            f"{blender.path} ({blender.origin}) does not look like Blender "
            f"(`--version` {_status(done.returncode)}); {HOW_TO_GET}"
        )
    version = tuple(int(g) for g in match.groups() if g is not None)
    if version[:2] < MIN_BLENDER:
        raise BlenderError(
            f"{blender.path} is Blender {'.'.join(map(str, version))}; MatLoom needs 4.2 or "
            f"newer: {HOW_TO_GET}"
        )
    return version


def _status(code: int) -> str:
    if code < 0:
        try:
            return f"killed by {signal.Signals(-code).name}"
        except ValueError:
            return f"killed by signal {-code}"
    return f"exited with status {code}"


def _tail(lines: list[str], n: int = 3) -> str:
    useful = [line.strip() for line in lines if line.strip()]
    text = " | ".join(useful[-n:])
    return text[-400:]


def run_worker(
    blender: Blender,
    job_path: Path,
    on_event: Callable[[dict[str, Any]], None] | None = None,
    timeout: float | None = None,
    temp_dir: Path | None = None,
) -> list[dict[str, Any]]:
    """Run the worker on ``job_path`` and return its events; :class:`BlenderError` on failure.

    ``on_event`` sees each event as it arrives (progress). Blender's own output is kept only
    to explain a failure. ``temp_dir``: Blender's temporary folder (its ``blender_*`` folder
    goes there): one of ours, so that it goes with ours even when Blender cannot remove it.
    """
    events: list[dict[str, Any]] = []
    other: list[str] = []
    env = dict(os.environ)
    if temp_dir is not None:
        # Blender leaves $TMPDIR/blender_* behind when it ends by os._exit or a signal
        env.update(TMPDIR=str(temp_dir), TEMP=str(temp_dir), TMP=str(temp_dir))
    env.setdefault("PYTHONUNBUFFERED", "1")
    env["MATLOOM_PARENT_PID"] = str(os.getpid())  # the worker ends itself if we are gone
    with _RUNNING_LOCK:  # checked and registered together: stop_all() misses no process
        if _STOPPING.is_set():
            raise BlenderError("stopped before Blender started (MatLoom is being stopped)")
        try:
            proc = subprocess.Popen(
                blender.command(job_path),
                stdout=subprocess.PIPE,
                stderr=subprocess.STDOUT,
                stdin=subprocess.DEVNULL,
                text=True,
                errors="replace",
                env=env,
                start_new_session=True,  # Ctrl-C reaches us; we stop Blender ourselves
            )
        except OSError as err:
            raise BlenderError(
                f"cannot run {blender.path}: {err.strerror or err}; {HOW_TO_GET}"
            ) from None
        _RUNNING.add(proc)
    try:
        assert proc.stdout is not None
        for line in proc.stdout:
            if line.startswith(PREFIX):
                try:
                    event = json.loads(line[len(PREFIX) :])
                except ValueError:
                    other.append(line)
                    continue
                if isinstance(event, dict):
                    events.append(event)
                    if on_event is not None:
                        on_event(event)
            else:
                other.append(line)
                del other[:-40]
        code = proc.wait(timeout=timeout)
    except BaseException:
        _stop(proc)
        raise
    finally:
        with _RUNNING_LOCK:
            _RUNNING.discard(proc)
    errors = [e for e in events if e.get("event") == "error"]
    if errors:
        raise BlenderError(f"Blender: {errors[-1].get('message', 'failed')} ({blender.path})")
    if code != 0:
        detail = _tail(other)
        raise BlenderError(
            f"Blender {_status(code)} ({blender.path})"
            + (f"; last output: {detail}" if detail else "")
            + ("; is it a working Blender 4.2+?" if not events else "")
        )
    if not any(e.get("event") == "done" for e in events):
        started = any(e.get("event") == "start" for e in events)
        raise BlenderError(
            f"Blender exited without finishing the job ({blender.path})"
            + ("" if started else f": the worker never started; {HOW_TO_GET}")
        )
    return events


def _stop(proc: subprocess.Popen[str]) -> None:
    try:
        os.killpg(proc.pid, signal.SIGTERM)
        proc.wait(timeout=10)
    except (OSError, subprocess.TimeoutExpired):
        try:
            os.killpg(proc.pid, signal.SIGKILL)
        except OSError:
            pass
        proc.wait()


def stop_all() -> None:
    """Stop every Blender process this MatLoom process started and that is still running, and
    start no new one (the command is ending: Ctrl-C or SIGTERM)."""
    _STOPPING.set()
    with _RUNNING_LOCK:
        running = list(_RUNNING)
    for proc in running:
        if proc.poll() is None:
            _stop(proc)
