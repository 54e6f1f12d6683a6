"""sRGB transfer functions with the reference's exact piecewise formulas.

The authored colour channels are sRGB on a 0..255 scale; compositing happens in linear light
and export converts back to sRGB. Both directions use the IEC 61966-2-1 piecewise curve with the
thresholds the reference uses (0.04045 decoding, 0.0031308 encoding).

The computation dtype follows the input: the reference decodes authored colours in float64
(its expression grids are float64) and encodes the blended float32 colour in float32, and the
callers pass arrays of those dtypes. NaN passes through both functions unchanged.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numpy.typing import ArrayLike

from matloom.engine.kernels.mathops import pow_

#: Encoded values at or below this are on the linear segment of the sRGB decode curve.
SRGB_DECODE_THRESHOLD = 0.04045
#: Linear values at or below this are on the linear segment of the sRGB encode curve.
SRGB_ENCODE_THRESHOLD = 0.0031308


def _float_array(values: ArrayLike) -> np.ndarray:
    """Return ``values`` as a floating array, keeping float32/float64 and promoting the rest."""
    array = np.asarray(values)
    if array.dtype not in (np.float32, np.float64):
        array = array.astype(np.float64)
    return array


def _power(base: np.ndarray, exponent: float) -> np.ndarray:
    """``base ** exponent`` in base's dtype (as numpy's power with a Python float exponent),
    with the portable power: the same bits on every CPU. A float32 array takes numpy's fast
    power in float64 and the portable one only where the float32 rounding of that is not
    certain (:func:`float32_of`): the same bits, about ten times faster."""
    power = np.asarray(exponent, dtype=base.dtype)
    if base.dtype != np.float32 or base.ndim == 0:
        return np.asarray(pow_(base, power))
    flat = np.ascontiguousarray(base).reshape(-1)
    out = np.empty(flat.shape, dtype=np.float32)
    with np.errstate(all="ignore"):
        for start in range(0, flat.size, _POWER_BLOCK):  # temporaries stay in the CPU cache
            part = flat[start : start + _POWER_BLOCK]
            fast = np.power(part.astype(np.float64), power.astype(np.float64))
            fast[part == 0.0] = np.nan  # (the sign of a zero result: the portable power's)
            out[start : start + _POWER_BLOCK] = float32_of(
                fast, lambda at, part=part: np.asarray(pow_(part[at], power))
            )
    return out.reshape(base.shape)


#: Elements per block of the float32 :func:`_power`.
_POWER_BLOCK = 1 << 16


def srgb_to_linear(values: ArrayLike) -> np.ndarray:
    """Decode sRGB values in [0, 1] to linear light: v/12.92 or ((v + 0.055)/1.055)^2.4.

    Computed element-wise in the input's float dtype (float64 for non-float input). NaN stays
    NaN (it takes the power branch). Returns a new array (0-d for a scalar input).
    """
    return _decode(_float_array(values), _power)


def _decode(encoded: np.ndarray, power: Callable[[np.ndarray, float], np.ndarray]) -> np.ndarray:
    """The sRGB decode curve of ``encoded`` with the given ``power(base, exponent)``."""
    with np.errstate(invalid="ignore"):
        linear = np.asarray(power((encoded + 0.055) / 1.055, 2.4))
    np.copyto(linear, encoded / 12.92, where=encoded <= SRGB_DECODE_THRESHOLD)
    return linear


#: Relative margin of the certainty test of :func:`float32_of` and of the numba compositor's
#: sRGB table: far above the error of any libm or SIMD ``power`` (a few 2**-53).
CERTAINTY_MARGIN = 2.0**-44


def fast_srgb_to_linear(encoded: np.ndarray) -> np.ndarray:
    """:func:`srgb_to_linear` of a float64 array with numpy's own ``power``: fast, but its last
    bit depends on the CPU. Only for :func:`float32_of`, which hides that bit."""
    return _decode(encoded, np.power)


def float32_of(fast: np.ndarray, exact: Callable[[np.ndarray], np.ndarray]) -> np.ndarray:
    """``fast`` (float64, within a few ulp of the exact values) rounded to float32, the same
    on every CPU: where every value within :data:`CERTAINTY_MARGIN` of ``fast`` rounds to one
    float32, that is the float32 of the exact value too; the other texels (about 1 in 10**6)
    take ``exact(mask)`` (the portable computation of the values at ``mask``)."""
    out = fast.astype(np.float32)
    with np.errstate(over="ignore", invalid="ignore"):
        unsure = (fast * (1.0 - CERTAINTY_MARGIN)).astype(np.float32) != (
            fast * (1.0 + CERTAINTY_MARGIN)
        ).astype(np.float32)
    if unsure.any():
        out[unsure] = exact(unsure).astype(np.float32)
    return out


def linear_to_srgb(values: ArrayLike) -> np.ndarray:
    """Encode linear values to sRGB: 12.92 v or 1.055 v^(1/2.4) - 0.055.

    Computed element-wise in the input's float dtype (float64 for non-float input); values are
    not clipped here (the PNG quantiser clips). NaN stays NaN.
    """
    return _encode(_float_array(values), _power)


def fast_linear_to_srgb(linear: np.ndarray) -> np.ndarray:
    """:func:`linear_to_srgb` of a float64 array with numpy's own ``power``: fast, but its last
    bit depends on the CPU. Only where a certainty test hides that bit (the flat preview's
    quantisation, :func:`matloom.render.preview.shade`)."""
    return _encode(linear, np.power)


def _encode(linear: np.ndarray, power: Callable[[np.ndarray, float], np.ndarray]) -> np.ndarray:
    """The sRGB encode curve of ``linear`` with the given ``power(base, exponent)``."""
    with np.errstate(invalid="ignore"):  # negative inputs: NaN in the discarded branch
        encoded = np.asarray(1.055 * power(linear, 1 / 2.4) - 0.055)
    np.copyto(encoded, linear * 12.92, where=linear <= SRGB_ENCODE_THRESHOLD)
    return encoded
