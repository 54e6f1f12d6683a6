"""Malformed programs: each gives the expected diagnostic code at the expected line and column.

Positions are 1-based (line, column) of the first character of the offending token or
expression. Where a message or hint should help the author (or a model) repair the program, the
table also names a word it must contain. The second half checks the reference's own rejected
programs (``tests/data/parity/rejected.json``), one-pass error collection and the warnings.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path

import pytest

import matloom

PARITY = Path(__file__).resolve().parents[1] / "data" / "parity"


_BIG = "9" * 300
"""An integer literal inside the float range whose square is not."""


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
    contains: str | None = None  # must appear in the message or hint (case-insensitive)
    errors: int = 1  # how many errors in total (no cascades unless stated)


# fmt: off
CASES = [
    # -- names, functions, parameters
    Case("unknown_function", _r("Noise(seed=1)"), "E030", 1, 29, "fBm"),
    Case("fbm_lowercase", _r("fbm(octaves=3, seed=1)"), "E030", 1, 29, "`fBm`"),
    Case("unknown_parameter", _r("fBm(octave=3, seed=1)"), "E031", 1, 33, "`octaves=`"),
    Case("unknown_name_nearest_define",
         "Define(grain, fBm(seed=1))\nMaterial(Layer(1).roughness(grian))", "E036", 2, 29,
         "`grain`"),
    Case("unknown_name_alias", _r("noise"), "E036", 1, 29, "fBm"),
    Case("function_without_call", _r("Bricks"), "E035", 1, 29, "Bricks()"),
    Case("unknown_channel", "Material(Layer(1).colour(1, 2, 3))", "E026", 1, 19, "basecolor"),
    Case("unknown_statement", "Materail(Layer(1))", "E012", 1, 1, "Material"),
    Case("segments_keyword", "Material(Layer(Fill(Path(0, 0, segments=LineTo(1, 1)))))",
         "E031", 1, 32, "positional", errors=2),
    # -- arity
    Case("basecolor_two_args", "Material(Layer(1).basecolor(200, 100))", "E027", 1, 19, "3"),
    Case("emissive_three_args", "Material(Layer(1).emissive(1, 2, 3))", "E027", 1, 19, "4"),
    Case("view_five_args", "View(0, 0, 1, 1, 2)\nMaterial(Layer(1))", "E027", 1, 16, "4"),
    Case("view_three_args", "View(0, 0, 1)\nMaterial(Layer(1))", "E010", 1, 13, "missing"),
    Case("layer_two_args", "Material(Layer(1, 0.5))", "E028", 1, 17, "alpha"),
    Case("x_with_argument", _r("X(1)"), "E032", 1, 31),
    Case("missing_required", "Material(Layer(Fill(Rect(0, 0, 1))))", "E034", 1, 21, "height"),
    Case("duplicate_keyword", _r("fBm(seed=1, seed=2)"), "E033", 1, 41, "seed"),
    Case("keyword_and_position", _r("Bricks(0.5, brick_width=0.5)"), "E033", 1, 41),
    # -- ranges and kinds of static parameters
    Case("negative_mortar", _r("Bricks(mortar=-0.1)"), "E050", 1, 43, ">= 0"),
    Case("zero_scale", _r("Scale(X(), 0, 1)"), "E054", 1, 40, "non-zero"),
    Case("octaves_zero", _r("fBm(octaves=0, seed=1)"), "E050", 1, 41, ">= 1"),
    Case("negative_seed", _r("fBm(seed=-1)"), "E050", 1, 38, ">= 0"),
    Case("warp_width_above_one", _r("Weave(warp_width=1.5)"), "E050", 1, 46, "(0, 1]"),
    Case("negative_feather",
         "Material(Layer(Fill(Ellipse(0.5, 0.5, 0.2, 0.2), feather=-0.01)))", "E050", 1, 58),
    Case("octaves_fractional", _r("fBm(octaves=2.5, seed=1)"), "E052", 1, 41, "integer"),
    Case("octaves_over_limit", _r("fBm(octaves=17, seed=1)"), "E070", 1, 41, "16"),
    Case("log_base_zero", _r("Log(X(), 0)"), "E050", 1, 38, "> 0"),
    Case("rect_negative_width", "Material(Layer(Fill(Rect(0, 0, -1, 1))))", "E050", 1, 32),
    Case("stroke_zero_width", "Material(Layer(Stroke(Ellipse(0, 0, 1, 1), 0)))", "E050", 1, 44),
    Case("freq_none_without_axes", _r("fBm(base_freq=None, base_freq_x=2, seed=1)"),
         "E055", 1, 29, "base_freq_y"),
    Case("field_in_numeric_slot", _r("Log(X(), fBm(seed=1))"), "E045", 1, 38),
    Case("bool_parameter_string", _r('fBm(to_01="yes", seed=1)'), "E053", 1, 39),
    Case("bad_enum", _r('Worley(distance="cosine", seed=1)'), "E051", 1, 45, "euclidean"),
    Case("bad_enum_nearest", _r('Bricks(axis="rows")'), "E051", 1, 41, "`row`"),
    Case("unquoted_enum", _r("Bricks(axis=row)"), "E051", 1, 41, 'axis="row"', errors=2),
    # -- shapes and segments
    Case("shape_outside_fill", _r("Rect(0, 0, 1, 1)"), "E040", 1, 29, "Fill"),
    Case("shape_in_define", "Define(box, Rect(0, 0, 1, 1))\nMaterial(Layer(box))", "E040",
         1, 13, "Define"),
    Case("segment_outside_path", _r("LineTo(1, 1)"), "E041", 1, 29, "Path"),
    Case("path_non_segment", "Material(Layer(Fill(Path(0, 0, X()))))", "E044", 1, 32),
    Case("path_without_segment", "Material(Layer(Fill(Path(0, 0))))", "E044", 1, 21, "segment"),
    Case("fill_of_non_shape", "Material(Layer(Fill(X())))", "E043", 1, 21, "shape"),
    # -- Defines and statement order
    Case("define_self_reference", "Define(a, a + 1)\nMaterial(Layer(a))", "E060", 1, 11,
         "itself"),
    Case("define_forward_reference", "Define(a, b)\nDefine(b, X())\nMaterial(Layer(a))",
         "E060", 1, 11, "before"),
    Case("define_twice", "Define(a, X())\nDefine(a, Y())\nMaterial(Layer(a))", "E038", 2, 8),
    Case("view_after_define", "Define(n, X())\nView(0, 0, 1, 1)\nMaterial(Layer(n))", "E020",
         2, 1, "first"),
    Case("second_view", "View(0, 0, 1, 1)\nView(0, 0, 2, 2)\nMaterial(Layer(1))", "E020", 2, 1),
    Case("second_material", "Material(Layer(1))\nMaterial(Layer(1))", "E023", 2, 1),
    Case("trailing_input", "Material(Layer(1))\nX()", "E012", 2, 1, "after Material"),
    Case("layer_outside_material", "Layer(1).roughness(0.5)", "E025", 1, 1, "Material"),
    Case("missing_material", "View(0, 0, 1, 1)", "E022", 1, 17),
    Case("empty_program", "", "E022", 1, 1),
    Case("empty_material", "Material()", "E024", 1, 1, "layer"),
    Case("view_zero_width", "View(0, 0, 0, 1)\nMaterial(Layer(1))", "E061", 1, 1),
    Case("view_field_argument", "View(0, 0, X(), 1)\nMaterial(Layer(1))", "E061", 1, 12,
         "numbers"),
    Case("view_inf_name", "View(0, 0, inf, 1)\nMaterial(Layer(1))", "E061", 1, 12, errors=2),
    Case("view_span_overflows", "View(-1e308, -1e308, 1e308, 1e308)\nMaterial(Layer(1))",
         "E061", 1, 1, "too large"),
    Case("view_past_float32_grid", "View(0, 0, 1e39, 1)\nMaterial(Layer(1))", "E061", 1, 1,
         "float32"),
    Case("view_integer_product_overflows",
         f"View(0, 0, {_BIG} * {_BIG}, 1)\nMaterial(Layer(1))", "E061", 1, 1, "finite"),
    Case("view_subnormal_span", "View(0, 0, 1e-320, 1)\nMaterial(Layer(1))", "E061", 1, 1,
         "too small"),
    # -- channels
    Case("keyword_in_channel", "Material(Layer(1).roughness(value=0.5))", "E031", 1, 29),
    Case("bool_channel", _r("True"), "E042", 1, 29, "bool"),
    Case("string_channel", _r('"rough"'), "E042", 1, 29, "string"),
    Case("none_channel", _r("None"), "E042", 1, 29),
    # -- lexical and syntax
    Case("unterminated_string", _r('Worley(distance="euclidean)'), "E002", 1, 45),
    Case("trailing_comma_layers", "Material(Layer(1),)", "E013", 1, 19, "comma"),
    Case("trailing_comma_args", _r("Min(X(), Y(),)"), "E013", 1, 41, "comma"),
    Case("trailing_comma_channel", "Material(Layer(1).roughness(0.5,))", "E013", 1, 32),
    Case("double_minus", _r("--X()"), "E011", 1, 30, "-(-x)"),
    Case("exponent_without_digits", _r("1e"), "E003", 1, 29, "exponent"),
    Case("number_too_large", _r("1e999"), "E003", 1, 29, "too large"),
    Case("integer_too_large", _r("9" * 350), "E003", 1, 29, "too large"),
    Case("integer_just_too_large", _r("2" + "0" * 308), "E003", 1, 29, "finite"),
    Case("integer_product_too_large", _r(f"Constant({_BIG} * {_BIG})"), "E050", 1, 38,
         "finite"),
    Case("integer_product_too_large_int", _r(f"fBm(octaves={_BIG} * {_BIG}, seed=1)"), "E050",
         1, 41, "finite"),
    Case("digit_underscore", _r("1_000"), "E010", 1, 30),
    Case("semicolon", "Material(Layer(1));", "E001", 1, 19, "';'"),
    Case("square_bracket", _r("[1]"), "E001", 1, 29, "parentheses"),
    Case("backtick_fence", "```\nMaterial(Layer(1))\n```", "E001", 1, 1, "fences"),
    Case("missing_comma_between_layers", "Material(\n  Layer(1)\n  Layer(0.5)\n)", "E010", 3, 3,
         "','"),
    Case("missing_comma_between_args", _r("Min(X() Y())"), "E010", 1, 37, "','"),
    Case("unclosed_material", "Material(Layer(1).roughness(0.5)", "E010", 1, 33),
    Case("too_deep_nesting", _r("(" * 150 + "X()" + ")" * 150), "E070", 1, 129, "Defines"),
    Case("too_long_chain", _r("+".join(["X()"] * 150)), "E070", 1, 428, "100"),
    Case("define_chain_too_deep",
         "Define(d0, X())\n" + "".join(f"Define(d{k}, d{k - 1} + 1)\n" for k in range(1, 150))
         + "Material(Layer(1).height(d149))", "E070", 101, 14, "substituted"),
]
# fmt: on


def _errors(text: str) -> list[matloom.Diagnostic]:
    return [d for d in matloom.check(text) if d.is_error]


def test_table_is_large_and_names_are_unique() -> None:
    assert len(CASES) >= 45
    assert len({c.name for c in CASES}) == len(CASES)


@pytest.mark.parametrize("case", CASES, ids=[c.name for c in CASES])
def test_malformed_program(case: Case) -> None:
    errors = _errors(case.text)
    found = [(d.code, d.line, d.column) for d in errors]
    assert (case.code, case.line, case.col) in found, found
    assert len(errors) == case.errors, found
    match = next(
        d for d in errors if (d.code, d.line, d.column) == (case.code, case.line, case.col)
    )
    if case.contains is not None:
        text = f"{match.message} {match.hint or ''} {match.expected or ''}".lower()
        assert case.contains.lower() in text, (match.message, match.hint, match.expected)
    # every diagnostic carries a caret excerpt of the offending line
    assert "^" in match.excerpt
    with pytest.raises(matloom.ProgramError) as info:
        matloom.parse(case.text)
    assert any(d.code == case.code for d in info.value.diagnostics)


# ---------------------------------------------------------------------------- reference rejects
#: Programs the reference rejects at parse time that MatLoom deliberately accepts
#: (listed in docs/compatibility.md): `#` comments and constant arithmetic in View.
ACCEPTED_EXTENSIONS = {"comment_line", "view_expression_arg"}


def _rejected() -> list[dict[str, object]]:
    return json.loads((PARITY / "rejected.json").read_text(encoding="utf-8"))


@pytest.mark.parametrize("entry", _rejected(), ids=lambda e: str(e["name"]))
def test_reference_rejected_programs(entry: dict[str, object]) -> None:
    text = str(entry["program"])
    errors = _errors(text)
    if entry["name"] in ACCEPTED_EXTENSIONS:
        assert errors == []
        return
    # stage "parse": we reject too. Stage "export" (an empty Material) is rejected earlier by us.
    assert errors, f"{entry['name']} should be rejected ({entry['error']})"


def test_accepted_extensions_mean_what_they_say() -> None:
    by_name = {e["name"]: str(e["program"]) for e in _rejected()}
    assert set(ACCEPTED_EXTENSIONS) <= set(by_name)
    view = matloom.parse(by_name["view_expression_arg"]).view
    assert view is not None and view.as_tuple() == (0, 0, 6, 1)
    commented = matloom.parse(by_name["comment_line"])
    assert len(commented.layers) == 1 and "#" not in matloom.format(commented)


# ---------------------------------------------------------------------------- one pass, warnings
def test_independent_errors_in_three_defines_are_all_reported() -> None:
    text = (
        "Define(a, fBm(octave=3, seed=1))\n"
        "Define(b, Bricks(mortar=-1))\n"
        'Define(c, Worley(distance="cosine", seed=2))\n'
        "Material(Layer(a + b + c))"
    )
    assert [(d.code, d.line) for d in _errors(text)] == [("E031", 1), ("E050", 2), ("E051", 3)]


def test_syntax_errors_in_three_defines_are_all_reported() -> None:
    text = "Define(a, (X())\nDefine(b, Min(X(),))\nDefine(c, --X())\nMaterial(Layer(a + b + c))"
    assert [(d.code, d.line) for d in _errors(text)] == [("E010", 2), ("E013", 2), ("E011", 3)]


def test_unused_define_warns_w001() -> None:
    diags = matloom.check("Define(n, X())\nMaterial(Layer(1).roughness(0.5))")
    assert [(d.code, d.severity, d.line, d.column) for d in diags] == [
        ("W001", matloom.Severity.WARNING, 1, 8)
    ]


def test_hidden_layer_warns_w002() -> None:
    text = "Material(\n  Layer(1).roughness(0.2),\n  Layer(1).roughness(0.9)\n)"
    assert [(d.code, d.line) for d in matloom.check(text)] == [("W002", 2)]
    invisible = "Material(\n  Layer(1),\n  Layer(0).roughness(0.9)\n)"
    assert [(d.code, d.line) for d in matloom.check(invisible)] == [("W002", 3)]
    # a coverage that varies over the image hides nothing
    assert matloom.check("Material(\n  Layer(1),\n  Layer(X())\n)") == []


def test_seedless_noise_warns_w003_and_still_parses() -> None:
    text = _r("fBm(octaves=3) + Worley()")
    assert [d.code for d in matloom.check(text)] == ["W003", "W003"]
    matloom.parse(text)  # warnings do not make a program invalid


def test_check_never_raises_on_the_table() -> None:
    for case in CASES:
        assert all(isinstance(d, matloom.Diagnostic) for d in matloom.check(case.text))


def test_threshold_target_without_cutoff_warns_w008_and_is_dropped() -> None:
    text = "Material(Layer(1).roughness(Threshold(X(), below_to=0.2, above_at=0.5, above_to=1)))"
    assert [(d.code, d.column) for d in matloom.check(text)] == [("W008", 44)]
    printed = matloom.format(matloom.parse(text))
    assert "below_to" not in printed and "above_to=1" in printed
    both = "Material(Layer(1).roughness(Threshold(X(), below_at=0.1, below_to=0.2)))"
    assert matloom.check(both) == []
    assert "below_to=0.2" in matloom.format(matloom.parse(both))


def test_transform_parameters_accept_fields() -> None:
    """Language 2: Translate/Scale/Rotate take field parameters (domain warping), printed as
    written (X()/Y() alone keep their language-1 meaning there: W004)."""
    text = (
        "Define(y, Y())\n"
        "Material(Layer(1).roughness(Rotate(Translate(X(), fBm(seed=1), y * 0.5), y)))"
    )
    assert matloom.check(text) == []
    printed = matloom.format(matloom.parse(text))
    assert "Translate(X(), fBm(seed=1), (y * 0.5)), y)" in printed
    assert [d.code for d in matloom.check("Material(Layer(1).roughness(Log(X(), X() + 2)))")] == [
        "W004"
    ]
