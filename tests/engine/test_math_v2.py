"""The language-2 math functions (Atan2, Fract, Mod, Clamp, Smoothstep, Mix, Exp) and Hash:
formulas, special values, bit-identity of the numpy and numba backends, properties, constant
folding, check/fmt, seeds and the seed sweep."""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
import pytest

import matloom
from matloom.engine.backends import available_backends, get_backend
from matloom.engine.evaluate import evaluate, prepare
from matloom.engine.grid import sample_axes
from matloom.engine.interpret import EvalStats, Evaluator
from matloom.engine.kernels import hashing, mathops
from matloom.engine.maps import ARRAY_FIELDS, View
from matloom.lang import ast as A
from matloom.lang.seeds import canonicalize_seeds, seed_variants
from matloom.lang.static import static_number
from matloom.ops import OPS

BACKENDS = available_backends()
NUMBA = "numba" in BACKENDS
needs_numba = pytest.mark.skipif(not NUMBA, reason="numba not installed")
VIEW = (-4.0, -3.0, 4.0, 5.0)
W, H = 40, 28


def _axes() -> tuple[np.ndarray, np.ndarray]:
    """The engine's sample axes of VIEW: float32 x (1, W) and y (H, 1)."""
    return sample_axes(View(*VIEW), W, H)


#: Numbers of a program are float64 scalars (numpy promotes float32 axes with them to float64;
#: two float32 operands give float32, as in the engine).
F = np.float64


def _height_program(expr: str) -> str:
    return f"View{VIEW}\nMaterial(Layer(1).height({expr}))"


def _field(expr: str, backend: str = "numpy") -> np.ndarray:
    """The float64 (or float32) value of ``expr`` on the grid, from the dense interpreter."""
    program = prepare(_height_program(expr))
    x, y = sample_axes(View(*VIEW), W, H)
    ev = Evaluator(program, x, y, get_backend(backend))
    return np.broadcast_to(ev.field(program.layers[0].channels[0].args[0]), (H, W))


def _bits(a: np.ndarray) -> np.ndarray:
    """Bit patterns with every NaN made the same (payloads are compared elsewhere)."""
    a = np.asarray(a, dtype=np.float64)
    return np.where(np.isnan(a), np.nan, a).view(np.uint64)


def _same(a: np.ndarray | list[float], b: np.ndarray | list[float]) -> bool:
    a, b = np.asarray(a), np.asarray(b)
    return a.shape == b.shape and bool(np.array_equal(_bits(a), _bits(b)))


# ------------------------------------------------------------------ each function vs its formula
def _fract(v: np.ndarray) -> np.ndarray:
    return v - np.floor(v)


def _mod(x: np.ndarray, m: np.ndarray | float) -> np.ndarray:
    return x - m * np.floor(x / m)


def _smooth(e0: float, e1: float, v: np.ndarray) -> np.ndarray:
    t = np.clip((v - e0) / (e1 - e0), 0.0, 1.0)
    return t * t * (3.0 - 2.0 * t)


# expression -> exact numpy formula on the axes (Atan2, Fract, Mod and Exp compute in float64)
EXACT: dict[str, Callable[[np.ndarray, np.ndarray], np.ndarray]] = {
    "Fract(X() * 3)": lambda x, y: _fract(x * F(3)),
    "Fract(Y() * -2.5)": lambda x, y: _fract(y * F(-2.5)),
    "Fract(X())": lambda x, y: _fract(x.astype(F)),
    "Mod(X() * 5, 2)": lambda x, y: _mod(x * F(5), F(2)),
    "Mod(X() * 5, -1.5)": lambda x, y: _mod(x * F(5), F(-1.5)),
    "Mod(X(), Y())": lambda x, y: np.where(y == 0, 0.0, _mod(x.astype(F), y.astype(F))),
    "Clamp(X() * 0.5)": lambda x, y: np.clip(x * F(0.5), F(0), F(1)),
    "Clamp(X(), -1, Y() * 0.5)": lambda x, y: np.minimum(np.maximum(x, F(-1)), y * F(0.5)),
    "Clamp(X(), hi=0.25)": lambda x, y: np.minimum(np.maximum(x, F(0)), F(0.25)),
    "Clamp(X(), Y(), Y() + 1)": lambda x, y: np.minimum(np.maximum(x, y), y + F(1)),
    "Smoothstep(-1, 2, X())": lambda x, y: _smooth(F(-1), F(2), x),
    "Smoothstep(1, -2, Y())": lambda x, y: _smooth(F(1), F(-2), y),
    "Smoothstep(Y(), Y() + 2, X())": lambda x, y: _smooth(y, y + F(2), x),
    "Mix(X(), Y(), 0.25)": lambda x, y: x + (y - x) * F(0.25),  # y - x in float32
    "Mix(2, -1, X() * 0.3)": lambda x, y: F(2) + (F(-1) - F(2)) * (x * F(0.3)),
    "Mix(X(), Y(), X())": lambda x, y: x + (y - x) * x,  # float32 throughout
}
# expression -> numpy's own function (its SIMD code may differ in the last bit)
CLOSE: dict[str, Callable[[np.ndarray, np.ndarray], np.ndarray]] = {
    "Atan2(Y(), X())": lambda x, y: np.arctan2(y.astype(F), x.astype(F)),
    "Atan2(Y() - 0.5, -X())": lambda x, y: np.arctan2(y - F(0.5), F(-1) * x),
    "Exp(X() * 2)": lambda x, y: np.exp(x * F(2)),
    "Exp(-Y() * 10)": lambda x, y: np.exp(F(-1) * y * F(10)),
}


