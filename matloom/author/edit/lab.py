"""CIELAB (D65) of sRGB colours, one colour at a time: what the edit rules move colours in (a
comparative step, a tint, a named colour's distance) and measure Delta E with."""

from __future__ import annotations

import math
from collections.abc import Sequence

from matloom.library.colour import RGB, clamp_rgb

Lab = tuple[float, float, float]


def _lin(c: float) -> float:
    c /= 255.0
    return c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4


def _enc(c: float) -> float:
    c = max(0.0, c)
    v = 12.92 * c if c <= 0.0031308 else 1.055 * c ** (1 / 2.4) - 0.055
    return v * 255.0


def _f(t: float) -> float:
    return t ** (1 / 3) if t > 216 / 24389 else (24389 / 27 * t + 16) / 116


def _finv(t: float) -> float:
    return t**3 if t**3 > 216 / 24389 else (116 * t - 16) / (24389 / 27)


_WHITE = (0.95047, 1.0, 1.08883)


def to_lab(rgb: Sequence[float]) -> Lab:
    r, g, b = (_lin(float(c)) for c in rgb)
    x = (0.4124 * r + 0.3576 * g + 0.1805 * b) / _WHITE[0]
    y = (0.2126 * r + 0.7152 * g + 0.0722 * b) / _WHITE[1]
    z = (0.0193 * r + 0.1192 * g + 0.9505 * b) / _WHITE[2]
    fx, fy, fz = _f(x), _f(y), _f(z)
    return (116 * fy - 16, 500 * (fx - fy), 200 * (fy - fz))


def from_lab(lab: Lab) -> RGB:
    """The sRGB colour of ``lab``, its chroma reduced until it fits the gamut."""
    L, a, b = lab
    for k in range(21):
        s = 1.0 - k * 0.05
        fy = (L + 16) / 116
        fx, fz = fy + a * s / 500, fy - b * s / 200
        x, y, z = _finv(fx) * _WHITE[0], _finv(fy) * _WHITE[1], _finv(fz) * _WHITE[2]
        rgb = (
            3.2406 * x - 1.5372 * y - 0.4986 * z,
            -0.9689 * x + 1.8758 * y + 0.0415 * z,
            0.0557 * x - 0.2040 * y + 1.0570 * z,
        )
        if all(-1e-3 <= v <= 1.001 for v in rgb) or k == 20:
            return clamp_rgb(tuple(_enc(v) for v in rgb))  # type: ignore[arg-type]
    raise AssertionError("unreachable")


def delta_e(a: Sequence[float], b: Sequence[float]) -> float:
    la, lb = to_lab(a), to_lab(b)
    return math.dist(la, lb)


def mix(a: RGB, b: RGB, t: float = 0.5) -> RGB:
    """``t`` of the way from ``a`` to ``b`` in CIELAB."""
    la, lb = to_lab(a), to_lab(b)
    return from_lab(tuple(x + (y - x) * t for x, y in zip(la, lb, strict=True)))  # type: ignore[arg-type]


def tinted(current: RGB, named: RGB, share: float, least: float, most: float) -> Lab:
    """``current`` with its hue and chroma ``share`` of the way to ``named``'s, its lightness
    kept; a share too small to see (under ``least`` Delta E) grows up to ``most``."""
    cur, nl = to_lab(current), to_lab(named)
    share = max(share, 0.05)
    for _ in range(12):  # 0.05 * 1.5 ** 12 > most: bounded whatever the share
        lab = (cur[0], cur[1] + (nl[1] - cur[1]) * share, cur[2] + (nl[2] - cur[2]) * share)
        if delta_e(current, from_lab(lab)) >= least or share >= most:
            break
        share = min(most, share * 1.5)
    return lab
