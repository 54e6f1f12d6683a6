"""Property tests over generated programs: round trips, printer fixed point, inliner semantics.

The generator builds an AST and prints it canonically. Canonical printing legitimately
normalises a few things (reference-engine.md §5.1), so the generator's AST is compared with the
parsed text after applying exactly those documented rules (:func:`printer_normal_form`):

* ``Constant(v)`` prints as the bare number ``v`` (``-v`` for negatives, which parses as ``Neg``);
* Bricks/Weave and the options of Fill/Stroke are printed only when they differ from the default;
* ``Rect`` prints its radius clamped to half the smaller side, and omits a zero radius;
* ``Log`` omits a base equal to e; Threshold omits ``*_to`` equal to ``*_at`` and a zero width;
* fBm/Worley keywords newer than language 1 (Worley's ``output``) print only when not default,
  and a seed used only for some values of another parameter (``used_when``: Bricks' seed
  without ``output="cell_value"``) is not printed without them;
* positional-style calls print every optional number (so an omitted one re-parses as written).
"""

from __future__ import annotations

import math
from dataclasses import replace

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import matloom
from matloom.lang import ast as A
from matloom.lang.inline import inline_defines
from matloom.lang.parser import parse_source
from matloom.lang.printer import format_program
from matloom.lang.random_program import RandomConfig, random_program, random_program_ast
from matloom.lang.rewrite import map_program
from matloom.lang.static import static_number
from matloom.vocab import CHANNELS, FUNCTIONS, FunctionSpec, Kind, ParamSpec, PrintStyle

SEEDS = st.integers(min_value=0, max_value=2**40)
PROPERTY_SETTINGS = settings(max_examples=30, deadline=None)


def _literal(value: float) -> A.Node:
    return A.Neg(A.Num(-value)) if value < 0 else A.Num(value)


def _drop_defaults(call: A.Call, spec: FunctionSpec, names: set[str]) -> A.Call:
    kept = []
    for arg in call.args:
        p = spec.param(arg.param)
        if arg.param in names and p is not None and _static(arg.value) == p.default:
            continue
        kept.append(arg)
    return replace(call, args=tuple(kept))


def _static(node: A.Node) -> object:
    if isinstance(node, A.Str | A.Lit):
        return node.value
    return static_number(node)


def _drop_unused(call: A.Call, spec: FunctionSpec) -> A.Call:
    """Without arguments whose ``used_when`` condition does not hold."""

    def unused(p: ParamSpec | None) -> bool:
        if p is None or p.used_when is None:
            return False
        name, values = p.used_when
        node = call.arg(name)
        value = spec.param(name).default if node is None else _static(node)  # type: ignore[union-attr]
        return value not in values

    return replace(call, args=tuple(a for a in call.args if not unused(spec.param(a.param))))


def _normal_call(call: A.Call) -> A.Node:  # noqa: C901 - one rule per documented print style
    spec = FUNCTIONS.get(call.func)
    if spec is None:
        return call
    call = _drop_unused(call, spec)
    style = spec.print_style
    if style is PrintStyle.WRITTEN_KEYWORDS:
        return _drop_defaults(call, spec, {p.name for p in spec.params if p.since > 1})
    if style is PrintStyle.CONSTANT:
        value = call.arg("value")
        return _literal(static_number(value)) if value is not None else A.Num(0)
    if style is PrintStyle.NONDEFAULT_KEYWORDS:  # required parameters (Tile's) positionally
        dropped = _drop_defaults(call, spec, {p.name for p in spec.params if not p.required})
        args = tuple(
            replace(a, keyword=False) if spec.param(a.param).required else a  # type: ignore[union-attr]
            for a in dropped.args
        )
        order = {p.name: k for k, p in enumerate(spec.params)}
        return replace(dropped, args=tuple(sorted(args, key=lambda a: order[a.param])))
    if style is PrintStyle.SHAPE_OP:
        return _drop_defaults(call, spec, {p.name for p in spec.params if not p.required})
    if style is PrintStyle.THRESHOLD:
        kept = []
        for arg in call.args:
            at = call.arg(arg.param.replace("_to", "_at")) if arg.param.endswith("_to") else None
            same_as_at = at is not None and _static(at) == _static(arg.value)
            inert = arg.param.endswith("_to") and (at is None or _static(at) is None)
            zero_width = arg.param == "transition_width" and _static(arg.value) == 0
            if not (same_as_at or inert or zero_width):
                kept.append(arg)
        return replace(call, args=tuple(kept))
    if call.func == "Log":
        keep = tuple(a for a in call.args if a.param != "base" or _static(a.value) != math.e)
        return replace(call, args=keep)
    if call.func == "Rect" and call.arg("radius") is not None:
        w, h, r = (float(_static(call.arg(n))) for n in ("width", "height", "radius"))
        radius = min(r, min(w, h) / 2)
        rest = tuple(a for a in call.args if a.param != "radius")
        return replace(call, args=rest + ((A.Arg("radius", _literal(radius)),) if radius else ()))
    if style is PrintStyle.POSITIONAL and call.func != "Rect":
        args = {a.param: a for a in call.args}
        for p in spec.params:
            if p.name not in args and not p.required and p.kind not in (Kind.EXPR, Kind.SHAPE):
                args[p.name] = A.Arg(p.name, _literal(p.default))
        return replace(call, args=tuple(args[p.name] for p in spec.params if p.name in args))
    return call


