"""Gallery of authored materials: previews, 2x2 tiled previews, programs, one HTML page and a
PNG contact sheet, so results can be judged at a glance without running anything.

Layout of the output folder::

    index.html            one row per prompt: preview, tiled preview, program, explanation
    contact_sheet.png     every preview with its prompt as the label
    previews/<id>.png     head-on preview (``size`` px)
    previews/<id>_tiled.png  2x2 tiling of a half-size preview (same pixel size), shows seams
    programs/<id>.mat     the canonical program
    gallery.json          prompt, source, recipe, modifiers, timing and line count per entry
"""

from __future__ import annotations

import html
import json
import re
import time
from collections.abc import Callable, Sequence
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any

from matloom.author.builtin.compose import AuthorResult, author


@dataclass(frozen=True)
class PromptEntry:
    """One gallery prompt: a stable id, its source (benchmark pool) and its text."""

    id: str
    source: str
    text: str


@dataclass
class GalleryEntry:
    """What the gallery recorded for one prompt."""

    id: str
    source: str
    text: str
    recipe: str
    modifiers: list[str]
    lines: int
    author_ms: float
    preview: str
    tiled: str
    program_file: str


def load_prompts(path: str | Path) -> list[PromptEntry]:
    """Read prompts from JSON: ``{"prompts": [...]}`` or a list; items are strings or objects
    with ``text`` (or ``prompt``) and optional ``id`` and ``source``."""
    data: Any = json.loads(Path(path).read_text(encoding="utf-8"))
    items = data.get("prompts", []) if isinstance(data, dict) else data
    out: list[PromptEntry] = []
    for i, item in enumerate(items):
        if isinstance(item, str):
            out.append(PromptEntry(f"p{i:03d}", "", item))
        else:
            text = str(item.get("text") or item.get("prompt") or "")
            out.append(
                PromptEntry(str(item.get("id") or f"p{i:03d}"), str(item.get("source", "")), text)
            )
    return out


def _safe_id(raw: str) -> str:
    return re.sub(r"[^A-Za-z0-9_.-]+", "_", raw)[:80] or "prompt"


def _row_html(entry: GalleryEntry, result: AuthorResult) -> str:
    program = html.escape(result.program)
    explanation = html.escape(result.explanation)
    return (
        "<tr>"
        f"<td class='prompt'><b>{html.escape(entry.id)}</b><br><i>{html.escape(entry.source)}</i>"
        f"<p>{html.escape(entry.text)}</p><p>recipe: <code>{html.escape(entry.recipe)}</code>"
        f"<br>modifiers: {html.escape(', '.join(entry.modifiers) or 'none')}"
        f"<br>{entry.lines} lines, {entry.author_ms:.0f} ms</p></td>"
        f"<td><img src='{entry.preview}' width='256' height='256' alt='preview'></td>"
        f"<td><img src='{entry.tiled}' width='256' height='256' alt='tiled 2x2'></td>"
        f"<td><pre>{program}</pre><details><summary>why</summary><pre>{explanation}</pre>"
        "</details></td></tr>"
    )


_PAGE = """<!doctype html>
<html lang="en"><head><meta charset="utf-8"><title>MatLoom built-in author gallery</title>
<style>
body {{ font-family: sans-serif; margin: 1em; background: #fafafa; }}
table {{ border-collapse: collapse; }}
td {{ border-top: 1px solid #ccc; vertical-align: top; padding: 6px; }}
td.prompt {{ width: 260px; font-size: 13px; }}
pre {{ font-size: 11px; max-width: 640px; overflow-x: auto; white-space: pre; }}
</style></head><body>
<h1>MatLoom built-in (offline) author: gallery</h1>
<p>{count} prompts, seed {seed}. Each row: the prompt, the head-on preview ({size} px), a 2&times;2
tiling of the same material (seams show where it does not tile), and the program with the
author's explanation. <a href="contact_sheet.png">Contact sheet</a>.</p>
<table><tr><th>prompt</th><th>preview</th><th>2&times;2 tiled</th><th>program</th></tr>
{rows}
</table></body></html>
"""


def build_gallery(
    prompts: Sequence[PromptEntry],
    out_dir: str | Path,
    *,
    seed: int = 0,
    size: int = 256,
    columns: int = 8,
    sheet_cell: int = 192,
    author_fn: Callable[[str, int], AuthorResult] = author,
) -> list[GalleryEntry]:
    """Author, render and write the gallery for ``prompts`` into ``out_dir``."""
    from matloom.render.api import preview
    from matloom.render.sheet import contact_sheet, save_png

    out = Path(out_dir)
    (out / "previews").mkdir(parents=True, exist_ok=True)
    (out / "programs").mkdir(parents=True, exist_ok=True)
    entries: list[GalleryEntry] = []
    rows: list[str] = []
    images = []
    for prompt in prompts:
        pid = _safe_id(prompt.id)
        start = time.perf_counter()
        result = author_fn(prompt.text, seed)
        elapsed = (time.perf_counter() - start) * 1000
        image = preview(result.program, size=size)
        tiled = preview(result.program, size=size // 2, tile=2)
        save_png(out / "previews" / f"{pid}.png", image)
        save_png(out / "previews" / f"{pid}_tiled.png", tiled)
        (out / "programs" / f"{pid}.mat").write_text(result.program + "\n", encoding="utf-8")
        entry = GalleryEntry(
            pid,
            prompt.source,
            prompt.text,
            result.recipe,
            result.modifiers,
            result.program.count("\n") + 1,
            elapsed,
            f"previews/{pid}.png",
            f"previews/{pid}_tiled.png",
            f"programs/{pid}.mat",
        )
        entries.append(entry)
        rows.append(_row_html(entry, result))
        images.append(image)
    if images:
        labels = [f"{e.id}: {e.text}" for e in entries]
        save_png(out / "contact_sheet.png", contact_sheet(images, labels, columns, sheet_cell))
    page = _PAGE.format(count=len(entries), seed=seed, size=size, rows="\n".join(rows))
    (out / "index.html").write_text(page, encoding="utf-8")
    (out / "gallery.json").write_text(
        json.dumps([asdict(e) for e in entries], indent=1) + "\n", encoding="utf-8"
    )
    return entries
