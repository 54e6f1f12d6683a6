"""`matloom dataset` on a real Dask ``LocalCluster`` (2 worker processes): 2 entries x 2
variants x 1 size, resume, deduplication, a filter, Parquet metadata, and the same bytes as the
inline executor (the engine is deterministic in the workers)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

pytest.importorskip("distributed", reason="needs the dask extra (make test-dask)")
pq = pytest.importorskip("pyarrow.parquet", reason="needs the dask extra (make test-dask)")

from click.testing import CliRunner  # noqa: E402

from matloom.cli.main import cli  # noqa: E402
from matloom.evaluation.dataset import DatasetOptions, build_dataset  # noqa: E402
from matloom.evaluation.dataset_sources import SourceProgram, library_sources  # noqa: E402
from matloom.evaluation.executor import InlineExecutor  # noqa: E402
from matloom.evaluation.executor_dask import DaskExecutor  # noqa: E402

pytestmark = pytest.mark.dask

ENTRIES = ["brick-herringbone-path", "coir-doormat"]
SIZE = 32


def _tree(folder: Path) -> dict[str, bytes]:
    return {
        p.relative_to(folder).as_posix(): p.read_bytes()
        for p in sorted(folder.rglob("*"))
        if p.is_file() and not p.name.startswith(".")
    }


@pytest.fixture(scope="module")
def cluster():
    ex = DaskExecutor("local", workers=2)
    yield ex
    ex.close()


def test_dataset_on_local_cluster(cluster: DaskExecutor, tmp_path: Path) -> None:
    sources = library_sources(ENTRIES)
    copy = SourceProgram("folder", "copy.mat", sources[0].text, unit_m=sources[0].unit_m)
    options = DatasetOptions(variants=2, sizes=(SIZE,))
    out = tmp_path / "dask"
    summary = build_dataset(out, [*sources, copy], options, cluster)
    assert (summary.planned, summary.kept, summary.duplicates, summary.failed) == (4, 4, 2, 0)
    rows = [json.loads(x) for x in (out / "metadata.jsonl").read_text().splitlines()]
    assert sorted(r["duplicates"] for r in rows)[-2:] == [
        ["folder:copy.mat#0"],
        ["folder:copy.mat#1"],
    ]
    assert len(list((out / "samples").iterdir())) == 4  # no staging folder left behind
    table = pq.read_table(out / "metadata.parquet").to_pylist()
    assert [t["key"] for t in table] == [r["key"] for r in rows]
    assert [t["pbr.plausible"] for t in table] == [r["pbr.plausible"] for r in rows]
    # the same dataset in process: every file of every sample is the same, byte for byte
    inline = tmp_path / "inline"
    build_dataset(inline, sources, options, InlineExecutor())
    assert _tree(out / "samples") == _tree(inline / "samples")
    # resume: nothing rebuilt; a filter drops without rebuilding
    stamps = {p: p.stat().st_mtime_ns for p in (out / "samples").rglob("basecolor.png")}
    strict = DatasetOptions(variants=2, sizes=(SIZE,), filters=("seam_ratio.max<=0",))
    again = build_dataset(out, sources, strict, cluster, resume=True)
    assert (again.skipped, again.kept, again.dropped) == (4, 0, 4)
    assert {p: p.stat().st_mtime_ns for p in stamps} == stamps
    dropped = [json.loads(x) for x in (out / "dropped.jsonl").read_text().splitlines()]
    assert all(d["dropped"].startswith("seam_ratio.max<=0 (was ") for d in dropped)


def test_cli_dataset_local_scheduler(tmp_path: Path) -> None:
    out = tmp_path / "ds"
    args = ["dataset", "--entries", ENTRIES[1], "--variants", "2", "--size", str(SIZE)]
    args += ["--scheduler", "local", "--workers", "2", "-o", str(out)]
    res = CliRunner().invoke(cli, args)
    assert res.exit_code == 0, res.output
    assert "2 samples in" in res.stderr and "2/2 done" in res.stderr
    assert (out / "metadata.parquet").is_file()
