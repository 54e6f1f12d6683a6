"""Benchmark: the seam ratio of every map of every example rendered tileable. Prints a table.

Run: PYTHONPATH=. .venv/bin/python benchmarks/seams_examples.py [--size 512] [--limit 1.2]
     [--backend auto] [FILE ...]

Each example (``docs/examples/*.mat`` and ``matloom/examples/*.mat`` unless files are given) is
evaluated once with ``tileable=True`` and the seam ratio of each exported map (the value
``material.json`` reports) is printed, one row per example, with the maps over the limit marked
``*``; constant maps are left out (they report 1.0).
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

import numpy as np  # noqa: E402

import matloom  # noqa: E402
from matloom.engine.tiling import manifest_entry  # noqa: E402
from matloom.vocab.layout import LAYOUT  # noqa: E402

DEFAULT = sorted((ROOT / "docs" / "examples").glob("*.mat")) + sorted(
    (ROOT / "matloom" / "examples").glob("*.mat")
)


def ratios(path: Path, size: int, backend: str) -> dict[str, float | None]:
    """Exported map name -> the seam ratio ``material.json`` reports for a tileable render
    (:func:`matloom.engine.tiling.manifest_entry`), None for a constant map."""
    maps = matloom.evaluate(
        path.read_text(encoding="utf-8"), size, size, backend=backend, tileable=True
    )
    reported = manifest_entry(maps, LAYOUT.maps)["seam_ratio"]
    out: dict[str, float | None] = {}
    for spec in LAYOUT.maps:
        if spec.name not in reported:
            continue
        values = np.asarray(getattr(maps, spec.sources[0]))
        finite = values[np.isfinite(values)]
        flat = finite.size == 0 or float(np.ptp(finite)) <= 1e-6 * max(
            1.0, float(np.abs(finite).max())
        )
        out[spec.name] = None if flat else reported[spec.name]
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("files", nargs="*", type=Path)
    ap.add_argument("--size", type=int, default=512)
    ap.add_argument("--limit", type=float, default=1.2)
    ap.add_argument("--backend", default="auto")
    args = ap.parse_args()
    worst: list[tuple[float, str, str]] = []
    for path in args.files or DEFAULT:
        t0 = time.perf_counter()
        table = ratios(path, args.size, args.backend)
        cells = []
        for name, value in table.items():
            if value is None:
                continue
            mark = "*" if value > args.limit else ""
            cells.append(f"{name}={value:.2f}{mark}")
            worst.append((value, path.stem, name))
        took = time.perf_counter() - t0
        print(f"{path.stem:28s} {took:5.1f}s  {' '.join(cells)}")
    over = [w for w in worst if w[0] > args.limit]
    print(f"\n{len(over)} map(s) over {args.limit}:")
    for value, stem, name in sorted(over, reverse=True):
        print(f"  {stem:28s} {name:18s} {value:.3f}")


if __name__ == "__main__":
    main()
