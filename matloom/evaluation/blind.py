"""Blind judging of a bench: sheets of shuffled images with only the descriptions, and the
judges' scores folded back as a metric.

``pack`` writes ``DIR/blind/<metric>/sheets/sheet_NN.png`` (images labelled only with opaque
ids) and ``sheet_NN.json`` (id -> the description), which is all a judge gets, and
``DIR/blind/<metric>/key.json`` (id -> cell, prompt, system, run), which stays with whoever
runs the bench. ``collect`` reads judges' files (JSON objects id -> {"score": 0-100, "why":
"..."}), caches each cell's mean score as metric ``<metric>`` and rebuilds the report.
"""

from __future__ import annotations

import io
import json
import math
import random
import re
import statistics
from collections import defaultdict
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
from PIL import Image, ImageDraw

BLIND_DIR = "blind"
_NAME = re.compile(r"^[A-Za-z0-9_]+$")


def contact_sheet(images: Sequence[np.ndarray], labels: Sequence[str]) -> Image.Image:
    """Two images a row, each with its label in a strip above it (uint8 RGB arrays)."""
    h, w = images[0].shape[:2]
    strip = 18
    rows = -(-len(images) // 2)
    sheet = Image.new("RGB", (2 * w + 8, rows * (h + strip)), (24, 24, 24))
    draw = ImageDraw.Draw(sheet)
    for n, (img, label) in enumerate(zip(images, labels, strict=True)):
        x, y = (n % 2) * (w + 8), (n // 2) * (h + strip)
        draw.text((x + 4, y + 3), label, fill=(240, 240, 240))
        sheet.paste(Image.fromarray(img), (x, y + strip))
    return sheet


def _check_name(metric_name: str) -> None:
    if not _NAME.match(metric_name):
        raise ValueError(f"--metric-name {metric_name!r}: use letters, digits and '_'")


def _png(image: Image.Image) -> bytes:
    buf = io.BytesIO()
    image.save(buf, format="PNG")
    return buf.getvalue()


def _load(path: Path, size: int | None) -> np.ndarray:
    with Image.open(path) as img:
        img = img.convert("RGB")
        if size is not None and img.size != (size, size):
            img = img.resize((size, size))
        return np.asarray(img)


def pack(
    folder: Path,
    metric_name: str = "judge_blind",
    *,
    layout: str = "quick",
    per_sheet: int = 6,
    seed: int = 7,
) -> Path:
    """Write the judges' sheets for every finished cell of the bench in ``folder``; return the
    folder of sheets."""
    from matloom.evaluation.bench import CELLS_DIR, _read_plan, cell_images
    from matloom.io.outdir import OutputFolder

    _check_name(metric_name)
    if per_sheet < 1:
        raise ValueError("--per-sheet: give at least 1")
    plan = _read_plan(folder)
    assert plan is not None
    texts = {p["id"]: p["text"] for p in plan["prompts"]}
    items: dict[str, dict[str, Any]] = {}
    for c in plan["cells"]:
        if c["key"] in items or not (folder / CELLS_DIR / c["key"]).is_dir():
            continue
        image = cell_images(folder, c["key"]).get(layout)
        if image is not None:
            items[c["key"]] = {**c, "layout": layout, "text": texts[c["prompt_id"]], "image": image}
    if not items:
        raise ValueError(f"{folder}: no finished cell has a {layout!r} image to judge")
    order = sorted(items)
    random.Random(seed).shuffle(order)
    base = f"{BLIND_DIR}/{metric_name}"
    key: dict[str, dict[str, Any]] = {}
    with Image.open(items[order[0]]["image"]) as first:
        side = max(int(first.size[0]), 64)
    with OutputFolder(folder) as out:
        ids = []
        for n, cell_key in enumerate(order):
            iid = f"m{n + 1:04d}"
            item = items[cell_key]
            key[iid] = {
                k: item[k] for k in ("key", "prompt_id", "system", "run", "seed", "layout", "text")
            }
            ids.append(iid)
        for s in range(0, len(ids), per_sheet):
            chunk = ids[s : s + per_sheet]
            name = f"{base}/sheets/sheet_{s // per_sheet + 1:03d}"
            images = [_load(items[key[i]["key"]]["image"], side) for i in chunk]
            out.write_bytes(f"{name}.png", _png(contact_sheet(images, chunk)))
            texts_json = {i: key[i]["text"] for i in chunk}
            out.write_bytes(f"{name}.json", json.dumps(texts_json, indent=1).encode("utf-8"))
        out.write_bytes(f"{base}/key.json", json.dumps(key, indent=1).encode("utf-8"))
    return folder / base / "sheets"


def read_scores(path: Path, known: set[str]) -> dict[str, tuple[float, str]]:
    """One judge's file: ``id -> (score, why)``; ValueError naming what is wrong."""
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, ValueError) as err:
        raise ValueError(f"{path}: not a JSON score file ({' '.join(str(err).split())})") from None
    if not isinstance(data, dict):
        raise ValueError(f'{path}: expected an object id -> {{"score": 0-100, "why": ...}}')
    out = {}
    for iid, entry in data.items():
        if iid not in known:
            raise ValueError(f"{path}: unknown image id {iid!r} (not in key.json)")
        score = entry.get("score") if isinstance(entry, dict) else None
        if isinstance(score, bool) or not isinstance(score, int | float):
            raise ValueError(f'{path}: {iid}: give a numeric "score"')
        if not (math.isfinite(score) and 0 <= score <= 100):
            raise ValueError(f"{path}: {iid}: score {score} is outside 0-100")
        out[iid] = (float(score), str(entry.get("why", "")))
    return out


def collect(folder: Path, files: Sequence[Path], metric_name: str = "judge_blind") -> int:
    """Cache each judged cell's mean score as ``metric_name`` and rebuild the report; return
    the number of cells scored."""
    from matloom.evaluation.bench import write_report
    from matloom.evaluation.bench_scores import write_scores
    from matloom.io.outdir import OutputFolder

    _check_name(metric_name)
    base = folder / BLIND_DIR / metric_name
    key_path = base / "key.json"
    if not key_path.is_file():
        raise ValueError(f"{key_path} is missing: run `matloom bench pack {folder}` first")
    key = json.loads(key_path.read_text(encoding="utf-8"))
    scores: dict[str, list[float]] = defaultdict(list)
    why: dict[str, list[str]] = defaultdict(list)
    for path in files:
        for iid, (score, reason) in read_scores(path, set(key)).items():
            scores[iid].append(score)
            why[iid].append(reason)
    if not scores:
        raise ValueError("the score files hold no scores")
    with OutputFolder(folder) as out:
        for iid, values in scores.items():
            write_scores(
                folder, metric_name, key[iid]["key"], {metric_name: statistics.mean(values)}
            )
        collected = {i: {"scores": scores[i], "why": why[i], **key[i]} for i in sorted(scores)}
        out.write_bytes(
            f"{BLIND_DIR}/{metric_name}/collected.json",
            json.dumps(collected, indent=1).encode("utf-8"),
        )
        write_report(folder, out)
    return len(scores)
