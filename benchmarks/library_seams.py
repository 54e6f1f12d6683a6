"""Benchmark: the seam ratio of the offline author's tileable materials, one row per prompt.

Run: PYTHONPATH=. .venv/bin/python benchmarks/library_seams.py [--size 512] [--limit 1.2]
     [--backend auto] [--all] [PROMPT ...]

Every prompt of ``tests/data/prompts-dev.json`` and ``benchmarks/data/prompts-own.json`` (or the
prompts given) is authored with the library (``matloom.library.author``, the defaults that
``matloom generate`` uses); each tileable result is evaluated at ``--size`` and the seam ratio of
every exported map is taken as ``material.json`` reports it
(:func:`matloom.engine.tiling.manifest_entry`). Printed: the worst map and its ratio per prompt
(``*`` over the limit), then the count over the limit and the worst values. ``--all`` lists
every map over the limit of each prompt. Non-tileable results are listed with the reason.
The column after the map says whether the maps repeat exactly with the View
(:func:`matloom.library.checks.period_problems` at 40 x 40: ``repeats`` or ``NO``): a ratio
over the limit on maps that repeat is where the wrap edge falls, not a seam.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

import matloom  # noqa: E402
from matloom.engine.tiling import manifest_entry  # noqa: E402
from matloom.library import author  # noqa: E402
from matloom.library.checks import period_problems  # noqa: E402
from matloom.vocab.layout import LAYOUT  # noqa: E402

DEV = ROOT / "tests" / "data" / "prompts-dev.json"
OWN = ROOT / "benchmarks" / "data" / "prompts-own.json"


def prompts() -> list[tuple[str, str]]:
    """(id, prompt) of the development and own prompt sets."""
    dev = [p["text"] for p in json.loads(DEV.read_text(encoding="utf-8"))["prompts"]]
    own = json.loads(OWN.read_text(encoding="utf-8")) if OWN.exists() else []
    own = [p if isinstance(p, str) else p["text"] for p in own]
    return [(f"dev{i:02d}", p) for i, p in enumerate(dev)] + [
        (f"own{i:02d}", p) for i, p in enumerate(own)
    ]


def seams(program: str, size: int, backend: str) -> dict[str, float]:
    """Exported map name -> the seam ratio ``material.json`` reports."""
    maps = matloom.evaluate(program, size, size, backend=backend)
    return manifest_entry(maps, LAYOUT.maps).get("seam_ratio", {})


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("prompts", nargs="*", help="prompts (default: the dev and own sets)")
    ap.add_argument("--size", type=int, default=512)
    ap.add_argument("--limit", type=float, default=1.2)
    ap.add_argument("--backend", default="auto")
    ap.add_argument("--all", action="store_true", help="list every map over the limit")
    args = ap.parse_args()
    todo = [(f"arg{i:02d}", p) for i, p in enumerate(args.prompts)] or prompts()
    rows: list[tuple[float, str, str, str]] = []
    untiled = broken = 0
    for key, prompt in todo:
        r = author(prompt)
        short = prompt if len(prompt) <= 48 else prompt[:45] + "..."
        if not r.tileable:
            untiled += 1
            why = next((n for n in r.notes if "tile" in n), "entry not tileable")
            print(f"{key}  {r.entry:34s} -      (not tileable: {why[:60]})  {short}")
            continue
        t0 = time.perf_counter()
        table = seams(r.program, args.size, args.backend)
        name, worst = max(table.items(), key=lambda kv: (kv[1], kv[0]))
        mark = "*" if worst > args.limit else " "
        repeats = "repeats" if not period_problems(r.program) else "NO"
        took = time.perf_counter() - t0
        extra = ""
        if args.all and worst > args.limit:
            extra = "  [" + ", ".join(f"{k} {v:.2f}" for k, v in table.items() if v > 1.2) + "]"
        print(
            f"{key}  {r.entry:34s} {worst:6.2f}{mark} {name:12s} {repeats:7s} {took:4.1f}s  "
            f"{short}{extra}",
            flush=True,
        )
        rows.append((worst, key, r.entry, name))
        broken += repeats == "NO"
    over = [row for row in rows if row[0] > args.limit]
    print(
        f"\n{len(rows)} tileable results ({untiled} not tileable); "
        f"{len(over)} over {args.limit} at {args.size} x {args.size}; "
        f"{broken} whose maps do not repeat"
    )
    for worst, key, entry, name in sorted(rows, reverse=True)[:8]:
        print(f"  {key}  {entry:34s} {name:10s} {worst:.3f}")


if __name__ == "__main__":
    main()
