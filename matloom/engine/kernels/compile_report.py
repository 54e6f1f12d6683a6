"""Who hears about numba compiling MatLoom's kernels (the CLI shows it on stderr).

A library stays silent: nothing is reported unless the session gives a :class:`CompileReporter`
(``Session(reporter=...)``, see :mod:`matloom.engine.session`). :mod:`matloom.engine.kernels.jit`
calls :func:`install_listener` when it imports numba; the listener forwards numba's
``numba:compile`` events to the reporter of the current session (the one evaluating in this
thread, else the process's default session: :func:`~matloom.engine.session.current_session`).
numba raises them only for real compilations (never for kernels loaded from its disk cache),
so a warm cache stays quiet. Only outermost compilations of MatLoom functions are
reported: the helpers a kernel calls compile inside it. Importing this module does not import
numba.
"""

from __future__ import annotations

import threading
import time
from typing import Any, Protocol


class CompileReporter(Protocol):
    """Receives compile events (possibly from several threads) and warm-up news."""

    def kernel_compiling(self, name: str) -> None:
        """numba starts compiling the kernel ``name`` (module.function)."""

    def kernel_compiled(self, name: str, seconds: float) -> None:
        """... and finished it after ``seconds``."""

    def background_compiling(self, done: int, total: int) -> None:
        """The kernels compile in a background process (``done`` of ``total`` steps); this
        process evaluates on the numpy path meanwhile."""


_installed = [False]
_local = threading.local()


def _kernel_name(data: dict[str, Any]) -> str | None:
    func = getattr(data.get("dispatcher"), "py_func", None)
    module = getattr(func, "__module__", "") or ""
    if not module.startswith("matloom."):
        return None
    return f"{module.rsplit('.', 1)[-1]}.{func.__name__}"  # type: ignore[union-attr]


def _reporter() -> CompileReporter | None:
    # (imported here: this module is in every kernel's ABI closure, the session is not)
    from matloom.engine.session import current_session

    return current_session().reporter


def install_listener() -> None:
    """Forward numba's compile events to the current session's reporter (idempotent; imports
    numba)."""
    if _installed[0]:
        return
    from numba.core import event

    class _Listener(event.Listener):  # type: ignore[misc]
        def on_start(self, ev: Any) -> None:
            stack = _local.__dict__.setdefault("stack", [])
            stack.append(time.perf_counter())
            reporter, name = _reporter(), _kernel_name(ev.data)
            if reporter is not None and name is not None and len(stack) == 1:
                reporter.kernel_compiling(name)

        def on_end(self, ev: Any) -> None:
            stack = _local.__dict__.setdefault("stack", [])
            start = stack.pop() if stack else time.perf_counter()
            reporter, name = _reporter(), _kernel_name(ev.data)
            if reporter is not None and name is not None and not stack:
                reporter.kernel_compiled(name, time.perf_counter() - start)

    event.register("numba:compile", _Listener())
    _installed[0] = True
