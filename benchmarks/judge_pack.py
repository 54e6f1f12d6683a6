"""Blind-judging packets for the offline author, and their summary.

``pack`` authors every prompt of the given prompt files with the library author (what
``matloom generate`` does offline), renders each program's preview (flat and lit side by side),
shuffles them under opaque ids and writes contact sheets of six previews labelled only with
their ids, plus one ``sheet_NN.json`` per sheet mapping id -> the request text. A judge sees only
the sheets and the texts. ``key.json`` (id -> prompt id, source, entry) stays with whoever runs
the packet.

``summary`` reads judges' score files (JSON objects id -> {"score": 0-100, "why": "..."})
and prints the mean per system and prompt file, per source, the number below 30 and the ten
worst.

To judge two builds in one run (before and after, shuffled together): ``author`` writes one
build's programs (run it with that build on ``PYTHONPATH``), and ``pack --programs NAME=FILE``
packs every build's programs at once (rendered by the current engine); a program several
builds share is judged once and counts for each of them.

    PYTHONPATH=. .venv/bin/python benchmarks/judge_pack.py pack -o /tmp/judge \\
        tests/data/prompts-dev.json benchmarks/data/prompts-own-2.json
    PYTHONPATH=/tmp/base .venv/bin/python benchmarks/judge_pack.py author -o before.json FILES
    PYTHONPATH=. .venv/bin/python benchmarks/judge_pack.py author -o after.json FILES
    PYTHONPATH=. .venv/bin/python benchmarks/judge_pack.py pack -o /tmp/judge \\
        FILES --programs before=before.json after=after.json
    PYTHONPATH=. .venv/bin/python benchmarks/judge_pack.py summary /tmp/judge scores_*.json
"""

from __future__ import annotations

import argparse
import json
import random
import statistics
import time
from collections import defaultdict
from pathlib import Path

from matloom.evaluation.blind import contact_sheet as _sheet
from matloom.library import author, load_library
from matloom.render.api import preview

PER_SHEET = 6


def _maps_of(program: object) -> str:
    """What decides a program's maps: its text without comment lines (two builds whose programs
    differ only in their ``# adapted:`` notes made the same material, judged once)."""
    return "\n".join(x for x in str(program).splitlines() if not x.lstrip().startswith("#"))


def _prompts(path: Path) -> list[tuple[str, str, str]]:
    data = json.loads(path.read_text(encoding="utf-8"))
    items = data["prompts"] if isinstance(data, dict) else data
    out = []
    for i, item in enumerate(items):
        if isinstance(item, str):
            out.append((f"{path.stem}-{i:03d}", path.stem, item))
        else:
            text = item["text"] if "text" in item else item["prompt"]
            out.append((item["id"], item.get("source", path.stem), text))
    return out


def author_all(out: Path, files: list[Path]) -> None:
    """Author every prompt with the library author of the build on ``PYTHONPATH``: file ->
    {prompt id: {text, program, entry, seconds}}."""
    lib = load_library()
    programs: dict[str, dict[str, dict[str, object]]] = {}
    for f in files:
        rows = programs.setdefault(f.stem, {})
        for pid, _source, text in _prompts(f):
            t0 = time.perf_counter()
            result = author(text, lib=lib)
            rows[pid] = {
                "text": text,
                "program": result.program,
                "entry": result.entry,
                "seconds": round(time.perf_counter() - t0, 4),
            }
    out.write_text(json.dumps(programs, indent=1), encoding="utf-8")
    print(f"{sum(len(v) for v in programs.values())} programs written to {out}")


def pack(
    out: Path,
    files: list[Path],
    size: int,
    shuffle_seed: int,
    programs: dict[str, Path] | None = None,
) -> None:
    out.mkdir(parents=True, exist_ok=True)
    lib = load_library()
    systems = {n: json.loads(p.read_text(encoding="utf-8")) for n, p in (programs or {}).items()}
    names = list(systems) or ["current"]
    rows = [(s, f.stem, *p) for s in names for f in files for p in _prompts(f)]
    if systems:  # a program two builds share is judged once, for both ("before+after")
        merged: dict[tuple[str, str, str], list[str]] = {}
        for s_, file, pid, _source, _text in rows:
            merged.setdefault((file, pid, _maps_of(systems[s_][file][pid]["program"])), []).append(
                s_
            )
        seen: set[tuple[str, str, str]] = set()
        unique = []
        for s_, file, pid, source, text in rows:
            k = (file, pid, _maps_of(systems[s_][file][pid]["program"]))
            if k not in seen:
                seen.add(k)
                unique.append(("+".join(merged[k]), file, pid, source, text))
        rows = unique
    order = list(range(len(rows)))
    random.Random(shuffle_seed).shuffle(order)
    key: dict[str, dict[str, str]] = {}
    images, ids = [], []
    for n, i in enumerate(order):
        system, file, pid, source, text = rows[i]
        if systems:
            made = systems[system.split("+")[0]][file][pid]
            program, entry = str(made["program"]), str(made["entry"])
        else:
            result = author(text, lib=lib)
            program, entry = result.program, result.entry
        iid = f"m{n + 1:03d}"
        key[iid] = {
            "system": system,
            "file": file,
            "id": pid,
            "source": source,
            "text": text,
            "entry": entry,
        }
        images.append(preview(program, size, layout="both"))
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
        for system in key[i].get("system", "current").split("+"):
            by_file[f"{system} {key[i]['file']}"].append(i)
    for file, ids in sorted(by_file.items()):
        vals = [mean[i] for i in ids]
        low = sum(v < 30 for v in vals)
        share = 100 * sum(v >= 60 for v in vals) / len(vals)
        print(
            f"{file}: n={len(vals)} mean={statistics.mean(vals):.1f} >=60 {share:.0f}% "
            f"below30={low}"
        )
        by_source: dict[str, list[float]] = defaultdict(list)
        for i in ids:
            by_source[key[i]["source"]].append(mean[i])
        for src, v in sorted(by_source.items()):
            print(f"  {src:18s} n={len(v):2d} mean={statistics.mean(v):.1f}")
        for i in sorted(ids, key=lambda i: mean[i])[:10]:
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
    p.add_argument(
        "--programs",
        nargs="+",
        default=[],
        metavar="NAME=FILE",
        help="builds' programs (from `author`), packed together, shuffled",
    )
    a = sub.add_parser("author")
    a.add_argument("-o", "--out", type=Path, required=True)
    a.add_argument("files", type=Path, nargs="+")
    s = sub.add_parser("summary")
    s.add_argument("folder", type=Path)
    s.add_argument("scores", type=Path, nargs="+")
    args = parser.parse_args()
    if args.cmd == "pack":
        programs = {}
        for item in args.programs:
            name, _, path = item.partition("=")
            programs[name] = Path(path)
        pack(args.out, args.files, args.size, args.shuffle_seed, programs)
    elif args.cmd == "author":
        author_all(args.out, args.files)
    else:
        summary(args.folder, args.scores)


if __name__ == "__main__":
    main()
