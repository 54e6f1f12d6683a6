"""The runtime state of one MatLoom user: a :class:`Session`, explicit, passed to the engine.

A process has one default session (:func:`default_session`); a long-lived server or a Dask
worker makes its own and passes it (``evaluate(..., session=s)``, ``shade(..., session=s)``),
or makes it the default for a while (:func:`use_session`, what the CLI does for one command).
The session holds what used to hide in module globals:

* the **backend policy** (:meth:`Session.choose_backend`, :meth:`Session.choose_shader`):
  ``auto`` weighs numba's one-off start-up (importing numba, loading its cached kernels: about
  0.3-1 s) against its speed, so a short command (one small image) runs on numpy and a large
  or repeated one on numba; both give the same maps;
* the **cold start** (:attr:`Session.cold_start`): what ``auto`` does while numba's kernels
  are not compiled yet. ``None`` (the library's default) compiles them on first use; the CLI
  gives a :class:`ColdStart` from :mod:`matloom.runtime.cold_start` that compiles them in a
  background process and keeps ``auto`` on numpy meanwhile;
* the compile/progress **reporter** (a ``CompileReporter``; None is silent);
* the evaluation **lock** (re-entrant): the numba kernels are ``parallel=True`` and share one
  thread pool whose default threading layer is not thread-safe, so ``evaluate`` takes it for
  each evaluation, and callers that run other engine work from several threads (shading,
  sweeps: the author's batch, the studio) hold it around that work too;
* **caches** (parsed and seeded programs, bounded LRU per kind) and the warm-up state.

Environment variables are read once, when :meth:`Session.from_env` creates a session (the
default session is created that way on first use): ``MATLOOM_BACKEND`` (``auto``, ``numpy`` or
``numba``: what ``auto`` means) and ``MATLOOM_PURE_NUMPY`` (``1``: the numpy backend's fBm on
the pure-numpy loops instead of the C extension's; the same numbers). Changing them later
affects new sessions only. ``Session()`` itself reads nothing: the library's defaults.
"""

from __future__ import annotations

import os
import sys
import threading
from collections import OrderedDict
from collections.abc import Callable, Hashable, Iterator, Mapping
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Protocol, TypeVar

if TYPE_CHECKING:
    from matloom.engine.kernels.compile_report import CompileReporter

T = TypeVar("T")

#: Environment variables :meth:`Session.from_env` reads.
BACKEND_ENV = "MATLOOM_BACKEND"
PURE_NUMPY_ENV = "MATLOOM_PURE_NUMPY"
BACKENDS = ("auto", "numpy", "numba")

#: ``auto`` picks numba for requests of at least this many texels (numba's start-up cost is
#: then small next to what it saves: a whole ``matloom render`` of the tile program breaks even
#: near 724 x 724 on the 2-core machines; at 512 x 512 numpy takes 0.72 s, numba 1.05 s) ...
AUTO_NUMBA_MIN_TEXELS = 768 * 768
#: ... and for every request once this many evaluations ran in the session, or numba is loaded
#: in the process already (its import is paid) ...
AUTO_NUMBA_AFTER_CALLS = 2
#: ... and for a request whose work (texels times the cost model's nodes per texel,
#: :func:`matloom.lang.cost.expanded_cost`) is at least this: three times the tile program's
#: break-even (122 nodes at 724 x 724). A program of many Tile instances or shapes ("climbing
#: ivy": 13,701 nodes) took 4.6 s on numpy at 512 x 512, well under a second on numba.
AUTO_NUMBA_MIN_WORK = 200_000_000
#: Entries kept per cache kind (:meth:`Session.cached`).
CACHE_SIZE = 64


class ColdStart(Protocol):
    """What ``auto`` asks while the numba kernels may not be compiled yet (the runtime's
    background compiler implements it, see :mod:`matloom.runtime.cold_start`)."""

    def compiling(self) -> tuple[int, int] | None:
        """None when numba may be used now (its kernels are ready, or compiling them elsewhere
        cannot help: numba then compiles on first use); ``(done, total)`` steps while they
        compile in the background (``auto`` then stays on numpy)."""


