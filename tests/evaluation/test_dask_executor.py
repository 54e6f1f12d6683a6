"""The Dask executor on a real ``LocalCluster`` (2 worker processes): tasks run, finished cells
are skipped, a failing task is an outcome, a worker killed mid-write is replaced and every cell
is written exactly once, and the cluster-wide LLM semaphore bounds concurrency."""

from __future__ import annotations

import json
import os
import sys
import time
from pathlib import Path

import pytest

pytest.importorskip("distributed", reason="needs the dask extra (make test-dask)")

import cloudpickle  # noqa: E402  (a dependency of distributed)

from matloom.evaluation.cells import commit_cell  # noqa: E402
from matloom.evaluation.executor import Task, make_executor  # noqa: E402
from matloom.evaluation.executor_dask import DaskExecutor  # noqa: E402

pytestmark = pytest.mark.dask

# The workers are other processes: ship this module's task functions by value.
cloudpickle.register_pickle_by_value(sys.modules[__name__])


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


@pytest.fixture(scope="module")
def executor():
    ex = DaskExecutor("local", workers=2, llm_slots=1)
    assert ex.worker_count() == 2
    yield ex
    ex.close()


def test_runs_skips_and_reports_failures(executor: DaskExecutor, tmp_path: Path) -> None:
    log = tmp_path / "attempts.log"
    tasks = [Task(f"k{i}", write_cell, (str(tmp_path), f"k{i}", i, str(log))) for i in range(4)]
    tasks.append(Task("bad", fail, ("no such thing",)))
    seen = []
    outcomes = executor.run(tasks, tmp_path, on_progress=lambda p: seen.append(p.line()))
    assert [o.key for o in outcomes] == ["k0", "k1", "k2", "k3", "bad"]
    assert all(o.ok and not o.skipped for o in outcomes[:4])
    assert [o.result["value"] for o in outcomes[:4]] == [0, 1, 2, 3]
    assert not outcomes[4].ok and outcomes[4].error == "ValueError: no such thing"
    assert "4/5 done (0 already), 0 running, 1 failed" in seen[-1]
    assert len({o.result["pid"] for o in outcomes[:4]}) >= 1
    assert (tmp_path / "k2" / "value.txt").read_text() == "2"
    # a rerun skips every finished cell and runs nothing
    before = log.read_text().count("\n")
    again = executor.run(tasks[:4], tmp_path)
    assert all(o.ok and o.skipped for o in again)
    assert log.read_text().count("\n") == before


def test_killed_worker_every_cell_exactly_once(executor: DaskExecutor, tmp_path: Path) -> None:
    root = tmp_path / "cells"
    log = tmp_path / "attempts.log"
    marker = tmp_path / "killed"
    tasks = [Task(f"w{i}", write_cell, (str(root), f"w{i}", i, str(log))) for i in range(6)]
    tasks.insert(
        2, Task("victim", die_once_mid_write, (str(root), "victim", str(marker), str(log)))
    )
    outcomes = executor.run(tasks, root)
    assert all(o.ok for o in outcomes), [o.error for o in outcomes]
    assert marker.exists()  # the first attempt did die
    cells = sorted(p.name for p in root.iterdir())
    assert cells == sorted(t.key for t in tasks)  # no staging folder left, no duplicates
    victim = root / "victim"
    assert sorted(p.name for p in victim.iterdir()) == ["cell.json", "part1.txt", "part2.txt"]
    attempts = [line.split()[0] for line in log.read_text().splitlines()]
    assert attempts.count("victim") == 2  # killed once, rerun elsewhere
    assert outcomes[2].result["pid"] != int(marker.read_text())
    for i in range(6):
        assert (root / f"w{i}" / "value.txt").read_text() == str(i)
    # the cluster replaced the dead worker
    deadline = time.time() + 20
    while executor.worker_count() < 2 and time.time() < deadline:
        time.sleep(0.2)
    assert executor.worker_count() == 2


def test_llm_semaphore_bounds_concurrency(executor: DaskExecutor, tmp_path: Path) -> None:
    times = tmp_path / "times"
    times.mkdir()
    tasks = [Task(f"m{i}", timed_llm_call, (str(times), f"m{i}"), uses_llm=True) for i in range(6)]
    outcomes = executor.run(tasks, tmp_path / "root")
    assert all(o.ok for o in outcomes)
    spans = [json.loads(p.read_text()) for p in times.iterdir()]
    assert len(spans) == 6
    assert len({pid for _, _, pid in spans}) == 2  # both workers took model tasks ...
    events = sorted([(s, 1) for s, _, _ in spans] + [(e, -1) for _, e, _ in spans])
    running = peak = 0
    for _, step in events:
        running += step
        peak = max(peak, running)
    assert peak <= 1  # ... yet never two at once: llm_slots=1 across the cluster


def test_make_executor_builds_dask(tmp_path: Path) -> None:
    ex = make_executor("tcp://127.0.0.1:1", workers=1)
    assert isinstance(ex, DaskExecutor)
    with pytest.raises(ValueError, match="unknown scheduler"):
        DaskExecutor("udp://x")
