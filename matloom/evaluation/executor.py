"""One executor for ``bench`` and ``dataset``: :func:`make_executor` returns tasks in process
(:class:`InlineExecutor`) or on a Dask cluster (:class:`~.executor_dask.DaskExecutor`). The task
types live in :mod:`.executor_base` (re-exported here), so the Dask module does not import this one.
"""

from __future__ import annotations

from matloom.evaluation.executor_base import (
    Executor,
    InlineExecutor,
    Outcome,
    Progress,
    ProgressCallback,
    Task,
    one_line,
)

__all__ = [
    "Executor",
    "ExecutorUnavailableError",
    "InlineExecutor",
    "Outcome",
    "Progress",
    "ProgressCallback",
    "Task",
    "default_scheduler",
    "make_executor",
    "one_line",
]


def default_scheduler() -> str:
    """``local`` (an embedded Dask ``LocalCluster``) when the ``[dask]`` extra is installed,
    else ``inline`` (threads in this process)."""
    try:
        import distributed  # noqa: F401
    except ImportError:
        return "inline"
    return "local"


def make_executor(
    scheduler: str | None = None, *, workers: int = 1, jobs: int = 1, llm_slots: int = 4
) -> Executor:
    """The executor a command asked for.

    ``scheduler``: ``None`` or ``"inline"`` runs in this process with ``jobs`` threads;
    ``"local"`` starts an embedded Dask ``LocalCluster`` of ``workers`` processes;
    ``"tcp://HOST:PORT"`` connects to a running Dask scheduler. Dask comes with the ``[dask]``
    extra; without it a Dask request raises :class:`ExecutorUnavailableError` saying how to
    install it.
    """
    if scheduler in (None, "", "inline"):
        return InlineExecutor(jobs=jobs, llm_slots=llm_slots)
    try:
        from matloom.evaluation.executor_dask import DaskExecutor
    except ImportError as err:
        raise ExecutorUnavailableError(
            f"Dask is not installed here ({err}): pip install 'matloom[dask]'"
        ) from None
    return DaskExecutor(scheduler=scheduler, workers=workers, llm_slots=llm_slots)


class ExecutorUnavailableError(RuntimeError):
    """The executor asked for cannot run here; the message says how to install it."""