@pytest.mark.parametrize("backend", BACKENDS)
@pytest.mark.parametrize("expr", sorted(EXACT))
def test_function_equals_its_formula(expr: str, backend: str) -> None:
    x, y = _axes()
    with np.errstate(all="ignore"):
        expected = np.broadcast_to(EXACT[expr](x, y), (H, W))
    assert _same(_field(expr, backend), expected)
    maps = evaluate(_height_program(expr), W, H, backend=backend)
    assert np.array_equal(maps.height, expected.astype(np.float32), equal_nan=True)


@pytest.mark.parametrize("backend", BACKENDS)
@pytest.mark.parametrize("expr", sorted(CLOSE))
def test_function_is_within_one_ulp_of_numpy(expr: str, backend: str) -> None:
    x, y = _axes()
    expected = np.broadcast_to(CLOSE[expr](x, y), (H, W))
    got = _field(expr, backend)
    assert got.dtype == np.float64
    np.testing.assert_array_max_ulp(got, expected, maxulp=2)
    maps = evaluate(_height_program(expr), W, H, backend=backend)
    assert np.array_equal(maps.height, got.astype(np.float32))


# ------------------------------------------------------------------ numpy and numba: same bits
ALL_FUNCTIONS = """View(-3, -2, 5, 6)
Define(warp, fBm(octaves=3, base_freq=2, to_01=True, seed=4))
Define(cells, Hash(X() * 6 + warp, Y() * 6, seed=11))
Material(
  Layer(1)
    .basecolor(Mix(40, 220, cells), Clamp(warp * 300, 30, 200), Smoothstep(-1, 4, X()) * 255)
    .roughness(Fract(X() * 2.5 + warp))
    .metallic(Mod(Y() * 3, 0.7 + warp) / 0.7)
    .height(Atan2(Y() - 1, X() - 1) * 0.1 + Exp(-Abs(X())) * cells),
  Layer(Smoothstep(0.2, 0.8, warp))
    .basecolor(200, Mix(X(), Y(), warp) * 30, 10)
    .sheen(Clamp(Hash(X() * 3, seed=2), Y() * 0.1, 0.9))
    .coat(Mod(X(), 0) + Exp(X() * 300) * 0 + Hash(X() * 1e19, Y(), seed=1))
    .height(Mod(X() * 7, 1) * Clamp(Y(), lo=0.5))
)"""


@needs_numba
@pytest.mark.parametrize("size", [(64, 48), (1, 1), (7, 3), (33, 65)])
def test_backends_give_the_same_bits(size: tuple[int, int]) -> None:
    ref = evaluate(ALL_FUNCTIONS, *size, backend="numpy")
    ours = evaluate(ALL_FUNCTIONS, *size, backend="numba")
    for key in ARRAY_FIELDS:
        a, b = getattr(ours, key), getattr(ref, key)
        assert a.shape == b.shape and a.dtype == b.dtype, key
        assert np.array_equal(a.view(np.uint32), b.view(np.uint32)), key


