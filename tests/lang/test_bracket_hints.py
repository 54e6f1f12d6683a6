"""Bracket diagnostics: every extra, missing or wrong parenthesis gets a hint that names the
construct it belongs to and where that opened (issue 15, item 5), and caret excerpts of long
lines are cut at token boundaries with the caret under the offending token.

The hints are compared whole: they are what the repair loop sends back to a model.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

import pytest
from click.testing import CliRunner

import matloom
from matloom.author.prompts.revision import diagnostics_message
from matloom.cli.main import cli
from matloom.lang.diagnostics import Span, caret_excerpt
from matloom.lang.excerpt import MAX_WIDTH, MORE
from matloom.lang.lexer import Lexer


def _r(expr: str) -> str:
    """A one-line program whose roughness expression starts at column 29."""
    return f"Material(Layer(1).roughness({expr}))"


@dataclass(frozen=True)
class Case:
    name: str
    text: str
    code: str
    line: int
    col: int
    hint: str
    errors: int = 1


_CHANNEL_LEFT_OPEN = (
    "Material(\n"
    "  Layer(1)\n"
    "    .roughness((0.85 + (X() * 0.1)),\n"
    "  Layer(0.5).basecolor(12, 13, 16)\n"
    ")"
)

# fmt: off
CASES = [
    # -- a ')' with no opening
    Case("extra_close_after_define", "Define(dash, Min(X(), Y())))\nMaterial(Layer(dash))",
         "E012", 1, 28,
         "the `)` at 1:28 has no opening; `Define(dash, …` opened at 1:1 was already closed "
         "at 1:27"),
    Case("extra_close_after_material", "Material(Layer(1)))", "E012", 1, 19,
         "the `)` at 1:19 has no opening; `Material(` opened at 1:1 was already closed at 1:18"),
    Case("stray_close_first", ")\nMaterial(Layer(1))", "E012", 1, 1,
         "the `)` at 1:1 has no opening '('"),
    Case("define_closed_early", "Define(a, Min(X(), Y())) + 1)\nMaterial(Layer(a))",
         "E012", 1, 26,
         "`Define(a, …` opened at 1:1 was already closed at 1:24, so the `)` at 1:29 has no "
         "opening: one ')' up to 1:24 is extra (or a '(' is missing)", errors=3),
    Case("material_closed_early", "Material(Layer(1)), Layer(2))", "E025", 1, 21,
         "`Material(` opened at 1:1 was already closed at 1:18, so the `)` at 1:29 has no "
         "opening: one ')' up to 1:18 is extra (or a '(' is missing)", errors=3),
    # -- a ')' missing
    Case("unclosed_material", "Material(Layer(1).roughness(0.5)", "E010", 1, 33,
         "`Material(` opened at 1:1 is never closed"),
    Case("unclosed_define", "Define(a, Min(X(), Y())\nMaterial(Layer(a))", "E010", 2, 1,
         "`Define(a, …` opened at 1:1 is never closed"),
    Case("unclosed_view", "View(0, 0, 2, 2\nMaterial(Layer(1))", "E010", 2, 1,
         "`View(` opened at 1:1 is never closed"),
    Case("unclosed_call_in_define", "Define(a, Min(X(),\nMaterial(Layer(a))", "E010", 2, 1,
         "`Min(` opened at 1:11 is never closed"),
    Case("channel_open_at_next_layer", _CHANNEL_LEFT_OPEN, "E010", 4, 3,
         "`.roughness(` opened at 3:5 is not closed before `Layer(` at 4:3"),
    Case("channel_open_at_next_channel", "Material(Layer(1).roughness(Min(0.5, 1).height(1))",
         "E010", 1, 40, "`.roughness(` opened at 1:18 is not closed before `.height(` at 1:40"),
    Case("layer_open_at_channel", "Material(Layer(Min(X(), Y()).roughness(0.5))", "E010", 1, 29,
         "`Layer(` opened at 1:10 is not closed before `.roughness(` at 1:29"),
    Case("ends_early", "Material(Layer(Min(X(),", "E011", 1, 24,
         "the program ends early: `Min(` opened at 1:16 is never closed (3 '(' are left open)"),
    # -- a '(' too many
    Case("extra_open_group", "Define(a, Min((X(), Y()))\nMaterial(Layer(a))", "E010", 1, 19,
         "the `(` at 1:15 groups one expression and cannot hold a ','; remove it if it is "
         "extra, or write the name of the function it should call"),
    Case("extra_open_in_material", "Material((Layer(1)))", "E025", 1, 10,
         "Material(...) holds only Layer(...) calls: remove the '(' at 1:10"),
    # -- the wrong kind of bracket
    Case("square_close", _r("Min(X(), Y()]"), "E001", 1, 41,
         "only round parentheses are used in MatLoom programs: the `]` at 1:41 cannot close "
         "`Min(` opened at 1:29; write ')'"),
    Case("square_open", _r("[1]"), "E001", 1, 29,
         "only round parentheses are used in MatLoom programs: write '(' instead of `[` and ')' "
         "instead of its `]`"),
    Case("curly_close_nothing_open", "Material(Layer(1))}", "E001", 1, 19,
         "only round parentheses are used in MatLoom programs: remove the `}` at 1:19, nothing "
         "is open there"),
    # -- trailing ',' and missing ','
    Case("trailing_comma_call", _r("Min(X(), Y(),)"), "E013", 1, 41,
         "remove the ',' at 1:41: the ')' after it closes `Min(` opened at 1:29"),
    Case("trailing_comma_layers", "Material(Layer(1),)", "E013", 1, 19,
         "remove the ',' at 1:18: the ')' after it closes `Material(` opened at 1:1"),
    Case("missing_comma", _r("Min(X() Y())"), "E010", 1, 37,
         "a ',' may be missing between the arguments of `Min(` opened at 1:29"),
]
# fmt: on


def _errors(text: str) -> list[matloom.Diagnostic]:
    return [d for d in matloom.check(text) if d.is_error]


def test_table_covers_many_cases_with_unique_names() -> None:
    assert len(CASES) >= 10
    assert len({c.name for c in CASES}) == len(CASES)


@pytest.mark.parametrize("case", CASES, ids=[c.name for c in CASES])
def test_bracket_hint(case: Case) -> None:
    errors = _errors(case.text)
    found = {(d.code, d.line, d.column): d for d in errors}
    assert (case.code, case.line, case.col) in found, list(found)
    assert len(errors) == case.errors, list(found)
    diag = found[(case.code, case.line, case.col)]
    assert diag.hint == case.hint
    # the rendered text, which the repair loop quotes to a model, carries the hint
    assert f"  hint: {case.hint}" in diag.format("program")
    assert case.hint in diagnostics_message(case.text, errors)


def test_every_error_of_a_bracket_case_has_a_hint() -> None:
    for case in CASES:
        assert all(d.hint for d in _errors(case.text)), case.name


def test_the_missing_paren_of_a_channel_replaces_the_unknown_function_cascade() -> None:
    """Before: E030 "unknown function 'Layer'" and an E010 at the next '.'; now one E010 at the
    Layer the channel's value runs into."""
    assert [(d.code, d.line) for d in _errors(_CHANNEL_LEFT_OPEN)] == [("E010", 4)]
    # a Layer inside an expression whose parentheses balance is still an unknown function
    assert [d.code for d in _errors(_r("Min(Layer(1), 2)"))] == ["E030"]


