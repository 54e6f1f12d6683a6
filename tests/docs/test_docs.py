"""Docs stay in sync with the registry, and their examples execute."""

import re
from pathlib import Path

import pytest

import matloom
from matloom.vocab.docs import render_language_reference

ROOT = Path(__file__).resolve().parents[2]
DOCS = sorted([ROOT / "README.md", *(ROOT / "docs").glob("*.md")])


def test_language_reference_is_generated_from_registry():
    on_disk = (ROOT / "docs" / "language.md").read_text(encoding="utf-8")
    assert on_disk == render_language_reference(), (
        "docs/language.md is stale: run python -m matloom.vocab.docs > docs/language.md"
    )


def _blocks(path: Path, lang: str) -> list[str]:
    text = path.read_text(encoding="utf-8")
    return re.findall(rf"```{lang}\n(.*?)```", text, re.DOTALL)


@pytest.mark.parametrize("path", DOCS, ids=lambda p: p.name)
def test_program_blocks_in_docs_check_clean(path):
    for block in _blocks(path, ""):
        if block.lstrip().startswith(("View(", "Define(", "Material(")):
            errors = [d for d in matloom.check(block) if d.is_error]
            assert not errors, "\n".join(d.format() for d in errors)


@pytest.mark.parametrize("path", DOCS, ids=lambda p: p.name)
def test_python_blocks_in_docs_run(path, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    tile = (ROOT / "tests" / "data" / "parity" / "tile.mat").read_text()
    for block in _blocks(path, "python"):
        namespace = {"text": tile}
        exec(compile(block, f"{path.name}:python-block", "exec"), namespace)  # noqa: S102 - runs our own docs
