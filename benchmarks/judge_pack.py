"""Blind-judging packets for the offline author, and their summary.

``pack`` authors every prompt of the given prompt files with the library author (what
``matloom generate`` does offline), renders each program's preview (flat and lit side by side),
shuffles them under opaque ids and writes contact sheets of six previews labelled only with
their ids, plus one ``sheet_NN.json`` per sheet mapping id -> the request text. A judge sees only
the sheets and the texts. ``key.json`` (id -> prompt id, source, entry) stays with whoever runs
the packet.

``summary`` reads judges' score files (JSON objects id -> {"score": 0-100, "why": "..."})
and prints the mean per prompt file, per source, the number below 30 and the five worst.

    PYTHONPATH=. .venv/bin/python benchmarks/judge_pack.py pack -o /tmp/judge \\
        tests/data/prompts-dev.json benchmarks/data/prompts-own-2.json
    PYTHONPATH=. .venv/bin/python benchmarks/judge_pack.py summary /tmp/judge scores_*.json
"""

from __future__ import annotations

import argparse
import json
import random
import statistics
from collections import defaultdict
from pathlib import Path

from matloom.evaluation.blind import contact_sheet as _sheet
from matloom.library import author, load_library
from matloom.render.api import preview

PER_SHEET = 6


def _prompts(path: Path) -> list[tuple[str, str, str]]:
    data = json.loads(path.read_text(encoding="utf-8"))
    items = data["prompts"] if isinstance(data, dict) else data
    out = []
    for i, item in enumerate(items):
        if isinstance(item, str):
            out.append((f"{path.stem}-{i:03d}", path.stem, item))
        else:
            out.append((item["id"], item.get("source", path.stem), item["text"]))
    return out


def pack(out: Path, files: list[Path], size: int, shuffle_seed: int) -> None:
    out.mkdir(parents=True, exist_ok=True)
    lib = load_library()
    rows = [(f.stem, *p) for f in files for p in _prompts(f)]
    order = list(range(len(rows)))
    random.Random(shuffle_seed).shuffle(order)
    key: dict[str, dict[str, str]] = {}
    images, ids = [], []
    for n, i in enumerate(order):
        file, pid, source, text = rows[i]
        result = author(text, lib=lib)
        iid = f"m{n + 1:03d}"
        key[iid] = {"file": file, "id": pid, "source": source, "text": text, "entry": result.entry}
        images.append(preview(result.program, size, layout="both"))
        ids.append(iid)
    for s in range(0, len(ids), PER_SHEET):
        chunk = ids[s : s + PER_SHEET]
        name = f"sheet_{s // PER_SHEET + 1:02d}"
        _sheet(images[s : s + PER_SHEET], chunk).save(out / f"{name}.png")
        texts = {i: key[i]["text"] for i in chunk}
        (out / f"{name}.json").write_text(json.dumps(texts, indent=1), encoding="utf-8")
    (out / "key.json").write_text(json.dumps(key, indent=1), encoding="utf-8")
    print(f"{len(ids)} previews in {-(-len(ids) // PER_SHEET)} sheets under {out}")


def summary(folder: Path, score_files: list[Path]) -> None:
    key = json.loads((folder / "key.json").read_text(encoding="utf-8"))
    scores: dict[str, list[float]] = defaultdict(list)
    why: dict[str, list[str]] = defaultdict(list)
    for f in score_files:
        for iid, v in json.loads(f.read_text(encoding="utf-8")).items():
            scores[iid].append(float(v["score"]))
            why[iid].append(str(v.get("why", "")))
    mean = {i: statistics.mean(v) for i, v in scores.items()}
    missing = sorted(set(key) - set(mean))
    if missing:
        print(f"not scored: {len(missing)} ({', '.join(missing[:8])})")
    by_file: dict[str, list[str]] = defaultdict(list)
    for i in mean:
        by_file[key[i]["file"]].append(i)
    for file, ids in sorted(by_file.items()):
        vals = [mean[i] for i in ids]
        low = sum(v < 30 for v in vals)
        print(f"{file}: n={len(vals)} mean={statistics.mean(vals):.1f} below30={low}")
        by_source: dict[str, list[float]] = defaultdict(list)
        for i in ids:
            by_source[key[i]["source"]].append(mean[i])
        for src, v in sorted(by_source.items()):
            print(f"  {src:18s} n={len(v):2d} mean={statistics.mean(v):.1f}")
        for i in sorted(ids, key=lambda i: mean[i])[:5]:
            k = key[i]
            print(f"  worst {mean[i]:5.1f} {k['id']} [{k['entry']}] {k['text'][:60]!r}")
            for w in why[i]:
                print(f"        - {w[:160]}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = parser.add_subparsers(dest="cmd", required=True)
    p = sub.add_parser("pack")
    p.add_argument("-o", "--out", type=Path, required=True)
    p.add_argument("files", type=Path, nargs="+")
    p.add_argument("--size", type=int, default=256)
    p.add_argument("--shuffle-seed", type=int, default=7)
    s = sub.add_parser("summary")
    s.add_argument("folder", type=Path)
    s.add_argument("scores", type=Path, nargs="+")
    args = parser.parse_args()
    if args.cmd == "pack":
        pack(args.out, args.files, args.size, args.shuffle_seed)
    else:
        summary(args.folder, args.scores)


if __name__ == "__main__":
    main()
