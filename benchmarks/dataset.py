"""Benchmark: `matloom dataset` throughput on an embedded Dask LocalCluster. Prints numbers.

Run: PYTHONPATH=. .venv-dask/bin/python benchmarks/dataset.py [--size 512] [--entries 6]
     [--variants 2] [--workers 1 2] [--inline]

For each worker count it starts a ``LocalCluster`` (one thread per worker), warms every worker
up on a small dataset (imports, kernel caches), then builds a fresh dataset of ``--entries``
library entries x ``--variants`` seed variants at ``--size``, and prints samples per second,
the scaling efficiency against one worker (rate_N / (N x rate_1)), each worker's peak resident
memory (``ru_maxrss`` read in the worker), and the bytes one sample takes on disk. It ends with
a planning table for 1M samples: core-hours (one worker = one core) and storage. The machine's
load average is printed first and last: other processes inflate wall times.
"""

from __future__ import annotations

import argparse
import os
import resource
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from matloom.evaluation.dataset import DatasetOptions, build_dataset  # noqa: E402
from matloom.evaluation.dataset_sources import library_sources  # noqa: E402
from matloom.evaluation.executor import InlineExecutor  # noqa: E402
from matloom.library import library  # noqa: E402

MILLION = 1_000_000


def peak_rss_mib() -> float:
    """This process's peak resident memory in MiB (Linux reports KiB)."""
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def folder_bytes(folder: Path) -> int:
    return sum(p.stat().st_size for p in folder.rglob("*") if p.is_file())


def pick_entries(count: int) -> list[str]:
    """``count`` entries spread over the categories (every k-th of the sorted library)."""
    entries = [e.name for e in library().by_category()]
    step = max(1, len(entries) // count)
    return entries[::step][:count]


def run_once(executor, names: list[str], size: int, variants: int, work: Path) -> dict:  # noqa: ANN001
    sources = library_sources(names)
    # warm-up: other programs (other cells) at a small size, so imports and caches are hot
    build_dataset(work / "warm", sources, DatasetOptions(sizes=(64,)), executor)
    start = time.perf_counter()
    summary = build_dataset(
        work / "run", sources, DatasetOptions(variants=variants, sizes=(size,)), executor
    )
    seconds = time.perf_counter() - start
    samples = work / "run" / "samples"
    return {
        "samples": summary.kept,
        "failed": summary.failed,
        "seconds": seconds,
        "rate": summary.kept / seconds,
        "bytes_per_sample": folder_bytes(samples) / max(1, summary.kept),
    }


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--size", type=int, default=512)
    ap.add_argument("--entries", type=int, default=6)
    ap.add_argument("--variants", type=int, default=2)
    ap.add_argument("--workers", type=int, nargs="+", default=[1, 2])
    ap.add_argument("--inline", action="store_true", help="Also time the inline executor.")
    args = ap.parse_args()
    from matloom.evaluation.executor_dask import DaskExecutor

    names = pick_entries(args.entries)
    print(f"load average at start: {os.getloadavg()}; cores: {os.cpu_count()}")
    print(f"{len(names)} entries x {args.variants} variants at {args.size}^2: {', '.join(names)}")
    results: dict[str, dict] = {}
    if args.inline:
        with tempfile.TemporaryDirectory() as tmp:
            res = run_once(InlineExecutor(), names, args.size, args.variants, Path(tmp))
        res["peak_mib"] = [peak_rss_mib()]
        results["inline"] = res
    for workers in args.workers:
        with tempfile.TemporaryDirectory() as tmp, DaskExecutor("local", workers=workers) as ex:
            ex.worker_count()  # the cluster is up before the clock starts
            res = run_once(ex, names, args.size, args.variants, Path(tmp))
            res["peak_mib"] = sorted(ex.client.run(peak_rss_mib).values())
        results[f"dask x{workers}"] = res
    print()
    print(
        f"{'executor':<10} {'samples':>7} {'seconds':>8} {'samples/s':>10} {'efficiency':>10} "
        f"{'peak MiB per worker':>22} {'MB/sample':>10}"
    )
    base = results.get("dask x1", {}).get("rate")
    for name, res in results.items():
        workers = int(name.split("x")[1]) if "x" in name else 1
        eff = f"{res['rate'] / (workers * base):.2f}" if base and name.startswith("dask") else "-"
        peaks = ", ".join(f"{p:.0f}" for p in res["peak_mib"])
        print(
            f"{name:<10} {res['samples']:>7} {res['seconds']:>8.2f} {res['rate']:>10.3f} "
            f"{eff:>10} {peaks:>22} {res['bytes_per_sample'] / 1e6:>10.2f}"
        )
    print()
    print(f"planning for {MILLION:,} samples at {args.size}^2 (one worker = one core):")
    print(
        f"{'from':<10} {'samples/s/core':>15} {'core-hours':>11} {'storage GB':>11} "
        f"{'hours on 64 cores':>18}"
    )
    for name, res in results.items():
        workers = int(name.split("x")[1]) if "x" in name else 1
        per_core = res["rate"] / workers
        core_hours = MILLION / per_core / 3600
        storage = res["bytes_per_sample"] * MILLION / 1e9
        print(
            f"{name:<10} {per_core:>15.3f} {core_hours:>11,.0f} {storage:>11,.0f} "
            f"{core_hours / 64:>18,.1f}"
        )
    print(f"\nload average at end: {os.getloadavg()}")


if __name__ == "__main__":
    main()
