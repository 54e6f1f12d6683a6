"""First-run compilation of the numba kernels: a readiness stamp and a background compiler.

numba compiles each kernel on its first call and caches the machine code on disk (the numba
cache: ``$NUMBA_CACHE_DIR``, else ``__pycache__`` next to the kernels, else the user's cache).
Compiling everything the evaluation path uses takes about 20 s of CPU on the 2-core machines we
measure on, loading it from the cache well under a second. So the CLI's session
(:mod:`matloom.cli.progress`, with :class:`matloom.runtime.cold_start.BackgroundCompile` as its
cold start) evaluates a request on the numpy/C path -- bit-identical maps -- while
:func:`ensure_background` has a detached process (:func:`main`, running the steps of
:mod:`warmup_steps`) compile every kernel once; that process writes a stamp into the cache
directory when it is done, and from then on the numba path is used.

The stamp holds a key of everything the cached code depends on (the numba and llvmlite installs,
Python, the CPU, the kernel sources -- the ABI hash of :mod:`abi`, which also keys each cached
kernel -- and numba's code-generation settings): an upgrade or an edited kernel makes the
kernels cold again. A lock file holds the background compiler's pid, so
that concurrent commands start one compiler only, and one that died is replaced. Nothing here
imports numba. Whether a background compiler may run at all (``$MATLOOM_BACKGROUND_COMPILE``)
is decided once per session (:func:`matloom.runtime.cold_start.background_compile`).
"""

from __future__ import annotations

import hashlib
import json
import os
import platform
import subprocess
import sys
import time
from collections.abc import Callable
from dataclasses import dataclass
from importlib.util import find_spec
from pathlib import Path

from matloom.engine.kernels import abi
from matloom.runtime.warmup_steps import STEPS

STAMP_NAME = "matloom-kernels.json"
LOCK_NAME = "matloom-kernels.lock"
STATUS_NAME = "matloom-kernels.status.json"
#: The module the background compiler runs (:func:`main`).
COMPILER_MODULE = "matloom.runtime.warmup"
#: Environment variables that change numba's generated code (part of the stamp key).
_CODEGEN_ENV = ("MATLOOM_NUMBA_WIDE_VECTORS", "NUMBA_CPU_FEATURES", "NUMBA_CPU_NAME", "NUMBA_OPT")
#: The numba kernels' directory (their ``__pycache__`` is numba's first cache candidate) and the
#: directory holding ``matloom``.
_KERNELS = abi.KERNELS
_PACKAGE_ROOT = abi.PACKAGE_ROOT

#: Seconds a lock without a pid yet counts as held.
_STARTING_GRACE_S = 60.0


@dataclass(frozen=True)
class WarmupState:
    """Where the kernels stand: ``ready`` (stamp matches), ``running`` (a live background
    compiler holds the lock; ``done`` of ``total`` steps finished), or neither (cold)."""

    ready: bool
    running: bool = False
    done: int = 0
    total: int = len(STEPS)
    error: str | None = None


def cache_dir() -> Path | None:
    """The directory of the numba cache of the kernels (numba's rule), or None when no location
    is writable (numba then compiles without caching and a warm-up could not persist)."""
    env = os.environ.get("NUMBA_CACHE_DIR")
    candidates = [Path(env)] if env else [_KERNELS / "__pycache__", _user_cache()]
    for path in candidates:
        try:
            path.mkdir(parents=True, exist_ok=True)
        except OSError:
            continue
        if os.access(path, os.W_OK):
            return path
    return None


def _user_cache() -> Path:
    if sys.platform == "darwin":
        return Path.home() / "Library" / "Caches" / "numba"
    return Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache") / "numba"


def stamp_key() -> str:
    """Hash of everything the cached kernels depend on (see the module docstring)."""
    parts: list[object] = [sys.version, platform.machine(), _cpu_flags()]
    for package in ("numba", "llvmlite"):
        spec = find_spec(package)
        origin = spec.origin if spec and spec.origin else ""
        parts.append((package, origin, _stat(Path(origin)) if origin else None))
    parts.append([(name, os.environ.get(name)) for name in _CODEGEN_ENV])
    parts.append(abi.kernels_hash())  # the kernels' sources, as numba's stamps see them (jit)
    return hashlib.sha256(json.dumps(parts, default=str).encode()).hexdigest()[:32]


