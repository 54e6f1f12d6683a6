"""The library's coverage table by category (docs/library.md embeds it; a test keeps it current).

``matloom library list --stats`` prints :func:`coverage_table`; :func:`update_doc` rewrites the
table between the ``<!-- coverage:start -->`` and ``<!-- coverage:end -->`` markers of a file.
"""

from __future__ import annotations

from pathlib import Path

from matloom.library.entry import CATEGORIES
from matloom.library.index import Library

START = "<!-- coverage:start -->"
END = "<!-- coverage:end -->"


def coverage_table(lib: Library) -> str:
    """A Markdown table: category, entries, tileable entries, and the entry names."""
    rows = ["| category | entries | tileable | entries (names) |", "|---|---|---|---|"]
    total = tiles = 0
    for cat in CATEGORIES:
        entries = lib.by_category(cat)
        n, t = len(entries), sum(e.tileable for e in entries)
        total, tiles = total + n, tiles + t
        names = ", ".join(e.name for e in entries) or "-"
        rows.append(f"| {cat} | {n} | {t} | {names} |")
    rows.append(f"| **total** | **{total}** | **{tiles}** | {len(lib.overlays)} overlays |")
    return "\n".join(rows)


def update_doc(path: Path | str, lib: Library) -> bool:
    """Replace the table between the markers of ``path``; True when the file changed."""
    path = Path(path)
    text = path.read_text(encoding="utf-8")
    start, end = text.index(START) + len(START), text.index(END)
    new = text[:start] + "\n" + coverage_table(lib) + "\n" + text[end:]
    if new == text:
        return False
    path.write_text(new, encoding="utf-8")
    return True


def doc_table(path: Path | str) -> str:
    """The table currently between the markers of ``path``."""
    text = Path(path).read_text(encoding="utf-8")
    return text[text.index(START) + len(START) : text.index(END)].strip()