def _long_define(extra: bool) -> str:
    """A 14-line program whose Define on line 14 is about 370 columns wide."""
    terms = " + ".join(f"fBm(octaves=3, base_freq={k}, seed={k})" for k in range(1, 10))
    head = "".join(f"Define(d{k}, X() * {k})\n" for k in range(13))
    line = f"Define(dash, Max({terms}, Y()){')' if extra else ''})"
    uses = " + ".join(f"d{k}" for k in range(13))
    return f"{head}{line}\nMaterial(Layer(dash + {uses}))"


def test_extra_close_at_the_end_of_a_long_line() -> None:
    """The reported case: an extra ')' far along a long line."""
    text = _long_define(extra=True)
    line14 = text.split("\n")[13]
    assert len(line14) > 350
    col = len(line14)
    closed = col - 1
    (diag,) = _errors(text)
    assert (diag.code, diag.line, diag.column) == ("E012", 14, col)
    assert diag.hint == (
        f"the `)` at 14:{col} has no opening; `Define(dash, …` opened at 14:1 was already "
        f"closed at 14:{closed}"
    )
    assert _errors(_long_define(extra=False)) == []


# ---------------------------------------------------------------------------- excerpts
def _excerpt_lines(excerpt: str) -> list[str]:
    return [line.split(" | ", 1)[1] if " | " in line else "" for line in excerpt.split("\n")]


def _token_bounds(line: str) -> tuple[set[int], set[int]]:
    tokens = [t for t in Lexer(line).tokens() if t.kind != "EOF"]
    return {t.span.start for t in tokens}, {t.span.end for t in tokens}


