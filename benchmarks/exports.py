"""Export times of the default maps and of each preset at 2048x2048 (or --size).

    python benchmarks/exports.py [--size 2048] [--repeat 1]

Evaluates ``matloom/examples/bricks_quickstart.mat`` once, then times ``write_maps`` into a
temporary folder: the default output (8-bit, 16-bit, all-EXR half/float) and each preset alone
(``maps_subset=[]``: the preset's own files only). Prints one line per row, in seconds.
"""

from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path

import matloom
from matloom.io.export import Encoding, write_maps
from matloom.io.presets import PRESETS

EXAMPLE = Path(__file__).resolve().parents[1] / "matloom" / "examples" / "bricks_quickstart.mat"


def _time(maps: object, repeat: int, **kwargs: object) -> float:
    best = float("inf")
    for _ in range(repeat):
        with tempfile.TemporaryDirectory() as folder:
            start = time.perf_counter()
            write_maps(maps, Path(folder), name="bricks", unit_m=0.5, **kwargs)  # type: ignore[arg-type]
            best = min(best, time.perf_counter() - start)
    return best


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--size", type=int, default=2048)
    parser.add_argument("--repeat", type=int, default=1)
    args = parser.parse_args()
    maps = matloom.evaluate(EXAMPLE.read_text(), args.size, args.size)
    print(f"export times at {args.size}x{args.size} (s, best of {args.repeat})")
    base = _time(maps, args.repeat)
    print(f"{'default maps, 8-bit PNG':32s} {base:7.2f}")
    rows = {
        "default maps, --bits 16": {"encoding": Encoding(bits=16)},
        "default maps, --format exr half": {"encoding": Encoding(float_format="exr")},
        "default maps, --format exr float": {
            "encoding": Encoding(float_format="exr", exr_precision="float")
        },
    }
    for label, kwargs in rows.items():
        print(f"{label:32s} {_time(maps, args.repeat, **kwargs):7.2f}")
    for name in PRESETS:
        alone = _time(maps, args.repeat, presets=[name], maps_subset=[])
        print(f"{'preset ' + name:32s} {alone:7.2f}")


if __name__ == "__main__":
    main()
