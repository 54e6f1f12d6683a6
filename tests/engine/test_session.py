"""The runtime :class:`Session`: an explicit backend policy, independent sessions, the process's
default session, the caches, and the compile reporter of the session that is evaluating."""

from __future__ import annotations

import os
import subprocess
import sys
import threading
from pathlib import Path

import pytest

from matloom.engine import session as session_module
from matloom.engine.backends import session_backend
from matloom.engine.evaluate import evaluate, prepare
from matloom.engine.session import (
    AUTO_NUMBA_AFTER_CALLS,
    AUTO_NUMBA_MIN_TEXELS,
    AUTO_NUMBA_MIN_WORK,
    CACHE_SIZE,
    Session,
    current_session,
    default_session,
    running,
    use_session,
)

ROOT = Path(__file__).resolve().parents[2]
SMALL, BIG = 64 * 64, AUTO_NUMBA_MIN_TEXELS
PROGRAM = "Material(Layer(1).basecolor(120 + fBm(seed=1) * 60, 90, 80))"


@pytest.fixture()
def cold_process(monkeypatch: pytest.MonkeyPatch) -> None:
    """As in a fresh process: numba not imported yet."""
    monkeypatch.setattr(session_module, "numba_loaded", lambda: False)


def _numba_installed() -> bool:
    from importlib.util import find_spec

    return find_spec("numba") is not None


def test_explicit_policy() -> None:
    assert session_backend(Session(backend="numpy"), "auto", BIG).name == "numpy"
    assert Session(backend="numpy").choose_shader("auto", BIG) == "numpy"
    assert session_backend(Session(), "numpy", BIG).name == "numpy"  # a name is kept
    assert Session(backend="numpy").choose_shader("numba", SMALL) == "numba"
    if _numba_installed():
        assert session_backend(Session(backend="numba"), "auto", SMALL).name == "numba"
        assert Session(backend="numba").choose_shader("auto", SMALL) == "numba"
    with pytest.raises(ValueError, match="unknown backend"):
        Session(backend="gpu")


def test_auto_is_numpy_for_a_short_command(cold_process: None) -> None:
    """One small image: numpy for evaluating and shading (numba's start-up would dominate);
    a large one, or a session that has evaluated a few times, goes to numba."""
    session = Session()
    assert session_backend(session, "auto", SMALL).name == "numpy"
    assert session.choose_shader("auto", SMALL) == "numpy"
    assert not session.numba_used
    if not _numba_installed():
        return
    assert session.choose_shader("auto", BIG) == "numba"
    assert session_backend(session, "auto", BIG).name == "numba"
    assert session.numba_used  # ... and small shading follows: its start-up is paid
    assert session.choose_shader("auto", SMALL) == "numba"
    warm = Session(evaluations=AUTO_NUMBA_AFTER_CALLS + 1)
    assert session_backend(warm, "auto", SMALL).name == "numba"


def test_auto_is_numba_for_a_small_image_of_a_costly_program(cold_process: None) -> None:
    """The cost model's work decides too: at 512 x 512 a program of thousands of nodes per
    texel (many Tile instances of shapes) goes to numba, a cheap one stays on numpy."""
    if not _numba_installed():
        return
    texels = 512 * 512
    assert session_backend(Session(), "auto", texels, 100 * texels).name == "numpy"
    heavy = Session()
    assert session_backend(heavy, "auto", texels, AUTO_NUMBA_MIN_WORK).name == "numba"
    # evaluate() weighs the program's own cost: a Tile of 400 path-drawn motifs per cell
    motif = (
        "Fill(Path(0, 0, "
        + ", ".join(f"LineTo({k % 7 * 0.01}, {k % 5 * 0.01})" for k in range(60))
        + "))"
    )
    costly = (
        f"Material(Layer(1).basecolor(Tile({motif}, 0.05, 0.05, rotate=90, seed=1) * 255, 0, 0))"
    )
    cheap = Session()
    evaluate(PROGRAM, 512, 512, session=cheap)
    assert not cheap.numba_used
    dear = Session()
    evaluate(costly, 512, 512, session=dear)
    assert dear.numba_used


