"""The numbers behind the material metrics (:mod:`.material`): pure functions of a material's
maps, of its program text or of its authoring record.

Every reduction is exact or exactly rounded (integer counts, :func:`math.fsum`), so equal maps
give equal numbers on every CPU; the maps themselves come from the engine's own evaluation.
The thresholds are named constants below, with where they come from.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from typing import Any

import numpy as np

from matloom.engine.colour import srgb_to_linear
from matloom.engine.maps import MaterialMaps
from matloom.engine.tiling import seam_ratio
from matloom.io.encode import normal_pixels
from matloom.io.export import MAP_SPECS, SEAM_BOUND
from matloom.lang import ast as A
from matloom.lang.lexer import Lexer, LexError
from matloom.lang.parser import parse_source
from matloom.render.lit import shade_lit
from matloom.render.lit_model import KEY_AZIMUTH_DEG, KEY_ELEVATION_DEG
from matloom.render.preview import Light

# --- PBR plausibility ranges ----------------------------------------------------------------
# Base colour ranges of the usual PBR authoring guides (Allegorithmic/Adobe, "The PBR Guide",
# part 2, 2015-2018: dielectric albedo no darker than 30-50 sRGB -- charcoal -- and no brighter
# than 240 sRGB -- fresh snow; metal reflectance 70-100 % specular, i.e. 180-255 sRGB). They
# are applied to the Rec.709 luminance of the linear base colour, decoded here from those
# sRGB 8-bit levels (30 -> 0.0130, 240 -> 0.8714, 180 -> 0.4564 linear).

#: Darkest plausible dielectric base colour: 30 sRGB (the guide's tolerant bound).
DIELECTRIC_MIN_SRGB8 = 30
#: Brightest plausible dielectric base colour: 240 sRGB (fresh snow).
DIELECTRIC_MAX_SRGB8 = 240
#: Darkest plausible raw metal: 180 sRGB (70 % specular reflectance); the brightest is 255.
METAL_MIN_SRGB8 = 180
DIELECTRIC_MIN = float(srgb_to_linear(DIELECTRIC_MIN_SRGB8 / 255.0))
DIELECTRIC_MAX = float(srgb_to_linear(DIELECTRIC_MAX_SRGB8 / 255.0))
METAL_MIN = float(srgb_to_linear(METAL_MIN_SRGB8 / 255.0))
METAL_MAX = 1.0
#: Rec.709 / sRGB luminance weights of linear RGB.
LUMA = (0.2126, 0.7152, 0.0722)
#: Texels with metallic above this count as metal (the guides: metalness is a mask).
METAL_SPLIT = 0.5
#: Metallic within this distance of 0 or 1 counts as "near 0 or 1" (0.1 < m < 0.9 does not).
METALLIC_MARGIN = 0.1
#: Lowest plausible perceptual roughness: Filament's MIN_PERCEPTUAL_ROUGHNESS (0.045; no real
#: surface is a perfect mirror, and renderers clamp below it). The engine clamps at 1.
ROUGHNESS_MIN = 0.045
ROUGHNESS_MAX = 1.0
#: A decoded 8-bit normal within this of unit length counts as unit (8-bit quantisation alone
#: moves a unit normal by at most sqrt(3) / 255 = 0.0068).
NORMAL_TOLERANCE = 0.02

# --- relighting ------------------------------------------------------------------------------
#: Key-light azimuths (degrees) of the three relit renders: the lit studio's own key light and
#: the same light turned by 120 and 240 degrees, all at the studio's key elevation.
RELIGHT_AZIMUTHS = (KEY_AZIMUTH_DEG, KEY_AZIMUTH_DEG + 120.0, KEY_AZIMUTH_DEG + 240.0)
RELIGHT_ELEVATION = KEY_ELEVATION_DEG
#: Brightness floor of the normalisation (one 8-bit level in linear light, about 0.0003):
#: a black material's drifts stay finite.
RELIGHT_FLOOR = float(srgb_to_linear(1.0 / 255.0))
#: Linear value of each 8-bit sRGB level.
_SRGB8_LINEAR = np.asarray(srgb_to_linear(np.arange(256, dtype=np.float64) / 255.0))


def exact_sum(values: np.ndarray) -> float:
    """The exactly rounded sum of ``values`` (:func:`math.fsum`: the same on every CPU)."""
    return math.fsum(np.asarray(values, dtype=np.float64).ravel().tolist())


def _share(hit: np.ndarray, weight: np.ndarray) -> float:
    """Weighted share of ``hit`` texels; NaN when the weights sum to 0."""
    total = exact_sum(weight)
    return exact_sum(weight * hit) / total if total > 0 else math.nan


def _rounded(values: Mapping[str, float], digits: int = 6) -> dict[str, float]:
    return {k: (round(v, digits) if math.isfinite(v) else float(v)) for k, v in values.items()}


# --- seams -----------------------------------------------------------------------------------


def seam_values(maps: MaterialMaps) -> dict[str, float]:
    """``seam_ratio.<map>`` of every exported map (as ``material.json`` records them for a
    tileable render), ``seam_ratio.max`` and ``seam_ratio.tiles`` (1.0 when every map is within
    :data:`~matloom.io.export.SEAM_BOUND`, else 0.0)."""
    out: dict[str, float] = {}
    for spec in MAP_SPECS:
        source = spec.sources[0] if spec.sources else None
        if source is not None and hasattr(maps, source):
            ratio = seam_ratio(getattr(maps, source), spec.period)
            out[f"seam_ratio.{spec.name}"] = round(ratio, 4) if math.isfinite(ratio) else ratio
    ratios = list(out.values())
    worst = math.nan if any(math.isnan(r) for r in ratios) else max(ratios)
    out["seam_ratio.max"] = worst
    out["seam_ratio.tiles"] = 1.0 if worst <= SEAM_BOUND else 0.0
    return out


# --- PBR plausibility ------------------------------------------------------------------------

#: The values :func:`pbr_values` reports.
PBR_NAMES: tuple[str, ...] = (
    "pbr.dielectric_albedo",
    "pbr.metal_albedo",
    "pbr.albedo",
    "pbr.metallic_binary",
    "pbr.roughness_range",
    "pbr.normal_length_error",
    "pbr.normal_backfacing",
    "pbr.normal_unit",
    "pbr.plausible",
)


def decoded_normals(normal: np.ndarray) -> np.ndarray:
    """The normal map as ``normal_gl.png`` stores it (8 bits, n * 0.5 + 0.5), decoded back to
    float64 vectors (q / 255 * 2 - 1)."""
    pixels = normal_pixels(np.asarray(normal, dtype=np.float32), "gl", 8)
    return pixels.astype(np.float64) / 255.0 * 2.0 - 1.0


def pbr_values(maps: MaterialMaps) -> dict[str, float]:
    """PBR plausibility shares (coverage-weighted, on [0, 1], higher is better) and the normal
    map's length error. NaN texels count as implausible; a share over no texels is NaN."""
    weight = np.clip(np.nan_to_num(np.asarray(maps.alpha, np.float64), nan=0.0), 0.0, 1.0)
    rgb = np.asarray(maps.basecolor_linear, np.float64)
    luma = rgb[..., 0] * LUMA[0] + rgb[..., 1] * LUMA[1] + rgb[..., 2] * LUMA[2]
    metallic = np.asarray(maps.metallic, np.float64)
    roughness = np.asarray(maps.roughness, np.float64)
    metal = metallic > METAL_SPLIT
    dielectric = metallic <= METAL_SPLIT  # NaN metallic is neither
    in_dielectric = (luma >= DIELECTRIC_MIN) & (luma <= DIELECTRIC_MAX)
    in_metal = (luma >= METAL_MIN) & (luma <= METAL_MAX)
    albedo_ok = (dielectric & in_dielectric) | (metal & in_metal)
    binary = (metallic <= METALLIC_MARGIN) | (metallic >= 1.0 - METALLIC_MARGIN)
    rough_ok = (roughness >= ROUGHNESS_MIN) & (roughness <= ROUGHNESS_MAX)
    n = decoded_normals(maps.normal)
    length = np.sqrt(n[..., 0] * n[..., 0] + n[..., 1] * n[..., 1] + n[..., 2] * n[..., 2])
    length_error = np.abs(length - 1.0)
    backfacing = n[..., 2] < 0.0
    normal_ok = (length_error <= NORMAL_TOLERANCE) & ~backfacing
    texels = length_error.size
    values = {
        "pbr.dielectric_albedo": _share(in_dielectric, weight * dielectric),
        "pbr.metal_albedo": _share(in_metal, weight * metal),
        "pbr.albedo": _share(albedo_ok, weight),
        "pbr.metallic_binary": _share(binary, weight),
        "pbr.roughness_range": _share(rough_ok, weight),
        "pbr.normal_length_error": exact_sum(length_error) / texels,
        "pbr.normal_backfacing": float(np.count_nonzero(backfacing)) / texels,
        "pbr.normal_unit": float(np.count_nonzero(normal_ok)) / texels,
    }
    parts = [values[k] for k in ("pbr.albedo", "pbr.metallic_binary", "pbr.roughness_range")]
    parts.append(values["pbr.normal_unit"])
    values["pbr.plausible"] = math.fsum(parts) / len(parts)
    return _rounded(values)


