"""``/api/compare``: how far apart two versions of a program are on one map (the inspector's
A/B compare): PSNR and SSIM of the map as the studio shows it (:mod:`matloom.studio.wire`).

SSIM is the usual one (Wang et al. 2004) with a 7 x 7 uniform window, K1 = 0.01, K2 = 0.03, on
values scaled to [0, 1], averaged over the channels; float maps (height, ior) are scaled by the
range of both versions together.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from matloom.studio.protocol import ApiError

WINDOW = 7


def _box(a: np.ndarray, k: int) -> np.ndarray:
    """Mean over every k x k window (valid positions only), by summed-area tables."""
    s = np.pad(a, ((1, 0), (1, 0))).cumsum(0).cumsum(1)
    return (s[k:, k:] - s[:-k, k:] - s[k:, :-k] + s[:-k, :-k]) / (k * k)


def ssim(a: np.ndarray, b: np.ndarray) -> float:
    """Mean SSIM of two (H, W) or (H, W, C) arrays on [0, 1]."""
    a = a.astype(np.float64).reshape(a.shape[0], a.shape[1], -1)
    b = b.astype(np.float64).reshape(b.shape[0], b.shape[1], -1)
    k = min(WINDOW, a.shape[0], a.shape[1])
    c1, c2 = 0.01**2, 0.03**2
    values = []
    for ch in range(a.shape[2]):
        x, y = a[..., ch], b[..., ch]
        mx, my = _box(x, k), _box(y, k)
        vx = _box(x * x, k) - mx * mx
        vy = _box(y * y, k) - my * my
        cov = _box(x * y, k) - mx * my
        num = (2 * mx * my + c1) * (2 * cov + c2)
        den = (mx * mx + my * my + c1) * (vx + vy + c2)
        values.append(float(np.mean(num / den)))
    return float(np.mean(values))


def psnr(a: np.ndarray, b: np.ndarray) -> float | None:
    """PSNR in dB of two arrays on [0, 1]; None when they are identical (infinite)."""
    mse = float(np.mean((a.astype(np.float64) - b.astype(np.float64)) ** 2))
    return None if mse == 0 else 10 * math.log10(1.0 / mse)


def unit_pair(a: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Both arrays on [0, 1]: u8 / 255, floats by their joint finite range."""
    if a.dtype == np.uint8:
        return a / 255.0, b / 255.0
    a64 = np.nan_to_num(a.astype(np.float64), nan=0.0, posinf=0.0, neginf=0.0)
    b64 = np.nan_to_num(b.astype(np.float64), nan=0.0, posinf=0.0, neginf=0.0)
    low = min(a64.min(), b64.min())
    span = max(a64.max(), b64.max()) - low
    if span <= 0:
        return np.zeros_like(a64), np.zeros_like(b64)
    return (a64 - low) / span, (b64 - low) / span


def compare_maps(maps_a: dict[str, np.ndarray], maps_b: dict[str, np.ndarray], name: str) -> dict:
    """``{psnr, ssim, map, identical}`` of map ``name`` (a map one version lacks counts as its
    default, zeros)."""
    if name not in maps_a and name not in maps_b:
        known = sorted(set(maps_a) | set(maps_b))
        raise ApiError(400, f"unknown map {name!r}; choose from {', '.join(known)}")
    ref = maps_a.get(name, maps_b.get(name))
    assert ref is not None
    a = maps_a.get(name, np.zeros_like(ref))
    b = maps_b.get(name, np.zeros_like(ref))
    x, y = unit_pair(a, b)
    value = psnr(x, y)
    result: dict[str, Any] = {"map": name, "psnr": value, "ssim": ssim(x, y)}
    result["identical"] = value is None
    return result