def test_environment_is_read_once_when_the_session_is_made(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    monkeypatch.setenv("MATLOOM_BACKEND", "numpy")
    monkeypatch.setenv("MATLOOM_PURE_NUMPY", "1")
    made = Session.from_env()
    assert (made.backend, made.pure_numpy) == ("numpy", True)
    monkeypatch.delenv("MATLOOM_BACKEND")
    monkeypatch.delenv("MATLOOM_PURE_NUMPY")
    assert (made.backend, made.pure_numpy) == ("numpy", True)  # unchanged
    assert (Session.from_env().backend, Session.from_env().pure_numpy) == ("auto", False)
    assert Session.from_env({"MATLOOM_BACKEND": "numba"}).backend == "numba"
    assert Session.from_env({"MATLOOM_BACKEND": "numba"}, backend="numpy").backend == "numpy"
    assert Session().backend == "auto"  # Session() reads nothing
    pure = session_backend(Session.from_env({"MATLOOM_PURE_NUMPY": "1"}), "numpy")
    assert pure.fbm_loops is not None and pure.fbm_loops().name == "numpy"


def test_two_sessions_are_independent(cold_process: None) -> None:
    a, b = Session(backend="numpy"), Session(backend="numpy")
    assert a.lock is not b.lock and a.caches is not b.caches
    for _ in range(3):
        evaluate(PROGRAM, 16, 16, session=a)
    assert (a.evaluations, b.evaluations) == (3, 0)
    assert ("parsed" in a.caches, "parsed" in b.caches) == (True, False)
    assert prepare(PROGRAM, session=a) is prepare(PROGRAM, session=a)
    assert prepare(PROGRAM, session=a) is not prepare(PROGRAM, session=b)
    assert prepare(PROGRAM, session=a) == prepare(PROGRAM, session=b)
    # a warm session goes to numba for small images, a fresh one does not
    if _numba_installed():
        assert session_backend(Session(evaluations=3), "auto", SMALL).name == "numba"
    assert session_backend(Session(), "auto", SMALL).name == "numpy"


def test_default_session() -> None:
    default = default_session()
    assert default_session() is default and current_session() is default
    before = default.evaluations
    evaluate(PROGRAM, 8, 8, backend="numpy")
    assert default.evaluations == before + 1
    own = Session(backend="numpy")
    with use_session(own) as used:
        assert used is own and default_session() is own and current_session() is own
        evaluate(PROGRAM, 8, 8)
        seen: list[Session] = []
        worker = threading.Thread(target=lambda: seen.append(default_session()))
        worker.start()
        worker.join()
        assert seen == [own]  # the default is the process's, every thread sees it
    assert default_session() is default
    assert own.evaluations == 1 and default.evaluations == before + 1


def test_running_session_is_current_in_its_thread_only() -> None:
    own = Session()
    with running(own):
        assert current_session() is own
        seen: list[Session] = []
        worker = threading.Thread(target=lambda: seen.append(current_session()))
        worker.start()
        worker.join()
        assert seen == [default_session()]
    assert current_session() is default_session()


def test_caches_are_bounded_and_skip_failures() -> None:
    session = Session()
    calls: list[int] = []
    for k in range(CACHE_SIZE + 5):
        session.cached("kind", k, lambda k=k: calls.append(k) or k)
    assert len(session.caches["kind"]) == CACHE_SIZE
    assert session.cached("kind", CACHE_SIZE + 4, lambda: -1) == CACHE_SIZE + 4  # kept
    assert session.cached("kind", 0, lambda: -1) == -1  # evicted, made again
    with pytest.raises(ZeroDivisionError):
        session.cached("kind", "bad", lambda: 1 // 0)
    assert "bad" not in session.caches["kind"]
    session.clear_caches()
    assert session.caches == {}


def test_a_short_render_never_imports_numba(tmp_path: Path) -> None:
    """The one-shot speed rule: ``matloom render --size 256`` (preview included) evaluates and
    shades on numpy and never pays numba's import, warm numba cache or not."""
    code = (
        "import sys\n"
        "from matloom.cli.main import cli\n"
        f"cli.main(['render', {str(ROOT / 'tests/data/parity/tile.mat')!r}, '--size', '256',"
        f" '-o', {str(tmp_path / 'out')!r}], standalone_mode=False)\n"
        "assert 'numba' not in sys.modules, 'numba was imported'\n"
    )
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    env.pop("MATLOOM_BACKEND", None)
    proc = subprocess.run(
        [sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=300
    )
    assert proc.returncode == 0, proc.stderr
    assert (tmp_path / "out" / "preview.png").exists()
