"""Benchmark of the offline author (the material library) over the 71 development prompts.

Prints two numbers:

1. **In process**: the median (p90, max) time of ``matloom.library.author(prompt)`` per prompt
   (reading the request, ranking, adapting, composing overlays, printing), the first call (which
   loads the library and builds its index) excluded and reported on its own; and the median
   program length in lines. Rendering is not included.
2. **Process time of ``matloom generate``**: whole ``python -m matloom generate PROMPT -o DIR``
   processes at the default export size (512; ``--export-size``), wall clock from start to
   exit, with CPU time (user + sys of the child) beside it, over ``--processes`` prompts spread
   over the development set. The numba kernels are compiled before timing (one untimed run), so
   this is the time of a user's second and later runs; ``--scorer`` is left at its default.

    PYTHONPATH=. .venv/bin/python benchmarks/offline_author.py [--repeat 5] [--processes 9]

The load average is printed first and last: other processes inflate wall times on the shared
2-core machines (the CPU time is less sensitive to them).
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from matloom.library import author  # noqa: E402

DEV = ROOT / "tests" / "data" / "prompts-dev.json"


def in_process(prompts: list[str], repeat: int) -> None:
    start = time.perf_counter()
    author(prompts[0])  # loads the library and builds the BM25 index
    first = time.perf_counter() - start
    per_prompt: list[float] = []
    lengths: list[int] = []
    for prompt in prompts:
        runs = []
        for _ in range(repeat):
            t0 = time.perf_counter()
            result = author(prompt)
            runs.append((time.perf_counter() - t0) * 1000)
        per_prompt.append(statistics.median(runs))
        lengths.append(result.program.count("\n") + 1)
    per_prompt.sort()
    p90 = per_prompt[int(0.9 * (len(per_prompt) - 1))]
    print(f"prompts: {len(prompts)} (repeat {repeat}); first call {1000 * first:.0f} ms")
    print(
        f"in process, library author per prompt: median {statistics.median(per_prompt):.1f} ms "
        f"(p90 {p90:.1f} ms, max {per_prompt[-1]:.1f} ms)"
    )
    print(
        f"median program length: {statistics.median(lengths):g} lines "
        f"(min {min(lengths)}, max {max(lengths)})"
    )


def _generate(prompt: str, out: Path, export_size: int) -> tuple[float, float]:
    """(wall seconds, child CPU seconds) of one `matloom generate` process."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    cmd = [sys.executable, "-m", "matloom", "generate", prompt, "-o", str(out), "--quiet"]
    cmd += ["--export-size", str(export_size)]
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    subprocess.run(cmd, check=True, env=env, cwd=ROOT, capture_output=True)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu


def processes(prompts: list[str], count: int, export_size: int) -> None:
    step = max(1, len(prompts) // count)
    chosen = prompts[::step][:count]
    with tempfile.TemporaryDirectory(prefix="matloom-bench-") as tmp:
        _generate(chosen[0], Path(tmp) / "warm", export_size)  # compiles / loads the kernels
        walls, cpus = [], []
        for k, prompt in enumerate(chosen):
            wall, cpu = _generate(prompt, Path(tmp) / f"run{k}", export_size)
            walls.append(wall)
            cpus.append(cpu)
    print(
        f"`matloom generate` process at --export-size {export_size} ({len(chosen)} prompts): "
        f"median {statistics.median(walls):.2f} s wall (min {min(walls):.2f}, "
        f"max {max(walls):.2f}), median CPU {statistics.median(cpus):.2f} s"
    )


def main() -> None:
    from matloom.author.config import AuthorConfig

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5, help="timed runs per prompt")
    parser.add_argument("--processes", type=int, default=9, help="`generate` processes timed")
    parser.add_argument("--export-size", type=int, default=AuthorConfig().export_size)
    args = parser.parse_args()
    prompts = [p["text"] for p in json.loads(DEV.read_text(encoding="utf-8"))["prompts"]]
    print(f"load average {os.getloadavg()[0]:.2f}")
    in_process(prompts, args.repeat)
    if args.processes > 0:
        processes(prompts, args.processes, args.export_size)
    print(f"load average {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
