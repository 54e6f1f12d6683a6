"""Benchmark of the built-in offline author over the 71 development prompts.

Prints the median (and 90th percentile) generation time per prompt, with the first call (which
imports the recipe library) excluded, and the median program length in lines. Rendering is
not included: this measures `author(prompt)` only, which is what `matloom generate` runs before
writing a program when no model is configured.

    PYTHONPATH=. .venv/bin/python benchmarks/offline_author.py [--repeat 5]
"""

from __future__ import annotations

import argparse
import json
import statistics
import time
from pathlib import Path

from matloom.author.builtin import author

DEV = Path(__file__).resolve().parents[1] / "tests" / "data" / "prompts-dev.json"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5, help="timed runs per prompt")
    args = parser.parse_args()
    prompts = [p["text"] for p in json.loads(DEV.read_text(encoding="utf-8"))["prompts"]]
    author(prompts[0])  # warm-up: imports and registers the recipe library
    per_prompt: list[float] = []
    lengths: list[int] = []
    for prompt in prompts:
        runs = []
        for _ in range(args.repeat):
            start = time.perf_counter()
            result = author(prompt)
            runs.append((time.perf_counter() - start) * 1000)
        per_prompt.append(statistics.median(runs))
        lengths.append(result.program.count("\n") + 1)
    per_prompt.sort()
    p90 = per_prompt[int(0.9 * (len(per_prompt) - 1))]
    print(f"prompts: {len(prompts)} (repeat {args.repeat})")
    print(
        f"median generation time: {statistics.median(per_prompt):.1f} ms "
        f"(p90 {p90:.1f} ms, max {per_prompt[-1]:.1f} ms)"
    )
    print(
        f"median program length: {statistics.median(lengths):g} lines "
        f"(min {min(lengths)}, max {max(lengths)})"
    )


if __name__ == "__main__":
    main()
