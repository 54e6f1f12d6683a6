"""Evaluation cost of every library entry: parse time and 512 x 512 evaluation time.

``matloom generate`` parses the chosen entry and evaluates it at the export size (512 by
default), so an entry's evaluation time is most of a user's wait. Prints the slowest entries
and the median, and how many take longer than ``--budget`` seconds. Each entry is evaluated
``--repeat`` times and its fastest evaluation reported: the first use of a kernel in a process
loads (or compiles) it, a cost paid once per process and measured by
``benchmarks/offline_author.py``.

    PYTHONPATH=. .venv/bin/python benchmarks/library_entries.py [--size 512] [--top 15]
"""

from __future__ import annotations

import argparse
import statistics
import time

import matloom
from matloom.library import load_library


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--size", type=int, default=512)
    parser.add_argument("--top", type=int, default=15)
    parser.add_argument("--budget", type=float, default=0.5, help="seconds per evaluation")
    parser.add_argument("--repeat", type=int, default=2, help="evaluations per entry (fastest)")
    parser.add_argument("--only", nargs="*", default=None, help="these entries only")
    args = parser.parse_args()
    lib = load_library()
    matloom.evaluate(matloom.parse(lib.entries["moss"].path.read_text()), 64, 64)  # warm-up
    rows = []
    for name, entry in sorted(lib.entries.items()):
        if args.only and name not in args.only:
            continue
        text = entry.path.read_text(encoding="utf-8")
        start = time.perf_counter()
        program = matloom.parse(text)
        parsed = time.perf_counter()
        times = []
        for _ in range(max(1, args.repeat)):
            begin = time.perf_counter()
            matloom.evaluate(program, args.size, args.size)
            times.append(time.perf_counter() - begin)
        rows.append((min(times), parsed - start, name))
    rows.sort(reverse=True)
    for ev, pa, name in rows[: args.top]:
        print(f"{name:40s} evaluate {ev:6.2f} s   parse {pa * 1000:5.0f} ms")
    evals = [r[0] for r in rows]
    over = sum(e > args.budget for e in evals)
    print(
        f"{len(rows)} entries at {args.size}x{args.size}: median {statistics.median(evals):.3f} s, "
        f"{over} over {args.budget:g} s"
    )


if __name__ == "__main__":
    main()
