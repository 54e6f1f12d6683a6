"""Constants of the portable transcendental functions (:mod:`.portable_math`).

The polynomial coefficients are fdlibm's (FreeBSD msun k_sin.c, k_cos.c, e_pow.c); the pieces of
pi/2 and the logarithm constants are derived here from pi and ln 2 computed with exact integer
arithmetic and :mod:`decimal` (both correctly rounded in software, so the same on every machine);
``tests/engine/test_portable_math.py`` checks them against fdlibm's published bit patterns.
"""

from __future__ import annotations

import decimal
import math
from fractions import Fraction

import numpy as np

#: The CPU's default NaN (sign bit set), the one 0/0 and inf - inf give on x86-64; spelled out
#: so that every NaN the engine makes has the same bits on every machine.
NAN = float(np.array(0xFFF8000000000000, dtype=np.uint64).view(np.float64)[()])


def _pi_fixed(bits: int) -> int:
    """pi * 2**bits, to within a few units (Machin's formula in integers, 32 guard bits)."""
    guard = bits + 32

    def arctan_inverse(n: int) -> int:  # atan(1/n) * 2**guard
        total, term, k, sign = 0, (1 << guard) // n, 1, 1
        while term:
            total += sign * (term // k)
            term //= n * n
            k += 2
            sign = -sign
        return total

    return (16 * arctan_inverse(5) - 4 * arctan_inverse(239)) >> 32


#: Bits after the binary point of :data:`TWO_OVER_PI_INT` (2/pi): enough for |x| up to 2**1024.
TWO_OVER_PI_BITS = 1344
#: floor(2/pi * 2**TWO_OVER_PI_BITS).
TWO_OVER_PI_INT = (1 << (2 * TWO_OVER_PI_BITS + 1 + 64)) // _pi_fixed(TWO_OVER_PI_BITS + 64)
#: Bits after the binary point of :data:`HALF_PI_INT` (pi/2).
HALF_PI_BITS = 256
HALF_PI_INT = _pi_fixed(HALF_PI_BITS + 8) >> 9
_HALF_PI = Fraction(HALF_PI_INT, 1 << HALF_PI_BITS)


def _unit(value: Fraction, bits: int) -> Fraction:
    """The weight of the last of ``bits`` significant bits of value (> 0, not near 2**k)."""
    return Fraction(2) ** (math.frexp(float(value))[1] - bits)


def _truncate(value: Fraction, bits: int) -> float:
    """value truncated to ``bits`` significant bits (exactly representable)."""
    unit = _unit(value, bits)
    return float(unit * (value // unit))


def _split(value: Fraction, bits: int) -> tuple[float, float, float]:
    """(value rounded, a head of ``bits`` significant bits rounded to nearest, the tail)."""
    unit = _unit(value, bits)
    head = float(unit * round(value / unit))
    return float(value), head, float(value - Fraction(head))


PIO2_1 = _truncate(_HALF_PI, 33)
PIO2_1T = float(_HALF_PI - Fraction(PIO2_1))
PIO2_2 = _truncate(_HALF_PI - Fraction(PIO2_1), 33)
PIO2_2T = float(_HALF_PI - Fraction(PIO2_1) - Fraction(PIO2_2))
PIO2_3 = _truncate(_HALF_PI - Fraction(PIO2_1) - Fraction(PIO2_2), 33)
PIO2_3T = float(_HALF_PI - Fraction(PIO2_1) - Fraction(PIO2_2) - Fraction(PIO2_3))
INVPIO2 = float(1 / _HALF_PI)
PIO4 = float(_HALF_PI / 2)

with decimal.localcontext() as _ctx:
    _ctx.prec = 80
    _LN2 = Fraction(decimal.Decimal(2).ln())
    _LOG10_2 = Fraction(decimal.Decimal(2).ln() / decimal.Decimal(10).ln())
#: ln 2 = LG2_H + LG2_L with LG2_H of 21 significant bits (t1 * LG2_H is exact).
LG2, LG2_H, LG2_L = _split(_LN2, 21)
#: log10(2) = LOG10_2_H + LOG10_2_L likewise.
LOG10_2, LOG10_2_H, LOG10_2_L = _split(_LOG10_2, 21)

# fdlibm k_sin.c / k_cos.c: sin(x) ~ x + S1 x**3 + ..., cos(x) ~ 1 - x**2/2 + C1 x**4 + ...
S1 = -1.66666666666666324348e-01
S2 = 8.33333333332248946124e-03
S3 = -1.98412698298579493134e-04
S4 = 2.75573137070700676789e-06
S5 = -2.50507602534068634195e-08
S6 = 1.58969099521155010221e-10
C1 = 4.16666666666666019037e-02
C2 = -1.38888888888741095749e-03
C3 = 2.48015872894767294178e-05
C4 = -2.75573143513906633035e-07
C5 = 2.08757232129817482790e-09
C6 = -1.13596475577881948265e-11

# fdlibm e_pow.c
DP_H1 = 5.84962487220764160156e-01  # log2(1.5) high part
DP_L1 = 1.35003920212974897128e-08  # log2(1.5) low part
L1 = 5.99999999999994648725e-01
L2 = 4.28571428578550184252e-01
L3 = 3.33333329818377432918e-01
L4 = 2.72728123808534006489e-01
L5 = 2.30660745775561754067e-01
L6 = 2.06975017800338417784e-01
P1 = 1.66666666666666019037e-01
P2 = -2.77777777770155933842e-03
P3 = 6.61375632143793436117e-05
P4 = -1.65339022054652515390e-06
P5 = 4.13813679705723846039e-08
OVT = 8.0085662595372944372e-17  # -(1024 - log2(overflow threshold + 0.5 ulp))
CP = 9.61796693925975554329e-01  # 2 / (3 ln 2)
CP_H = 9.61796700954437255859e-01  # (float) CP
CP_L = -7.02846165095275826516e-09  # CP - CP_H
IVLN2 = 1.44269504088896338700e00  # 1 / ln 2
IVLN2_H = 1.44269502162933349609e00  # 24 bits of 1 / ln 2
IVLN2_L = 1.92596299112661746887e-08  # the tail
