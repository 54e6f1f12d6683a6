"""Gallery of library-authored materials: previews, 2x2 tiled previews, programs, one HTML page
and a PNG contact sheet, so results can be judged at a glance without running anything.

Every prompt goes through :func:`matloom.library.author` (the offline author of
``matloom generate``); each row shows the chosen entry, the overlays and the explanation.

Layout of the output folder::

    index.html            one row per prompt: preview, tiled preview, program, explanation
    contact_sheet.png     every preview with its prompt as the label
    previews/<id>.png     head-on preview (``size`` px)
    previews/<id>_tiled.png  2x2 tiling of a half-size preview (same pixel size), shows seams
    programs/<id>.mat     the canonical program
    gallery.json          prompt, source, entry, overlays, timing and line count per prompt
"""

from __future__ import annotations

import hashlib
import html
import json
import re
import time
from collections.abc import Callable, Sequence
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any

from matloom.library.author import LibraryResult, author


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
    #: The library entry the program came from, and the overlays composed on it.
    entry: str
    overlays: list[str]
    lines: int
    author_ms: float
    preview: str
    tiled: str
    program_file: str
    #: The prompt's id as written in the prompts file (``id`` is its file-name form).
    prompt_id: str = ""


class PromptFileError(ValueError):
    """The prompts file is not a list of prompts; the message names the file and the item."""


_PROMPTS_SHAPE = 'a JSON list of prompts, or {"prompts": [...]}'


def load_prompts(path: str | Path) -> list[PromptEntry]:
    """Read prompts from JSON: ``{"prompts": [...]}`` or a list; items are strings or objects
    with ``text`` (or ``prompt``) and optional ``id`` and ``source``.

    Raises :class:`PromptFileError` for unreadable or malformed files, items that are neither,
    empty prompt texts and ids given twice.
    """
    try:
        data: Any = json.loads(Path(path).read_text(encoding="utf-8"))
    except OSError as e:
        raise PromptFileError(f"cannot read {path}: {e.strerror}") from None
    except UnicodeDecodeError:
        raise PromptFileError(f"{path} is not UTF-8 text") from None
    except json.JSONDecodeError as e:
        raise PromptFileError(
            f"{path} is not valid JSON ({e.msg} at line {e.lineno}, column {e.colno})"
        ) from None
    except ValueError as e:  # e.g. an integer with more digits than Python converts
        raise PromptFileError(f"{path} is not usable JSON ({e})") from None
    if isinstance(data, dict) and "prompts" in data:
        data = data["prompts"]
    if not isinstance(data, list):
        raise PromptFileError(f"{path} must hold {_PROMPTS_SHAPE}, not {_json_kind(data)}")
    out = [_prompt_entry(path, i, item) for i, item in enumerate(data)]
    _refuse_duplicate_ids(path, data, out)
    return out


def _json_kind(value: object) -> str:
    if isinstance(value, dict):
        return "an object" if value else "an empty object"
    if isinstance(value, list):
        return "a list"
    if isinstance(value, str):
        return "a string"
    if isinstance(value, bool) or value is None:
        return json.dumps(value)
    return "a number"


def _prompt_entry(path: str | Path, index: int, item: object) -> PromptEntry:
    where = f"{path}: prompt {index}"
    if isinstance(item, str):
        item = {"text": item}
    if not isinstance(item, dict):
        raise PromptFileError(
            f'{where} must be a string or an object with "text", not {_json_kind(item)}'
        )
    text = item.get("text", item.get("prompt"))
    if not isinstance(text, str) or not text.strip():
        raise PromptFileError(f'{where}: "text" (or "prompt") is {_text_problem(text)}')
    raw_id, source = item.get("id"), item.get("source", "")
    if raw_id is not None and (isinstance(raw_id, bool) or not isinstance(raw_id, str | int)):
        raise PromptFileError(f'{where}: "id" must be a string or an integer')
    if not isinstance(source, str):
        raise PromptFileError(f'{where}: "source" must be a string')
    pid = str(raw_id) if raw_id is not None and str(raw_id) else f"p{index:03d}"
    return PromptEntry(pid, source, text)