def _special_inputs(n: int = 200_000) -> tuple[np.ndarray, np.ndarray]:
    rng = np.random.default_rng(12)
    scales = rng.choice([1e-300, 1e-8, 1e-3, 1.0, 10.0, 700.0, 1e6, 1e200], size=n)
    special = np.array(
        [0.0, -0.0, np.inf, -np.inf, np.nan, 1.0, -1.0, 5e-324, -5e-324, 1e308, -1e308]
        + [0.4375, 0.6875, 1.1875, 2.4375, 2.0**66, 709.78, 709.79, -745.13, -745.14, -708.5]
    )
    a = np.concatenate([rng.normal(size=n) * scales, np.repeat(special, special.size)])
    b = np.concatenate([rng.normal(size=n) * scales[::-1], np.tile(special, special.size)])
    return a, b


@needs_numba
@pytest.mark.parametrize("name", ["atan2", "fract", "mod", "exp"])
def test_numba_scalar_functions_repeat_numpy_bit_for_bit(name: str) -> None:
    """mathops_numba (the register machine's opcodes) vs mathops, NaN payloads included."""
    import numba

    from matloom.engine.kernels import mathops_numba

    function = getattr(mathops_numba, name)
    reference = getattr(mathops, "exp_" if name == "exp" else name)
    a, b = _special_inputs()
    if name == "exp":
        a = np.concatenate([a, np.random.default_rng(3).uniform(-750.0, 712.0, 100_000)])
        b = a

    @numba.njit
    def unary(a: np.ndarray) -> np.ndarray:  # pragma: no cover - numba
        out = np.empty_like(a)
        for i in range(a.size):
            out[i] = function(a[i])
        return out

    @numba.njit
    def binary(a: np.ndarray, b: np.ndarray) -> np.ndarray:  # pragma: no cover - numba
        out = np.empty_like(a)
        for i in range(a.size):
            out[i] = function(a[i], b[i])
        return out

    if name in ("atan2", "mod"):
        got, expected = binary(a, b), reference(a, b)
    else:
        got, expected = unary(a), reference(a)
    assert np.array_equal(got.view(np.uint64), expected.view(np.uint64))


def test_exp_and_atan2_are_within_one_ulp_of_libm() -> None:
    rng = np.random.default_rng(5)
    x = rng.uniform(-745.0, 709.7, 50_000)
    ours = mathops.exp_(x)
    libm = np.array([math.exp(v) for v in x])
    assert np.abs(ours.view(np.int64) - libm.view(np.int64)).max() <= 1
    y, z = rng.normal(size=(2, 50_000)) * rng.choice([1e-5, 1.0, 1e5], size=(2, 50_000))
    ours = mathops.atan2(y, z)
    libm = np.array([math.atan2(u, v) for u, v in zip(y, z, strict=True)])
    assert np.abs(ours.view(np.int64) - libm.view(np.int64)).max() <= 1


@needs_numba
def test_hash_kernels_give_the_same_bits() -> None:
    from matloom.engine.kernels import hash_numba

    rng = np.random.default_rng(9)
    x = rng.normal(size=(1, 1, 300)) * 1e3
    x[0, 0, :6] = [np.nan, np.inf, -np.inf, 2.0**63, -(2.0**63), 9.2e18]
    y = rng.normal(size=(1, 50, 1)) * 40
    keys = [hashing.seed_key(s) for s in (0, 1, 2**40, 12345)]
    expected = hashing.cell_hash(x, y, keys)
    got = hash_numba.cell_hash(x, y, keys)
    assert got.dtype == expected.dtype == np.float32 and got.shape == (4, 50, 300)
    assert np.array_equal(got.view(np.uint32), expected.view(np.uint32))
    batched = rng.normal(size=(4, 1, 300)) * 50  # operands with a candidate axis (sweeps)
    assert np.array_equal(
        hash_numba.cell_hash(batched, y, keys), hashing.cell_hash(batched, y, keys)
    )


