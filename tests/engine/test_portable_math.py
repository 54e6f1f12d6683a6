"""The portable transcendental functions (matloom.ops.portable_math): fdlibm's constants,
accuracy against exact arithmetic, C99/numpy special values, dtypes, and constant folding
that gives the bits the arrays get."""

from __future__ import annotations

import decimal
import math
import struct
from fractions import Fraction

import numpy as np
import pytest

import matloom
from matloom.engine.kernels import mathops
from matloom.lang.static import static_number
from matloom.ops import portable_constants as K
from matloom.ops import portable_math as pm

#: fdlibm's bit patterns (FreeBSD msun e_rem_pio2.c, k_sin.c, k_cos.c, e_pow.c).
FDLIBM_BITS = {
    "PIO2_1": "3FF921FB54400000", "PIO2_1T": "3DD0B4611A626331", "PIO2_2": "3DD0B4611A600000",
    "PIO2_2T": "3BA3198A2E037073", "PIO2_3": "3BA3198A2E000000", "PIO2_3T": "397B839A252049C1",
    "INVPIO2": "3FE45F306DC9C883", "PIO4": "3FE921FB54442D18", "LG2": "3FE62E42FEFA39EF",
    "LG2_H": "3FE62E4300000000", "LG2_L": "BE205C610CA86C39", "S1": "BFC5555555555549",
    "S2": "3F8111111110F8A6", "S3": "BF2A01A019C161D5", "S4": "3EC71DE357B1FE7D",
    "S5": "BE5AE5E68A2B9CEB", "S6": "3DE5D93A5ACFD57C", "C1": "3FA555555555554C",
    "C2": "BF56C16C16C15177", "C3": "3EFA01A019CB1590", "C4": "BE927E4F809C52AD",
    "C5": "3E21EE9EBDB4B1C4", "C6": "BDA8FAE9BE8838D4", "L1": "3FE3333333333303",
    "L2": "3FDB6DB6DB6FABFF", "L3": "3FD55555518F264D", "L4": "3FD17460A91D4101",
    "L5": "3FCD864A93C9DB65", "L6": "3FCA7E284A454EEF", "DP_H1": "3FE2B80340000000",
    "DP_L1": "3E4CFDEB43CFD006", "CP": "3FEEC709DC3A03FD", "CP_H": "3FEEC709E0000000",
    "CP_L": "BE3E2FE0145B01F5", "OVT": "3C971547652B82FE",
}  # fmt: skip


@pytest.mark.parametrize("name", sorted(FDLIBM_BITS))
def test_constants_are_fdlibms(name):
    assert struct.pack(">d", getattr(K, name)).hex().upper() == FDLIBM_BITS[name]


def test_log10_2_split_is_exact_enough():
    """LOG10_2_H has 21 significant bits (t1 * LOG10_2_H is exact) and the tail completes it."""
    decimal.getcontext().prec = 60
    exact = Fraction(decimal.Decimal(2).ln() / decimal.Decimal(10).ln())
    head = Fraction(K.LOG10_2_H)
    assert (head * 2**22).denominator == 1
    assert abs(head + Fraction(K.LOG10_2_L) - exact) < Fraction(1, 2**75)


_PI = Fraction(K._pi_fixed(1500), 1 << 1500)  # enough for |x| up to 2**1024


def _sin_exact(x: float) -> float:
    """sin(x) correctly rounded, by Decimal (x reduced exactly with the long pi)."""
    with decimal.localcontext() as ctx:
        ctx.prec = 70
        r = Fraction(x) - _PI * 2 * math.floor(Fraction(x) / (_PI * 2))
        d = decimal.Decimal(r.numerator) / decimal.Decimal(r.denominator)
        total, term, k = decimal.Decimal(0), d, 1
        while abs(term) > decimal.Decimal(10) ** -65:
            total += term
            term = -term * d * d / ((k + 1) * (k + 2))
            k += 2
        return float(Fraction(total))


def _ulps(a: float, b: float) -> int:
    ia, ib = (struct.unpack(">q", struct.pack(">d", v))[0] for v in (a, b))
    return abs(ia - ib)


@pytest.mark.parametrize("scale", [1.0, 100.0, 1e6, 1e300])
def test_sin_within_one_ulp_of_the_exact_value(scale):
    """Both reductions (Cody-Waite below 2**19 pi/2, exact integers beyond) and the kernels."""
    x = np.random.default_rng(3).uniform(-scale, scale, 60)
    got = pm.sin(x)
    assert max(_ulps(float(g), _sin_exact(float(v))) for g, v in zip(got, x)) <= 1
    shifted = pm.cos(x - K.PIO2_1 - K.PIO2_1T)  # cos(x - pi/2) = sin(x), to rounding
    assert np.all(np.abs(shifted - got) <= 1e-15 * np.maximum(1.0, np.abs(x)) * 4)


def test_logs_are_correctly_rounded_on_a_sample():
    rng = np.random.default_rng(5)
    x = np.concatenate([rng.uniform(0.5, 2.0, 300), np.exp(rng.uniform(-700, 700, 300))])
    with decimal.localcontext() as ctx:
        ctx.prec = 50
        ln2, ln10 = decimal.Decimal(2).ln(), decimal.Decimal(10).ln()
        exact = {
            "log": [float(Fraction(decimal.Decimal(v).ln())) for v in x],
            "log2": [float(Fraction(decimal.Decimal(v).ln() / ln2)) for v in x],
            "log10": [float(Fraction(decimal.Decimal(v).ln() / ln10)) for v in x],
        }
    for name, values in exact.items():
        assert np.array_equal(getattr(pm, name)(x), np.array(values)), name
    assert np.array_equal(pm.log10(10.0 ** np.arange(23)), np.arange(23.0))
    assert np.array_equal(pm.log2(2.0 ** np.arange(-1074, 1024)), np.arange(-1074.0, 1024.0))


