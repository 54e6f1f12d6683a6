"""The Dask executor: the tasks of ``bench`` and ``dataset`` on a Dask cluster.

``DaskExecutor("local", workers=N)`` starts an embedded ``distributed.LocalCluster`` (N worker
processes of one thread each, no dashboard, listening on 127.0.0.1 only);
``DaskExecutor("tcp://HOST:PORT")`` connects to a running scheduler (a Slurm or Kubernetes
cluster, docs/datasets.md). The semantics are those of
:class:`~matloom.evaluation.executor.InlineExecutor`:

* a task whose folder ``root/key`` exists is skipped (its function writes the folder through
  :func:`~matloom.evaluation.cells.commit_cell`, so a folder is a finished cell);
* a task that raises is retried ``retries`` times, then reported as an :class:`Outcome` with a
  one-line error, never raised; a task whose worker dies (killed, out of memory) is rescheduled
  on another worker by the scheduler; a retried task finds a finished cell and writes nothing
  again, and a half-written attempt's staging folder is removed when the run ends;
* a task with ``uses_llm`` holds one lease of a ``distributed.Semaphore`` named
  :data:`LLM_SEMAPHORE` shared by every worker, so at most ``llm_slots`` model-using tasks run
  at once across the cluster.

Workers run the same engine code as the calling process, so the maps they make are the same,
byte for byte (tests/evaluation/test_dask_executor.py).
"""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

from distributed import Client, LocalCluster, Semaphore, as_completed

from matloom.evaluation.cells import remove_stale_stages
from matloom.evaluation.executor_base import Outcome, Progress, ProgressCallback, Task, one_line

#: Name of the cluster-wide semaphore that bounds model-using tasks.
LLM_SEMAPHORE = "matloom-llm"
#: How often a raising task is tried again before it counts as failed.
DEFAULT_RETRIES = 2


def _call(fn: Callable[..., dict[str, Any]], args: tuple[Any, ...], sem: Semaphore | None) -> Any:
    """Run one task on a worker (holding a lease of ``sem`` when given)."""
    if sem is None:
        return fn(*args)
    with sem:
        return fn(*args)


class DaskExecutor:
    """Runs tasks on a Dask cluster (see the module docstring).

    ``scheduler``: ``"local"`` (an embedded ``LocalCluster`` of ``workers`` processes) or a
    scheduler address ``"tcp://HOST:PORT"``. The cluster is started on the first :meth:`run`
    and shut down by :meth:`close`.
    """

    def __init__(
        self,
        scheduler: str = "local",
        workers: int = 1,
        llm_slots: int = 4,
        *,
        retries: int = DEFAULT_RETRIES,
        memory_limit: str | int | None = "auto",
        quiet: bool = True,
    ) -> None:
        if scheduler != "local" and not scheduler.startswith(("tcp://", "tls://")):
            raise ValueError(
                f"unknown scheduler {scheduler!r}: give 'local', 'inline' or tcp://HOST:PORT"
            )
        self.scheduler = scheduler
        self.workers = max(1, workers)
        self.llm_slots = max(1, llm_slots)
        self.retries = max(0, retries)
        self.memory_limit = memory_limit
        #: Only errors from the embedded cluster's logs (a killed worker is expected, not news).
        self.quiet = quiet
        self._cluster: LocalCluster | None = None
        self._client: Client | None = None
        self._sem: Semaphore | None = None

    @property
    def client(self) -> Client:
        """The connected client (the cluster is started or reached on first use)."""
        if self._client is None:
            if self.scheduler == "local":
                self._cluster = LocalCluster(
                    n_workers=self.workers,
                    threads_per_worker=1,
                    processes=True,
                    host="127.0.0.1",
                    dashboard_address=None,  # no dashboard; its bare HTTP server on loopback:
                    scheduler_kwargs={"dashboard_address": "127.0.0.1:0"},
                    memory_limit=self.memory_limit,
                    silence_logs=40 if self.quiet else 20,  # logging.ERROR or INFO
                )
                self._client = Client(self._cluster)
            else:
                self._client = Client(self.scheduler, timeout="30s")
        return self._client

    def _semaphore(self) -> Semaphore:
        if self._sem is None:
            self._sem = Semaphore(max_leases=self.llm_slots, name=LLM_SEMAPHORE)
        return self._sem

    def run(
        self, tasks: Sequence[Task], root: Path, on_progress: ProgressCallback | None = None
    ) -> list[Outcome]:
        """Run every task not already finished; outcomes in the order of ``tasks``."""
        root = Path(root)
        progress = Progress(total=len(tasks))
        outcomes: dict[str, Outcome] = {}
        todo: list[Task] = []
        for task in tasks:
            if (root / task.key).is_dir():
                outcomes[task.key] = Outcome(task.key, True, skipped=True)
                progress.skipped += 1
            elif task.key not in outcomes and all(t.key != task.key for t in todo):
                todo.append(task)
        if on_progress:
            on_progress(progress)
        if todo:
            self._submit_all(todo, outcomes, progress, on_progress)
            remove_stale_stages(root, [t.key for t in todo])
        return [outcomes[t.key] for t in tasks]

    def _submit_all(
        self,
        todo: list[Task],
        outcomes: dict[str, Outcome],
        progress: Progress,
        on_progress: ProgressCallback | None,
    ) -> None:
        client = self.client
        sem = self._semaphore() if any(t.uses_llm for t in todo) else None
        stamp = f"{time.time_ns():x}"
        futures = {}
        for task in todo:
            fut = client.submit(
                _call,
                task.fn,
                task.args,
                sem if task.uses_llm else None,
                key=f"matloom-{task.key}-{stamp}",
                retries=self.retries,
                pure=False,
            )
            futures[fut] = task
        progress.running = len(futures)
        if on_progress:
            on_progress(progress)
        for fut in as_completed(list(futures)):
            task = futures[fut]
            # result() rather than status: a finished result held by a worker that then dies is
            # lost and recomputed by the scheduler, so the status can leave "finished" for a
            # while; result() waits for the recomputation, or raises the task's error (or
            # KilledWorker, CancelledError) which becomes a one-line failed outcome.
            try:
                result = fut.result()
            except Exception as err:  # noqa: BLE001 - any task error is an outcome, not a raise
                outcomes[task.key] = Outcome(task.key, False, error=one_line(err))
                progress.failed += 1
            else:
                outcomes[task.key] = Outcome(task.key, True, result=result)
                progress.done += 1
            fut.release()
            progress.running -= 1
            if on_progress:
                on_progress(progress)

    def worker_count(self) -> int:
        """Workers connected now."""
        return len(self.client.scheduler_info().get("workers", {}))

    def close(self) -> None:
        """Disconnect; an embedded cluster is shut down."""
        if self._sem is not None:
            try:
                self._sem.close()
            except Exception:  # noqa: BLE001, S110 - closing a semaphore of a gone scheduler
                pass
            self._sem = None
        if self._client is not None:
            self._client.close()
            self._client = None
        if self._cluster is not None:
            self._cluster.close()
            self._cluster = None

    def __enter__(self) -> DaskExecutor:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()
