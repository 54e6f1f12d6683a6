"""Benchmark of edits by words (`matloom edit`): applied, locality, refusals, and a blind-judge
packet for "did it do what was asked".

Runs every request of ``benchmarks/data/edit_requests.json`` (held out: committed before any
result was looked at) over its program, offline (the rules) or with an OpenAI-compatible model
(``--base-url`` and ``--model``; e.g. ``../shared/tools/bridge_openai.py`` with a strong model
answering), and prints per request and in total:

* applied: the edit produced a program that checks clean (refusals are counted apart);
* locality: the largest fraction of texels changed in a map outside the intended channels
  (goal <= 1 % on every edit) and the leaks;
* refused: which requests the offline rules refused, and why.

``--pack DIR`` also writes, for the applied edits, a blind-judge packet: one image per edit
(before | after; the flat preview above, the lit studio below; an edit that makes the program
tileable shows both sides repeated 2 x 2, one that sets the physical size has each side's width
written under it) under a shuffled opaque id, ``requests.json`` (id -> request text, all a judge
sees) and ``key.json`` (id -> request id). ``collect DIR ANSWERS...`` folds judges'
answers (JSON objects id -> "yes"/"no") into the share of yes per judge and overall.

    PYTHONPATH=. .venv/bin/python benchmarks/edits.py run [--requests FILE] [--json OUT] [--pack DIR]
    PYTHONPATH=. .venv/bin/python benchmarks/edits.py run --base-url URL --model NAME
    PYTHONPATH=. .venv/bin/python benchmarks/edits.py collect DIR answers_*.json
    PYTHONPATH=. .venv/bin/python benchmarks/edits.py merge REQUESTS before.json after.json DIR
"""

from __future__ import annotations

import argparse
import json
import random
import statistics
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
REQUESTS = ROOT / "benchmarks" / "data" / "edit_requests.json"
PREVIEW = 192


def _program(ref: str) -> str:
    if ref.startswith("library:"):
        from matloom.library import load_library

        return load_library().entry(ref.split(":", 1)[1]).program
    return (ROOT / ref).read_text(encoding="utf-8")


def _model(base_url: str | None, name: str | None):  # noqa: ANN202 - a ChatModel or None
    if not base_url or not name:
        return None
    from matloom.author.config import ModelSettings
    from matloom.author.llm.providers import get_model

    return get_model(ModelSettings(model=name, base_url=base_url, max_retries=2))


def _view(text: str):  # noqa: ANN202 - the program's ViewDecl or None
    from matloom.lang.api import parse

    return parse(text).view


def _width_caption(view) -> str:  # noqa: ANN001 - a ViewDecl or None
    if view is None or view.unit_m is None:
        return "physical size: not set"
    return f"{abs(view.x2 - view.x1) * view.unit_m:.3g} m wide"


def _side_by_side(before: str, after: str) -> np.ndarray:
    """Before (left) and after (right); the flat preview above, the lit studio below (it shows
    gloss and relief, which the flat preview barely does). What a View edit changes shows too:
    an edit that makes the program tileable shows both sides repeated 2 x 2 (seams show where
    they are), one that sets the physical size has each side's width written under it."""
    from matloom.render.api import preview

    va, vb = _view(before), _view(after)
    tiled = bool(vb is not None and vb.tileable and not (va is not None and va.tileable))
    tile = 2 if tiled else 1
    size = PREVIEW // tile
    a = preview(before, size, layout="both", tile=tile)
    b = preview(after, size, layout="both", tile=tile)
    w = a.shape[1] // 2
    gap = np.full((a.shape[0], 8, 3), 255, np.uint8)
    flat = np.concatenate([a[:, :w], gap, b[:, :w]], axis=1)
    lit = np.concatenate([a[:, w:], gap, b[:, w:]], axis=1)
    out = np.concatenate([flat, np.full((8, flat.shape[1], 3), 255, np.uint8), lit], axis=0)
    if (va.unit_m if va else None) != (vb.unit_m if vb else None):
        out = _captioned(out, _width_caption(va), _width_caption(vb), w + 8)
    return out


