"""First-run kernel compilation: readiness stamp and lock, the CLI session's cold start, the
compile progress messages, and (slow) the whole flow from an empty numba cache."""

from __future__ import annotations

import io
import os
import signal
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path

import pytest

from matloom.cli.progress import COMPILING, KernelProgress
from matloom.engine.backends import session_backend
from matloom.engine.session import Session, running, use_session
from matloom.runtime import warmup
from matloom.runtime.cold_start import BACKGROUND_ENV, BackgroundCompile, background_compile

ROOT = Path(__file__).resolve().parents[2]
TILE = ROOT / "tests" / "data" / "parity" / "tile.mat"


def _dead_pid() -> int:
    proc = subprocess.run(
        [sys.executable, "-c", "import os; print(os.getpid())"],
        check=True,
        capture_output=True,
        text=True,
    )
    return int(proc.stdout)


def test_state_follows_the_stamp_and_the_lock(tmp_path: Path) -> None:
    assert warmup.state(tmp_path) == warmup.WarmupState(ready=False)
    (tmp_path / warmup.LOCK_NAME).write_text(str(os.getpid()))  # a live "compiler"
    warmup.write_json(tmp_path / warmup.STATUS_NAME, {"done": 2, "total": 6})
    assert warmup.state(tmp_path) == warmup.WarmupState(False, running=True, done=2, total=6)
    (tmp_path / warmup.LOCK_NAME).write_text(str(_dead_pid()))  # it died
    assert not warmup.state(tmp_path).running
    warmup.write_json(tmp_path / warmup.STAMP_NAME, {"key": "an older install"})
    assert not warmup.state(tmp_path).ready
    warmup.write_json(tmp_path / warmup.STAMP_NAME, {"key": warmup.stamp_key()})
    assert warmup.state(tmp_path).ready
    warmup.write_json(tmp_path / warmup.STAMP_NAME, {"key": warmup.stamp_key(), "error": "x"})
    assert warmup.state(tmp_path) == warmup.WarmupState(ready=False, error="x")


def test_stamp_key_follows_code_generation_settings(monkeypatch: pytest.MonkeyPatch) -> None:
    key = warmup.stamp_key()
    monkeypatch.setenv("MATLOOM_NUMBA_WIDE_VECTORS", "0")
    assert warmup.stamp_key() != key


def test_background_compiler_can_be_switched_off(monkeypatch: pytest.MonkeyPatch) -> None:
    """$MATLOOM_BACKGROUND_COMPILE=0: the CLI's session gets no cold start (numba compiles on
    first use); the variable is read when the session is made."""
    monkeypatch.setenv(BACKGROUND_ENV, "0")
    assert background_compile() is None
    assert background_compile({}) is not None or os.name != "posix"
    monkeypatch.delenv(BACKGROUND_ENV)
    if os.name == "posix":
        assert isinstance(background_compile(), BackgroundCompile)


class _Recorder:
    def __init__(self) -> None:
        self.events: list[tuple[str, ...]] = []

    def kernel_compiling(self, name: str) -> None:
        self.events.append(("compiling", name))

    def kernel_compiled(self, name: str, seconds: float) -> None:
        self.events.append(("compiled", name))

    def background_compiling(self, done: int, total: int) -> None:
        self.events.append(("background", f"{done}/{total}"))


@pytest.fixture()
def recorder() -> Iterator[_Recorder]:
    """A recorder, the reporter of the default session during the test."""
    rec = _Recorder()
    with use_session(Session(reporter=rec)):
        yield rec