def _window_of(shown: str, line: str) -> tuple[int, int]:
    """Where the text of a shown (possibly cut) line lies in the source line."""
    body = shown.removeprefix(MORE).removesuffix(MORE)
    lo = line.find(body)
    assert lo >= 0, (shown, line)
    return lo, lo + len(body)


def test_short_lines_are_shown_whole() -> None:
    (diag,) = _errors("Material(Layer(1).roughness(grian))")
    assert diag.excerpt == (
        " 1 | Material(Layer(1).roughness(grian))\n   |                             ^^^^^"
    )


@pytest.mark.parametrize("name", ["grian", "Noize"])
def test_long_line_is_cut_at_token_boundaries_with_the_caret_under_the_token(name: str) -> None:
    terms = " + ".join(f"fBm(octaves=2, base_freq={k}, seed={k})" for k in range(1, 7))
    call = f"{name}(seed=1)" if name == "Noize" else name
    line = f"Material(Layer(1).roughness({terms} + {call} + {terms}))"
    (diag,) = _errors(line)
    shown, carets = _excerpt_lines(diag.excerpt)
    assert shown.startswith(MORE) and shown.endswith(MORE)
    assert len(shown) <= MAX_WIDTH + 2 * len(MORE)
    lo, hi = _window_of(shown, line)
    starts, ends = _token_bounds(line)
    assert lo in starts and hi in ends
    at = carets.index("^")
    width = carets.count("^")
    assert shown[at : at + width] == name


def test_the_line_before_a_long_line_is_cut_too() -> None:
    terms = " + ".join(f"Min(X(), {k})" for k in range(40))
    text = f"Define(a, {terms})\nMaterial(Layer(a).roughness({terms} + grian))"
    (diag,) = _errors(text)
    before, shown, carets = _excerpt_lines(diag.excerpt)
    for row, source in ((before, text.split("\n")[0]), (shown, text.split("\n")[1])):
        assert len(row) <= MAX_WIDTH + 2 * len(MORE)
        lo, hi = _window_of(row, source)
        starts, ends = _token_bounds(source)
        assert lo in starts and hi in ends
    assert shown[carets.index("^") :].startswith("grian")


def test_a_token_wider_than_the_window_keeps_its_caret() -> None:
    digits = "9" * 350
    (diag,) = _errors(_r(digits))
    shown, carets = _excerpt_lines(diag.excerpt)
    assert diag.code == "E003"
    at = carets.index("^")
    assert shown[at - 1 : at + carets.count("^")] == "(" + "9" * carets.count("^")
    assert shown.startswith(MORE) and shown.endswith(MORE)


def test_tabs_keep_the_caret_under_the_token() -> None:
    (diag,) = _errors("Material(Layer(1).roughness(\t\tgrian))")
    shown, carets = _excerpt_lines(diag.excerpt)
    assert shown[carets.index("^") :].startswith("grian")


def test_caret_excerpt_at_end_of_input() -> None:
    source = "Material(Layer(1)"
    excerpt = caret_excerpt(source, Span(len(source), len(source), 1, len(source) + 1))
    shown, carets = _excerpt_lines(excerpt)
    assert shown == source and carets.index("^") == len(source)


# ---------------------------------------------------------------------------- the CLI
def test_check_prints_one_header_line_per_diagnostic_with_its_hint(tmp_path: Path) -> None:
    path = tmp_path / "brackets.mat"
    path.write_text(
        "Define(a, Min(X(), Y())\nDefine(b, X()))\nMaterial(Layer(a + b).roughness(0.5)\n",
        encoding="utf-8",
    )
    result = CliRunner().invoke(cli, ["check", str(path)])
    assert result.exit_code == 2, result.output
    assert result.exception is None or isinstance(result.exception, SystemExit)
    assert "Traceback" not in result.output
    header = re.compile(rf"^{re.escape(str(path))}:(\d+):(\d+): error (E\d{{3}}): ")
    heads = [m.groups() for m in map(header.match, result.stderr.splitlines()) if m]
    assert heads == [("2", "1", "E010"), ("2", "15", "E012"), ("4", "1", "E010")]
    assert "1 file(s): 3 error(s), 0 warning(s)" in result.stderr
    hints = [line for line in result.stderr.splitlines() if line.startswith("  hint: ")]
    assert hints == [
        "  hint: `Define(a, …` opened at 1:1 is never closed",
        "  hint: the `)` at 2:15 has no opening; `Define(b, …` opened at 2:1 was already "
        "closed at 2:14",
        "  hint: `Material(` opened at 3:1 is never closed",
    ]