# ------------------------------------------------------------------ special values and rules
def test_special_values() -> None:
    pi = math.pi
    y = np.array([0.0, -0.0, 0.0, -0.0, 1.0, -1.0, np.inf, -np.inf, np.inf, 2.0, -2.0, np.nan])
    x = np.array([-1.0, -1.0, -0.0, 0.0, 0.0, -0.0, np.inf, np.inf, -np.inf, -np.inf, np.inf, 1])
    expected = [pi, pi, pi, 0.0, pi / 2, -pi / 2, pi / 4, -pi / 4, 3 * pi / 4, pi, -0.0, np.nan]
    angles = mathops.atan2(y, x)
    assert _same(angles, np.array(expected))
    assert np.all((angles[:-1] > -pi) & (angles[:-1] <= pi))  # never -pi: -0 counts as +0
    assert _same(
        mathops.fract([-1e-20, -0.25, 2.5, np.inf, np.nan]),
        [mathops.FRACT_MAX, 0.75, 0.5, np.nan, np.nan],
    )
    assert mathops.FRACT_MAX < 1.0
    with np.errstate(invalid="ignore"):
        default_nan = np.array([np.inf]) - np.inf  # the CPU's NaN (sign bit set)
    assert mathops.atan2(np.nan, 1.0).view(np.uint64) == default_nan.view(np.uint64)[0]
    assert hashing.NAN32.view(np.uint32) == default_nan.astype(np.float32).view(np.uint32)[0]
    m = mathops.mod(
        [-1.0, 1.0, -1.0, -7.5, 5.0, np.nan, np.inf, 3.0], [3, -3, -3, 2, 0, 0, 2, np.inf]
    )
    assert _same(m, [2.0, -2.0, -1.0, 0.5, 0.0, 0.0, np.nan, np.nan])
    e = mathops.exp_([0.0, 1.0, 710.0, -746.0, -np.inf, np.inf, np.nan, mathops.EXP_OVERFLOW])
    assert _same(e[[0, 2, 3, 4, 5, 6]], [1.0, np.inf, 0.0, 0.0, np.inf, np.nan])
    assert abs(int(e[1:2].view(np.int64)[0]) - int(np.float64(math.e).view(np.int64))) <= 1
    assert math.isfinite(e[7])


def test_fract_is_in_unit_interval() -> None:
    rng = np.random.default_rng(1)
    values = np.concatenate(
        [
            rng.normal(size=100_000) * rng.choice([1e-30, 1e-10, 1.0, 1e6, 1e15], size=100_000),
            -np.logspace(-320, 0, 2000),
            np.nextafter(np.arange(-50.0, 50.0), -np.inf),
            np.nextafter(np.arange(-50.0, 50.0), np.inf),
        ]
    )
    f = mathops.fract(values)
    assert np.all((f >= 0.0) & (f < 1.0))


def test_smoothstep_matches_glsl_at_the_edges() -> None:
    x = np.array([-5.0, 0.125, 0.25, 0.5, 0.75, 0.875, 9.0])
    s = mathops.smoothstep(np.float64(0.25), np.float64(0.75), x)
    assert list(s) == [0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0]
    assert float(mathops.smoothstep(np.float64(0), np.float64(1), 0.25)) == 0.15625
    ramp = mathops.smoothstep(np.float64(0.25), np.float64(0.75), np.linspace(0.25, 0.75, 101))
    assert np.all(np.diff(ramp) > 0) and ramp[0] == 0.0 and ramp[-1] == 1.0
    falling = mathops.smoothstep(np.float64(0.75), np.float64(0.25), x)
    assert list(falling) == [1.0, 1.0, 1.0, 0.5, 0.0, 0.0, 0.0]
    assert list(mathops.smoothstep(np.float64(0.5), np.float64(0.5), x)) == [0.0] * 7
    assert np.isnan(mathops.smoothstep(np.float64(0), np.float64(1), np.nan))


@pytest.mark.parametrize("backend", BACKENDS)
@pytest.mark.parametrize("divisor", ["0", "Y() * 0", "Floor(X())"])
def test_mod_counts_divisions_by_zero_like_div(divisor: str, backend: str) -> None:
    counts = []
    for expr in (f"Mod(X(), {divisor})", f"X() / ({divisor})"):
        stats = EvalStats()
        evaluate(_height_program(expr), 8, 4, backend=backend, stats=stats)
        counts.append(stats.zero_divisions)
    assert counts[0] == counts[1] > 0


# ------------------------------------------------------------------ Hash properties
def _hash_grid(seed: int, n: int = 200, offset: float = 0.0) -> np.ndarray:
    """Hash at the centres of n x n cells (plus ``offset`` inside the cell)."""
    cx = np.arange(n, dtype=np.float64)[None, :] - n // 2 + 0.5 + offset
    cy = np.arange(n, dtype=np.float64)[:, None] - n // 2 + 0.5 + offset
    return hashing.cell_hash(cx, cy, [hashing.seed_key(seed)])[0].astype(np.float64)


