"""Statistics that compare a render with a reference photo (``generate --reference``).

Both images are sRGB, the same size (the caller resizes the photo), and are described the same
way, so that a critic (and the parameter fit of ``--polish``) can tell how far apart they are:

* **Colour distribution** in CIELAB (D65, the same formulas as ``author/edit/colours.py``):
  the mean L*a*b* and the 5, 25, 50, 75 and 95 % quantiles of each of L*, a* and b*.
* **Contrast**: the standard deviation of L* (0-100), the RMS contrast a viewer sees.
* **Detail per scale**: the standard deviation of L* in octave bands of the windowed power
  spectrum (:mod:`matloom.render.spectrum`): 2-4, 4-8, ... repeats across the image, up to
  the pixel grid's limit. A photo of fine sand and a render of coarse blobs differ here even
  when their colours agree.
* **Directionality** of the L* detail (0 = none, 1 = stripes) and its orientation, and the
  **dominant periods**: up to two periodic components of the L* spectrum
  (:func:`matloom.render.spectral_peaks.find_peaks`) with their period in pixels and
  orientation (degrees, the direction in which the value changes: 0 = vertical stripes).
  An image whose L* varies by less than :data:`MIN_CONTRAST` has neither (its spectrum is
  quantisation noise).

:func:`stats_distance` sums these differences into one number (0 = the same statistics; about
1 per clearly visible difference), which ``--polish cmaes`` minimises when a reference photo
is given. Its terms and their scales are :data:`WEIGHTS`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from matloom.render import spectral_peaks, spectrum

#: Quantiles of L*, a* and b* that describe the colour distribution.
QUANTILES: tuple[float, ...] = (0.05, 0.25, 0.5, 0.75, 0.95)

#: The distance's terms: each difference is divided by its scale (a clearly visible
#: difference), then summed. ``colour`` is in CIELAB units (Delta E), ``contrast`` in L* units,
#: ``detail`` the summed difference of the bands' L* standard deviations, ``direction``
#: anisotropy units (counted in full only when both images have :data:`DIRECTION_CONTRAST`),
#: ``period`` octaves (log2 of the ratio of the dominant periods).
WEIGHTS: dict[str, float] = {
    "colour": 10.0,
    "contrast": 5.0,
    "detail": 5.0,
    "direction": 0.5,
    "period": 1.0,
}

#: L* standard deviation under which an image has no direction and no period.
MIN_CONTRAST: float = 1.0

#: L* standard deviation from which the direction term counts in full (less: in proportion).
DIRECTION_CONTRAST: float = 5.0

#: A photo peak counts as matched by a render peak within this many degrees of orientation.
MATCH_ANGLE_DEG: float = 20.0

#: The period term when one image repeats and the other does not (in octaves).
UNMATCHED_PERIOD: float = 1.0

#: Lowest band edge, in repeats across the image (lower holds the window's leakage).
FIRST_BAND: float = 2.0

_WHITE = (0.95047, 1.0, 1.08883)
_XYZ = (
    np.array([[0.4124, 0.3576, 0.1805], [0.2126, 0.7152, 0.0722], [0.0193, 0.1192, 0.9505]])
    / np.array(_WHITE)[:, None]
)


@dataclass(frozen=True)
class PeriodInfo:
    """A periodic component: period in pixels, orientation in degrees, strength."""

    period_px: float
    orientation_deg: float
    strength: float


@dataclass(frozen=True)
class ImageStats:
    """The comparison statistics of one image (see the module docstring)."""

    width: int
    height: int
    lab_mean: tuple[float, float, float]
    #: Per channel (L*, a*, b*): its values at :data:`QUANTILES`.
    lab_quantiles: tuple[tuple[float, ...], ...]
    contrast: float
    #: Standard deviation of L* per octave band (``band_edges`` gives the bands).
    bands: tuple[float, ...]
    band_edges: tuple[float, ...]
    anisotropy: float
    orientation_deg: float
    periods: tuple[PeriodInfo, ...]


def srgb_to_lab(image: np.ndarray) -> np.ndarray:
    """CIELAB (D65) of an (H, W, 3) sRGB image (uint8 0-255 or float 0-255), float64."""
    rgb = np.asarray(image, dtype=np.float64)[..., :3] / 255.0
    linear = np.where(rgb <= 0.04045, rgb / 12.92, ((rgb + 0.055) / 1.055) ** 2.4)
    xyz = linear @ _XYZ.T
    f = np.where(xyz > 216 / 24389, np.cbrt(xyz), (24389 / 27 * xyz + 16) / 116)
    lab = np.empty_like(f)
    lab[..., 0] = 116 * f[..., 1] - 16
    lab[..., 1] = 500 * (f[..., 0] - f[..., 1])
    lab[..., 2] = 200 * (f[..., 1] - f[..., 2])
    return lab


def _band_edges(height: int, width: int) -> tuple[float, ...]:
    top = min(height, width) / 2.0
    edges = [FIRST_BAND]
    while edges[-1] * 2 < top:
        edges.append(edges[-1] * 2)
    edges.append(top)
    return tuple(edges)


def _bands(spec: spectrum.Spectrum | None, edges: tuple[float, ...]) -> tuple[float, ...]:
    """Standard deviation in each band [edges[i], edges[i+1]) of radius (repeats per image):
    the square root of its power (the spectrum sums to about the variance)."""
    if spec is None:
        return tuple(0.0 for _ in edges[1:])
    height, width = spec.power.shape
    radius = spectrum.spectrum_geometry(height, width)[2]
    return tuple(
        math.sqrt(float(spec.power[(radius >= lo) & (radius < hi)].sum()))
        for lo, hi in zip(edges[:-1], edges[1:], strict=True)
    )


def image_stats(image: np.ndarray) -> ImageStats:
    """The comparison statistics of an (H, W, 3) sRGB image."""
    lab = srgb_to_lab(image)
    height, width = lab.shape[:2]
    flat = lab.reshape(-1, 3)
    lightness = lab[..., 0]
    spec = spectrum.power_spectrum(lightness)
    edges = _band_edges(height, width)
    anisotropy, orientation = 0.0, 0.0
    periods: tuple[PeriodInfo, ...] = ()
    if spec is not None and float(lightness.std()) >= MIN_CONTRAST:
        anisotropy, orientation, _ = spectrum.directionality(spec)
        periods = tuple(
            PeriodInfo(p.period_px, p.orientation_deg, p.strength)
            for p in spectral_peaks.find_peaks(spec)
        )
    quantiles = np.quantile(flat, QUANTILES, axis=0)  # (len(QUANTILES), 3)
    mean = flat.mean(axis=0)
    return ImageStats(
        width=width,
        height=height,
        lab_mean=(float(mean[0]), float(mean[1]), float(mean[2])),
        lab_quantiles=tuple(tuple(float(v) for v in quantiles[:, c]) for c in range(3)),
        contrast=float(lightness.std()),
        bands=_bands(spec, edges),
        band_edges=edges,
        anisotropy=float(anisotropy),
        orientation_deg=float(orientation),
        periods=periods,
    )


def _period_term(render: ImageStats, photo: ImageStats) -> float:
    """Octaves between the photo's dominant period and the render's period nearest in
    orientation; :data:`UNMATCHED_PERIOD` when only one of them repeats."""
    if not photo.periods:
        return UNMATCHED_PERIOD / 2 if render.periods else 0.0
    target = photo.periods[0]
    near = [
        p
        for p in render.periods
        if spectrum.angle_difference(p.orientation_deg, target.orientation_deg) <= MATCH_ANGLE_DEG
    ]
    if not near:
        return UNMATCHED_PERIOD
    return min(abs(math.log2(p.period_px / target.period_px)) for p in near)


def distance_terms(render: ImageStats, photo: ImageStats) -> dict[str, float]:
    """Each term of :func:`stats_distance`, already divided by its scale in :data:`WEIGHTS`."""
    if (render.width, render.height) != (photo.width, photo.height):
        raise ValueError("compare images of the same size (resize the photo first)")
    mean_delta = math.dist(render.lab_mean, photo.lab_mean)
    spread = float(
        np.mean(np.abs(np.asarray(render.lab_quantiles) - np.asarray(photo.lab_quantiles)))
    )
    detail = float(np.abs(np.asarray(render.bands) - np.asarray(photo.bands)).sum())
    turn = spectrum.angle_difference(render.orientation_deg, photo.orientation_deg) / 90.0
    direction = abs(render.anisotropy - photo.anisotropy)
    direction += min(render.anisotropy, photo.anisotropy) * turn
    direction *= min(1.0, min(render.contrast, photo.contrast) / DIRECTION_CONTRAST)
    raw = {
        "colour": (mean_delta + spread) / 2,
        "contrast": abs(render.contrast - photo.contrast),
        "detail": detail,
        "direction": direction,
        "period": _period_term(render, photo),
    }
    return {name: value / WEIGHTS[name] for name, value in raw.items()}


def stats_distance(render: ImageStats, photo: ImageStats) -> float:
    """One number for how far the render's statistics are from the photo's (0 = the same)."""
    return float(sum(distance_terms(render, photo).values()))


def _n(value: float) -> str:
    """One decimal, without a minus sign on zero."""
    return f"{round(value, 1) + 0.0:.1f}"


def _triple(values: tuple[float, ...]) -> str:
    return "(" + ", ".join(_n(v) for v in values) + ")"


def _periods(stats: ImageStats) -> str:
    if not stats.periods:
        return "none"
    return "; ".join(f"{p.period_px:.1f} px at {p.orientation_deg:.0f} deg" for p in stats.periods)


def _bands_text(stats: ImageStats) -> str:
    return "/".join(_n(std) for std in stats.bands)


def comparison_text(render: ImageStats, photo: ImageStats) -> str:
    """The comparison as lines for a critic (render first, photo second)."""
    terms = distance_terms(render, photo)
    edges = render.band_edges
    band_names = ", ".join(f"{lo:g}-{hi:g}" for lo, hi in zip(edges[:-1], edges[1:], strict=True))
    l_lo, l_hi = render.lab_quantiles[0][0], render.lab_quantiles[0][-1]
    p_lo, p_hi = photo.lab_quantiles[0][0], photo.lab_quantiles[0][-1]
    lines = [
        f"Render vs reference photo (both {render.width} x {render.height} px; CIELAB, "
        "L* 0-100; the render is the flat preview, the photo is lit as it was taken):",
        f"- mean colour L*a*b*: render {_triple(render.lab_mean)}, photo "
        f"{_triple(photo.lab_mean)} (Delta E {math.dist(render.lab_mean, photo.lab_mean):.1f})",
        f"- L* 5-95 %: render {l_lo:.0f}-{l_hi:.0f}, photo {p_lo:.0f}-{p_hi:.0f}; "
        f"a* median render {_n(render.lab_quantiles[1][2])}, photo "
        f"{_n(photo.lab_quantiles[1][2])}; b* median render {_n(render.lab_quantiles[2][2])}, "
        f"photo {_n(photo.lab_quantiles[2][2])}",
        f"- contrast (std of L*): render {render.contrast:.1f}, photo {photo.contrast:.1f}",
        f"- detail per scale (std of L* at {band_names} repeats across the image): "
        f"render {_bands_text(render)}, photo {_bands_text(photo)}",
        f"- directionality (0 none, 1 stripes): render {render.anisotropy:.2f} at "
        f"{render.orientation_deg:.0f} deg, photo {photo.anisotropy:.2f} at "
        f"{photo.orientation_deg:.0f} deg",
        f"- repeating pattern: render {_periods(render)}; photo {_periods(photo)}",
        "- distance per term (1 = a clearly visible difference): "
        + ", ".join(f"{name} {value:.2f}" for name, value in terms.items())
        + f"; total {sum(terms.values()):.2f}",
    ]
    return "\n".join(lines)
