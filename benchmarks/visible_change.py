"""How much do critic-style edits change the previews? The measurement behind
``no_change_threshold`` (critic loop v3; docs/authoring.md).

Real programs (library entries drawn with a fixed seed, and the few-shot examples) get the
numeric edits a critic asks for: one exposed parameter scaled by 2, 5, 10 or 25 % (a number) or
shifted by 2, 5, 10 or 25 levels (a colour). For every pair this prints the preview difference
the loop uses (:func:`matloom.author.stages.loop.block_difference`: the mean absolute difference
in levels of 255 over the worst block of 1/32 of the side) in the flat and lit layouts at the
critique size, and the plain mean absolute difference over the whole image; ``--sheet DIR`` writes side-by-side pairs (before | after, flat over lit) sorted by
the difference, to judge by eye where changes start to show::

    .venv/bin/python benchmarks/visible_change.py --programs 12 --size 512 --sheet /tmp/vc
"""

from __future__ import annotations

import argparse
import json
import random
import statistics
from pathlib import Path

import numpy as np

STEPS = (0.02, 0.05, 0.10, 0.25)
COLOUR_STEPS = (2, 5, 10, 25)
#: Parameters a critic would not edit to change the look (seeds, counts, View corners).
_SKIPPED_KINDS = frozenset({"seed", "count"})


def _programs(count: int, seed: int) -> list[tuple[str, str]]:
    from matloom.author.prompts.system import FEW_SHOT_EXAMPLES
    from matloom.library import load_library

    lib = load_library()
    names = sorted(lib.entries)
    chosen = random.Random(seed).sample(names, count)
    programs = [(f"library:{n}", lib.entry(n).program) for n in chosen]
    programs += [(f"example:{e.file_name}", e.program()) for e in FEW_SHOT_EXAMPLES]
    return programs


def _edits(text: str, rng: random.Random, per_program: int) -> list[tuple[str, str]]:
    """(label, edited program) for ``per_program`` parameters at every step."""
    from matloom.lang.params import list_params, set_params

    params = [
        p
        for p in list_params(text)
        if p.kind not in _SKIPPED_KINDS and not p.address.startswith("View")
    ]
    out = []
    for p in rng.sample(params, min(per_program, len(params))):
        if isinstance(p.value, tuple):
            for step in COLOUR_STEPS:
                sign = 1 if sum(p.value) < 3 * 128 else -1
                value = tuple(min(255, max(0, c + sign * step)) for c in p.value)
                out.append((f"{p.address} {sign * step:+d} levels", value, p.address))
        else:
            for step in STEPS:
                value = p.value * (1 + step) if p.value else step
                if p.high is not None and value > p.high:
                    value = p.value * (1 - step)
                out.append((f"{p.address} x{1 + step:g}", value, p.address))
    edited = []
    for label, value, address in out:
        try:
            new, _ = set_params(text, {address: value})
        except ValueError:
            continue
        edited.append((label, new))
    return edited


def _images(text: str, size: int) -> list[np.ndarray]:
    from matloom.author.views import Renderer

    renderer = Renderer()
    return [renderer.image(text, size, view) for view in ("flat", "lit")]


def _mean(a: np.ndarray, b: np.ndarray) -> float:
    return float(np.mean(np.abs(a.astype(np.int16) - b.astype(np.int16))))


def _sheet(rows: list[dict], folder: Path) -> None:
    from PIL import Image

    folder.mkdir(parents=True, exist_ok=True)
    for n, row in enumerate(sorted(rows, key=lambda r: r["difference"])):
        before, after = row.pop("_before"), row.pop("_after")
        top = np.concatenate([before[0], after[0]], axis=1)
        bottom = np.concatenate([before[1], after[1]], axis=1)
        name = f"{n:03d}_{row['difference']:.2f}.png"
        Image.fromarray(np.concatenate([top, bottom], axis=0)).save(folder / name)
        row["sheet"] = name


def main() -> None:
    from matloom.author.stages.loop import block_difference

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--programs", type=int, default=12, help="library entries drawn")
    parser.add_argument("--params", type=int, default=2, help="parameters edited per program")
    parser.add_argument("--size", type=int, default=512, help="the critique size")
    parser.add_argument("--seed", type=int, default=26)
    parser.add_argument("--sheet", type=Path, help="write side-by-side pairs here")
    parser.add_argument("--json", type=Path, help="write the rows here")
    args = parser.parse_args()
    rng = random.Random(args.seed)
    rows = []
    for name, text in _programs(args.programs, args.seed):
        base = _images(text, args.size)
        for label, edited in _edits(text, rng, args.params):
            after = _images(edited, args.size)
            row = {
                "program": name,
                "edit": label,
                "flat": block_difference(base[0], after[0]),
                "lit": block_difference(base[1], after[1]),
                "flat_mean": _mean(base[0], after[0]),
                "lit_mean": _mean(base[1], after[1]),
            }
            row["difference"] = max(row["flat"], row["lit"])
            if args.sheet:
                row["_before"], row["_after"] = base, after
            rows.append(row)
            print(
                f"{row['difference']:7.2f}  flat {row['flat']:6.2f} (mean {row['flat_mean']:5.2f})"
                f"  lit {row['lit']:6.2f} (mean {row['lit_mean']:5.2f})  {name}  {label}",
                flush=True,
            )
    if args.sheet:
        _sheet(rows, args.sheet)
    values = sorted(r["difference"] for r in rows)
    print(f"{len(values)} pairs; median {statistics.median(values):.2f}")
    for cut in (1.0, 2.0, 3.0, 4.0, 6.0, 8.0):
        print(f"  under {cut:g}: {sum(v < cut for v in values)}")
    if args.json:
        args.json.write_text(json.dumps(rows, indent=1), encoding="utf-8")


if __name__ == "__main__":
    main()
