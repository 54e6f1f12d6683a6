"""Windowed power spectra of scalar maps and their directional energy.

Periodic peaks are found in these spectra by :mod:`matloom.render.spectral_peaks`.

Conventions (shared with :mod:`matloom.render.visible_stats`):

* The field is sampled on the map's pixel grid, row 0 at the top; the frequency axes are
  ``kx`` (cycles across the image width, + to the right) and ``ky`` (cycles across the image
  height, + upward), so angles are those a viewer sees on screen (square pixels).
* **Orientation** is the direction in which the value *changes* (the wave vector), in degrees
  counter-clockwise from +X, folded into [0, 180): 0 = the value varies along X (vertical
  stripes), 90 = it varies along Y (horizontal bands), 45 = it varies along the up-right
  diagonal (stripes running from top-left to bottom-right), 135 = stripes running from
  bottom-left to top-right.
* Before the transform the field loses its mean (over the mask) and is multiplied by a
  periodic 2-D Hann window, so that a pattern which does not tile the image does not smear
  its energy over every frequency. The power is normalised so that it sums to about the
  variance of the field.

The **directionality** (anisotropy) is the length of the energy-weighted mean of the doubled
wave-vector angle over the bins from radius :data:`MIN_DIRECTION_RADIUS` to the inscribed
circle (the corners are left out: they exist only toward the diagonals): 1 when all the
energy has one orientation (stripes), 0 when it has none (isotropic noise) or when two
orientations at right angles balance (a checker or a square grid).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

#: Lowest radius (bins) that counts toward the directionality.
MIN_DIRECTION_RADIUS: float = 2.0

#: Fields smaller than this on either side get no spectrum.
MIN_SIZE: int = 16


@dataclass(frozen=True)
class Spectrum:
    """A centred (fftshifted) power spectrum of one field.

    ``power[i, j]`` is the power at ``kx[j]`` cycles across the width and ``ky[i]`` cycles
    across the height (+ upward); ``total`` is the power summed over every bin.
    """

    power: np.ndarray
    width: int
    height: int

    @property
    def total(self) -> float:
        return float(self.power.sum())


def fold_angle(angle_deg: float) -> float:
    """Angle folded into [0, 180), rounding -0 and 180 to 0."""
    folded = angle_deg % 180.0
    return 0.0 if folded >= 180.0 - 1e-9 else folded


def angle_difference(a_deg: float, b_deg: float) -> float:
    """Smallest difference between two orientations (mod 180), in [0, 90]."""
    d = abs(a_deg - b_deg) % 180.0
    return min(d, 180.0 - d)


@lru_cache(maxsize=8)
def _window(height: int, width: int) -> np.ndarray:
    """Periodic 2-D Hann window (read-only)."""
    rows = 0.5 - 0.5 * np.cos(2.0 * np.pi * np.arange(height) / height)
    cols = 0.5 - 0.5 * np.cos(2.0 * np.pi * np.arange(width) / width)
    window = rows[:, None] * cols[None, :]
    window.setflags(write=False)
    return window


@lru_cache(maxsize=8)
def spectrum_geometry(
    height: int, width: int
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """For a centred spectrum: kx (row vector), ky (column vector, + up), radius in bins and
    radial frequency in cycles per pixel (both full arrays, read-only)."""
    kx = (np.arange(width) - width // 2)[None, :].astype(np.float64)
    ky = -(np.arange(height) - height // 2)[:, None].astype(np.float64)
    radius = np.hypot(kx, ky)
    rho = np.hypot(kx / width, ky / height)
    for array in (kx, ky, radius, rho):
        array.setflags(write=False)
    return kx, ky, radius, rho


def power_spectrum(field: np.ndarray, mask: np.ndarray | None = None) -> Spectrum | None:
    """Windowed power spectrum of ``field`` over ``mask`` (None: everywhere).

    The spectrum covers the bounding box of the mask (the whole field when it is full), so
    that the window tapers to the material's own edges; texels outside the mask and
    non-finite values count as the mean. None when that box is smaller than
    :data:`MIN_SIZE` on a side or the mask is empty.
    """
    values = np.asarray(field, dtype=np.float64)
    if values.ndim != 2:
        return None
    inside = np.isfinite(values) if mask is None else (np.asarray(mask, bool) & np.isfinite(values))
    if not inside.any():
        return None
    rows = np.flatnonzero(inside.any(axis=1))
    cols = np.flatnonzero(inside.any(axis=0))
    box = (slice(rows[0], rows[-1] + 1), slice(cols[0], cols[-1] + 1))
    values, inside = values[box], inside[box]
    height, width = values.shape
    if min(height, width) < MIN_SIZE:
        return None
    window = _window(height, width)
    centred = np.where(inside, values - values[inside].mean(), 0.0) * window
    magnitude = np.fft.fftshift(np.fft.fft2(centred))
    scale = float((window * window).sum()) * height * width
    power = (magnitude.real**2 + magnitude.imag**2) / scale
    return Spectrum(power=power, width=width, height=height)


def directionality(spec: Spectrum, *, slope_weighted: bool = False) -> tuple[float, float, float]:
    """(anisotropy in [0, 1], orientation in degrees, band power) of the spectrum.

    Bins from :data:`MIN_DIRECTION_RADIUS` to the inscribed circle count, weighted by their
    power (``slope_weighted``: times the squared frequency, i.e. the energy of the slope, for
    height fields seen through their shading). The band power is the summed weight before
    that optional factor (about the variance of the detail above the lowest bins).
    """
    height, width = spec.power.shape
    kx, ky, radius, rho = spectrum_geometry(height, width)
    band = (radius >= MIN_DIRECTION_RADIUS) & (rho <= 0.5)
    fx = np.broadcast_to(kx / width, spec.power.shape)[band]
    fy = np.broadcast_to(ky / height, spec.power.shape)[band]
    weight = spec.power[band]
    band_power = float(weight.sum())
    if slope_weighted:
        weight = weight * (fx * fx + fy * fy)
    total = float(weight.sum())
    if total <= 0.0:
        return 0.0, 0.0, band_power
    # cos/sin of the doubled angle without trigonometry: (fx^2 - fy^2, 2 fx fy) / |f|^2.
    r2 = fx * fx + fy * fy
    c = float((weight * (fx * fx - fy * fy) / r2).sum())
    s = float((weight * (2.0 * fx * fy) / r2).sum())
    anisotropy = min(1.0, math.hypot(c, s) / total)
    orientation = fold_angle(math.degrees(0.5 * math.atan2(s, c)))
    return anisotropy, orientation, band_power