# --- relighting ------------------------------------------------------------------------------

#: The values :func:`relight_values` reports.
RELIGHT_NAMES: tuple[str, ...] = (
    "relight.luminance",
    "relight.mean_drift",
    "relight.contrast_drift",
    "relight.colour_drift",
    "relight.consistency",
)


def relight_lights() -> tuple[Light, ...]:
    """The three key lights of :func:`relight_values`."""
    return tuple(
        Light(azimuth_deg=a % 360.0, elevation_deg=RELIGHT_ELEVATION) for a in RELIGHT_AZIMUTHS
    )


def image_statistics(image: np.ndarray) -> tuple[float, float, float, float]:
    """(mean luminance, luminance standard deviation, mean r and g chromaticity) of an 8-bit
    sRGB image, in linear light, exactly rounded."""
    linear = _SRGB8_LINEAR[np.asarray(image)[..., :3]]
    luma = linear[..., 0] * LUMA[0] + linear[..., 1] * LUMA[1] + linear[..., 2] * LUMA[2]
    count = luma.size
    mean = exact_sum(luma) / count
    var = exact_sum((luma - mean) ** 2) / count
    sums = [exact_sum(linear[..., c]) for c in range(3)]
    total = math.fsum(sums)
    r, g = (sums[0] / total, sums[1] / total) if total > 0 else (1 / 3, 1 / 3)
    return mean, math.sqrt(var), r, g


