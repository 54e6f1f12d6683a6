"""The diagnostic code table (matloom/lang/codes.py): every code emitted is in it, every entry
is emitted somewhere, and docs/diagnostics.md lists them all."""

from __future__ import annotations

import ast
import re
from pathlib import Path

import pytest

import matloom.lang.api as api
from matloom.lang.codes import CODES, Code
from matloom.lang.codes_doc import render_diagnostics_reference
from matloom.lang.diagnostics import Severity

ROOT = Path(__file__).resolve().parents[2]
PACKAGE = ROOT / "matloom"
TABLE = PACKAGE / "lang" / "codes.py"
CODE_TEXT = re.compile(r"[EW]\d{3}")


def _sources() -> list[tuple[Path, ast.AST]]:
    return [
        (path, ast.parse(path.read_text(), str(path)))
        for path in sorted(PACKAGE.rglob("*.py"))
        if path != TABLE
    ]


def test_the_table_is_well_formed() -> None:
    assert len(CODES) == len(Code)  # no two members share a code
    for member in Code:
        info = member.value
        assert CODE_TEXT.fullmatch(info.code), member
        want = Severity.ERROR if info.code[0] == "E" else Severity.WARNING
        assert member.severity is want, member
        for text in (info.meaning, info.hint):
            assert text and "\n" not in text and "|" not in text, member


def test_no_code_is_written_as_a_literal_outside_the_table() -> None:
    """Emitters name codes by constant, so every code emitted is in the table."""
    found = [
        f"{path.relative_to(ROOT)}:{node.lineno}: {node.value}"
        for path, tree in _sources()
        for node in ast.walk(tree)
        if isinstance(node, ast.Constant)
        and isinstance(node.value, str)
        and CODE_TEXT.fullmatch(node.value)
    ]
    assert not found, found


def test_every_code_of_the_table_is_emitted_somewhere() -> None:
    used = {
        node.attr
        for _, tree in _sources()
        for node in ast.walk(tree)
        if isinstance(node, ast.Attribute)
        and isinstance(node.value, ast.Name)
        and node.value.id == "Code"
    }
    unknown = used - {member.name for member in Code} - {"diagnostic", "code", "severity"}
    assert not unknown, sorted(unknown)
    unused = [member.name for member in Code if member.name not in used]
    assert not unused, unused


def test_docs_list_every_code() -> None:
    text = (ROOT / "docs" / "diagnostics.md").read_text()
    assert text == render_diagnostics_reference(), (
        "docs/diagnostics.md is stale: run python -m matloom.lang.codes_doc > docs/diagnostics.md"
    )
    for member in Code:
        assert f"| {member.code} | `{member.name}` |" in text


@pytest.mark.parametrize(
    ("source", "code"),
    [
        ("Material(Layer(1).basecolor(1, 2, 3);)", "E001"),
        ("Define(a, 1)\nDefine(a, 2)\nMaterial(Layer(1).roughness(a))", "E038"),
        ("Material(Layer(1).roughness(fBm(octaves=99, seed=1)))", "E070"),
        ("Define(a, 1)\nMaterial(Layer(1))", "W001"),
        ("View(0, 0, 1, 1, tileable=True)\nMaterial(Layer(1).roughness(X()))", "W010"),
    ],
)
def test_diagnostics_carry_the_code_and_severity_of_the_table(source: str, code: str) -> None:
    diags = api.check(source)
    assert code in [d.code for d in diags], [d.code for d in diags]
    for d in diags:
        assert d.severity is CODES[d.code].severity, d
