"""Registry entries of the math functions added in language 2 (angles, wrap-around maths,
interpolation, per-cell random values). They join :data:`matloom.vocab.functions.FUNCTIONS`.

Every operand is a field (``Kind.EXPR``), Clamp's bounds and Smoothstep's edges included. Calls
with an optional field operand (Clamp, Hash) print with keywords (``PrintStyle.WRITTEN_KEYWORDS``:
what the author wrote, the seed always), so that an omitted operand stays omitted and Hash's
``seed=N`` is a literal that seed variants and sweeps rewrite.
"""

from __future__ import annotations

from typing import Any

from matloom.vocab.spec import REQUIRED, FunctionSpec, Kind, ParamSpec, PrintStyle

_V2 = 2


def _field(
    name: str, doc: str, default: Any = REQUIRED, cycle: float | str | None = None
) -> ParamSpec:
    return ParamSpec(name, Kind.EXPR, doc, default, cycle=cycle)


def _seed() -> ParamSpec:
    return ParamSpec(
        "seed",
        Kind.INT,
        "seed of the random values (integer >= 0); omitted seeds are made explicit by "
        "canonicalisation",
        default=None,
        nullable=True,
        lo=0,
        is_seed=True,
    )


def math_v2_specs() -> list[FunctionSpec]:
    """The language-2 math functions (each with ``since=2``)."""
    return [
        FunctionSpec(
            "Atan2",
            "math",
            "angle of the point (x, y) seen from the origin, in radians in (-pi, pi]: "
            "0 along +x, pi/2 along +y, pi along -x (Atan2(0, -1) = pi), -pi/2 along -y; "
            "Atan2(0, 0) = 0; NaN if y or x is NaN",
            "Atan2(Y() - 0.5, X() - 0.5)",
            (_field("y", "vertical component"), _field("x", "horizontal component")),
            since=_V2,
        ),
        FunctionSpec(
            "Fract",
            "math",
            "fractional part x - Floor(x), in [0, 1) also for negative x (Fract(-0.25) = "
            "0.75); a sawtooth that repeats every unit; NaN for infinite x",
            "Fract(X() * 4)",
            (_field("x", "input field", cycle=1.0),),
            since=_V2,
        ),
        FunctionSpec(
            "Mod",
            "math",
            "floored remainder x - m * Floor(x / m): repeats every |m| and has the sign of m "
            "(Mod(-1, 3) = 2, Mod(1, -3) = -2); 0 where m is exactly 0, like `/`; NaN where x or "
            "m is infinite",
            "Mod(X() * 5, 2)",
            (_field("x", "dividend", cycle="m"), _field("m", "divisor: the period")),
            since=_V2,
        ),
        FunctionSpec(
            "Clamp",
            "math",
            "x limited to [lo, hi], i.e. Min(Max(x, lo), hi); lo and hi are fields like x "
            "(where lo > hi the result is hi); NaN stays NaN",
            "Clamp(X() * 2 - 0.5, 0, 1)",
            (
                _field("x", "input field"),
                _field("lo", "lower bound (a field)", 0.0),
                _field("hi", "upper bound (a field)", 1.0),
            ),
            print_style=PrintStyle.WRITTEN_KEYWORDS,
            since=_V2,
        ),
        FunctionSpec(
            "Smoothstep",
            "math",
            "smooth 0-to-1 ramp between two edges, as GLSL: t = Clamp((x - edge0) / (edge1 - "
            "edge0), 0, 1), then t * t * (3 - 2 * t); 0 at or below edge0, 1 at or above edge1 "
            "(a falling ramp when edge0 > edge1); 0 where edge0 == edge1 (safe division)",
            "Smoothstep(0.3, 0.7, X())",
            (
                _field("edge0", "where the ramp starts (result 0)"),
                _field("edge1", "where the ramp ends (result 1)"),
                _field("x", "input field"),
            ),
            since=_V2,
        ),
        FunctionSpec(
            "Mix",
            "math",
            "linear interpolation a + (b - a) * t: a where t = 0, b where t = 1; t is not "
            "clamped (it extrapolates outside [0, 1]); blend two fields by a mask t",
            "Mix(0.2, 0.8, X())",
            (
                _field("a", "value at t = 0"),
                _field("b", "value at t = 1"),
                _field("t", "blend weight"),
            ),
            since=_V2,
        ),
        FunctionSpec(
            "Exp",
            "math",
            "exponential e ** x; inf above about 709.78, 0 below about -745.13",
            "Exp(-4 * X())",
            (_field("x", "exponent"),),
            since=_V2,
        ),
        FunctionSpec(
            "Hash",
            "noise",
            "a random value in [0, 1) for each unit cell (Floor(x), Floor(y)): constant inside a "
            "cell, independent between cells and between seeds, depending only on the cell and "
            "the seed; scale the operands to size the cells (Hash(X() * 8, Y() * 8) gives 8 x 8 "
            "cells per unit); NaN where x or y is NaN, infinite or beyond +-9.2e18",
            "Hash(X() * 8, Y() * 8, seed=5)",
            (
                _field("x", "cell coordinate along x", cycle=1.0),
                _field("y", "cell coordinate along y (0: one row of cells)", 0.0, cycle=1.0),
                _seed(),
            ),
            print_style=PrintStyle.WRITTEN_KEYWORDS,
            since=_V2,
        ),
    ]
