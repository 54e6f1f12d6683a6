"""stderr progress displays: :class:`LazyProgress` for long loops (appears only for work longer
than a second) and :class:`KernelProgress` for the numba kernels' first-run compilation.

:func:`command_session` is called by the ``matloom`` command group for every command: it makes
the command's :class:`~matloom.engine.session.Session` (backend settings from the environment,
a :class:`KernelProgress` reporter, the background compiler of :mod:`matloom.runtime.cold_start`
as its cold start, so ``auto`` evaluations stay on the numpy path while the kernels compile) and
makes it the process's default session while the command runs. Nothing here imports numba or
rich at import time (every command pays for this module).
"""

from __future__ import annotations

import sys
import threading
import time
from types import TracebackType
from typing import TYPE_CHECKING, Any, TextIO

if TYPE_CHECKING:
    from matloom.engine.session import Session

#: The words every compile message starts with (tests look for them).
COMPILING = "compiling kernels (first run only)"


class LazyProgress:
    """Callable ``(done, total)`` progress sink; draws on stderr after ``delay`` seconds."""

    def __init__(self, label: str, delay: float = 1.0, enabled: bool = True) -> None:
        self.label, self.delay, self.enabled = label, delay, enabled
        self.start = time.perf_counter()
        self.progress: Any = None
        self.task = None

    def __call__(self, done: int, total: int) -> None:
        if not self.enabled:
            return
        elapsed = time.perf_counter() - self.start
        if self.progress is None:
            if elapsed < self.delay:
                return
            from rich.console import Console
            from rich.progress import (
                BarColumn,
                MofNCompleteColumn,
                Progress,
                TextColumn,
                TimeRemainingColumn,
            )

            self.progress = Progress(
                TextColumn(f"[bold]{self.label}"),
                BarColumn(),
                MofNCompleteColumn(),
                TextColumn("{task.fields[rate]}"),
                TimeRemainingColumn(),
                console=Console(stderr=True),
                transient=True,
            )
            self.progress.start()
            self.task = self.progress.add_task(self.label, total=total, rate="")
        rate = done / elapsed if elapsed > 0 else 0.0
        self.progress.update(self.task, completed=done, total=total, rate=f"{rate:.0f}/s")

    def __enter__(self) -> LazyProgress:
        return self

    def __exit__(
        self, et: type[BaseException] | None, ev: BaseException | None, tb: TracebackType | None
    ) -> None:
        if self.progress is not None:
            self.progress.stop()


class KernelProgress:
    """A :class:`~matloom.engine.kernels.compile_report.CompileReporter` writing to stderr.

    Kernels compiling in this process: "compiling kernels (first run only) 3 done, now
    composite_numba.composite_rows, 9 s" while each one compiles (a status line erased when it
    is done on a terminal, one line per kernel otherwise). Kernels compiling in the background:
    one line with the steps done ("... 2/6 in the background ..."). :meth:`close` ends with a
    summary. Nothing at all is written when no kernel compiles.
    """

    def __init__(self, stream: TextIO | None = None) -> None:
        self.stream = stream or sys.stderr
        self.tty = bool(getattr(self.stream, "isatty", lambda: False)())
        self.lock = threading.Lock()
        self.start: float | None = None
        self.end = 0.0
        self.compiled = 0
        self.background: tuple[int, int] | None = None

    def kernel_compiling(self, name: str) -> None:
        with self.lock:
            if self.start is None:
                self.start = time.perf_counter()
            elapsed = time.perf_counter() - self.start
            text = f"{COMPILING} {self.compiled} done, now {name}, {elapsed:.0f} s"
            self.stream.write(f"\r\x1b[2K{text}" if self.tty else text + "\n")
            self.stream.flush()

    def kernel_compiled(self, name: str, seconds: float) -> None:
        with self.lock:
            self.compiled += 1
            self.end = time.perf_counter()
            if self.tty:  # erase the status line: other output starts on a clean line
                self.stream.write("\r\x1b[2K")
                self.stream.flush()

    def background_compiling(self, done: int, total: int) -> None:
        with self.lock:
            if self.background is None:
                self.stream.write(
                    f"{COMPILING} {done}/{total} in the background; "
                    "meanwhile this run uses the numpy path (same maps)\n"
                )
                self.stream.flush()
            self.background = (done, total)

    def close(self) -> None:
        """Write the summary line(s), if anything compiled."""
        with self.lock:
            if self.start is not None:
                elapsed = max(self.end, self.start) - self.start
                self.stream.write(
                    f"{COMPILING}: {self.compiled} kernel(s) compiled in {elapsed:.1f} s "
                    "and cached for later runs\n"
                )
            if self.background is not None:
                self.stream.write(self._background_summary() + "\n")
            self.stream.flush()

    @staticmethod
    def _background_summary() -> str:
        from matloom.runtime import warmup

        current = warmup.state()
        if current.ready:
            return f"{COMPILING}: done in the background; later runs use them"
        if current.running:
            return (
                f"{COMPILING}: {current.done}/{current.total} done, continuing in the "
                "background; later runs use them once it has finished"
            )
        if current.error:
            return f"{COMPILING}: the background compiler stopped ({current.error})"
        return (
            f"{COMPILING}: the background compiler did not finish (it was stopped, or the "
            "kernels changed meanwhile); the next command starts it again"
        )


def command_session() -> Session | None:
    """The session of the current click command (None outside one): created here and the
    process's default session until the command ends, when its reporter writes its summary
    and the previous default comes back."""
    import click

    from matloom.engine.session import Session, use_session
    from matloom.runtime.cold_start import background_compile

    ctx = click.get_current_context(silent=True)
    if ctx is None:
        return None
    reporter = KernelProgress()
    session = Session.from_env(reporter=reporter, cold_start=background_compile())
    ctx.with_resource(use_session(session))
    ctx.call_on_close(reporter.close)
    return session
