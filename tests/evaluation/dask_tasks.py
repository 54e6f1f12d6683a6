"""Task functions for the Dask executor tests, in a module of their own so that the worker
processes import them by name (the tests put this folder on the workers' PYTHONPATH)."""

from __future__ import annotations

import json
import os
import time
from pathlib import Path

from matloom.evaluation.cells import commit_cell


def _log(path: Path, line: str) -> None:
    with open(path, "a", encoding="utf-8") as handle:
        handle.write(line + "\n")


def write_cell(root: str, key: str, value: int, log: str) -> dict:
    """A task: one cell holding ``value``; every attempt logged."""
    _log(Path(log), f"{key} {os.getpid()}")

    def write(stage: Path) -> dict:
        (stage / "value.txt").write_text(str(value))
        return {"value": value, "pid": os.getpid()}

    return commit_cell(Path(root), key, write)


def fail(message: str) -> dict:
    raise ValueError(message + "\nsecond line")


def die_once_mid_write(root: str, key: str, marker: str, log: str) -> dict:
    """A task that kills its own worker process half-way through its first attempt."""
    _log(Path(log), f"{key} {os.getpid()}")

    def write(stage: Path) -> dict:
        (stage / "part1.txt").write_text("half")
        if not Path(marker).exists():
            Path(marker).write_text(str(os.getpid()))
            os._exit(17)  # the worker process dies with a staged, half-written cell
        (stage / "part2.txt").write_text("whole")
        return {"pid": os.getpid()}

    return commit_cell(Path(root), key, write)


def timed_llm_call(folder: str, name: str) -> dict:
    """A model-using task: records when it held its slot."""
    start = time.time()
    time.sleep(0.4)
    end = time.time()
    Path(folder, f"{name}.json").write_text(json.dumps([start, end, os.getpid()]))
    return {"pid": os.getpid()}