def printer_normal_form(program: A.Program) -> A.Program:
    """``program`` with the canonical printer's documented normalisations applied."""

    def rule(node: A.Node) -> A.Node:
        return _normal_call(node) if isinstance(node, A.Call) else node

    return map_program(program, rule)


def substitute_defines(program: A.Program) -> A.Program:
    """Independent reference inliner for the test: replace each Ref by its resolved expression."""
    resolved: dict[str, A.Node] = {}

    def resolve(node: A.Node) -> A.Node:
        if isinstance(node, A.Ref):
            return resolved[node.name]
        if isinstance(node, A.Neg):
            return A.Neg(resolve(node.operand))
        if isinstance(node, A.BinOp):
            return A.BinOp(node.op, resolve(node.left), resolve(node.right))
        if isinstance(node, A.Call):
            args = tuple(replace(a, value=resolve(a.value)) for a in node.args)
            return replace(node, args=args, extra=tuple(resolve(e) for e in node.extra))
        return node

    for d in program.defines:
        resolved[d.name] = resolve(d.expr)
    layers = tuple(
        A.Layer(
            resolve(layer.alpha) if layer.alpha is not None else None,
            tuple(A.ChannelSet(c.name, tuple(resolve(a) for a in c.args)) for c in layer.channels),
        )
        for layer in program.layers
    )
    return A.Program(program.view, (), layers)


def _has_ref(program: A.Program) -> bool:
    return any(isinstance(n, A.Ref) for _, e in A.program_expressions(program) for n in A.walk(e))


# ---------------------------------------------------------------------------- round trips
@PROPERTY_SETTINGS
@given(SEEDS)
def test_generated_program_properties(seed: int) -> None:
    """One generated program per example (parsing is shared by the four properties)."""
    text = random_program(seed)
    # 1. always valid
    assert [d for d in matloom.check(text) if d.is_error] == []
    # 2. parse -> print -> parse: the same AST, and printing is a fixed point
    first = matloom.parse(text)
    printed = format_program(first)
    assert printed == text
    assert matloom.parse(printed) == first
    # 3. the generator's own AST survives printing up to the documented normalisations
    assert first == printer_normal_form(random_program_ast(seed))
    # 4. the inliner: no Define and no Ref left (except Defines of X()/Y() only that a field
    #    parameter needs per sample), every use replaced by the resolved expression, and the
    #    inlined text re-parses to the same tree
    inlined = inline_defines(first)
    kept = {d.name for d in inlined.defines}
    assert all(static_number(d.expr) is not None for d in inlined.defines), kept
    if not kept:
        assert not _has_ref(inlined)
        assert inlined == substitute_defines(first)
    reparsed, diags = parse_source(format_program(inlined))
    assert [d for d in diags if d.is_error] == []
    assert reparsed == inlined


def test_normalisation_helper_is_not_vacuous() -> None:
    """The comparison above would catch a dropped argument (the helper does not hide it)."""
    built = random_program_ast(3)
    layer = built.layers[0]
    tampered = replace(layer, channels=layer.channels[:-1])
    assert printer_normal_form(replace(built, layers=(tampered, *built.layers[1:]))) != (
        matloom.parse(random_program(3))
    )


# ---------------------------------------------------------------------------- generator contract
def test_generator_is_deterministic_and_seed_sensitive() -> None:
    assert random_program(42) == random_program(42)
    assert len({random_program(s) for s in range(20)}) == 20


def test_generated_programs_are_warning_free_in_practice() -> None:
    warned = [s for s in range(60) if matloom.check(random_program(s))]
    assert len(warned) <= 1, warned


def test_counts_and_config_are_honoured() -> None:
    cfg = RandomConfig(random_view=False, opaque_base=True, max_octaves=2, max_path_segments=1)
    for seed in range(30):
        program = random_program_ast(seed, layers=2, defines=1, config=cfg)
        assert len(program.layers) == 2 and [d.name for d in program.defines] == ["def1"]
        assert program.view == A.ViewDecl(0.0, 0.0, 1.0, 1.0)
        assert program.layers[0].alpha == A.Num(1)
        for _, expr in A.program_expressions(program):
            for node in A.walk(expr):
                if isinstance(node, A.Call) and node.func == "fBm" and node.arg("octaves"):
                    assert 1 <= static_number(node.arg("octaves")) <= 2
                if isinstance(node, A.Call) and node.func == "Path":
                    assert len(node.extra) == 1


