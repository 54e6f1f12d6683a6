"""Numbers at and past the float range: diagnostics from check, fmt and evaluate, never an
``OverflowError`` (issue "Reliability" #4 and #16).

Integer literals of 309-400 digits used to pass the lexer as exact ints and overflow later
(``float(int)`` in View, in numeric parameters and in the evaluator); constant integer
arithmetic (``10**200 * 10**200`` written in digits) did the same; and a View whose width
overflows (``View(-1e308, -1e308, 1e308, 1e308)``) was accepted with an infinite texel size.
"""

from __future__ import annotations

import math

import pytest

import matloom
from matloom.engine.evaluate import evaluate
from matloom.lang import ast as A
from matloom.lang.lexer import as_float
from matloom.lang.printer import format_program

BIG = "9" * 300  # a float; its square is not
HUGE = "9" * 350  # the reproducer: an integer literal past the float range


def _codes(text: str) -> list[str]:
    return [d.code for d in matloom.check(text) if d.is_error]


@pytest.mark.parametrize(
    "text",
    [
        f"Material(Layer(1).height({HUGE}))",
        f"Material(Layer(1).height(X() * {HUGE}))",
        f"View(0, 0, {HUGE}, 10)\nMaterial(Layer(1))",
        f"Material(Layer(1).basecolor({HUGE}, 0, 0))",
        f"Material(Layer(1).height(fBm(seed={HUGE})))",
        f"Material(Layer(1).height({'1' + '0' * 399}))",  # 400 digits: the longest literal
    ],
)
def test_integer_literal_past_float_range_is_e003_everywhere(text: str) -> None:
    assert _codes(text) == ["E003"]
    for entry_point in (matloom.parse, matloom.format, lambda t: evaluate(t, 8, 8)):
        with pytest.raises(matloom.ProgramError) as info:
            entry_point(text)
        assert [d.code for d in info.value.diagnostics if d.is_error] == ["E003"]


def test_e003_message_abbreviates_the_literal() -> None:
    (diag,) = matloom.check(f"Material(Layer(1).height({HUGE}))")
    assert "350 characters" in diag.message and "too large" in diag.message
    assert len(diag.message) < 120


def test_largest_float_integers_are_still_numbers() -> None:
    largest = str(int(1.7976931348623157e308))  # 309 digits, exactly the largest float
    assert _codes(f"Material(Layer(1).height(X() * {largest}))") == []
    assert _codes(f"Material(Layer(1).height(X() * {BIG}))") == []
    maps = evaluate(f"Material(Layer(1).height(X() * {BIG}))", 8, 8)
    assert maps.height.shape == (8, 8)


@pytest.mark.parametrize(
    ("text", "code"),
    [
        (f"Material(Layer(1).height(Constant({BIG} * {BIG})))", "E050"),
        (f"Material(Layer(1).height(Bricks(brick_width={BIG} * {BIG})))", "E050"),
        (f"Material(Layer(1).height(Weave(over={BIG} * {BIG})))", "E050"),
        (f"View(0, 0, {BIG} * {BIG}, 1)\nMaterial(Layer(1))", "E061"),
    ],
)
def test_constant_integer_arithmetic_past_float_range_is_not_finite(text: str, code: str) -> None:
    assert _codes(text) == [code]
    with pytest.raises(matloom.ProgramError):
        evaluate(text, 8, 8)


def test_huge_constant_alpha_warns_without_printing_a_huge_integer() -> None:
    alpha = " * ".join([BIG] * 16)  # 4,800 digits as an exact int: too long for str()
    diags = matloom.check(f"Material(Layer(-({alpha})).height(1))")
    assert [d.code for d in diags] == ["W002"]
    assert "-inf" in diags[0].message


def test_printer_folds_unchecked_huge_integers_to_inf() -> None:
    big = A.Num(int(BIG))
    call = A.Call("Constant", (A.Arg("value", A.BinOp("*", big, big)),))
    program = A.Program(None, (), (A.Layer(A.Num(1), (A.ChannelSet("height", (call,)),)),))
    assert ".height(inf)" in format_program(program)  # Constant prints as its value


def test_as_float() -> None:
    assert as_float(3) == 3.0 and as_float(-2.5) == -2.5
    assert as_float(10**400) == math.inf and as_float(-(10**400)) == -math.inf


# ---------------------------------------------------------------------------- View (E061)
@pytest.mark.parametrize(
    ("view", "words"),
    [
        ("View(-1e308, -1e308, 1e308, 1e308)", "too large"),  # the reproducer
        ("View(1e308, 0, -1e308, 1)", "too large"),  # reversed and overflowing
        ("View(-2e38, 0, 2e38, 1)", "too large"),  # finite in float64, not in the float32 grid
        ("View(0, 0, 1e39, 1)", "too large"),
        ("View(0, 0, 1e-320, 1)", "too small"),  # subnormal span: zero texel size
        ("View(0, 0, 1, 5e-324)", "too small"),
    ],
)
def test_view_with_non_finite_or_zero_texel_size_is_e061(view: str, words: str) -> None:
    text = f"{view}\nMaterial(Layer(1))"
    errors = [d for d in matloom.check(text) if d.is_error]
    assert [d.code for d in errors] == ["E061"]
    assert words in errors[0].message
    with pytest.raises(matloom.ProgramError):
        evaluate(text, 8, 8)


def test_large_but_representable_view_renders_with_finite_texel_size() -> None:
    maps = evaluate("View(-1e38, -1e38, 1e38, 1e38)\nMaterial(Layer(1).height(X()))", 8, 8)
    dx, dy = maps.view.texel_size(8, 8)
    assert math.isfinite(dx) and math.isfinite(dy) and dx > 0
