"""Every function of the language, declared once (reference-engine.md §1.6, §2)."""

from __future__ import annotations

import math

from matloom.vocab.functions_math import math_v2_specs
from matloom.vocab.instancing import instancing_specs
from matloom.vocab.patterns import freq_param as _freq
from matloom.vocab.patterns import pattern_specs
from matloom.vocab.quantize import quantize_specs
from matloom.vocab.spec import FunctionSpec, Kind, ParamSpec, PrintStyle, Returns

P = ParamSpec
_COORD_SEARCH = (0.0, 5.0)


def _expr(name: str, doc: str) -> ParamSpec:
    return P(name, Kind.EXPR, doc)


def _seed() -> ParamSpec:
    return P(
        "seed",
        Kind.INT,
        "noise seed (integer >= 0); omitted seeds are made explicit by canonicalisation",
        default=None,
        nullable=True,
        lo=0,
        is_seed=True,
    )


def _to01() -> ParamSpec:
    return P("to_01", Kind.BOOL, "remap the output to [0, 1] instead of the raw range", False)


_UNARY = {
    "Abs": "absolute value |expr|",
    "Sqrt": "square root (NaN for negative input)",
    "Floor": "largest integer <= expr",
    "Ceil": "smallest integer >= expr",
    "Sin": "sine of expr in radians",
    "Cos": "cosine of expr in radians",
}

#: The unary functions that repeat: their argument's cycle (``ParamSpec.cycle``).
_CYCLES = {"Sin": 2 * math.pi, "Cos": 2 * math.pi}

_BINARY = {
    "Add": ("+", ("left", "right"), "sum; prefer the `+` operator"),
    "Sub": ("-", ("minuend", "subtrahend"), "difference; prefer the `-` operator"),
    "Mul": ("*", ("left", "right"), "product; prefer the `*` operator"),
    "Div": ("/", ("dividend", "divisor"), "quotient, 0 where the divisor is exactly 0"),
    "Pow": ("**", ("base", "exponent"), "power (NaN for a negative base with fractional exponent)"),
}


def _math_specs() -> list[FunctionSpec]:
    specs = [
        FunctionSpec("X", "coord", "the x coordinate of the sample point", "X() * 4"),
        FunctionSpec("Y", "coord", "the y coordinate of the sample point (+y is up)", "Y() * 4"),
        FunctionSpec(
            "Constant",
            "coord",
            "a uniform value (a bare number means the same)",
            "Constant(0.5)",
            (P("value", Kind.FLOAT, "the value", 0.0, search=(-10, 10)),),
            print_style=PrintStyle.CONSTANT,
        ),
    ]
    for name, doc in _UNARY.items():
        expr = P("expr", Kind.EXPR, "input field", cycle=_CYCLES.get(name))
        specs.append(FunctionSpec(name, "math", doc, f"{name}(X() - 0.5)", (expr,)))
    specs.append(
        FunctionSpec(
            "Log",
            "math",
            "logarithm in the given base (natural by default); -inf at 0, NaN below 0",
            "Log(X() + 1, 10)",
            (
                _expr("expr", "input field"),
                P(
                    "base",
                    Kind.FLOAT,
                    "logarithm base",
                    math.e,
                    lo=0,
                    lo_open=True,
                    search=(1.1, 10),
                ),
            ),
        )
    )
    for name, doc in (
        ("Min", "element-wise minimum (mask intersection)"),
        ("Max", "element-wise maximum (mask union)"),
    ):
        more = "the smallest" if name == "Min" else "the largest"
        specs.append(
            FunctionSpec(
                name,
                "math",
                f"{doc}; takes two or more fields (language 3: {name}(a, b, c, ...) is "
                f"{more} of them, {name}({name}(a, b), c) ...)",
                f"{name}(X(), Y(), 0.5)",
                (_expr("expr1", "first field"), _expr("expr2", "second field")),
                variadic=P("exprs", Kind.EXPR, "more fields (language 3)", since=3),
            )
        )
    for name, (op, pnames, doc) in _BINARY.items():
        specs.append(
            FunctionSpec(
                name,
                "math",
                doc,
                f"{name}(X(), 2)",
                tuple(_expr(p, f"{p} operand") for p in pnames),
                print_style=PrintStyle.OPERATOR,
                operator=op,
            )
        )
    return specs