def test_pow_within_one_ulp_including_x_near_one_and_huge_y():
    rng = np.random.default_rng(9)
    x = np.concatenate([np.exp(rng.uniform(-20, 20, 150)), 1 + rng.uniform(-1e-7, 1e-7, 150)])
    y = np.concatenate([rng.uniform(-30, 30, 150), rng.uniform(-1e10, 1e10, 150)])
    got = pm.pow_(x, y)
    with decimal.localcontext() as ctx:
        ctx.prec = 60
        for g, a, b in zip(got, x, y):
            if not 1e-300 < g < 1e300:
                continue  # over- and underflow: checked against numpy below
            exact = (decimal.Decimal(a).ln() * decimal.Decimal(b)).exp()
            assert _ulps(float(g), float(Fraction(exact))) <= 1, (a, b)
    k = np.arange(23.0)
    assert np.array_equal(pm.pow_(10.0, k), 10.0**k)
    assert np.array_equal(pm.pow_(2.0, np.arange(-1074.0, 1024.0)), 2.0 ** np.arange(-1074, 1024))


SPECIAL = [0.0, -0.0, 1.0, -1.0, 0.5, -0.5, 2.0, -2.0, 3.0, -3.0, 2.5, 1e300, -1e300, 5e-324]
SPECIAL += [math.inf, -math.inf, math.nan]


def _same(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return ((a == b) & (np.signbit(a) == np.signbit(b))) | (np.isnan(a) & np.isnan(b))


def test_special_values_follow_numpy():
    v = np.array(SPECIAL)
    with np.errstate(all="ignore"):
        for name, ufunc in (("log", np.log), ("log2", np.log2), ("log10", np.log10)):
            assert np.all(_same(getattr(pm, name)(v), ufunc(v))), name
        for name, ufunc in (("sin", np.sin), ("cos", np.cos)):
            got, want = getattr(pm, name)(v), ufunc(v)
            assert np.all(_same(got, want) | (np.abs(got - want) <= 2e-16)), name
        a, b = (g.ravel() for g in np.meshgrid(v, v))
        got, want = pm.pow_(a, b), np.power(a, b)
        close = np.abs(got - want) <= 2.3e-16 * np.abs(want)  # 1 ulp: numpy's own may be off
        assert np.all(_same(got, want) | close)


@pytest.mark.parametrize("exponent", [2.0, 1.0])
def test_a_square_or_first_power_of_an_array_keeps_the_general_paths_bits(exponent):
    # pow_ answers x ** 2 and x ** 1 without fdlibm's main path (x * x, x): the same bits as
    # the general path on finite, huge, tiny, signed-zero, infinite and NaN bases
    rng = np.random.default_rng(7)
    x = np.concatenate(
        [rng.standard_normal(4000) * 10, rng.standard_normal(200) * 1e160]
        + [rng.standard_normal(200) * 1e-160, np.array(SPECIAL), -np.array(SPECIAL)]
    )
    with np.errstate(all="ignore"):
        fast, general = pm.pow_(x, exponent), pm._pow_general(x, exponent)
    assert np.array_equal(fast.view(np.uint64), general.view(np.uint64))


def test_made_nans_are_the_engines_nan():
    bits = np.array([K.NAN]).view(np.uint64)
    for made in (pm.sin(np.array([np.inf])), pm.log(np.array([-1.0])), pm.pow_(-2.0, 0.5)):
        assert np.array_equal(np.asarray(made, dtype=np.float64).reshape(-1).view(np.uint64), bits)


def test_mathops_keep_numpys_dtypes():
    x32 = np.linspace(0.1, 3.0, 7, dtype=np.float32)
    assert mathops.sin(x32).dtype == np.float32
    assert mathops.log(x32, 7.0).dtype == np.float32
    assert mathops.pow_(x32, x32).dtype == np.float32
    assert mathops.pow_(x32, 2.5).dtype == np.float64  # a Python float operand is float64 here
    assert isinstance(mathops.cos(np.float64(1.0)), np.float64)
    assert np.array_equal(mathops.sin(x32), pm.sin(x32.astype(np.float64)).astype(np.float32))


@pytest.mark.parametrize(
    "expr", ["Sin(1.3)", "Cos(-7.25)", "Log(3.7)", "Log(3.7, 10)", "Log(3.7, 2)", "Log(3.7, 6)",
             "Pow(2.2, 0.37)", "Sin(123456789.5)"],
)  # fmt: skip
def test_constant_folding_gives_the_arrays_bits(expr):
    """A static parameter value is the value the same expression gets as an array."""
    program = matloom.parse(f"Material(Layer().height({expr}))")
    folded = static_number(program.layers[0].channel("height").args[0])
    name, args = expr.split("(", 1)
    values = [np.array([float(a)]) for a in args.rstrip(")").split(",")]
    kernel = {"Sin": mathops.sin, "Cos": mathops.cos, "Log": mathops.log, "Pow": mathops.pow_}
    if name == "Log" and len(values) == 2:
        array = mathops.log(values[0], float(values[1][0]))
    else:
        array = kernel[name](*values)
    assert folded == float(array[0])
