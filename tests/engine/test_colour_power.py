"""The sRGB curves' float32 power: numpy's fast power where its float32 rounding is certain, the
portable power elsewhere -- the same bits as the portable power everywhere."""

from __future__ import annotations

import numpy as np
import pytest

from matloom.engine import colour
from matloom.engine.kernels.mathops import pow_


def _portable(base: np.ndarray, exponent: float) -> np.ndarray:
    return np.asarray(pow_(base, np.asarray(exponent, dtype=base.dtype)))


def _samples() -> list[np.ndarray]:
    rng = np.random.default_rng(23)
    start = int(rng.integers(0, 2**32 - 300_000))
    bits = np.arange(start, start + 300_000, dtype=np.uint64).astype(np.uint32)
    wide = np.exp(rng.normal(0.0, 20.0, 300_000)).clip(0.0, 3e38).astype(np.float32)
    wide[::97], wide[::89], wide[::83], wide[::79], wide[::73] = np.nan, np.inf, -np.inf, 0, -0.0
    return [
        rng.random(300_000, dtype=np.float32),
        (rng.random(300_000) * 3.0 - 1.0).astype(np.float32),
        bits.view(np.float32),  # every bit pattern of a slice: NaNs, subnormals, ...
        wide,
        rng.random((7, 300, 3), dtype=np.float32)[:, ::2],  # not contiguous
    ]


@pytest.mark.parametrize("exponent", [1 / 2.4, 2.4, 0.5, 2.2])
def test_float32_power_has_the_portable_bits(exponent: float) -> None:
    for base in _samples():
        with np.errstate(all="ignore"):
            fast = colour._power(base, exponent)
        exact = _portable(base, exponent)
        assert fast.dtype == exact.dtype == np.float32 and fast.shape == exact.shape
        assert np.array_equal(fast.view(np.uint32), exact.view(np.uint32))


def test_curves_keep_dtype_and_scalars() -> None:
    assert colour.linear_to_srgb(np.float32(0.5)).dtype == np.float32
    assert colour.linear_to_srgb(np.zeros((2, 3), np.float32)).shape == (2, 3)
    assert colour.srgb_to_linear(0.5).dtype == np.float64
    values = np.linspace(0.0, 1.0, 1001, dtype=np.float32)
    assert np.allclose(colour.srgb_to_linear(colour.linear_to_srgb(values)), values, atol=1e-6)