def test_default_view_is_random_and_always_written() -> None:
    views = {random_program(s).splitlines()[0] for s in range(10)}
    assert all(v.startswith("View(") for v in views) and len(views) == 10


def test_leaf_bias_one_gives_single_terminals() -> None:
    cfg = RandomConfig(leaf_bias=1.0, min_defs=0, max_defs=0)
    program = random_program_ast(5, config=cfg)
    for _, expr in A.program_expressions(program):
        calls = [n for n in A.walk(expr) if isinstance(n, A.Call | A.BinOp)]
        producers = [
            c
            for c in calls
            if isinstance(c, A.Call) and any(p.kind is Kind.EXPR for p in FUNCTIONS[c.func].params)
        ]
        assert producers == []


def test_every_function_enum_and_channel_is_generated() -> None:
    seen_funcs: set[str] = set()
    seen_enums: set[tuple[str, str, str]] = set()
    seen_channels: set[str] = set()
    operators = {s.operator: s.name for s in FUNCTIONS.values() if s.operator}
    for seed in range(60):
        program = random_program_ast(seed)
        for layer in program.layers:
            seen_channels |= {c.name for c in layer.channels}
        for _, expr in A.program_expressions(program):
            for node in A.walk(expr):
                if isinstance(node, A.BinOp):
                    seen_funcs.add(operators[node.op])
                if isinstance(node, A.Call):
                    seen_funcs.add(node.func)
                    seen_funcs |= {e.func for e in node.extra if isinstance(e, A.Call)}
                    for arg in node.args:
                        if isinstance(arg.value, A.Str):
                            seen_enums.add((node.func, arg.param, arg.value.value))
    assert seen_funcs == set(FUNCTIONS)
    all_enums = {
        (s.name, p.name, c) for s in FUNCTIONS.values() for p in s.params for c in p.choices
    }
    assert seen_enums == all_enums
    assert seen_channels == set(CHANNELS) - {"alpha"}


def test_a_new_registry_function_is_generated_automatically(monkeypatch) -> None:
    spec = FunctionSpec(
        "Wobble",
        "math",
        "test-only function",
        "Wobble(X(), 2)",
        (
            ParamSpec("expr", Kind.EXPR, "input"),
            ParamSpec("amount", Kind.FLOAT, "strength", 1.0, lo=0.0, lo_open=True),
        ),
    )
    monkeypatch.setitem(FUNCTIONS, "Wobble", spec)
    texts = [random_program(s) for s in range(25)]
    assert any("Wobble(" in t for t in texts)
    for text in texts:
        assert [d for d in matloom.check(text) if d.is_error] == []


@pytest.mark.parametrize("bad", [{"layers": 0}, {"defines": -1}])
def test_invalid_counts_are_refused(bad: dict[str, int]) -> None:
    with pytest.raises(ValueError):
        random_program(0, **bad)


def test_invalid_config_is_refused() -> None:
    with pytest.raises(ValueError, match="min_layers"):
        RandomConfig(min_layers=0)


def test_inliner_keeps_defines_that_field_parameters_need_per_sample() -> None:
    """Written inline, X() in a field parameter means its value at the origin; the Define that
    makes it per-sample stays, so the inlined program evaluates to the same maps."""
    import numpy as np

    text = (
        "Define(swirl, X() * 40)\nDefine(unused_inline, Y() * 2)\n"
        "Material(Layer(1).height(Rotate(Bricks(), swirl) + Translate(X(), unused_inline + "
        "fBm(seed=1), 0)))"
    )
    inlined = inline_defines(matloom.parse(text))
    assert [d.name for d in inlined.defines] == ["swirl"]
    out = format_program(inlined)
    assert "Translate(X(), ((Y() * 2) + fBm(seed=1)), 0)" in out
    a = matloom.evaluate(text, 32, 32, backend="numpy").height
    b = matloom.evaluate(out, 32, 32, backend="numpy").height
    assert np.array_equal(a, b)


def test_pinned_define_stays_a_reference_inside_other_defines() -> None:
    """A Define kept for a field parameter stays a reference in other Defines' bodies too:
    written out inside ``Scale``'s sy there, its Y() would mean the origin value (found by the
    generated-program property test, seed 5332, and in 16 library entries)."""
    import numpy as np

    text = (
        "Define(row, Y())\nDefine(wavy, Scale(Bricks(), 1, row))\n"
        "Material(Layer(1).height(wavy + Translate(X(), row, 0)))"
    )
    inlined = inline_defines(matloom.parse(text))
    assert [d.name for d in inlined.defines] == ["row"]
    out = format_program(inlined)
    assert "Scale(Bricks(), 1, row)" in out
    a = matloom.evaluate(text, 32, 32, backend="numpy").height
    b = matloom.evaluate(out, 32, 32, backend="numpy").height
    assert np.array_equal(a, b)
    generated = matloom.parse(random_program(5332))
    inlined = inline_defines(generated)
    assert matloom.parse(format_program(inlined)) == inlined