def test_hash_is_constant_per_cell() -> None:
    centre = _hash_grid(7)
    for offset in (-0.5, -0.25, 0.49999):
        assert np.array_equal(_hash_grid(7, offset=offset), centre)
    x, y = _axes()  # through the language: 2 x 2 cells over 8 x 8 units
    value = _field("Hash(X() / 4, Y() / 4, seed=3)")
    cells = np.floor(np.broadcast_to(x / 4, (H, W))) * 10 + np.floor(np.broadcast_to(y / 4, (H, W)))
    for cell in np.unique(cells):
        assert np.unique(value[cells == cell]).size == 1


def test_hash_is_uniform() -> None:
    """Chi-square over 40 000 cells and 20 bins (fixed seed: deterministic, but it can fail)."""
    values = _hash_grid(2024).ravel()
    assert values.min() >= 0.0 and values.max() < 1.0
    counts = np.bincount((values * 20).astype(int), minlength=20)
    expected = values.size / 20
    chi2 = float(((counts - expected) ** 2 / expected).sum())
    assert chi2 < 43.8  # 99.9 % quantile of chi-square with 19 degrees of freedom


@pytest.mark.parametrize("seed", [0, 1, 99])
def test_hash_neighbours_are_independent(seed: int) -> None:
    v = _hash_grid(seed) - 0.5
    for a, b in ((v[:, 1:], v[:, :-1]), (v[1:, :], v[:-1, :]), (v[1:, 1:], v[:-1, :-1])):
        r = np.corrcoef(a.ravel(), b.ravel())[0, 1]
        assert abs(r) < 0.025  # about 5 standard errors of a 40 000-sample correlation
    assert np.unique(v).size > 0.99 * v.size


def test_hash_changes_with_the_seed() -> None:
    a, b = _hash_grid(1), _hash_grid(2)
    assert np.count_nonzero(a == b) < 0.001 * a.size
    assert abs(np.corrcoef(a.ravel(), b.ravel())[0, 1]) < 0.025
    assert np.array_equal(_hash_grid(1), a)  # and only with the seed


def test_hash_nan_rules() -> None:
    keys = [hashing.seed_key(5)]
    x = np.array(
        [[np.nan, np.inf, -np.inf, 2.0**63, 1e19, -(2.0**63) - 4096.0, 9.2e18, -(2.0**63)]]
    )
    out = hashing.cell_hash(x, 0.0, keys)[0, 0]
    assert np.isnan(out[:6]).all() and np.isfinite(out[6:]).all()
    assert np.isnan(hashing.cell_hash(1.0, np.nan, keys)).all()


@pytest.mark.parametrize("backend", BACKENDS)
def test_hash_in_programs(backend: str) -> None:
    value = _field("Hash(X() * 2, Y() * 3, seed=8)", backend)
    x, y = _axes()
    direct = hashing.cell_hash(x * 2.0, y * 3.0, [hashing.seed_key(8)])[0]
    assert value.dtype == np.float32 and np.array_equal(value, direct)
    row = _field("Hash(X(), seed=8)", backend)  # y defaults to 0
    assert np.array_equal(
        row, np.broadcast_to(hashing.cell_hash(x, 0.0, [hashing.seed_key(8)])[0], (H, W))
    )
    assert static_number(
        matloom.parse(_height_program("Hash(2.5, -1.5, 8)")).layers[0].channels[0].args[0]
    ) == float(hashing.cell_hash(2.5, -1.5, [hashing.seed_key(8)])[0, 0, 0])


# ------------------------------------------------------------------ constant folding, check, fmt
def _static(expr: str) -> float | int | None:
    return static_number(matloom.parse(_height_program(expr)).layers[0].channels[0].args[0])


def test_constant_folding() -> None:
    assert _static("Atan2(1, 1)") == float(mathops.atan2(1.0, 1.0)) == pytest.approx(math.pi / 4)
    assert _static("Atan2(0, -1)") == math.pi
    assert _static("Fract(-0.25)") == 0.75
    assert _static("Mod(-1, 3)") == 2.0 and _static("Mod(1, -3)") == -2.0
    assert _static("Mod(5, 0)") == 0.0
    assert _static("Exp(1)") == float(mathops.exp_(1.0)) and _static("Exp(0)") == 1.0
    assert _static("Clamp(1.5)") == 1.0 and _static("Clamp(0.7, 0.2, 0.5)") == 0.5
    assert _static("Clamp(0.7, hi=0.5)") is None  # values without names: ambiguous, not folded
    assert _static("Smoothstep(0, 1, 0.25)") == 0.15625
    assert _static("Mix(0, 10, 0.25)") == 2.5
    assert _static("Hash(2.5, seed=3)") is None  # y or the seed: ambiguous
    assert _static("Mix(X(), 1, 0)") == 0.0  # X() counts as 0 where a number is needed
    assert _static("Clamp(fBm(seed=1))") is None