def _noise_specs() -> list[FunctionSpec]:
    fbm = FunctionSpec(
        "fBm",
        "noise",
        "fractal Brownian motion of OpenSimplex noise: smooth organic variation in [-1, 1] "
        "(or [0, 1] with to_01=True)",
        "fBm(octaves=4, base_freq=3, to_01=True, seed=7)",
        (
            P(
                "octaves",
                Kind.INT,
                "number of summed noise layers (detail)",
                6,
                lo=1,
                search=(1, 8),
            ),
            P(
                "lacunarity",
                Kind.FLOAT,
                "frequency multiplier per octave",
                2.0,
                lo=0,
                lo_open=True,
                search=(1.5, 3.0),
            ),
            P(
                "gain",
                Kind.FLOAT,
                "amplitude multiplier per octave (roughness of the noise)",
                0.5,
                lo=0,
                lo_open=True,
                search=(0.2, 0.8),
            ),
            _freq("base_freq", "features per coordinate unit (negative mirrors)", 1.0, False),
            _freq("base_freq_x", "per-axis frequency override along x", None, False),
            _freq("base_freq_y", "per-axis frequency override along y", None, False),
            _to01(),
            _seed(),
        ),
        print_style=PrintStyle.WRITTEN_KEYWORDS,
    )
    worley = FunctionSpec(
        "Worley",
        "noise",
        "cellular (Voronoi) noise: one random feature point per unit cell (after scaling x, y "
        "by the frequencies); gives distances to the nearest feature points, a random value "
        "per cell or the distance to the cell borders (see output)",
        'Worley(distance="euclidean", combination="F2-F1", base_freq=6, to_01=True, seed=3)',
        (
            P(
                "distance",
                Kind.ENUM,
                "distance metric",
                "euclidean",
                choices=("euclidean", "manhattan", "chebyshev"),
            ),
            P(
                "combination",
                Kind.ENUM,
                "F1 = nearest, F2 = second nearest; F2-F1 gives cell edges",
                "F1",
                choices=("F1", "F2", "F2-F1", "F2+F1"),
            ),
            _freq("base_freq", "cells per coordinate unit (negative mirrors)", 1.0, False),
            _freq("base_freq_x", "per-axis frequency override along x", None, False),
            _freq("base_freq_y", "per-axis frequency override along y", None, False),
            _to01(),
            _seed(),
            P(
                "output",
                Kind.ENUM,
                '"distance": the combination of feature-point distances in cell units (raw F1 '
                "below sqrt(2) Euclidean, 2 Manhattan, 1 Chebyshev; F2 below sqrt(5), 3 and 2; "
                "to_01=True divides by a fixed norm per metric and combination and clips to "
                "[0, 1], and the values then seldom pass 0.7: 5th to 95th percentile about "
                "0.1-0.5 for F1, 0.25-0.6 for F2, 0.01-0.4 for F2-F1, 0.2-0.6 for F2+F1, "
                'so threshold inside those bands); "cell_value": a uniform random value in '
                "[0, 1), constant over each "
                "cell (the cell of the nearest feature point under distance) and set by seed; "
                '"edge": the Euclidean distance, in coordinate units, from the sample to the '
                "nearest border of its cell, the cells taken as Euclidean whatever distance is "
                "(0 on a border, below sqrt(2) / min(|freq_x|, |freq_y|)). combination and "
                'to_01 apply to "distance" only',
                "distance",
                choices=("distance", "cell_value", "edge"),
                since=2,
            ),
            P(
                "smoothness",
                Kind.FLOAT,
                "rounded cells (language 3): s > 0 replaces F1 by the smooth minimum F1 - s * "
                "ln(sum over the feature points of exp(-(d - F1) / s)), in cell units: "
                "dimples and pebbles without creases at the cell borders, at most F1 and at "
                "least F1 - 3.2 s (0 near a feature point, after the clamp at 0); F2 is "
                'unchanged, and so are output="cell_value" and "edge"; 0 = the exact F1; '
                "above about 0.25 faint steps can appear where a far feature point enters the "
                "searched 5 x 5 cells",
                0.0,
                lo=0,
                hi=0.5,
                search=(0.0, 0.3),
                since=3,
            ),
        ),
        print_style=PrintStyle.WRITTEN_KEYWORDS,
    )
    return [fbm, worley]


def _transform_specs() -> list[FunctionSpec]:
    body = _expr("expr", "field to transform (noise included)")
    return [
        FunctionSpec(
            "Translate",
            "transform",
            "move a field by (dx, dy); dx/dy may be fields (domain warping): Translate(f, dx, dy) at p is f(x - dx(p), y - dy(p))",
            "Translate(X(), 0.5, 0)",
            (
                body,
                P("dx", Kind.FLOAT, "offset along x", 0.0, search=(-100, 100), field=True),
                P("dy", Kind.FLOAT, "offset along y", 0.0, search=(-100, 100), field=True),
            ),
        ),
        FunctionSpec(
            "Scale",
            "transform",
            "scale a field about the origin (negative mirrors); sx/sy may be fields, evaluated at each sample: f(x / sx(p), y / sy(p))",
            "Scale(Bricks(), 2, 1)",
            (
                body,
                P(
                    "sx",
                    Kind.FLOAT,
                    "factor along x",
                    1.0,
                    nonzero=True,
                    search=(0.1, 10),
                    field=True,
                ),
                P(
                    "sy",
                    Kind.FLOAT,
                    "factor along y",
                    1.0,
                    nonzero=True,
                    search=(0.1, 10),
                    field=True,
                ),
            ),
        ),
        FunctionSpec(
            "Rotate",
            "transform",
            "rotate a field counter-clockwise about the origin; degrees may be a field, evaluated at each sample (a swirl)",
            "Rotate(Bricks(), 45)",
            (
                body,
                P(
                    "degrees",
                    Kind.FLOAT,
                    "angle in degrees",
                    0.0,
                    search=(-360, 360),
                    field=True,
                    cycle=360.0,
                ),
            ),
        ),
    ]


