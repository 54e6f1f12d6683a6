"""The coverage table in docs/library.md is the one `matloom library list --stats` prints."""

from __future__ import annotations

from pathlib import Path

from matloom.library import CATEGORIES, library
from matloom.library.coverage import coverage_table, doc_table

DOC = Path(__file__).resolve().parents[2] / "docs" / "library.md"


def test_docs_coverage_table_is_current() -> None:
    assert doc_table(DOC) == coverage_table(library()), (
        "docs/library.md's coverage table is stale: paste `matloom library list --stats` "
        "between its coverage markers"
    )


def test_every_category_folder_is_a_category() -> None:
    root = Path(library().entries["cobblestone"].path).parents[1]
    for folder in root.iterdir():
        if folder.is_dir() and not folder.name.startswith("_"):
            assert folder.name in CATEGORIES, folder
