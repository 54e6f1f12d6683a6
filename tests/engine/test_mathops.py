"""Math nodes and Threshold/clamp: parity with the reference's fixtures, plus rule checks.

Fixture expressions (tests/data/parity/expressions.json) are transcribed by hand into kernel
calls. X()/Y() are the sample coordinates (float64, or float32 for ``points_f32_axes``) and
every numeric literal is a float64 Constant grid, as in the reference (so mixed arithmetic
promotes to float64 exactly as it does there). Whole-grid checks rebuild a few fixture programs'
``height``/``roughness`` maps from these kernels and compare with the reference's arrays.
"""

from __future__ import annotations

import json
import math
import warnings
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest

from matloom.engine.kernels import mathops as m
from matloom.engine.kernels.threshold import clamp, threshold

PARITY = Path(__file__).resolve().parents[1] / "data" / "parity"
EXPRESSIONS = {e["expr"]: e for e in json.loads((PARITY / "expressions.json").read_text())}
F32 = np.float32
Kernel = Callable[[np.ndarray, np.ndarray], np.ndarray]


def C(value: float) -> np.ndarray:
    """A Constant grid (float64), as the reference builds literals."""
    return np.full((1, 1), value, dtype=np.float64)


def X(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """The X() node: a copy of the x coordinates in their own dtype."""
    return np.array(np.broadcast_to(x, np.broadcast_shapes(x.shape, y.shape)))


def Y(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """The Y() node."""
    return np.array(np.broadcast_to(y, np.broadcast_shapes(x.shape, y.shape)))


def _threshold(**kw: float) -> Callable[[np.ndarray], np.ndarray]:
    """Threshold with the registry defaults (to-values None, transition_width 0)."""
    params = dict(below_at=None, below_to=None, above_at=None, above_to=None, transition_width=0)
    params.update(kw)
    return lambda v: threshold(v, **params)


MATH_EXPRESSIONS: dict[str, Kernel] = {
    "X()": lambda x, y: X(x, y),
    "(X() - Y()) / 4": lambda x, y: m.safe_div(m.sub(X(x, y), Y(x, y)), C(4)),
    "X() / Y()": lambda x, y: m.safe_div(X(x, y), Y(x, y)),
    "1 / (X() - 0.5)": lambda x, y: m.safe_div(C(1), m.sub(X(x, y), C(0.5))),
    "2 ** 3 ** 2 - X()": lambda x, y: m.sub(m.pow_(C(2), m.pow_(C(3), C(2))), X(x, y)),
    "-2 ** 2 + X()": lambda x, y: m.add(m.mul(C(-1.0), m.pow_(C(2), C(2))), X(x, y)),
    "(X() - 0.5) ** 0.5": lambda x, y: m.pow_(m.sub(X(x, y), C(0.5)), C(0.5)),
    "pi * X() + e * Y()": lambda x, y: m.add(m.mul(C(math.pi), X(x, y)), m.mul(C(math.e), Y(x, y))),
    "Abs(X() - 0.6)": lambda x, y: m.abs_(m.sub(X(x, y), C(0.6))),
    "Sqrt(X() - 0.5)": lambda x, y: m.sqrt(m.sub(X(x, y), C(0.5))),
    "Floor(X() * 4 - 1.5)": lambda x, y: m.floor(m.sub(m.mul(X(x, y), C(4)), C(1.5))),
    "Sin(X() * pi) + Cos(Y() * pi)": lambda x, y: m.add(
        m.sin(m.mul(X(x, y), C(math.pi))), m.cos(m.mul(Y(x, y), C(math.pi)))
    ),
    "Log(X())": lambda x, y: m.log(X(x, y)),
    "Log(Y() + 1, 10)": lambda x, y: m.log(m.add(Y(x, y), C(1)), 10),
    "Log(X() + 2, 2)": lambda x, y: m.log(m.add(X(x, y), C(2)), 2),
    "Min(X(), Y())": lambda x, y: m.minimum(X(x, y), Y(x, y)),
    "Max(X() * 2, Y())": lambda x, y: m.maximum(m.mul(X(x, y), C(2)), Y(x, y)),
    "Add(X(), Mul(Y(), 3))": lambda x, y: m.add(X(x, y), m.mul(Y(x, y), C(3))),
    "Sub(Div(X(), 2), Pow(Y(), 2))": lambda x, y: m.sub(
        m.safe_div(X(x, y), C(2)), m.pow_(Y(x, y), C(2))
    ),
    # A scalar parameter given as an expression is evaluated at (0, 0): dx = 0 + 0.25.
    "Translate(X(), X() + 0.25, 0)": lambda x, y: X(x - 0.25, y - 0.0),
    # Translate samples at (x - dx, y - dy), Rotate at (c x + s y, -s x + c y), Scale at (x/sx,
    # y/sy); coordinates stay in their dtype (Python-float parameters).
    "Translate(Rotate(Scale(X() * 10, 2, 0.5), 90), 0.3, 0.1)": lambda x, y: _rotated_scaled(
        x - 0.3, y - 0.1
    ),
}

THRESHOLD_EXPRESSIONS: dict[str, Kernel] = {
    "Threshold(X(), below_at=0.3)": lambda x, y: _threshold(below_at=0.3)(X(x, y)),
    "Threshold(Y(), above_at=0.6, above_to=0)": lambda x, y: _threshold(above_at=0.6, above_to=0)(
        Y(x, y)
    ),
    "Threshold(X() + Y(), below_at=0.5, below_to=-1, above_at=1.2, above_to=2)": lambda x, y: (
        _threshold(below_at=0.5, below_to=-1, above_at=1.2, above_to=2)(m.add(X(x, y), Y(x, y)))
    ),
    "Threshold(X(), below_at=0.3, below_to=0, above_at=0.7, above_to=1, transition_width=0.2)": (
        lambda x, y: _threshold(
            below_at=0.3, below_to=0, above_at=0.7, above_to=1, transition_width=0.2
        )(X(x, y))
    ),
    "Threshold(Y(), above_at=0.6, above_to=1, transition_width=0.3)": lambda x, y: _threshold(
        above_at=0.6, above_to=1, transition_width=0.3
    )(Y(x, y)),
}


def _rotated_scaled(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Rotate(Scale(X() * 10, 2, 0.5), 90) sampled at (x, y)."""
    c, s = math.cos(math.radians(90)), math.sin(math.radians(90))
    xr, yr = c * x + s * y, -s * x + c * y
    return m.mul(X(xr / 2, yr / 0.5), C(10))


def _decode(value: float | str) -> float:
    """Fixture number: floats, or the strings "nan"/"inf"/"-inf"."""
    return float(value)


def expected_samples(entry: dict, dtype: type) -> list[tuple[float, float, float]]:
    """(x, y, value) samples for float64 axes, or float32 axes (falls back to ``points``)."""
    key = "points_f32_axes" if dtype is F32 and "points_f32_axes" in entry else "points"
    return [(px, py, _decode(v)) for px, py, v in entry[key]]


def evaluate_at(kernel: Kernel, px: float, py: float, dtype: type) -> float:
    """Evaluate a kernel on a 1x1 grid whose axes have ``dtype``."""
    x = np.full((1, 1), px, dtype=dtype)
    y = np.full((1, 1), py, dtype=dtype)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no RuntimeWarning may leak out of the kernels
        result = np.asarray(kernel(x, y))
    assert result.shape == (1, 1)
    return float(result[0, 0])


def assert_same(got: float, want: float, context: str) -> None:
    """Equal to 1e-12 relative; NaN equals NaN, infinities must match exactly."""
    if math.isnan(want) or math.isinf(want):
        assert (math.isnan(got) and math.isnan(want)) or got == want, context
    else:
        assert got == pytest.approx(want, rel=1e-12, abs=0.0), context


@pytest.mark.parametrize("dtype", [np.float64, F32], ids=["f64_axes", "f32_axes"])
@pytest.mark.parametrize("expr", sorted({**MATH_EXPRESSIONS, **THRESHOLD_EXPRESSIONS}))
def test_fixture_expression(expr: str, dtype: type) -> None:
    kernel = {**MATH_EXPRESSIONS, **THRESHOLD_EXPRESSIONS}[expr]
    for px, py, want in expected_samples(EXPRESSIONS[expr], dtype):
        assert_same(evaluate_at(kernel, px, py, dtype), want, f"{expr} at ({px}, {py})")


# --- whole-grid checks against fixture programs -------------------------------------------------

GRID_SIZES = [(64, 64), (48, 32)]


def grid_axes(view: tuple[float, float, float, float], width: int, height: int):
    """float32 X (1, W) and Y (H, 1) texel-centre axes, built as the reference does."""
    x1, y1, x2, y2 = view
    x = (np.arange(width, dtype=F32) + 0.5) * F32((x2 - x1) / width) + F32(x1)
    y = (np.arange(height, dtype=F32) + 0.5) * F32((y1 - y2) / height) + F32(y2)
    return x[None, :], y[:, None]


def fixture_maps(name: str, width: int, height: int) -> dict[str, np.ndarray]:
    """The reference's composited float32 maps for a fixture program."""
    with np.load(PARITY / f"{name}_{width}x{height}.npz") as data:
        return {key: data[key] for key in data.files}


def channel(values: np.ndarray, shape: tuple[int, int]) -> np.ndarray:
    """An authored channel as the reference stores it: evaluated, then cast to float32."""
    return np.broadcast_to(np.asarray(values), shape).astype(F32)


def composite_height(layers: list[tuple[np.ndarray, np.ndarray]], shape) -> np.ndarray:
    """Max layer height over layers with alpha > 0 and a finite height (0 where none)."""
    best = np.full(shape, -np.inf, dtype=F32)
    for alpha, height in layers:
        a = clamp(channel(alpha, shape), 0.0, 1.0)
        h = channel(height, shape)
        best = np.where((a > 0) & np.isfinite(h), np.maximum(best, h), best)
    return np.where(np.isneginf(best), F32(0), best) + F32(0)


def _div_zero_stripes(x: np.ndarray, y: np.ndarray) -> dict[str, np.ndarray]:
    stripe = m.sub(m.ceil(m.mul(X(x, y), C(3))), C(3))
    ratio = m.safe_div(C(1), stripe)
    height = m.add(m.mul(m.safe_div(C(0), stripe), C(0.01)), m.mul(ratio, C(0.005)))
    return {"height": height, "roughness": m.abs_(ratio)}


def _log_scales(x: np.ndarray, y: np.ndarray) -> dict[str, np.ndarray]:
    ly = m.log(m.add(Y(x, y), C(1)), 2)
    roughness = m.safe_div(m.log(m.mul(C(math.e), m.add(C(1), X(x, y)))), C(3))
    return {"height": m.mul(ly, C(0.05)), "roughness": roughness}


def _power_unary(x: np.ndarray, y: np.ndarray) -> dict[str, np.ndarray]:
    u = m.add(m.pow_(X(x, y), C(2)), m.mul(C(-1.0), m.pow_(Y(x, y), C(3))))
    roughness = m.pow_(m.sub(X(x, y), C(0.5)), C(0.5))
    return {"height": m.mul(C(-1.0), m.mul(u, C(0.01))), "roughness": roughness}


SINGLE_LAYER_PROGRAMS = {
    "div_zero_stripes": ((0, 0, 2, 2), _div_zero_stripes),
    "log_scales": ((0.01, 0.01, 4, 4), _log_scales),
    "power_unary": ((0, 0, 1, 1), _power_unary),
}


@pytest.mark.parametrize("size", GRID_SIZES, ids=lambda s: f"{s[0]}x{s[1]}")
@pytest.mark.parametrize("name", sorted(SINGLE_LAYER_PROGRAMS))
def test_single_layer_program_grid(name: str, size: tuple[int, int]) -> None:
    """One opaque layer: height is the float32 channel (0 where not finite), roughness is the
    clamped float32 channel (NaN kept)."""
    view, build = SINGLE_LAYER_PROGRAMS[name]
    x, y = grid_axes(view, *size)
    shape = (size[1], size[0])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        maps = build(x, y)
        want = fixture_maps(name, *size)
        got_height = composite_height([(C(1), maps["height"])], shape)
        got_roughness = clamp(channel(maps["roughness"], shape), 0.0, 1.0).astype(F32)
    np.testing.assert_array_equal(got_height, want["height"])
    np.testing.assert_array_equal(got_roughness, want["roughness"])


@pytest.mark.parametrize("size", GRID_SIZES, ids=lambda s: f"{s[0]}x{s[1]}")
def test_nan_inf_fields_height(size: tuple[int, int]) -> None:
    """Sqrt/Floor/Abs/Log/Div with NaN and inf: layers whose height is not finite drop out."""
    x, y = grid_axes((-1, -1, 1, 1), *size)
    shape = (size[1], size[0])
    dome = m.sqrt(m.sub(m.sub(C(0.36), m.pow_(X(x, y), C(2))), m.pow_(Y(x, y), C(2))))
    band = m.safe_div(m.floor(m.mul(m.abs_(Y(x, y)), C(2))), C(2))
    layers = [
        (C(1), C(-0.05)),
        (C(0.8), m.mul(dome, C(0.2))),
        (C(0.5), m.mul(m.mul(C(-1.0), m.log(band)), C(0.01))),
    ]
    want = fixture_maps("nan_inf_fields", *size)["height"]
    np.testing.assert_array_equal(composite_height(layers, shape), want)


# --- rule checks (spec §2.2, §2.7) --------------------------------------------------------------


def test_safe_div_zero_divisor_gives_zero_and_is_counted() -> None:
    a = np.array([1.0, 0.0, -2.0, np.inf, np.nan, 3.0])
    b = np.array([0.0, 0.0, -0.0, np.inf, 0.0, 2.0])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        got = m.safe_div(a, b)
    np.testing.assert_array_equal(got, [0.0, 0.0, 0.0, np.nan, 0.0, 1.5])
    assert m.count_zero(b) == 4


def test_math_keeps_float32_when_both_inputs_are_float32() -> None:
    """float32 coordinate grids stay float32 (the reference promotes only via float64 grids)."""
    a, b = np.array([[0.1]], dtype=F32), np.array([[0.3]], dtype=F32)
    assert m.safe_div(a, b).dtype == F32
    assert m.add(a, b).dtype == F32
    assert m.log(a, 3.0).dtype == F32
    assert m.safe_div(a, C(3)).dtype == np.float64


def test_log_special_values_and_bases() -> None:
    v = np.array([0.0, -1.0, 8.0, 1000.0, math.e**2, 81.0])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        ln, l2, l10, l3 = m.log(v), m.log(v, 2), m.log(v, 10), m.log(v, 3)
    assert ln[0] == -np.inf and math.isnan(ln[1]) and ln[4] == 2.0
    assert l2[2] == 3.0 and l10[3] == 3.0
    assert l3[5] == pytest.approx(4.0, rel=1e-15)


def test_pow_sqrt_domain_errors_give_nan_quietly() -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert math.isnan(m.pow_(np.array(-8.0), np.array(1 / 3)))
        assert m.pow_(np.array(-2.0), np.array(3.0)) == -8.0
        assert m.pow_(np.array(0.0), np.array(-1.0)) == np.inf
        assert math.isnan(m.sqrt(np.array(-1e-300)))
        assert math.isnan(m.sub(np.array(np.inf), np.array(np.inf)))


THRESHOLD_VARIANTS = [
    dict(below_at=0.3),
    dict(above_at=0.6, above_to=0.0),
    dict(below_at=0.5, below_to=-1.0, above_at=1.2, above_to=2.0),
    dict(below_at=0.3, below_to=0.0, above_at=0.7, above_to=1.0, transition_width=0.2),
    dict(above_at=0.6, above_to=1.0, transition_width=0.3),
]


@pytest.mark.parametrize("dtype", [np.float64, F32])
@pytest.mark.parametrize("params", THRESHOLD_VARIANTS, ids=range(len(THRESHOLD_VARIANTS)))
def test_threshold_passes_nan_through(params: dict, dtype: type) -> None:
    v = np.array([[np.nan, 0.0, np.nan]], dtype=dtype)
    got = _threshold(**params)(v)
    assert got.dtype == np.float64 and got.shape == v.shape
    assert np.isnan(got[0, 0]) and np.isnan(got[0, 2]) and not np.isnan(got[0, 1])


def test_clamp_keeps_nan_and_clamps_infinities() -> None:
    v = np.array([np.nan, -np.inf, -0.5, 0.25, 1.5, np.inf], dtype=F32)
    got = clamp(v, 0.0, 1.0)
    np.testing.assert_array_equal(got, [np.nan, 0.0, 0.0, 0.25, 1.0, 1.0])
    np.testing.assert_array_equal(clamp(v, 1.0, None)[2:], [1.0, 1.0, 1.5, np.inf])


def test_threshold_rules_from_the_spec() -> None:
    """Inclusive cut-offs, below wins over above, ramps lie inside the pass-through band."""
    binarise = _threshold(below_at=0.5, below_to=0.0, above_at=0.5, above_to=1.0)
    np.testing.assert_array_equal(binarise(np.array([0.4, 0.5, 0.6])), [0.0, 0.0, 1.0])
    ramp_above = _threshold(above_at=0.7, above_to=1.0, transition_width=0.2)
    got = ramp_above(np.array([0.5, 0.6, 0.7, 0.9]))
    np.testing.assert_allclose(got, [0.5, 0.5 * 0.6 + 0.5 * 1.0, 1.0, 1.0], rtol=1e-15)
    ramp_below = _threshold(below_at=0.3, below_to=0.0, transition_width=0.2)
    got = ramp_below(np.array([0.3, 0.4, 0.5, 0.8]))
    np.testing.assert_allclose(got, [0.0, 0.5 * 0.0 + 0.5 * 0.4, 0.5, 0.8], rtol=1e-15)