def _stat(path: Path) -> tuple[int, int] | None:
    try:
        st = path.stat()
    except OSError:
        return None
    return st.st_mtime_ns, st.st_size


def _cpu_flags() -> str:
    """The CPU model and feature flags (they select numba's code), as far as cheaply known."""
    try:
        with open("/proc/cpuinfo", encoding="utf-8", errors="replace") as f:
            lines = [
                ln for ln in f.read().splitlines()[:40] if ln.startswith(("model name", "flags"))
            ]
        return hashlib.sha256("\n".join(lines).encode()).hexdigest()[:16]
    except OSError:
        return platform.processor()


def _read_json(path: Path) -> dict | None:
    try:
        value = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    return value if isinstance(value, dict) else None


def write_json(path: Path, value: dict) -> None:
    """Write ``value`` as JSON atomically (readers never see a partial file)."""
    tmp = path.with_name(f"{path.name}.{os.getpid()}.tmp")
    tmp.write_text(json.dumps(value), encoding="utf-8")
    os.replace(tmp, path)


#: Background compilers started by this process (polled, so that they are reaped when done).
_children: list[subprocess.Popen[bytes]] = []


def _alive(pid: int) -> bool:
    for child in _children:
        if child.pid == pid:
            return child.poll() is None
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except (PermissionError, OSError):
        return True
    return True


def state(directory: Path | None = None) -> WarmupState:
    """The current :class:`WarmupState` of the cache in ``directory`` (default :func:`cache_dir`)."""
    directory = directory or cache_dir()
    if directory is None:
        return WarmupState(ready=False, error="no writable numba cache directory")
    stamp = _read_json(directory / STAMP_NAME)
    if stamp and stamp.get("key") == stamp_key():
        return WarmupState(ready=not stamp.get("error"), error=stamp.get("error"))
    pid = _lock_pid(directory)
    if pid is not None and _alive(pid):
        status = _read_json(directory / STATUS_NAME) or {}
        done, total = int(status.get("done", 0)), int(status.get("total", len(STEPS)))
        return WarmupState(ready=False, running=True, done=done, total=total)
    return WarmupState(ready=False)


def _lock_pid(directory: Path) -> int | None:
    """The background compiler's pid from the lock; None without a (fresh) lock. A lock still
    without a pid (the starter writes it after spawning) counts for a minute."""
    lock = directory / LOCK_NAME
    try:
        text = lock.read_text(encoding="utf-8").strip()
        age = time.time() - lock.stat().st_mtime
    except OSError:
        return None
    if text.isdigit() and int(text) > 0:
        return int(text)
    return os.getpid() if age < _STARTING_GRACE_S else None


def ensure_background(directory: Path | None = None) -> WarmupState:
    """Start the background compiler unless the kernels are ready, it runs already, or it
    failed before for this key (whether one should run at all is decided by the caller:
    :func:`matloom.runtime.cold_start.background_compile`)."""
    directory = directory or cache_dir()
    current = state(directory)
    if current.ready or current.running or current.error or directory is None:
        return current
    lock = directory / LOCK_NAME
    if lock.exists():  # state() found no live compiler behind it: it died, take over
        lock.unlink(missing_ok=True)
    try:
        fd = os.open(lock, os.O_CREAT | os.O_EXCL | os.O_WRONLY)
    except FileExistsError:
        return state(directory)
    except OSError as exc:
        return WarmupState(ready=False, error=str(exc))
    with os.fdopen(fd, "w") as f:
        f.write("0")
    try:
        child = _spawn(directory)
    except OSError as exc:
        lock.unlink(missing_ok=True)
        return WarmupState(ready=False, error=str(exc))
    _children.append(child)
    lock.write_text(str(child.pid), encoding="utf-8")
    return WarmupState(ready=False, running=True)


