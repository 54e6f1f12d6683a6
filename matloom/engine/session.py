"""The runtime state of one MatLoom user: a :class:`Session`, explicit, passed to the engine.

A process has one default session (:func:`default_session`); a long-lived server or a Dask
worker makes its own. The session holds what used to hide in module globals: the backend
policy, the compile/progress reporter, the evaluation lock (the numba kernels are
``parallel=True`` and share one thread pool, so engine work is serialised per session), and
caches.

(Skeleton written first so that every part of the wave-3 architecture work shares one
interface; the backend policy and caches are filled in by that work.)
"""

from __future__ import annotations

import threading
from dataclasses import dataclass, field
from typing import Any


@dataclass
class Session:
    """Explicit runtime state for evaluations (see the module docstring)."""

    #: Backend name asked for when a call says ``auto`` (``auto``, ``numpy`` or ``numba``).
    backend: str = "auto"
    #: What ``auto`` does while the numba kernels are not compiled: ``compile`` or
    #: ``background`` (the CLI's).
    cold_start: str = "compile"
    #: Receives compile and progress events (a ``CompileReporter``); None is silent.
    reporter: Any = None
    #: Serialises engine work of this session (re-entrant).
    lock: threading.RLock = field(default_factory=threading.RLock, repr=False)
    #: Evaluations run in this session (``auto``'s warm-process rule reads it).
    evaluations: int = 0
    #: Free-form caches keyed by purpose (parsed programs, plans, Define values).
    caches: dict[str, Any] = field(default_factory=dict, repr=False)


_DEFAULT: list[Session | None] = [None]
_DEFAULT_LOCK = threading.Lock()


def default_session() -> Session:
    """The process's default session (created on first use)."""
    with _DEFAULT_LOCK:
        if _DEFAULT[0] is None:
            _DEFAULT[0] = Session()
        return _DEFAULT[0]
