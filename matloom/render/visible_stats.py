"""Statistics of what a viewer sees in the preview: an addition to the paper's 28 statistics.

:mod:`matloom.render.stats` keeps the paper's 28 statistics on a 128x128 grid (reference
parity). This module describes the maps *as given*, at the resolution the critic looks at
(e.g. 512x512), so fine weaves, glue lines and veins are still there, and it reports things
a reader can check against the picture:

* **Constant channels** once, as values ("metallic 0, IOR 1.5"), instead of means and spreads
  that only repeat the code. A channel is constant when its range over the material is at most
  :data:`CONSTANT_RANGE` (the base colour: when every sRGB component spans less than half an
  8-bit level).
* **Albedo**: mean colour in sRGB (0-255), luminance mean, spread and 5-95 % range (Rec.709
  luma of the sRGB albedo, 0-255), RMS contrast, saturation.
* **Repeating pattern** of the albedo luminance and of the height: the strongest periodic
  component of a windowed spectrum, ignoring the lowest bins (broad noise), reported with its
  period in pixels, its frequency in cycles per image (the square root of the image's
  pixel count over the period: repeats across a square image), its orientation (defined in
  :mod:`matloom.render.spectrum`: 0 deg = the value changes along X, i.e. vertical stripes;
  90 deg = along Y, horizontal bands), its strength and, for thin lines and sharp edges, its
  number of harmonics (:mod:`matloom.render.spectral_peaks`); "none" when no peak stands
  out. A second pattern at another orientation (a grid, a weave, a checker) is reported too.
* **Directionality** (anisotropy) in [0, 1] with its orientation: the share of the contrast
  above the lowest bins that has one orientation (albedo: luminance energy; relief: slope
  energy). "n/a" when there is too little contrast to have a direction: an albedo luminance
  standard deviation under :data:`MIN_LUMINANCE_STD` (0-255 scale), or a relief whose mean
  surface tilt is under :data:`MIN_MEAN_TILT_DEG`.
* **Ranges** of the other varying channels (5-95 % and mean), the metal share, the height
  range in coordinate units and in pixels of the maps, the surface tilt, AO and emission.

Everything is taken over the material region (coverage above 1e-3), with NaN/inf as in
:mod:`matloom.render.stats`.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from matloom.engine.maps import MaterialMaps
from matloom.render import spectral_peaks, spectrum
from matloom.render.stats import MASK_THRESHOLD, _finite, _luminance, _saturation, _srgb_albedo

#: The resolution the critic's preview is rendered at (what callers usually evaluate at).
VISIBLE_GRID: int = 512

#: Albedo luminance standard deviation (0-255) under which there is no visible pattern.
MIN_LUMINANCE_STD: float = 2.0

#: Mean surface tilt (degrees) under which the relief is too shallow to show a direction.
MIN_MEAN_TILT_DEG: float = 0.5

#: A scalar channel whose range over the material is at most this is constant.
CONSTANT_RANGE: float = 1e-4

#: A height whose range is at most this (coordinate units) is flat.
FLAT_HEIGHT_RANGE: float = 1e-7

#: The base colour is constant when every sRGB component spans less than this (0-255).
CONSTANT_COLOUR_RANGE: float = 0.5

#: Scalar channels reported as constants or ranges, in reporting order (field, label).
_SCALARS: tuple[tuple[str, str], ...] = (
    ("roughness", "roughness"),
    ("metallic", "metallic"),
    ("sheen", "sheen"),
    ("coat", "clearcoat"),
    ("transmission", "transmission"),
    ("subsurface", "subsurface"),
    ("anisotropy", "anisotropy"),
    ("anisotropy_angle", "anisotropy angle"),
    ("ior", "IOR"),
)

#: Strengths above this are reported as this (a clean synthetic pattern has no background).
STRENGTH_CAP: float = 1e6

#: How many repeating patterns are reported per map.
PATTERN_LIMIT: int = 2

#: Two patterns whose periods differ by at most this share form one lattice (a grid, a checker).
LATTICE_TOLERANCE: float = 0.03


def _number(value: float) -> str:
    """Compact number: 3 significant digits, no exponent for ordinary magnitudes."""
    if value == 0 or not math.isfinite(value):
        return "0" if value == 0 else str(value)
    magnitude = abs(value)
    if magnitude >= 100:
        return f"{value:.0f}"
    if magnitude >= 0.001:
        return f"{value:.3g}"
    return f"{value:.2e}"


def _summary(values: np.ndarray) -> dict[str, float]:
    """mean, 5th and 95th percentiles, min and max of a 1-D array."""
    p5, p95 = np.percentile(values, (5.0, 95.0))
    return {
        "mean": float(values.mean()),
        "p5": float(p5),
        "p95": float(p95),
        "min": float(values.min()),
        "max": float(values.max()),
    }


def _spectral(field: np.ndarray, mask: np.ndarray, slope: bool) -> dict[str, Any]:
    """{"patterns": [...], "directionality": {value, orientation_deg} or None} of a field."""
    spec = spectrum.power_spectrum(field, mask)
    if spec is None:
        return {"patterns": [], "directionality": None}
    patterns = [
        {
            "period_px": peak.period_px,
            "cycles_per_image": math.sqrt(field.shape[0] * field.shape[1]) / peak.period_px,
            "orientation_deg": peak.orientation_deg,
            "strength": min(peak.strength, STRENGTH_CAP),
            "harmonics": peak.harmonics,
        }
        for peak in spectral_peaks.find_peaks(spec, limit=PATTERN_LIMIT)
    ]
    anisotropy, orientation, band_power = spectrum.directionality(spec, slope_weighted=slope)
    direction = {"value": anisotropy, "orientation_deg": orientation} if band_power > 0 else None
    return {"patterns": patterns, "directionality": direction}


def _albedo(maps: MaterialMaps, mask: np.ndarray) -> tuple[dict[str, Any], list[float] | None]:
    """The albedo section, and the constant sRGB colour (0-255) when it does not vary."""
    albedo = _srgb_albedo(np.moveaxis(maps.basecolor_linear, -1, 0))
    inside = albedo[:, mask]
    mean_srgb = [float(v) * 255.0 for v in inside.mean(axis=1)]
    if max(float(np.ptp(plane)) for plane in inside) * 255.0 < CONSTANT_COLOUR_RANGE:
        return {}, mean_srgb
    luminance = _luminance(albedo)
    lum = luminance[mask] * 255.0
    lum_mean, lum_std = float(lum.mean()), float(lum.std())
    p5, p95 = np.percentile(lum, (5.0, 95.0))
    section: dict[str, Any] = {
        "mean_srgb": mean_srgb,
        "luminance_mean": lum_mean,
        "luminance_std": lum_std,
        "luminance_p5": float(p5),
        "luminance_p95": float(p95),
        "rms_contrast": lum_std / lum_mean if lum_mean > 1e-6 else 0.0,
        "saturation": float(_saturation(inside).mean()),
    }
    if lum_std >= MIN_LUMINANCE_STD:
        section.update(_spectral(luminance, mask, slope=False))
    else:
        section.update(patterns=None, directionality=None)
    return section, None


def _relief(maps: MaterialMaps, mask: np.ndarray) -> tuple[dict[str, Any], float | None]:
    """The height section, and the constant height when the surface is flat."""
    height = _finite(maps.height)
    inside = height[mask]
    span = float(inside.max() - inside.min())
    if span <= FLAT_HEIGHT_RANGE:
        return {}, float(inside.mean())
    dx, dy = maps.view.texel_size(maps.width, maps.height_px)
    texel = math.sqrt(dx * dy) if dx > 0 and dy > 0 else 0.0
    nz = np.clip(_finite(maps.normal[..., 2], fallback=1.0)[mask], -1.0, 1.0)
    tilt = np.degrees(np.arccos(nz))
    ao = _finite(maps.ao, fallback=1.0)[mask]
    section: dict[str, Any] = {
        "range_units": span,
        "range_px": span / texel if texel > 0 else None,
        "std_units": float(inside.std()),
        "tilt_mean_deg": float(tilt.mean()),
        "tilt_p95_deg": float(np.percentile(tilt, 95.0)),
        "ao_mean": float(ao.mean()),
        "ao_p5": float(np.percentile(ao, 5.0)),
    }
    if section["tilt_mean_deg"] >= MIN_MEAN_TILT_DEG:
        section.update(_spectral(height, mask, slope=True))
    else:
        section.update(patterns=None, directionality=None)
    return section, None


def visible_stats(maps: MaterialMaps) -> dict[str, Any]:
    """Statistics of ``maps`` at their own resolution, as a JSON-ready dict.

    Keys:

    * ``size`` [width, height]; ``texel_units`` (coordinate units per pixel); ``coverage``
      (share of the image that is material); ``layers``;
    * ``constants`` {label: value}: the base colour as ``basecolor_srgb`` [r, g, b] (0-255),
      ``height`` when flat, ``emissive`` 0 when nothing glows;
    * ``albedo`` (absent when the colour is constant): ``mean_srgb``,
      ``luminance_mean/std/p5/p95`` (0-255), ``rms_contrast``, ``saturation``, ``patterns``
      (list of {period_px, cycles_per_image, orientation_deg, strength, harmonics}; None when
      the contrast is too low), ``directionality`` ({value, orientation_deg} or None);
    * ``channels`` {label: {mean, p5, p95, min, max}} for the varying scalar channels;
      ``metal_share`` (share with metallic > 0.5, when metallic varies);
    * ``relief`` (absent when flat): ``range_units``, ``range_px``, ``std_units``,
      ``tilt_mean_deg``, ``tilt_p95_deg``, ``ao_mean``, ``ao_p5``, ``patterns``,
      ``directionality``;
    * ``emissive`` {mean, max} of the emitted luminance when it varies or is not 0.
    """
    alpha = np.asarray(maps.alpha, dtype=np.float64)
    mask = alpha > MASK_THRESHOLD
    dx, dy = maps.view.texel_size(maps.width, maps.height_px)
    out: dict[str, Any] = {
        "size": [maps.width, maps.height_px],
        "texel_units": math.sqrt(dx * dy),
        "coverage": float(np.count_nonzero(mask)) / max(mask.size, 1),
        "layers": int(maps.n_layers),
    }
    if maps.n_layers == 0 or not mask.any():
        out["coverage"] = 0.0
        return out
    constants: dict[str, Any] = {}
    out["constants"] = constants
    albedo, colour = _albedo(maps, mask)
    if colour is not None:
        constants["basecolor_srgb"] = colour
    else:
        out["albedo"] = albedo

    channels: dict[str, dict[str, float]] = {}
    anisotropic = True
    for field, label in _SCALARS:
        values = _finite(getattr(maps, field))[mask]
        if field == "anisotropy_angle" and not anisotropic:
            continue  # the angle of no anisotropy is invisible
        if float(np.ptp(values)) <= CONSTANT_RANGE:
            constants[label] = float(values.mean())
            if field == "anisotropy" and constants[label] == 0.0:
                anisotropic = False
        else:
            channels[label] = _summary(values)
        if field == "metallic" and label in channels:
            out["metal_share"] = float(np.count_nonzero(values > 0.5)) / values.size
    out["channels"] = channels

    emissive = _luminance(np.maximum(_finite(np.moveaxis(maps.emissive_linear, -1, 0)), 0.0))
    glow = emissive[mask]
    if float(np.ptp(glow)) <= CONSTANT_RANGE and float(glow.max()) <= CONSTANT_RANGE:
        constants["emissive"] = 0.0
    else:
        out["emissive"] = {"mean": float(glow.mean()), "max": float(glow.max())}

    relief, flat = _relief(maps, mask)
    if flat is not None:
        constants["height"] = flat
    else:
        out["relief"] = relief
    return out


# --------------------------------------------------------------------------------------------
# Text


def _degrees(angle_deg: float) -> int:
    """Whole degrees in [0, 180) (179.7 shows as 0, the same orientation)."""
    return round(angle_deg) % 180


def orientation_words(angle_deg: float) -> str:
    """What a pattern whose value changes along ``angle_deg`` looks like (the convention of
    :mod:`matloom.render.spectrum`): within 10 degrees of 0 / 45 / 90 / 135 it is named,
    otherwise the direction its lines run is given."""
    names = {
        0: "vertical stripes",
        45: "diagonal stripes running top-left to bottom-right",
        90: "horizontal bands",
        135: "diagonal stripes running bottom-left to top-right",
    }
    for centre, words in names.items():
        if spectrum.angle_difference(angle_deg, centre) <= 10.0:
            return words
    return f"oblique stripes, lines running at {_degrees(angle_deg + 90.0)}° from +X"


def _strength_text(strength: float) -> str:
    return ">1000x" if strength > 1000 else f"{strength:.0f}x"


def _pattern_text(patterns: list[dict[str, Any]] | None, what: str) -> str:
    if patterns is None:
        return f"n/a (too little {what} to show a pattern)"
    if not patterns:
        return "none (no periodic peak stands out above the noise)"
    parts = []
    for k, p in enumerate(patterns):
        angle = p["orientation_deg"]
        lead = "every" if k == 0 else "also every"
        sharp = f", sharp-edged ({p['harmonics']} harmonics)" if p["harmonics"] >= 3 else ""
        parts.append(
            f"{lead} {p['period_px']:.1f} px ({p['cycles_per_image']:.1f} cycles per image) at "
            f"{_degrees(angle)}° ({orientation_words(angle)}), strength "
            f"{_strength_text(p['strength'])}{sharp}"
        )
    return "; ".join(parts) + _lattice_text(patterns)


def _lattice_text(patterns: list[dict[str, Any]]) -> str:
    """The two first patterns read together, when they are one lattice: equal periods (within
    :data:`LATTICE_TOLERANCE`) at right angles. Along the axes they are a grid of square cells
    of that period; along the diagonals a checker, whose squares' side is the period over
    sqrt 2 (its fundamentals are the diagonal waves)."""
    if len(patterns) < 2:
        return ""
    a, b = patterns[0], patterns[1]
    if abs(a["period_px"] - b["period_px"]) > LATTICE_TOLERANCE * a["period_px"]:
        return ""
    if abs(spectrum.angle_difference(a["orientation_deg"], b["orientation_deg"]) - 90.0) > 5.0:
        return ""
    period = 0.5 * (a["period_px"] + b["period_px"])
    cycles = 0.5 * (a["cycles_per_image"] + b["cycles_per_image"])
    if min(spectrum.angle_difference(a["orientation_deg"], c) for c in (45.0, 135.0)) <= 10.0:
        side = period / math.sqrt(2.0)
        across = cycles * math.sqrt(2.0)
        return f" (together: a checker of {side:.1f} px squares, {across:.1f} across the image)"
    if min(spectrum.angle_difference(a["orientation_deg"], c) for c in (0.0, 90.0)) <= 10.0:
        return f" (together: a grid of {period:.1f} px square cells, {cycles:.1f} across the image)"
    return f" (together: a lattice of {period:.1f} px cells)"


def _direction_text(direction: dict[str, float] | None, what: str) -> str:
    if direction is None:
        return f"n/a (too little {what} to have a direction)"
    value, angle = direction["value"], direction["orientation_deg"]
    if value < 0.15:
        return f"{value:.2f} (no preferred direction)"
    words = {
        0: "changes mostly along X: vertical structures",
        45: "changes mostly along the up-right diagonal",
        90: "changes mostly along Y: horizontal structures",
        135: "changes mostly along the up-left diagonal",
    }
    nearest = min(words, key=lambda centre: spectrum.angle_difference(angle, centre))
    return f"{value:.2f} toward {_degrees(angle)}° ({words[nearest]})"


def _constant_text(label: str, value: Any) -> str:
    if label == "basecolor_srgb":
        r, g, b = (round(v) for v in value)
        return f"base colour sRGB ({r}, {g}, {b})"
    if label == "height":
        return f"height {_number(value)} (flat)"
    return f"{label} {_number(value)}"


def _range_text(label: str, s: dict[str, float]) -> str:
    return (
        f"- {label[:1].upper() + label[1:]}: {_number(s['p5'])}–{_number(s['p95'])} "
        f"(5–95 %), mean {_number(s['mean'])}, full range {_number(s['min'])}–{_number(s['max'])}"
    )


def _albedo_lines(albedo: dict[str, Any]) -> list[str]:
    r, g, b = (round(v) for v in albedo["mean_srgb"])
    return [
        f"- Albedo: mean sRGB ({r}, {g}, {b}); luminance {albedo['luminance_mean']:.0f} ± "
        f"{albedo['luminance_std']:.1f} of 255 (5–95 %: {albedo['luminance_p5']:.0f}–"
        f"{albedo['luminance_p95']:.0f}); RMS contrast {albedo['rms_contrast']:.2f}; "
        f"saturation {albedo['saturation']:.2f}",
        "- Albedo repeating pattern: " + _pattern_text(albedo["patterns"], "contrast"),
        "- Albedo directionality (0 = none, 1 = all contrast in one orientation): "
        + _direction_text(albedo["directionality"], "contrast"),
    ]


def _relief_lines(relief: dict[str, Any]) -> list[str]:
    in_px = relief["range_px"]
    px = f" = {in_px:.2g} px of the maps" if in_px is not None else ""
    return [
        f"- Height: range {_number(relief['range_units'])} units{px}, std "
        f"{_number(relief['std_units'])}; surface tilt mean {relief['tilt_mean_deg']:.1f}°, "
        f"95 % under {relief['tilt_p95_deg']:.1f}°; AO mean {relief['ao_mean']:.2f}, "
        f"5 % under {relief['ao_p5']:.2f}",
        "- Height repeating pattern: " + _pattern_text(relief["patterns"], "relief"),
        "- Relief directionality (slope energy): "
        + _direction_text(relief["directionality"], "relief"),
    ]


def format_visible_stats(stats: dict[str, Any]) -> str:
    """The text block of :func:`visible_stats` for a critic prompt."""
    width, height = stats["size"]
    lines = [
        f"Visible statistics (computed on the {width}x{height} maps the preview shows; "
        f"1 px = {_number(stats['texel_units'])} units; orientation 0° = the value changes "
        "along X (vertical stripes), 90° = along Y (horizontal bands); a pattern's strength is "
        "its spectral peak over the spectrum around it):"
    ]
    if not stats["coverage"]:
        lines.append("- No material: nothing has coverage.")
        return "\n".join(lines)
    layers = stats["layers"]
    lines.append(
        f"- Material covers {stats['coverage'] * 100.0:.0f} % of the image "
        f"({layers} layer{'s' * (layers != 1)})"
    )
    constants = stats.get("constants", {})
    if constants:
        joined = ", ".join(_constant_text(k, v) for k, v in constants.items())
        lines.append(f"- Constant channels: {joined}")
    if stats.get("albedo"):
        lines += _albedo_lines(stats["albedo"])
    for label, summary in stats.get("channels", {}).items():
        line = _range_text(label, summary)
        if label == "metallic" and "metal_share" in stats:
            line += f"; metal (> 0.5) on {stats['metal_share'] * 100:.0f} % of the material"
        lines.append(line)
    if stats.get("relief"):
        lines += _relief_lines(stats["relief"])
    emissive = stats.get("emissive")
    if emissive:
        lines.append(
            f"- Emission: mean luminance {_number(emissive['mean'])}, "
            f"max {_number(emissive['max'])}"
        )
    return "\n".join(lines)


def visible_stats_text(maps: MaterialMaps) -> str:
    """The visible-statistics block of ``maps`` (evaluate them at the critique resolution)."""
    return format_visible_stats(visible_stats(maps))