def _shape_specs() -> list[FunctionSpec]:
    def f_(name: str, doc: str, **kw: object) -> ParamSpec:
        kw.setdefault("search", _COORD_SEARCH)
        return P(name, Kind.FLOAT, doc, **kw)  # type: ignore[arg-type]

    f = Kind.FLOAT
    pos = {"lo": 0.0, "lo_open": True}
    seg_x = f_("x", "end point x")
    seg_y = f_("y", "end point y")
    return [
        FunctionSpec(
            "Rect",
            "shape",
            "rectangle with optional rounded corners, (x, y) = bottom-left",
            "Fill(Rect(0.1, 0.1, 0.8, 0.3, 0.05))",
            (
                f_("x", "left edge"),
                f_("y", "bottom edge"),
                P("width", f, "width", search=(0.01, 5), **pos),
                P("height", f, "height", search=(0.01, 5), **pos),
                P(
                    "radius",
                    f,
                    "corner radius (clamped to half the smaller side)",
                    0.0,
                    lo=0,
                    search=(0.0, 1.0),
                ),
            ),
            returns=Returns.SHAPE,
        ),
        FunctionSpec(
            "Ellipse",
            "shape",
            "ellipse centred at (cx, cy) with radii rx, ry",
            "Fill(Ellipse(0.5, 0.5, 0.3, 0.2))",
            (
                f_("cx", "centre x"),
                f_("cy", "centre y"),
                P("rx", f, "radius along x", search=(0.01, 5), **pos),
                P("ry", f, "radius along y", search=(0.01, 5), **pos),
            ),
            returns=Returns.SHAPE,
        ),
        FunctionSpec(
            "Path",
            "shape",
            "polyline/curve starting at (start_x, start_y); Fill closes it",
            "Fill(Path(0, 0, LineTo(1, 0), LineTo(0.5, 1)))",
            (f_("start_x", "start point x"), f_("start_y", "start point y")),
            returns=Returns.SHAPE,
            variadic=P("segments", Kind.SEGMENT, "LineTo/CubicTo segments"),
            min_variadic=1,
        ),
        FunctionSpec(
            "LineTo",
            "segment",
            "straight segment to (x, y); only inside Path",
            "Path(0, 0, LineTo(1, 1))",
            (seg_x, seg_y),
            returns=Returns.SEGMENT,
        ),
        FunctionSpec(
            "CubicTo",
            "segment",
            "cubic Bezier segment with controls c1, c2 to (x, y); only inside Path",
            "Path(0, 0, CubicTo(0.3, 1, 0.7, 1, 1, 0))",
            (
                f_("c1x", "first control x"),
                f_("c1y", "first control y"),
                f_("c2x", "second control x"),
                f_("c2y", "second control y"),
                seg_x,
                seg_y,
            ),
            returns=Returns.SEGMENT,
        ),
        FunctionSpec(
            "Fill",
            "shape",
            "coverage of a shape's interior: 1 inside, 0 outside",
            "Fill(Ellipse(0.5, 0.5, 0.3, 0.3), feather=0.01)",
            (
                P("shape", Kind.SHAPE, "an inline Rect, Ellipse or Path"),
                P(
                    "mode",
                    Kind.ENUM,
                    "fill rule for self-intersecting paths",
                    "NonZero",
                    choices=("NonZero", "EvenOdd"),
                ),
                P("feather", f, "edge softening width", 0.0, lo=0, search=(0.0, 0.2)),
            ),
            print_style=PrintStyle.SHAPE_OP,
        ),
        FunctionSpec(
            "Stroke",
            "shape",
            "coverage of a band of the given width along a shape's outline",
            "Stroke(Path(0, 0.5, LineTo(1, 0.5)), 0.02)",
            (
                P("shape", Kind.SHAPE, "an inline Rect, Ellipse or Path"),
                P("width", f, "stroke width", search=(0.001, 10), **pos),
                P("feather", f, "edge softening width", 0.0, lo=0, search=(0.0, 0.2)),
            ),
            print_style=PrintStyle.SHAPE_OP,
        ),
    ]


FUNCTIONS: dict[str, FunctionSpec] = {
    spec.name: spec
    for spec in (
        *_math_specs(),
        *_noise_specs(),
        *pattern_specs(),
        *_transform_specs(),
        *_shape_specs(),
        *math_v2_specs(),
        *instancing_specs(),
        *quantize_specs(),
    )
}
"""Name -> spec for every callable of the language."""

CONSTANTS: dict[str, float] = {"pi": math.pi, "e": math.e}
"""Named numeric constants."""

LITERALS: dict[str, bool | None] = {
    "True": True,
    "true": True,
    "False": False,
    "false": False,
    "None": None,
    "null": None,
}
"""Literal words accepted where a bool or an omitted value is expected."""