def _spawn(directory: Path) -> subprocess.Popen[bytes]:
    """``python -m matloom.runtime.warmup DIR`` (:func:`main`), detached, output discarded."""
    package_root = str(_PACKAGE_ROOT)
    env = dict(
        os.environ,
        PYTHONPATH=os.pathsep.join(filter(None, [package_root, os.environ.get("PYTHONPATH")])),
    )
    return subprocess.Popen(  # noqa: S603 - our own module, same interpreter
        [sys.executable, "-m", COMPILER_MODULE, str(directory)],
        stdin=subprocess.DEVNULL,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
        cwd=package_root,
        env=env,
        start_new_session=True,  # outlives the command, and its Ctrl-C
    )


def reap(timeout: float = 30.0) -> None:
    """Wait until the background compilers this process started have exited (they release
    the lock just before they exit), so that none outlives a command that waited for them."""
    deadline = time.monotonic() + timeout
    for child in _children:
        try:
            child.wait(timeout=max(0.0, deadline - time.monotonic()))
        except subprocess.TimeoutExpired:
            pass


def stop_background(directory: Path | None = None) -> None:
    """Stop the background compilers this process started that still run, with their helper
    (each leads its own process group), and release their lock; the next command that needs
    the kernels starts one again. A compiler another command started is left alone."""
    import signal

    directory = directory or cache_dir()
    for child in _children:
        if child.poll() is not None:
            continue
        try:
            os.killpg(child.pid, signal.SIGTERM)
            child.wait(timeout=10.0)
        except subprocess.TimeoutExpired:
            os.killpg(child.pid, signal.SIGKILL)
            child.wait()
        except OSError:
            continue
        try:  # a helper of the group that outlived SIGTERM goes too
            os.killpg(child.pid, signal.SIGKILL)
        except OSError:  # the group is already empty
            pass
        if directory is not None and _lock_pid(directory) == child.pid:
            (directory / LOCK_NAME).unlink(missing_ok=True)
            (directory / STATUS_NAME).unlink(missing_ok=True)


def wait(
    directory: Path | None = None,
    timeout: float = 600.0,
    progress: Callable[[int, int], None] | None = None,
    steps: int | None = None,
    poll: float = 0.2,
) -> WarmupState:
    """Wait until the background compiler is no longer running, or has finished ``steps``
    steps, or ``timeout`` seconds passed; ``progress(done, total)`` is called while waiting."""
    deadline = time.monotonic() + timeout
    current = state(directory)
    while current.running and time.monotonic() < deadline:
        if steps is not None and current.done >= steps:
            break
        if progress is not None:
            progress(current.done, current.total)
        time.sleep(poll)
        current = state(directory)
    return current


def main(argv: list[str] | None = None) -> int:
    """The background compiler (``python -m matloom.runtime.warmup DIR``): run the steps of
    :mod:`warmup_steps` into the cache directory ``DIR``, then write the stamp (or the error)
    and release the lock."""
    from matloom.runtime.warmup_steps import run_steps

    args = sys.argv[1:] if argv is None else argv
    os.nice(5)  # the foreground work comes first
    directory = Path(args[0]) if args else cache_dir()
    if directory is None:
        return 1
    key = stamp_key()
    status = directory / STATUS_NAME

    def report(done: int, total: int, label: str) -> None:
        write_json(status, {"done": done, "total": total, "step": label})

    try:
        seconds = run_steps(report)
        write_json(directory / STAMP_NAME, {"key": key, "seconds": round(seconds, 2)})
        return 0
    except Exception as exc:  # noqa: BLE001 - recorded, so that the CLI stops waiting for us
        error = f"{type(exc).__name__}: {exc}"
        write_json(directory / STAMP_NAME, {"key": key, "error": error})
        return 1
    finally:
        status.unlink(missing_ok=True)
        (directory / LOCK_NAME).unlink(missing_ok=True)


if __name__ == "__main__":
    sys.exit(main())