@dataclass
class Session:
    """Explicit runtime state for evaluations (see the module docstring)."""

    #: Backend name asked for when a call says ``auto`` (``auto``, ``numpy`` or ``numba``).
    backend: str = "auto"
    #: The numpy backend runs the pure-numpy fBm loops even where the C extension is built.
    pure_numpy: bool = False
    #: What ``auto`` does while the numba kernels are not compiled (None: compile on first
    #: use; the CLI gives the runtime's background compiler).
    cold_start: ColdStart | None = None
    #: Receives compile and progress events (a ``CompileReporter``); None is silent.
    reporter: CompileReporter | None = None
    #: Serialises engine work of this session (re-entrant).
    lock: threading.RLock = field(default_factory=threading.RLock, repr=False)
    #: Evaluations run in this session (``auto``'s warm-process rule reads it).
    evaluations: int = 0
    #: Whether this session picked numba (where installed) for some evaluation (its shading
    #: follows).
    numba_used: bool = False
    #: Whether the cold start reported the kernels usable (asked until it does).
    kernels_ready: bool = False
    #: Bounded caches by kind (parsed programs, seeded programs, ...): see :meth:`cached`.
    caches: dict[str, OrderedDict[Hashable, Any]] = field(default_factory=dict, repr=False)
    _cache_lock: threading.Lock = field(default_factory=threading.Lock, repr=False)

    def __post_init__(self) -> None:
        if self.backend not in BACKENDS:
            raise ValueError(f"unknown backend {self.backend!r}; choose {', '.join(BACKENDS)}")

    @classmethod
    def from_env(cls, environ: Mapping[str, str] | None = None, **settings: Any) -> Session:
        """A session whose backend settings come from the environment (read now, once; see
        the module docstring); ``settings`` override them and set the other fields."""
        env = os.environ if environ is None else environ
        values: dict[str, Any] = {
            "backend": env.get(BACKEND_ENV, "auto") or "auto",
            "pure_numpy": env.get(PURE_NUMPY_ENV) == "1",
        }
        return cls(**{**values, **settings})

    # --- backend policy -------------------------------------------------------------------

    def choose_backend(self, name: str = "auto", texels: int = 0, work: int = 0) -> str:
        """The backend name to load for an evaluation of ``texels`` texels (the backend itself:
        :func:`matloom.engine.backends.session_backend`). A name other than ``auto`` (or a
        session whose :attr:`backend` is not ``auto``) is kept. ``auto`` weighs numba's
        start-up: ``auto`` again (numba where installed, else numpy) when numba is loaded in
        the process already, or this session has run more than
        :data:`AUTO_NUMBA_AFTER_CALLS` evaluations, or the request has at least
        :data:`AUTO_NUMBA_MIN_TEXELS` texels or :data:`AUTO_NUMBA_MIN_WORK` ``work`` -- and
        :meth:`numba_kernels_usable`; else ``numpy``."""
        if name == "auto":
            name = self.backend
        if name != "auto":
            return name
        warm = numba_loaded() or self.evaluations > AUTO_NUMBA_AFTER_CALLS
        big = texels >= AUTO_NUMBA_MIN_TEXELS or work >= AUTO_NUMBA_MIN_WORK
        if (warm or big) and self.numba_kernels_usable():
            self.numba_used = True
            return "auto"
        return "numpy"

    def choose_shader(self, name: str = "auto", texels: int = 0) -> str:
        """The preview shader (``numba`` or ``numpy``: the same images but for one level on
        rare texels) for an image of ``texels`` texels. A name other than ``auto`` is kept;
        ``auto`` is this session's :attr:`backend` when it names one, else numba where its
        start-up is paid or worth it: numba is loaded in the process, or this session
        evaluated on it, or the image has at least :data:`AUTO_NUMBA_MIN_TEXELS` texels. So a
        short command (one small render, a preview, a check) never imports numba to shade.

        Unlike :meth:`choose_backend` this does not look at the cold start, so a render or
        preview command writes the same image whether the kernels were compiled before it or
        not (below the size the evaluation and the shading stay on numpy either way; above it
        both runs shade on numba). A session that evaluates several times (``generate``)
        shades on numba once it has evaluated on it, which a cold start delays. The caller
        falls back to numpy where numba is not installed."""
        if name == "auto":
            name = self.backend
        if name != "auto":
            return name
        warm = self.numba_used or numba_loaded()
        return "numba" if warm or texels >= AUTO_NUMBA_MIN_TEXELS else "numpy"

    def numba_kernels_usable(self) -> bool:
        """False while ``auto`` should stay on numpy: the :attr:`cold_start` reports the
        kernels compiling in the background (the :attr:`reporter` hears of it)."""
        if self.cold_start is None or self.kernels_ready:
            return True
        from importlib.util import find_spec

        if find_spec("numba") is None:
            return True  # the numba backend falls back to numpy by itself
        progress = self.cold_start.compiling()
        if progress is None:
            self.kernels_ready = True
            return True
        if self.reporter is not None:
            self.reporter.background_compiling(*progress)
        return False

    # --- caches ---------------------------------------------------------------------------

    def cached(self, kind: str, key: Hashable, make: Callable[[], T]) -> T:
        """``make()``, memoised under ``(kind, key)``; the :data:`CACHE_SIZE` most recently
        used entries of each kind are kept. Only immutable values belong here (they are
        shared). An exception from ``make`` is not cached."""
        with self._cache_lock:
            entries = self.caches.setdefault(kind, OrderedDict())
            if key in entries:
                entries.move_to_end(key)
                return entries[key]
        value = make()
        with self._cache_lock:
            entries[key] = value
            while len(entries) > CACHE_SIZE:
                entries.popitem(last=False)
        return value

    def clear_caches(self) -> None:
        """Forget every cached entry."""
        with self._cache_lock:
            self.caches.clear()


def numba_loaded() -> bool:
    """Whether numba is imported in this process (a process fact, not session state: its
    import cost is paid once for every session)."""
    return sys.modules.get("numba") is not None


_DEFAULT: list[Session | None] = [None]
_DEFAULT_LOCK = threading.Lock()
#: The session of the evaluation running in this thread (set by :func:`running`).
_RUNNING: ContextVar[Session | None] = ContextVar("matloom_session", default=None)


def default_session() -> Session:
    """The process's default session (created on first use, from the environment)."""
    with _DEFAULT_LOCK:
        if _DEFAULT[0] is None:
            _DEFAULT[0] = Session.from_env()
        return _DEFAULT[0]


@contextmanager
def use_session(session: Session) -> Iterator[Session]:
    """Make ``session`` the process's default session inside the block (the previous one
    comes back after it); what a front end does for one command."""
    with _DEFAULT_LOCK:
        previous, _DEFAULT[0] = _DEFAULT[0], session
    try:
        yield session
    finally:
        with _DEFAULT_LOCK:
            _DEFAULT[0] = previous


@contextmanager
def running(session: Session) -> Iterator[Session]:
    """Mark ``session`` as the one evaluating in this thread inside the block (compile events
    of numba go to its reporter, see :func:`current_session`)."""
    token = _RUNNING.set(session)
    try:
        yield session
    finally:
        _RUNNING.reset(token)


def current_session() -> Session:
    """The session evaluating in this thread (:func:`running`), else the default session."""
    return _RUNNING.get() or default_session()