def relight_values(
    maps: MaterialMaps, *, backend: str = "auto", session: Any = None
) -> dict[str, float]:
    """Drift of image statistics over the lit preview under :func:`relight_lights` (0 = the
    three renders have the same statistics)."""
    stats = [
        image_statistics(shade_lit(maps, key_light=light, backend=backend, session=session))
        for light in relight_lights()
    ]
    means = [s[0] for s in stats]
    stds = [s[1] for s in stats]
    scale = max(math.fsum(means) / len(means), RELIGHT_FLOOR)
    colour = max(
        math.hypot(a[2] - b[2], a[3] - b[3]) for i, a in enumerate(stats) for b in stats[i + 1 :]
    )
    values = {
        "relight.luminance": math.fsum(means) / len(means),
        "relight.mean_drift": (max(means) - min(means)) / scale,
        "relight.contrast_drift": (max(stds) - min(stds)) / scale,
        "relight.colour_drift": colour,
    }
    total = values["relight.mean_drift"] + values["relight.contrast_drift"] + colour
    values["relight.consistency"] = math.exp(-total)
    return _rounded(values)


# --- program size ----------------------------------------------------------------------------


def _expression_nodes(program: A.Program) -> Iterable[A.Node]:
    for _, expr in A.program_expressions(program):
        yield from A.walk(expr)


def size_values(text: str) -> dict[str, float]:
    """Program size: characters, code lines (lines with a token: blank and comment-only lines
    excluded), DSL tokens, layers, Defines, expression nodes and function calls (NaN for the
    counts that need a program that parses)."""
    out = {
        "size.characters": float(len(text)),
        "size.lines": math.nan,
        "size.tokens": math.nan,
        "size.layers": math.nan,
        "size.defines": math.nan,
        "size.nodes": math.nan,
        "size.calls": math.nan,
    }
    try:
        tokens = [t for t in Lexer(text).tokens() if t.kind != "EOF"]
    except LexError:
        return out
    out["size.lines"] = float(len({t.span.line for t in tokens}))
    out["size.tokens"] = float(len(tokens))
    program, diagnostics = parse_source(text)
    if program is None or any(d.is_error for d in diagnostics):
        return out
    nodes = list(_expression_nodes(program))
    out["size.layers"] = float(len(program.layers))
    out["size.defines"] = float(len(program.defines))
    out["size.nodes"] = float(len(nodes))
    out["size.calls"] = float(sum(isinstance(n, A.Call) for n in nodes))
    return out


# --- authoring -------------------------------------------------------------------------------

#: ``Sample.record`` keys read by :func:`authoring_values`.
RECORD_KEYS = ("seconds", "prompt_tokens", "completion_tokens")


def _number(value: object) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float):
        return math.nan
    return float(value)


def authoring_values(record: Mapping[str, Any]) -> dict[str, float]:
    """Authoring seconds and model tokens from a sample's record (NaN when not recorded);
    ``authoring.tokens`` is prompt + completion tokens (NaN unless both are known)."""
    seconds, prompt, completion = (_number(record.get(k)) for k in RECORD_KEYS)
    return {
        "authoring.seconds": seconds,
        "authoring.prompt_tokens": prompt,
        "authoring.completion_tokens": completion,
        "authoring.tokens": prompt + completion,
    }