def _captioned(image: np.ndarray, left: str, right: str, offset: int) -> np.ndarray:
    from PIL import Image, ImageDraw

    strip = Image.new("RGB", (image.shape[1], 18), (255, 255, 255))
    draw = ImageDraw.Draw(strip)
    draw.text((4, 3), left, fill=(0, 0, 0))
    draw.text((offset + 4, 3), right, fill=(0, 0, 0))
    return np.concatenate([image, np.asarray(strip)], axis=0)


def run(args: argparse.Namespace) -> None:
    from matloom.author.edit.api import edit
    from matloom.author.edit.rules import EditRefused
    from matloom.lang.api import check

    data = json.loads(Path(args.requests).read_text(encoding="utf-8"))
    model = _model(args.base_url, args.model)
    rows = []
    for item in data["requests"]:
        text = _program(data["programs"][item["program"]])
        row = {"id": item["id"], "program": item["program"], "request": item["request"]}
        t0 = time.perf_counter()
        try:
            result = edit(text, item["request"], model=model)
        except EditRefused as err:
            row.update(status="refused", why=err.reason)
        except Exception as err:  # noqa: BLE001 - a benchmark records every failure
            row.update(status="failed", why=f"{type(err).__name__}: {err}")
        else:
            errors = [d for d in check(result.program) if d.is_error]
            loc = result.report.locality
            allowed = loc.allowed
            outside = [c.fraction for n, c in loc.maps.items() if n not in allowed]
            row.update(
                status="applied" if not errors else "invalid",
                rule=result.report.plan.get("rule", result.report.mode),
                note=result.report.plan.get("note", ""),
                changed=[c.to_json()["address"] for c in result.report.changes],
                intended=list(loc.intended),
                maps_changed=list(loc.changed),
                outside_max=max(outside, default=0.0),
                leaks=list(loc.leaks),
                program_after=result.program,
                program_before=text,
            )
        row["seconds"] = round(time.perf_counter() - t0, 3)
        rows.append(row)
        print(
            f"{row['id']} {row['status']:8s} {row['program'][:24]:24s} {row['request'][:40]:40s} "
            + (
                f"outside {row['outside_max']:.4f} leaks {','.join(row['leaks']) or '-'}"
                if "outside_max" in row
                else row.get("why", "")[:70]
            )
        )
    _summary(rows, "model" if model else "offline")
    if args.json:
        kept = [{k: v for k, v in r.items() if k != "program_before"} for r in rows]
        Path(args.json).parent.mkdir(parents=True, exist_ok=True)
        Path(args.json).write_text(json.dumps(kept, indent=1) + "\n", encoding="utf-8")
    if args.pack:
        _pack(Path(args.pack), [r for r in rows if r["status"] == "applied"], args.seed)


def _summary(rows: list[dict], mode: str) -> None:
    n = len(rows)
    by = {s: [r for r in rows if r["status"] == s] for s in ("applied", "invalid", "refused")}
    failed = [r for r in rows if r["status"] == "failed"]
    accepted = n - len(by["refused"])
    outside = [r["outside_max"] for r in by["applied"]]
    print(f"\n{mode}: {n} requests over {len({r['program'] for r in rows})} programs")
    print(
        f"applied (checks clean) {len(by['applied'])} of {accepted} accepted "
        f"({100 * len(by['applied']) / max(accepted, 1):.0f} %); invalid {len(by['invalid'])}; "
        f"failed {len(failed)}; refused {len(by['refused'])}"
    )
    if outside:
        over = sum(1 for v in outside if v > 0.01)
        print(
            f"locality: outside the intended maps, max {max(outside) * 100:.2f} % of texels, "
            f"median {statistics.median(outside) * 100:.2f} %; edits over 1 %: {over}"
        )
    for r in by["refused"] + failed:
        print(f"  {r['status']} {r['id']} {r['request']!r}: {r['why'][:110]}")