def test_cold_start_evaluates_on_numpy_while_the_kernels_compile(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    pytest.importorskip("numba")
    states = [warmup.WarmupState(False, running=True, done=1, total=6)]
    monkeypatch.setattr(warmup, "ensure_background", lambda: states[0])
    big = 1024 * 1024
    rec = _Recorder()
    library = Session(reporter=rec)  # the library's default: numba compiles on first use
    assert session_backend(library, "auto", big).name == "numba"
    assert rec.events == []
    cli = Session(reporter=rec, cold_start=BackgroundCompile())
    assert session_backend(cli, "auto", big).name == "numpy"
    assert rec.events == [("background", "1/6")]
    # the preview's shader does not follow the cold start: a cold and a warm run of one
    # command write the same preview (the shaders may differ by one level on rare texels)
    assert cli.choose_shader("auto", big) == library.choose_shader("auto", big) == "numba"
    assert session_backend(cli, "numba", big).name == "numba"  # asked for: no fallback
    assert cli.choose_shader("numba", big) == "numba"
    states[0] = warmup.WarmupState(ready=True)
    assert session_backend(cli, "auto", big).name == "numba"
    assert cli.kernels_ready
    states[0] = warmup.WarmupState(False, running=True)  # asked until ready, not after
    assert session_backend(cli, "auto", big).name == "numba"


def test_compile_events_of_matloom_kernels_reach_the_reporter(recorder: _Recorder) -> None:
    numba = pytest.importorskip("numba")
    import matloom.engine.kernels.jit  # noqa: F401 - installs the listener

    def ours(x: float) -> float:
        return x + 1.0

    def theirs(x: float) -> float:
        return x * 2.0

    ours.__module__ = "matloom.engine.kernels.example"
    numba.njit(ours)(1.0)
    numba.njit(theirs)(1.0)
    assert recorder.events == [
        ("compiling", "example.ours"),
        ("compiled", "example.ours"),
    ]
    evaluating = _Recorder()  # the session evaluating in this thread hears, not the default
    with running(Session(reporter=evaluating)):
        numba.njit(ours)(2.0)
    assert evaluating.events == [("compiling", "example.ours"), ("compiled", "example.ours")]
    assert len(recorder.events) == 2


def test_kernel_progress_lines(monkeypatch: pytest.MonkeyPatch) -> None:
    out = io.StringIO()
    progress = KernelProgress(out)
    progress.close()
    assert out.getvalue() == ""  # nothing compiled: quiet
    progress = KernelProgress(out)
    progress.kernel_compiling("composite_numba.composite_rows")
    progress.kernel_compiled("composite_numba.composite_rows", 5.0)
    progress.close()
    first, summary = out.getvalue().splitlines()
    assert first.startswith(COMPILING) and "composite_rows" in first
    assert summary.startswith(COMPILING) and "1 kernel(s) compiled" in summary
    out = io.StringIO()
    progress = KernelProgress(out)
    progress.background_compiling(2, 6)
    monkeypatch.setattr(warmup, "state", lambda: warmup.WarmupState(False, True, 3, 6))
    progress.close()
    started, summary = out.getvalue().splitlines()
    assert started.startswith(COMPILING) and "2/6 in the background" in started
    assert "3/6 done, continuing in the background" in summary


def _render(out: Path, env: dict[str, str]) -> subprocess.CompletedProcess[str]:
    # (a size at which ``auto`` wants numba: smaller ones stay on numpy, cold or warm)
    cmd = [sys.executable, "-m", "matloom", "render", str(TILE), "--size", "1024", "-o", str(out)]
    return subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=600, check=False)


@pytest.mark.slow
@pytest.mark.numba
def test_first_render_says_it_compiles_and_a_warm_one_is_quiet(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Empty numba cache: the first render reports the (background) compilation and renders on
    the numpy path; once compiled, a render is quiet and its maps are the same bytes. Slow: the
    background compiler needs 20 s of CPU or more."""
    pytest.importorskip("numba")
    cache = tmp_path / "numba-cache"
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(cache))
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    env.pop(BACKGROUND_ENV, None)
    try:
        cold = _render(tmp_path / "cold", env)
        assert cold.returncode == 0, cold.stderr
        assert f"{COMPILING} 0/{len(warmup.STEPS)} in the background" in cold.stderr
        assert warmup.wait(cache, timeout=900).ready
        warm = _render(tmp_path / "warm", env)
        assert warm.returncode == 0, warm.stderr
        assert COMPILING not in warm.stderr, warm.stderr
    finally:
        pid = warmup._lock_pid(cache) if cache.exists() else None
        if pid and pid != os.getpid() and warmup._alive(pid):
            os.killpg(pid, signal.SIGTERM)
    maps = sorted(p.name for p in (tmp_path / "cold").iterdir() if not p.name.startswith("."))
    assert "basecolor.png" in maps and "height.exr" in maps
    for name in maps:  # every file, the preview included: a cold start changes no byte
        a, b = (tmp_path / run / name for run in ("cold", "warm"))
        assert a.read_bytes() == b.read_bytes(), name
