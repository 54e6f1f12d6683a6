"""The registry is the single source of truth: every entry must be complete and round-trip."""

import pytest

import matloom
from matloom.lang import ast as A
from matloom.lang.printer import format_expr
from matloom.vocab import CHANNELS, FUNCTIONS, Kind, PrintStyle, Returns


def _program_for(example: str, spec_returns: Returns) -> str:
    expr = example
    if example.startswith(("Rect(", "Ellipse(", "Path(")):
        expr = f"Fill({example})"
    return f"Material(\n  Layer(1)\n    .basecolor(128, 128, 128)\n    .height(({expr}) * 0.01)\n)"


@pytest.mark.parametrize("name", sorted(FUNCTIONS))
def test_function_entry_is_complete(name):
    spec = FUNCTIONS[name]
    assert spec.doc and len(spec.doc) > 10, f"{name} lacks a doc line"
    assert spec.example, f"{name} lacks an example"
    assert name in spec.example, f"{name}'s example does not use it"
    assert spec.family in {
        "coord",
        "math",
        "noise",
        "pattern",
        "mask",
        "transform",
        "shape",
        "segment",
    }
    for p in spec.params:
        assert p.doc, f"{name}.{p.name} lacks a doc"
        if p.kind in (Kind.FLOAT, Kind.INT) and not p.is_seed:
            assert p.search is not None, f"{name}.{p.name} lacks a search range"
            lo, hi = p.search
            assert lo < hi
        if p.kind is Kind.ENUM:
            assert p.choices and p.default in p.choices
    if spec.print_style is PrintStyle.OPERATOR:
        assert spec.operator in {"+", "-", "*", "/", "**"}


@pytest.mark.parametrize("name", sorted(FUNCTIONS))
def test_function_example_parses_prints_and_reparses(name):
    spec = FUNCTIONS[name]
    src = _program_for(spec.example, spec.returns)
    diags = [d for d in matloom.check(src) if d.is_error]
    assert not diags, "\n".join(d.format() for d in diags)
    prog = matloom.parse(src)
    text = matloom.format(prog)
    assert matloom.format(matloom.parse(text)) == text
    used = {
        n.func for _, e in A.program_expressions(prog) for n in A.walk(e) if isinstance(n, A.Call)
    }
    if spec.print_style is not PrintStyle.OPERATOR:
        assert name in used or name in text


@pytest.mark.parametrize("name", sorted(CHANNELS))
def test_channel_entry_is_complete(name):
    ch = CHANNELS[name]
    assert ch.doc and ch.example.startswith(f".{name}(")
    assert ch.arity == len(ch.defaults) >= 1
    assert ch.units
    src = f"Material(\n  Layer(1)\n    .basecolor(10, 10, 10)\n    {ch.example}\n)"
    assert not [d for d in matloom.check(src) if d.is_error]


def test_channel_order_matches_reference():
    """The language-1 channels keep the reference's order; newer ones sit among them."""
    assert [name for name, ch in CHANNELS.items() if ch.since == 1] == [
        "alpha",
        "basecolor",
        "metallic",
        "roughness",
        "sheen",
        "coat",
        "transmission",
        "ior",
        "subsurface",
        "anisotropy",
        "emissive",
        "height",
    ]
    assert [name for name, ch in CHANNELS.items() if ch.since == 2] == ["anisotropy_angle"]
    assert list(CHANNELS).index("anisotropy_angle") == list(CHANNELS).index("anisotropy") + 1


def test_printer_has_a_path_for_every_function():
    for name, spec in FUNCTIONS.items():
        args = []
        for p in spec.params:
            if p.kind is Kind.EXPR:
                args.append(A.Arg(p.name, A.Call("X")))
            elif p.kind is Kind.SHAPE:
                args.append(
                    A.Arg(
                        p.name,
                        A.Call(
                            "Ellipse", tuple(A.Arg(q, A.Num(1)) for q in ("cx", "cy", "rx", "ry"))
                        ),
                    )
                )
            elif p.required:
                args.append(A.Arg(p.name, A.Num(1)))
        extra = (
            (A.Call("LineTo", (A.Arg("x", A.Num(1)), A.Arg("y", A.Num(1)))),)
            if spec.variadic
            else ()
        )
        text = format_expr(A.Call(name, tuple(args), extra))
        assert text, name
