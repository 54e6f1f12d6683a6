"""Tasks and the in-process executor (:class:`InlineExecutor`); :mod:`.executor` chooses between it
and the Dask executor (:mod:`.executor_dask`, an embedded ``LocalCluster`` or ``--scheduler ADDRESS``).

A :class:`Task` is idempotent: its function writes its output under ``root / key`` through a
staged folder renamed into place (:func:`matloom.evaluation.cells.commit_cell`), and a task whose
folder exists is skipped, so a rerun or a retried task (a killed worker) writes nothing twice or
half. A task with ``uses_llm`` runs holding one slot of a limit shared by every worker
(``llm_slots``), so model requests are rate-limited across the cluster; 429 answers are retried
with backoff by the model client.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable, Sequence
from concurrent.futures import FIRST_COMPLETED, Future, ThreadPoolExecutor, wait
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Protocol


@dataclass(frozen=True)
class Task:
    """One cell of work: ``fn(*args)`` returns a JSON-able summary (its files are under ``root/key``).

    ``fn`` must be a module-level function and ``args`` picklable (Dask ships them to workers).
    """

    key: str
    fn: Callable[..., dict[str, Any]]
    args: tuple[Any, ...] = ()
    uses_llm: bool = False


@dataclass(frozen=True)
class Outcome:
    """What one task came to: ``result`` when it succeeded, else ``error`` (one line)."""

    key: str
    ok: bool
    result: dict[str, Any] | None = None
    error: str | None = None
    skipped: bool = False


@dataclass
class Progress:
    """Counts for the progress line: cells done, running, failed, skipped and the ETA."""

    total: int
    done: int = 0
    running: int = 0
    failed: int = 0
    skipped: int = 0
    started: float = field(default_factory=time.monotonic)

    @property
    def eta_s(self) -> float | None:
        """Seconds left at the rate so far (None until a task has finished)."""
        worked = self.done + self.failed
        left = self.total - worked - self.skipped
        if worked == 0:
            return None
        return (time.monotonic() - self.started) / worked * max(left, 0)

    def line(self) -> str:
        eta = self.eta_s
        tail = f", ETA {eta:.0f} s" if eta is not None else ""
        return (
            f"{self.done + self.skipped}/{self.total} done ({self.skipped} already), "
            f"{self.running} running, {self.failed} failed{tail}"
        )


ProgressCallback = Callable[[Progress], None]


class Executor(Protocol):
    """Runs tasks; both implementations skip a task whose output folder ``root/key`` exists."""

    def run(
        self, tasks: Sequence[Task], root: Path, on_progress: ProgressCallback | None = None
    ) -> list[Outcome]:
        """Run every task not already finished; outcomes in the order of ``tasks``."""
        ...

    def close(self) -> None:
        """Release workers (a no-op for the inline executor)."""
        ...


def one_line(err: BaseException) -> str:
    text = str(err).strip().splitlines()
    return f"{type(err).__name__}: {text[0] if text else ''}".rstrip(": ")


class InlineExecutor:
    """Threads in this process; ``llm_slots`` bounds concurrent model-using tasks."""

    def __init__(self, jobs: int = 1, llm_slots: int = 4) -> None:
        self.jobs = max(1, jobs)
        self._llm = threading.Semaphore(max(1, llm_slots))

    def _call(self, task: Task) -> dict[str, Any]:
        if task.uses_llm:
            with self._llm:
                return task.fn(*task.args)
        return task.fn(*task.args)

    def run(
        self, tasks: Sequence[Task], root: Path, on_progress: ProgressCallback | None = None
    ) -> list[Outcome]:
        progress = Progress(total=len(tasks))
        outcomes: dict[str, Outcome] = {}
        todo: list[Task] = []
        for task in tasks:
            if (Path(root) / task.key).is_dir():
                outcomes[task.key] = Outcome(task.key, True, skipped=True)
                progress.skipped += 1
            else:
                todo.append(task)
        if on_progress:
            on_progress(progress)
        with ThreadPoolExecutor(max_workers=self.jobs) as pool:
            pending: dict[Future[dict[str, Any]], Task] = {}
            queue = list(todo)
            while queue or pending:
                while queue and len(pending) < self.jobs:
                    task = queue.pop(0)
                    pending[pool.submit(self._call, task)] = task
                progress.running = len(pending)
                finished, _ = wait(pending, return_when=FIRST_COMPLETED)
                for fut in finished:
                    task = pending.pop(fut)
                    try:
                        outcomes[task.key] = Outcome(task.key, True, result=fut.result())
                        progress.done += 1
                    except Exception as err:  # noqa: BLE001 - a failed cell is reported, not raised
                        outcomes[task.key] = Outcome(task.key, False, error=one_line(err))
                        progress.failed += 1
                progress.running = len(pending)
                if on_progress:
                    on_progress(progress)
        return [outcomes[t.key] for t in tasks]

    def close(self) -> None:
        return None
