"""Language 3: parameterised Defines ``Define(name(a, b), expr)`` used as ``name(x, y)``:
parsing and diagnostics, the canonical text, expansion (checker, engine), the cost model and
the inliner."""

from __future__ import annotations

import numpy as np
import pytest

from matloom.engine.evaluate import evaluate
from matloom.lang.api import check, format, parse
from matloom.lang.cost import expanded_cost
from matloom.lang.diagnostics import ProgramError
from matloom.lang.inline import inline_defines
from matloom.lang.macros import expand_program
from matloom.lang.parser import parse_source
from matloom.lang.printer import format_program

SOURCE = """View(0, 0, 1, 1)
# stripes
Define(stripe(k, phase), Fract(((X() * k) + phase)))  # a ramp
Define(row(w), Bricks(brick_width=w))
Define(base, fBm(seed=3))
Material(
  Layer(1)
    .height(((stripe(4, 0.25) * row(0.5)) + Max(base, stripe(2, base), 0.1)))
)
"""
EXPANDED = """View(0, 0, 1, 1)
Define(base, fBm(seed=3))
Material(Layer(1).height(((Fract(((X() * 4) + 0.25)) * Bricks(brick_width=0.5))
  + Max(base, Fract(((X() * 2) + base)), 0.1))))
"""


def test_canonical_text_is_a_fixed_point_with_comments() -> None:
    assert check(SOURCE) == []
    text = format(parse(SOURCE), comments=True)
    assert text == SOURCE.rstrip("\n")
    assert format(parse(text), comments=True) == text
    assert format(parse("Define(f(a),a*2)\nMaterial(Layer(f(a=X())))")).startswith(
        "Define(f(a), (a * 2))"
    )


@pytest.mark.parametrize("backend", ["numpy", "auto"])
def test_evaluates_as_its_expansion(backend: str) -> None:
    a = evaluate(SOURCE, 32, 24, backend=backend)
    b = evaluate(EXPANDED, 32, 24, backend=backend)
    assert np.array_equal(a.height, b.height)
    assert np.std(a.height) > 0


def test_expansion_and_inlining_leave_no_parameterised_define() -> None:
    program = parse(SOURCE)
    expanded = expand_program(program)
    assert [d.name for d in expanded.defines] == ["base"]
    inlined = format_program(inline_defines(program))
    assert "Define" not in inlined and "stripe" not in inlined
    assert format_program(parse(inlined)) == format_program(inline_defines(parse(EXPANDED)))


def test_seeds_are_shared_by_the_uses() -> None:
    text = "Define(n(s), fBm() * s)\nMaterial(Layer(1).height(n(1) - n(1)))"
    maps = evaluate(text, 8, 8, backend="numpy")
    assert np.all(maps.height == 0)  # both uses have the body's (one) drawn seed


BAD = {
    "Define(f(a), a)\nMaterial(Layer(f))": ("E062", "takes parameters (a)"),
    "Define(f(a), a)\nMaterial(Layer(f(1, 2)))": ("E062", "too many arguments"),
    "Define(f(a), a)\nMaterial(Layer(f()))": ("E062", "missing argument: a"),
    "Define(f(a), a)\nMaterial(Layer(f(b=1)))": ("E062", "no parameter 'b'"),
    "Define(g, 1)\nMaterial(Layer(g(1)))": ("E062", "Define without parameters"),
    "Define(f(a, a), a)\nMaterial(Layer(f(1, 2)))": ("E063", "is repeated"),
    "Define(f(X), 1)\nMaterial(Layer(f(1)))": ("E063", "built-in"),
    "Define(g, 1)\nDefine(f(g), g)\nMaterial(Layer(f(1)))": ("E063", "name of a Define"),
    "Define(f(a), f(a))\nMaterial(Layer(f(1)))": ("E060", "refers to itself"),
    "Define(f(a), g(a))\nDefine(g(a), a)\nMaterial(Layer(f(1)))": ("E060", "before"),
    "Define(f(a), a(1))\nMaterial(Layer(f(1)))": ("E062", "a parameter"),
    "Define(f(a), Bricks(brick_width=a))\nMaterial(Layer(f(fBm(seed=1))))": ("E045", "field"),
    "Define(f(a), Bricks(brick_width=a))\nMaterial(Layer(f(-1)))": ("E050", "> 0"),
}


@pytest.mark.parametrize("text", list(BAD))
def test_diagnostics(text: str) -> None:
    code, words = BAD[text]
    found = [d for d in check(text) if d.code == code]
    assert any(words in d.message for d in found), check(text)


def test_constant_argument_folds_into_a_static_parameter() -> None:
    text = "Define(w, 0.25)\nDefine(row(k), Bricks(brick_width=k * 2))\nMaterial(Layer(1).roughness(row(w)))"
    assert [d for d in check(text) if d.is_error] == []
    a = evaluate(text, 128, 128, backend="numpy")
    b = evaluate("Material(Layer(1).roughness(Bricks(brick_width=0.5)))", 128, 128, backend="numpy")
    assert np.array_equal(a.roughness, b.roughness) and np.std(a.roughness) > 0


def test_each_use_is_counted_as_its_expansion() -> None:
    one = expanded_cost(parse("Define(f(a), fBm(octaves=4, seed=1) * a)\nMaterial(Layer(f(1)))"))
    two = expanded_cost(
        parse("Define(f(a), fBm(octaves=4, seed=1) * a)\nMaterial(Layer(f(1) + f(2)))")
    )
    assert two.nodes > 2 * one.nodes - 5


def test_a_cost_bomb_through_parameterised_defines_is_refused() -> None:
    # each level applies the previous one 9 times (a Tile): 9**6 motifs per sample
    levels = "".join(
        f"Define(t{k}(a), Tile(t{k - 1}(a), 0.5, 0.5, seed={k}))\n" for k in range(1, 7)
    )
    text = "Define(t0(a), fBm(octaves=2, seed=1) * a)\n" + levels + "Material(Layer(t6(X())))"
    assert "E071" in {d.code for d in check(text)}
    # doubling per level: the expansion itself is bounded before anything walks it
    doubling = "Define(f0(a), a + a)\n" + "".join(
        f"Define(f{k}(a), f{k - 1}(f{k - 1}(a)))\n" for k in range(1, 40)
    )
    diags = check(doubling + "Material(Layer(f39(X())))")
    assert [d.code for d in diags] == ["E070"]
    program, _ = parse_source(doubling + "Material(Layer(f39(X())))")
    assert program is not None
    with pytest.raises(ProgramError, match="E070"):
        inline_defines(program)
