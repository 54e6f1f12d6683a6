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

from matloom.evaluation.executor import Task, make_executor  # noqa: E402
from matloom.evaluation.executor_dask import DaskExecutor  # noqa: E402

pytestmark = pytest.mark.dask

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from dask_tasks import die_once_mid_write, fail, timed_llm_call, write_cell  # noqa: E402


@pytest.fixture(scope="module")
def executor():
    """A 2-worker LocalCluster whose workers (restarted ones too) import ``dask_tasks``."""
    old = os.environ.get("PYTHONPATH")
    os.environ["PYTHONPATH"] = os.pathsep.join(p for p in (str(HERE), old) if p)
    ex = DaskExecutor("local", workers=2, llm_slots=1)
    try:
        assert ex.worker_count() == 2
        yield ex
    finally:
        ex.close()
        if old is None:
            os.environ.pop("PYTHONPATH", None)
        else:
            os.environ["PYTHONPATH"] = old


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
