"""Benchmark of the library author (retrieval + adaptation) over the 71 development prompts.

Prints the one-time cost per process (reading the library's front matter and building the BM25
index) and the median / p90 / max time of ``matloom.library.author(prompt)`` per prompt: reading
the request, ranking every entry, parsing the chosen entry (its parsed program is dropped
before every run, so parsing is included), adapting it, composing overlays, the tileable check
and printing the canonical program. Rendering is not included.

    PYTHONPATH=. .venv/bin/python benchmarks/library.py [--repeat 5]
"""

from __future__ import annotations

import argparse
import json
import statistics
import time
from pathlib import Path

from matloom.library import author, load_library

DEV = Path(__file__).resolve().parents[1] / "tests" / "data" / "prompts-dev.json"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5, help="timed runs per prompt")
    args = parser.parse_args()
    prompts = [p["text"] for p in json.loads(DEV.read_text(encoding="utf-8"))["prompts"]]
    start = time.perf_counter()
    lib = load_library()
    loaded = time.perf_counter()
    lib.index  # noqa: B018 - builds the BM25 index
    indexed = time.perf_counter()
    author(prompts[0], lib=lib)  # warm-up of the code paths (not of the entry cache)
    per_prompt: list[float] = []
    for prompt in prompts:
        runs = []
        for _ in range(args.repeat):
            lib._asts.clear()
            t0 = time.perf_counter()
            author(prompt, lib=lib)
            runs.append((time.perf_counter() - t0) * 1000)
        per_prompt.append(statistics.median(runs))
    per_prompt.sort()
    p90 = per_prompt[int(0.9 * (len(per_prompt) - 1))]
    print(f"library: {len(lib.entries)} entries, {len(lib.overlays)} overlays")
    print(
        f"per process: load {1000 * (loaded - start):.0f} ms, "
        f"BM25 index {1000 * (indexed - loaded):.0f} ms"
    )
    print(f"prompts: {len(prompts)} (repeat {args.repeat})")
    print(
        f"retrieval + adaptation per prompt: median {statistics.median(per_prompt):.1f} ms "
        f"(p90 {p90:.1f} ms, max {per_prompt[-1]:.1f} ms)"
    )


if __name__ == "__main__":
    main()
