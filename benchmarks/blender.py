"""Blender render times of `matloom blender` (needs Blender or `make blender-venv`).

    python benchmarks/blender.py batch   [--materials 10] [--size 128] [--samples 8] [--jobs 2]
    python benchmarks/blender.py layouts [--size 512]

``batch`` renders the first ``--materials`` programs of ``docs/examples`` in both layouts, once
with ``--jobs N`` and once one at a time (``--jobs 1``), and prints both wall times.
``layouts`` renders ``docs/examples/01_plank_floor.mat`` flat and staged at ``--size`` with the
reference's sample counts (64 flat, 160 staged; ``--samples`` overrides both) and prints, for
each, the Cycles render time the worker reports and the command's wall time (which adds
evaluating the program, starting Blender and building the scene).

Every run goes through the command itself (``python -m matloom blender``), as a user runs it,
into a temporary folder. Blender is found as the command finds it (``--blender`` here is passed
on). Cycles uses every core in each Blender process, so ``--jobs`` overlaps the serial parts
(program evaluation, Blender start-up, scene building, denoising) more than the path tracing.
"""

from __future__ import annotations

import argparse
import os
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = sorted((ROOT / "docs" / "examples").glob("*.mat"))
PLANK = ROOT / "docs" / "examples" / "01_plank_floor.mat"
_VIEW = re.compile(r"(flat|staged) view \d+ \(\d+/\d+\) in ([0-9.]+) s")


def _matloom(args: list[str], blender: str | None) -> tuple[float, str]:
    """Run `matloom blender ARGS`; return the wall time and the progress (stderr)."""
    command = [sys.executable, "-m", "matloom", "blender", *args]
    if blender:
        command += ["--blender", blender]
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    start = time.perf_counter()
    done = subprocess.run(command, capture_output=True, text=True, env=env)
    wall = time.perf_counter() - start
    if done.returncode != 0:
        sys.exit(f"matloom blender failed:\n{done.stderr[-2000:]}")
    return wall, done.stderr


def batch(args: argparse.Namespace) -> None:
    programs = [str(p) for p in EXAMPLES[: args.materials]]
    common = ["--layout", "both", "--size", str(args.size), "--samples", str(args.samples)]
    print(
        f"batch of {len(programs)} materials x 2 layouts at {args.size} px, "
        f"{args.samples} samples (wall time, s; {os.cpu_count()} CPU cores)"
    )
    for jobs in (args.jobs, 1):
        with tempfile.TemporaryDirectory(prefix="matloom-bench-") as out:
            wall, _ = _matloom([*programs, "-o", out, "--jobs", str(jobs), *common], args.blender)
        label = f"--jobs {jobs}" + (" (one at a time)" if jobs == 1 else "")
        print(f"{label:24s} {wall:8.1f}")


def layouts(args: argparse.Namespace) -> None:
    print(f"01_plank_floor at {args.size} px (s; {os.cpu_count()} CPU cores)")
    print(f"{'layout':8s} {'samples':>7s} {'render':>8s} {'command':>8s}")
    for layout, samples in (("flat", 64), ("staged", 160)):
        samples = args.samples or samples
        with tempfile.TemporaryDirectory(prefix="matloom-bench-") as out:
            wall, log = _matloom(
                [str(PLANK), "--layout", layout, "-o", out, "--size", str(args.size)]
                + ["--samples", str(samples)],
                args.blender,
            )
        render = sum(float(m.group(2)) for m in _VIEW.finditer(log))
        print(f"{layout:8s} {samples:7d} {render:8.1f} {wall:8.1f}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("mode", choices=["batch", "layouts"])
    parser.add_argument("--materials", type=int, default=10)
    parser.add_argument("--size", type=int, default=None, help="128 (batch), 512 (layouts)")
    parser.add_argument("--samples", type=int, default=None, help="8 (batch), 64/160 (layouts)")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--blender", default=None)
    args = parser.parse_args()
    if args.mode == "batch":
        args.size = args.size or 128
        args.samples = args.samples or 8
        batch(args)
    else:
        args.size = args.size or 512
        layouts(args)


if __name__ == "__main__":
    main()