def test_folded_constants_equal_evaluated_ones() -> None:
    for expr in ("Exp(0.3)", "Atan2(-2, -3)", "Smoothstep(0.1, 0.9, 0.33)", "Mix(3, -1, 0.3)"):
        assert _static(expr) == float(_field(expr)[0, 0]), expr


def test_static_parameters_accept_the_functions() -> None:
    text = "Material(Layer(1).height(Bricks(brick_width=Clamp(3, 0.5, 2), mortar=Exp(-3))))"
    assert matloom.check(text) == []
    bricks = matloom.parse(text).layers[0].channels[0].args[0]
    assert isinstance(bricks, A.Call) and static_number(bricks.arg("brick_width")) == 2.0
    maps = evaluate(text, 16, 16, backend="numpy")
    assert np.array_equal(
        maps.height,
        evaluate(
            "Material(Layer(1).height(Bricks(brick_width=2, mortar=Exp(-3))))",
            16,
            16,
            backend="numpy",
        ).height,
    )


PROGRAM = """View(0, 0, 4, 4)
Material(
  Layer(1)
    .basecolor(Mix(20, 240, Hash(X() * 4, Y() * 4, seed=9)), 128, Clamp(Y() * 60, hi=255))
    .roughness(Smoothstep(0.2, 0.8, Fract(X())))
    .metallic(Clamp(Mod(X() - Y(), 1.5), lo=0.1, hi=0.9))
    .height(Exp(-Atan2(Y() - 2, X() - 2) ** 2) * 0.05)
)
"""


def test_check_accepts_and_fmt_round_trips() -> None:
    assert matloom.check(PROGRAM) == []
    text = matloom.format(matloom.parse(PROGRAM))
    assert matloom.format(matloom.parse(text)) == text
    assert matloom.parse(text) == matloom.parse(PROGRAM)
    assert "Clamp(x=(Y() * 60), hi=255)" in text  # keywords: an omitted bound stays omitted
    assert "Hash(x=(X() * 4), y=(Y() * 4), seed=9)" in text
    assert "Smoothstep(0.2, 0.8, Fract(X()))" in text


# ------------------------------------------------------------------ seeds
def test_hash_seed_is_a_noise_seed() -> None:
    text = "Material(Layer(1).height(Hash(X() * 4) + Hash(Y() * 4, X())))"
    assert [d.code for d in matloom.check(text)] == ["W003", "W003"]
    seeded = canonicalize_seeds(matloom.parse(text), 5)
    calls = [n for n in A.walk(seeded.layers[0].channels[0].args[0]) if isinstance(n, A.Call)]
    seeds = [c.arg("seed") for c in calls if c.func == "Hash"]
    assert all(isinstance(s, A.Num) for s in seeds) and seeds[0] != seeds[1]
    canonical = matloom.format(seeded)
    assert canonical.count("seed=") == 2 and matloom.check(canonical) == []
    variants = seed_variants(canonical, 3, seed=1)
    assert len(set(variants)) == 4
    maps = [evaluate(v, 16, 16, backend="numpy").height for v in variants]
    assert not any(np.array_equal(maps[0], m) for m in maps[1:])


def test_dependency_analysis_sees_the_hash_seed() -> None:
    from matloom.lang.deps import seed_dependent_outputs

    program = matloom.parse("Material(Layer(1).roughness(Hash(X() * 4, seed=3)))")
    assert "roughness" in seed_dependent_outputs(program)
    assert "metallic" not in seed_dependent_outputs(program)