def _text_problem(text: object) -> str:
    if text is None:
        return "missing"
    return "empty" if isinstance(text, str) else f"{_json_kind(text)}, not a string"


def _refuse_duplicate_ids(path: str | Path, items: list, entries: list[PromptEntry]) -> None:
    """Ids written twice are ambiguous (which row is "a"?), so they are refused."""
    first: dict[str, int] = {}
    for i, (item, entry) in enumerate(zip(items, entries, strict=True)):
        if not (isinstance(item, dict) and item.get("id") is not None):
            continue
        if entry.id in first:
            raise PromptFileError(
                f"{path}: prompts {first[entry.id]} and {i} have the same id {entry.id!r}"
            )
        first[entry.id] = i


_MAX_STEM = 80
_WINDOWS_RESERVED = frozenset(
    ["con", "prn", "aux", "nul"] + [f"{p}{d}" for p in ("com", "lpt") for d in range(1, 10)]
)


def _safe_id(raw: str) -> str:
    """``raw`` as a portable file-name stem: ASCII letters, digits, ``_ . -`` only."""
    stem = re.sub(r"[^A-Za-z0-9_.-]+", "_", raw)[:_MAX_STEM].strip(".")
    return stem or "prompt"


def assign_file_ids(ids: Sequence[str]) -> list[str]:
    """A distinct file-name stem for each prompt id, in order, deterministically.

    Ids that are already safe keep their name; the others are sanitised (``a/b`` -> ``a_b``).
    When two ids would share files (``a/b`` and ``a_b``, ``A`` and ``a`` on a case-insensitive
    disk, ``x`` and ``x_tiled`` whose tiled preview is ``x_tiled.png``, or a reserved Windows
    name), the later one gets a suffix from a hash of its id: ``a_b-1f3a9c``. No prompt is lost.
    """
    taken: set[str] = set()
    out: list[str | None] = [None] * len(ids)
    exact = [i for i, raw in enumerate(ids) if _safe_id(raw) == raw]  # claim their names first
    for i in exact + [i for i in range(len(ids)) if _safe_id(ids[i]) != ids[i]]:
        out[i] = _claim(ids[i], taken)
    return [stem for stem in out if stem is not None]


def _claim(raw: str, taken: set[str]) -> str:
    base = _safe_id(raw)
    stem, attempt = base, 0
    while _clashes(stem, taken):
        digest = hashlib.sha1(f"{raw}\0{attempt}".encode(), usedforsecurity=False).hexdigest()[:6]
        stem, attempt = f"{base[: _MAX_STEM - 7]}-{digest}", attempt + 1
    taken.update(name.casefold() for name in (stem, f"{stem}_tiled"))
    return stem


def _clashes(stem: str, taken: set[str]) -> bool:
    names = (stem.casefold(), f"{stem}_tiled".casefold())
    return any(n in taken for n in names) or stem.split(".")[0].casefold() in _WINDOWS_RESERVED


def _sheet_label(entry: GalleryEntry, cell: int) -> str:
    """The contact-sheet label, cut to at most ``cell`` characters before it is fitted.

    Every glyph is at least a pixel wide, so nothing visible is lost, and fitting (which
    shortens one character at a time) stays cheap for a 200 KB prompt.
    """
    label = " ".join(f"{entry.prompt_id or entry.id}: {entry.text}".split())  # linear
    limit = max(cell, 16)
    return label if len(label) <= limit else label[:limit] + "..."