def _pack(folder: Path, rows: list[dict], seed: int) -> None:
    from PIL import Image

    folder.mkdir(parents=True, exist_ok=True)
    ids = [f"x{k:03d}" for k in random.Random(seed).sample(range(1000), len(rows))]
    requests, key = {}, {}
    for opaque, row in zip(ids, rows, strict=True):
        Image.fromarray(_side_by_side(row["program_before"], row["program_after"])).save(
            folder / f"{opaque}.png"
        )
        requests[opaque] = row["request"]
        key[opaque] = row["id"]
    order = sorted(requests)
    (folder / "requests.json").write_text(
        json.dumps({k: requests[k] for k in order}, indent=1) + "\n", encoding="utf-8"
    )
    (folder / "key.json").write_text(json.dumps(key, indent=1) + "\n", encoding="utf-8")
    print(f"judge packet: {len(rows)} images in {folder} (requests.json for judges, key.json)")


def merge(args: argparse.Namespace) -> None:
    """One blind packet of two builds' ``run --json`` rows (before, after) on one request set,
    shuffled under opaque ids; an edit both builds made identically is judged once ("both")."""
    from PIL import Image

    data = json.loads(Path(args.requests).read_text(encoding="utf-8"))
    before = {r["id"]: r for r in json.loads(Path(args.before).read_text(encoding="utf-8"))}
    after = {r["id"]: r for r in json.loads(Path(args.after).read_text(encoding="utf-8"))}
    items = []
    for item in data["requests"]:
        b, a = before[item["id"]], after[item["id"]]
        text = _program(data["programs"][item["program"]])
        if b["status"] == a["status"] == "applied" and b["program_after"] == a["program_after"]:
            items.append(("both", item, text, a["program_after"]))
            continue
        items += [(k, item, text, r["program_after"]) for k, r in (("before", b), ("after", a))
                  if r["status"] == "applied"]  # fmt: skip
    folder = Path(args.folder)
    folder.mkdir(parents=True, exist_ok=True)
    ids = [f"e{k:03d}" for k in random.Random(args.seed).sample(range(1000), len(items))]
    requests, key = {}, {}
    for opaque, (build, item, text, edited) in zip(ids, items, strict=True):
        Image.fromarray(_side_by_side(text, edited)).save(folder / f"{opaque}.png")
        requests[opaque] = item["request"]
        key[opaque] = {"build": build, "request": item["id"]}
    (folder / "requests.json").write_text(
        json.dumps({k: requests[k] for k in sorted(requests)}, indent=1) + "\n", encoding="utf-8"
    )
    (folder / "key.json").write_text(json.dumps(key, indent=1) + "\n", encoding="utf-8")
    shared = sum(1 for x in items if x[0] == "both")
    print(f"judge packet: {len(items)} images ({shared} shared) in {folder}")


def collect(args: argparse.Namespace) -> None:
    folder = Path(args.folder)
    key = json.loads((folder / "key.json").read_text(encoding="utf-8"))
    total_yes = total = 0
    for path in args.answers:
        answers = json.loads(Path(path).read_text(encoding="utf-8"))
        yes = sum(1 for k in key if str(answers.get(k, "")).lower().startswith("y"))
        total_yes, total = total_yes + yes, total + len(key)
        no = sorted(key[k] for k in key if not str(answers.get(k, "")).lower().startswith("y"))
        print(
            f"{Path(path).name}: yes {yes} of {len(key)} ({100 * yes / len(key):.0f} %); no: {no}"
        )
    print(f"overall: yes {100 * total_yes / max(total, 1):.1f} %")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    sub = parser.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("run")
    r.add_argument(
        "--requests",
        default=str(REQUESTS),
        help="the request set (default: the v1 development set, benchmarks/data/edit_requests.json)",
    )
    r.add_argument("--base-url", default=None)
    r.add_argument("--model", default=None)
    r.add_argument("--json", default=None, help="write the rows as JSON")
    r.add_argument("--pack", default=None, help="write a blind-judge packet into this folder")
    r.add_argument("--seed", type=int, default=0, help="shuffle seed of the packet ids")
    c = sub.add_parser("collect")
    c.add_argument("folder")
    c.add_argument("answers", nargs="+")
    m = sub.add_parser("merge", help="one blind packet of two builds' run --json rows")
    m.add_argument("requests")
    m.add_argument("before")
    m.add_argument("after")
    m.add_argument("folder")
    m.add_argument("--seed", type=int, default=0, help="shuffle seed of the packet ids")
    args = parser.parse_args()
    {"run": run, "collect": collect, "merge": merge}[args.cmd](args)


if __name__ == "__main__":
    main()