@needs_numba
def test_seed_batch_gives_each_candidate_its_hash() -> None:
    """The sweep's seed-batched evaluation: candidate k equals the dense value of variant k."""
    from matloom.engine.lazy import materialise
    from matloom.engine.schedules.seed_batch import SweepEvaluator
    from matloom.lang.seeds import apply_seed_map, seed_assignments

    text = matloom.format(
        "Material(Layer(1).height(Hash(X() * 8 + fBm(seed=2), Y() * 8, seed=7) * Mix(0, 1, X())))"
    )
    maps = [{}, *seed_assignments(text, 3, seed=4)]
    program = prepare(text)
    x, y = sample_axes(View(0, 0, 1, 1), 24, 24)
    ev = SweepEvaluator(program, x, y, get_backend("numba"))
    ev.begin_chunk(maps)
    batch = np.asarray(materialise(ev.field(program.layers[0].channels[0].args[0])))
    assert batch.shape == (4, 24, 24)
    for k, seed_map in enumerate(maps):
        variant = prepare(apply_seed_map(text, seed_map))
        dense = Evaluator(variant, x, y, get_backend("numpy"))
        assert np.array_equal(batch[k], dense.field(variant.layers[0].channels[0].args[0]))


@needs_numba
def test_sweep_varies_the_hash_seed() -> None:
    from matloom.engine.schedules.sweep import run_sweep, variant_program
    from matloom.render.preview import ShadeParams

    text = "Material(Layer(1).basecolor(Hash(X() * 6, Y() * 6, seed=3) * 255, 90, 40))"
    result = run_sweep(text, variants=3, shading=ShadeParams.of(), size=32, jobs=1, keep=4)
    assert result.n_candidates == 4
    images = dict(result.top_images)
    assert not np.array_equal(images[0], images[1])
    canonical = matloom.format(text)
    for index, image in images.items():
        preview = matloom.preview(variant_program(canonical, index, 3), 32)
        assert np.abs(image.astype(np.int16) - preview.astype(np.int16)).max() <= 1


# ------------------------------------------------------------------ the op entries
def test_op_entries() -> None:
    for name in ("Atan2", "Fract", "Mod", "Exp"):
        op = OPS[name]
        assert op.fast == name.lower() and op.dtype == "float64" and not op.materialised
    assert OPS["Mod"].divisor == 1
    for name in ("Clamp", "Mix", "Smoothstep", "Hash"):
        assert OPS[name].kind.value == "field"


def test_bounds_rules() -> None:
    assert OPS["Atan2"].bounds((-1.0, 1.0), (2.0, 3.0)) == (-math.pi, math.pi)
    assert OPS["Fract"].bounds((-1e9, 1e9)) == (0.0, 1.0)
    lo, hi = OPS["Mod"].bounds((-10.0, 10.0), (3.0, 3.0))  # type: ignore[misc]
    assert -1e-12 < lo <= 0.0 and 3.0 <= hi < 3.0 + 1e-12
    assert OPS["Mod"].bounds((0.0, 1.0), (-1.0, 1.0)) is None
    assert OPS["Mod"].bounds((0.0, 1.0), (0.0, 0.0)) == (0.0, 0.0)
    lo, hi = OPS["Exp"].bounds((0.0, 1.0))  # type: ignore[misc]
    assert lo <= 1.0 and math.e <= hi < math.e * (1 + 1e-14)
    assert OPS["Exp"].bounds((0.0, 800.0)) is None
    assert OPS["Clamp"].bounds((-5.0, 5.0), (0.0, 1.0), (2.0, 3.0)) == (0.0, 3.0)
    assert OPS["Mix"].bounds((0.0, 1.0), (2.0, 2.0), (0.0, 1.0)) == (0.0, 3.0)
    assert OPS["Smoothstep"].bounds((0.0, 0.0), (1.0, 1.0), (-9.0, 9.0)) == (0.0, 1.0)
    assert OPS["Hash"].bounds((-1e3, 1e3), (0.0, 0.0)) == (0.0, 1.0)
    assert OPS["Hash"].bounds((-1e19, 1e3), (0.0, 0.0)) is None


def test_mod_bounds_hold_on_sampled_values() -> None:
    rng = np.random.default_rng(0)
    for x_range, m_range in (((-10.0, 10.0), (3.0, 3.0)), ((-1e12, 1e12), (-0.7, -0.1))):
        x, m = rng.uniform(*x_range, 100_000), rng.uniform(*m_range, 100_000)
        values = mathops.mod(x, m)
        lo, hi = OPS["Mod"].bounds(x_range, m_range)  # type: ignore[misc]
        assert np.all((values >= lo) & (values <= hi))