def _row_html(entry: GalleryEntry, result: LibraryResult) -> str:
    program = html.escape(result.program)
    explanation = html.escape(result.explanation)
    return (
        "<tr>"
        f"<td class='prompt'><b>{html.escape(entry.prompt_id or entry.id)}</b>"
        f"<br><i>{html.escape(entry.source)}</i>"
        f"<p>{html.escape(entry.text)}</p><p>entry: <code>{html.escape(entry.entry)}</code>"
        f"<br>overlays: {html.escape(', '.join(entry.overlays) or 'none')}"
        f"<br>{entry.lines} lines, {entry.author_ms:.0f} ms</p></td>"
        f"<td><img src='{entry.preview}' width='256' height='256' alt='preview'></td>"
        f"<td><img src='{entry.tiled}' width='256' height='256' alt='tiled 2x2'></td>"
        f"<td><pre>{program}</pre><details><summary>why</summary><pre>{explanation}</pre>"
        "</details></td></tr>"
    )


_PAGE = """<!doctype html>
<html lang="en"><head><meta charset="utf-8"><title>MatLoom library author gallery</title>
<style>
body {{ font-family: sans-serif; margin: 1em; background: #fafafa; }}
table {{ border-collapse: collapse; }}
td {{ border-top: 1px solid #ccc; vertical-align: top; padding: 6px; }}
td.prompt {{ width: 260px; font-size: 13px; }}
pre {{ font-size: 11px; max-width: 640px; overflow-x: auto; white-space: pre; }}
</style></head><body>
<h1>MatLoom material library (offline author): gallery</h1>
<p>{count} prompts, seed {seed}. Each row: the prompt, the head-on preview ({size} px), a 2&times;2
tiling of the same material (seams show where it does not tile), and the program with the
library's explanation (candidates, entry, adaptations, ignored words). <a href="contact_sheet.png">Contact sheet</a>.</p>
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
    author_fn: Callable[[str, int], LibraryResult] | None = None,
) -> list[GalleryEntry]:
    """Author (``author_fn(text, seed)``, default :func:`matloom.library.author`), render and
    write the gallery for ``prompts`` into ``out_dir``.

    The whole gallery is staged and installed at the end (``index.html`` last); files in
    ``out_dir`` that MatLoom did not write are never touched.
    """
    from matloom.io.outdir import OutputFolder

    with OutputFolder(out_dir) as folder, folder.batch("gallery", marker="index.html") as staging:
        return _write_gallery(
            prompts, staging, seed, size, columns, sheet_cell, author_fn or library_author
        )


def library_author(text: str, seed: int) -> LibraryResult:
    """The library's program for ``text`` (tileable wherever the entry allows it)."""
    return author(text, seed=seed)


def _write_gallery(  # noqa: PLR0913 - build_gallery's options, passed through
    prompts: Sequence[PromptEntry],
    out: Path,
    seed: int,
    size: int,
    columns: int,
    sheet_cell: int,
    author_fn: Callable[[str, int], LibraryResult],
) -> list[GalleryEntry]:
    from matloom.render.api import preview
    from matloom.render.sheet import contact_sheet, save_png

    (out / "previews").mkdir(parents=True, exist_ok=True)
    (out / "programs").mkdir(parents=True, exist_ok=True)
    entries: list[GalleryEntry] = []
    rows: list[str] = []
    images = []
    for prompt, pid in zip(prompts, assign_file_ids([p.id for p in prompts]), strict=True):
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
            result.entry,
            list(result.overlays),
            result.program.count("\n") + 1,
            elapsed,
            f"previews/{pid}.png",
            f"previews/{pid}_tiled.png",
            f"programs/{pid}.mat",
            prompt.id,
        )
        entries.append(entry)
        rows.append(_row_html(entry, result))
        images.append(image)
    if images:
        labels = [_sheet_label(e, sheet_cell) for e in entries]
        save_png(out / "contact_sheet.png", contact_sheet(images, labels, columns, sheet_cell))
    page = _PAGE.format(count=len(entries), seed=seed, size=size, rows="\n".join(rows))
    (out / "index.html").write_text(page, encoding="utf-8")
    (out / "gallery.json").write_text(
        json.dumps([asdict(e) for e in entries], indent=1) + "\n", encoding="utf-8"
    )
    return entries
