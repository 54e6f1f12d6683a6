"""The CLI's cold start: compile numba's kernels in a background process, numpy meanwhile.

:class:`BackgroundCompile` is the :class:`~matloom.engine.session.ColdStart` a front end gives
its :class:`~matloom.engine.session.Session`: when ``auto`` would pick numba, the session asks
:meth:`BackgroundCompile.compiling`, which starts the background compiler of
:mod:`matloom.runtime.warmup` unless the kernels are ready, and ``auto`` evaluates on numpy (the
same maps) until it has finished. Where it cannot help (no writable numba cache, or the
compiler failed) it answers None and numba compiles on first use, as without it.

Importing this module imports nothing else of MatLoom: a short command that never needs numba
never loads the warm-up machinery.
"""

from __future__ import annotations

import os
from collections.abc import Mapping

#: Set to "0" to turn the background compiler off (the CLI then compiles in the foreground).
BACKGROUND_ENV = "MATLOOM_BACKGROUND_COMPILE"


class BackgroundCompile:
    """A :class:`~matloom.engine.session.ColdStart` backed by the background compiler."""

    def compiling(self) -> tuple[int, int] | None:
        """None when numba may be used now; ``(done, total)`` steps while the background
        compiler runs (started here if need be)."""
        from matloom.runtime import warmup

        current = warmup.ensure_background()
        return (current.done, current.total) if current.running else None


def background_compile(environ: Mapping[str, str] | None = None) -> BackgroundCompile | None:
    """The cold start for a front end's session: a :class:`BackgroundCompile`, or None (numba
    compiles on first use) where ``$MATLOOM_BACKGROUND_COMPILE=0`` switches it off or the
    platform is not POSIX, where the compiler's pid checks do not work (read now, once per
    session)."""
    env = os.environ if environ is None else environ
    if env.get(BACKGROUND_ENV, "1") == "0" or os.name != "posix":
        return None
    return BackgroundCompile()
