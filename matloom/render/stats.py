"""The 28 unlit material statistics shown to the critic (the reference's ``diagnostics.py``, §7).

Every statistic is taken over the material region only, the texels with coverage A > 1e-3.
Blended channels have NaN/+-inf replaced by 0 first. "Luminance" is Rec.709 luma of the
sRGB-encoded albedo in [0, 1]. The reference evaluates the material on a 128x128 grid over its
View (:data:`STATS_GRID`) before computing these; :func:`material_stats` accepts maps of any
size, so that evaluation is the caller's job.

Points the spec leaves open, and what this module does (each is also stated in the definitions):

* saturation and colour span use the sRGB-encoded albedo (the same albedo as the luminance);
  the colour span is computed on unquantised 255 * sRGB values;
* edge density: image borders do not erode the mask (edge-replicated padding), which is why
  the spec's "one-sided at borders" gradient matters; an empty eroded mask gives 0;
* FFT bandwidth weights each band bin's radius by its radial-profile magnitude; bandwidth and
  anisotropy are 0, like the dominant frequency, when the band holds no energy (max <= 1e-12),
  so a flat field reports no pattern instead of rounding noise;
* non-finite normals and AO (not blended channels, so the spec does not cover them) are treated
  like the preview does: a non-finite nz counts as 1 (flat) and a non-finite AO as 1.
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np

from matloom.engine.colour import linear_to_srgb
from matloom.engine.maps import MaterialMaps

#: The grid size on which the reference evaluates materials for these statistics.
STATS_GRID: int = 128

#: Coverage above which a texel belongs to the material region.
MASK_THRESHOLD: float = 1e-3

#: Radial-profile peaks at or below this magnitude mean "no pattern".
_SPECTRUM_FLOOR: float = 1e-12

#: Rec.709 luma weights.
_REC709: np.ndarray = np.array([0.2126, 0.7152, 0.0722])

#: Bins of the tonal-entropy histogram over luminance [0, 1].
_ENTROPY_BINS: int = 32

STAT_DEFINITIONS: dict[str, str] = {
    "albedo_luminance_mean": "mean Rec.709 luminance of the sRGB albedo, on a 0-255 scale",
    "albedo_luminance_std": "standard deviation of the sRGB albedo luminance, on a 0-255 scale",
    "albedo_rms_contrast": "luminance standard deviation divided by its mean (0 for black)",
    "albedo_saturation": "mean per-texel 1 - min/max over the sRGB albedo RGB (0 = grey)",
    "albedo_edge_density": (
        "mean luminance gradient magnitude per texel (0-1 luminance units) inside the material"
    ),
    "albedo_dominant_freq": (
        "strongest spatial frequency of the albedo luminance, in cycles per image (0 = none)"
    ),
    "albedo_freq_bandwidth": (
        "spread of the luminance spectrum around its mean frequency, relative to the highest "
        "frequency (0 = one frequency)"
    ),
    "albedo_anisotropy": (
        "directionality of the luminance spectrum: 0 = no preferred direction, 1 = stripes"
    ),
    "albedo_color_span": "largest per-channel range (max - min) of the sRGB albedo, 0-255",
    "albedo_tonal_entropy": (
        "entropy of a 32-bin luminance histogram divided by 5 bits (0 = one tone, 1 = all "
        "tones equally often)"
    ),
    "roughness_mean": "mean roughness (0 = mirror, 1 = fully rough)",
    "roughness_std": "standard deviation of roughness",
    "metallic_mean": "mean metallic value",
    "metallic_coverage": "fraction of the material whose metallic value exceeds 0.5",
    "height_range": "highest minus lowest height, in the same units as X and Y",
    "height_std": "standard deviation of height, in the same units as X and Y",
    "height_dominant_freq": (
        "strongest spatial frequency of the height field, in cycles per image (0 = none)"
    ),
    "height_anisotropy": "directionality of the height spectrum: 0 = none, 1 = parallel ridges",
    "normal_mean_tilt_deg": "mean angle between the surface normal and straight up, in degrees",
    "ao_mean": "mean ambient occlusion (1 = unoccluded, lower = deeper cavities)",
    "ao_std": "standard deviation of ambient occlusion",
    "sheen_mean": "mean sheen amount",
    "coat_mean": "mean clear-coat amount",
    "transmission_mean": "mean transmission (0 = opaque, 1 = fully transmissive)",
    "subsurface_mean": "mean subsurface-scattering amount",
    "anisotropy_mean": "mean specular anisotropy amount",
    "ior_mean": "mean index of refraction",
    "emissive_mean": "mean Rec.709 luminance of the linear emitted light (can exceed 1)",
}

#: The 28 statistic keys in the reference's reporting order.
STAT_NAMES: tuple[str, ...] = tuple(STAT_DEFINITIONS)

_UPPERCASE_WORDS: frozenset[str] = frozenset({"ao", "ior", "rms"})

#: Channels whose statistic is just "<name>_mean" over the material region.
_PLAIN_MEANS: tuple[str, ...] = ("sheen", "coat", "transmission", "subsurface", "anisotropy", "ior")


def _finite(values: np.ndarray, fallback: float = 0.0) -> np.ndarray:
    """float64 copy with NaN/+-inf replaced by ``fallback``."""
    out = np.asarray(values, dtype=np.float64).copy()
    out[~np.isfinite(out)] = fallback
    return out


def _srgb_albedo(linear: np.ndarray) -> np.ndarray:
    """sRGB-encoded albedo in [0, 1] from linear colour (non-finite -> 0, then clipped)."""
    return linear_to_srgb(np.clip(_finite(linear), 0.0, 1.0))


def _eroded(mask: np.ndarray) -> np.ndarray:
    """Mask eroded by one texel with the 4-neighbour cross; the image border does not erode."""
    p = np.pad(mask, 1, mode="edge")
    return mask & p[:-2, 1:-1] & p[2:, 1:-1] & p[1:-1, :-2] & p[1:-1, 2:]


def _luminance(planes: np.ndarray) -> np.ndarray:
    """Rec.709 luma of colour planes shaped (3, ...)."""
    return _REC709[0] * planes[0] + _REC709[1] * planes[1] + _REC709[2] * planes[2]


def _saturation(planes: np.ndarray) -> np.ndarray:
    """Per-texel 1 - min/max over the (3, H, W) colour planes, 0 where max is 0."""
    hi = np.maximum(np.maximum(planes[0], planes[1]), planes[2])
    lo = np.minimum(np.minimum(planes[0], planes[1]), planes[2])
    safe = np.where(hi > 0.0, hi, 1.0)
    return np.where(hi > 0.0, 1.0 - lo / safe, 0.0)


def _tonal_entropy(luminance: np.ndarray) -> float:
    """Entropy (bits) of a 32-bin histogram over [0, 1], divided by log2(32)."""
    counts, _ = np.histogram(luminance, bins=_ENTROPY_BINS, range=(0.0, 1.0))
    p = counts[counts > 0] / counts.sum()
    return float(-(p * np.log2(p)).sum() / math.log2(_ENTROPY_BINS))


@lru_cache(maxsize=8)
def _spectrum_geometry(shape: tuple[int, int]) -> tuple[np.ndarray, np.ndarray, np.ndarray, int]:
    """For an fftshifted spectrum: integer radius bin, dy and dx from the centre, and r_max."""
    ny, nx = shape
    cy, cx = ny // 2, nx // 2
    dy = (np.arange(ny) - cy)[:, None].astype(np.float64)
    dx = (np.arange(nx) - cx)[None, :].astype(np.float64)
    radius_bin = np.sqrt(dy * dy + dx * dx).astype(np.int64)  # truncated integer radius
    for array in (radius_bin, dy, dx):
        array.setflags(write=False)
    return radius_bin, dy, dx, min(cy, cx)


def _spectral_features(field: np.ndarray, mask: np.ndarray) -> tuple[float, float, float]:
    """(dominant frequency, bandwidth, anisotropy) of ``field`` over ``mask``.

    The field minus its mean over the mask, times the mask, is Fourier transformed; |F| is
    fftshifted. Radial profile = mean |F| per truncated-radius bin; the band is bins 1..r_max
    with r_max = min(cy, cx). Anisotropy = 1 - l2/l1 of the |F|^2-weighted second moments.
    """
    if not mask.any() or min(field.shape) < 4:
        return 0.0, 0.0, 0.0
    radius_bin, dy, dx, r_max = _spectrum_geometry(field.shape)
    if r_max < 2:
        return 0.0, 0.0, 0.0
    centred = (field - field[mask].mean()) * mask
    magnitude = np.abs(np.fft.fftshift(np.fft.fft2(centred)))

    sums = np.bincount(radius_bin.ravel(), weights=magnitude.ravel(), minlength=r_max + 1)
    counts = np.bincount(radius_bin.ravel(), minlength=r_max + 1)
    band = sums[1 : r_max + 1] / counts[1 : r_max + 1]
    if band.max() <= _SPECTRUM_FLOOR:
        return 0.0, 0.0, 0.0
    dominant = float(np.argmax(band) + 1)

    radii = np.arange(1, r_max + 1, dtype=np.float64)
    mean_radius = (band * radii).sum() / band.sum()
    variance = (band * (radii - mean_radius) ** 2).sum() / band.sum()
    bandwidth = math.sqrt(variance) / r_max

    energy = magnitude * magnitude
    mxx, myy, mxy = (energy * dx * dx).sum(), (energy * dy * dy).sum(), (energy * dx * dy).sum()
    lam_small, lam_large = np.linalg.eigvalsh(np.array([[mxx, mxy], [mxy, myy]]))
    anisotropy = 1.0 - lam_small / lam_large if lam_large > 0.0 else 0.0
    return dominant, bandwidth, float(anisotropy)


def _albedo_stats(maps: MaterialMaps, mask: np.ndarray) -> dict[str, float]:
    """Statistics 1-10, all on the sRGB-encoded albedo."""
    # Channel-first planes: reductions over a size-3 trailing axis are slow in numpy.
    albedo = _srgb_albedo(np.moveaxis(maps.basecolor_linear, -1, 0))
    luminance = _luminance(albedo)
    lum = luminance[mask]
    lum_mean, lum_std = float(lum.mean()), float(lum.std())

    gradient_rows, gradient_cols = np.gradient(luminance)
    eroded = _eroded(mask)
    edge_density = (
        float(np.hypot(gradient_rows, gradient_cols)[eroded].mean()) if eroded.any() else 0.0
    )

    dominant, bandwidth, anisotropy = _spectral_features(luminance, mask)
    return {
        "albedo_luminance_mean": lum_mean * 255.0,
        "albedo_luminance_std": lum_std * 255.0,
        "albedo_rms_contrast": lum_std / lum_mean if lum_mean > 1e-6 else 0.0,
        "albedo_saturation": float(_saturation(albedo)[mask].mean()),
        "albedo_edge_density": edge_density,
        "albedo_dominant_freq": dominant,
        "albedo_freq_bandwidth": bandwidth,
        "albedo_anisotropy": anisotropy,
        "albedo_color_span": 255.0 * max(float(np.ptp(plane[mask])) for plane in albedo),
        "albedo_tonal_entropy": _tonal_entropy(lum),
    }


def _relief_stats(maps: MaterialMaps, mask: np.ndarray) -> dict[str, float]:
    """Statistics 15-21: height, its spectrum, normal tilt and AO."""
    height = _finite(maps.height)
    inside = height[mask]
    dominant, _, anisotropy = _spectral_features(height, mask)
    nz = np.clip(_finite(maps.normal[..., 2], fallback=1.0)[mask], -1.0, 1.0)
    ao = _finite(maps.ao, fallback=1.0)[mask]
    return {
        "height_range": float(inside.max() - inside.min()),
        "height_std": float(inside.std()),
        "height_dominant_freq": dominant,
        "height_anisotropy": anisotropy,
        "normal_mean_tilt_deg": float(np.degrees(np.arccos(nz)).mean()),
        "ao_mean": float(ao.mean()),
        "ao_std": float(ao.std()),
    }


def material_stats(maps: MaterialMaps) -> dict[str, float]:
    """The 28 statistics of ``maps`` as {key: value} in :data:`STAT_NAMES` order.

    All values are 0 when the material has no layers or no texel has coverage A > 1e-3.
    """
    alpha = np.asarray(maps.alpha, dtype=np.float64)
    mask = alpha > MASK_THRESHOLD  # NaN coverage is outside
    if maps.n_layers == 0 or not mask.any():
        return dict.fromkeys(STAT_NAMES, 0.0)

    def inside(name: str) -> np.ndarray:
        return _finite(getattr(maps, name))[mask]

    roughness, metallic = inside("roughness"), inside("metallic")
    emissive = np.maximum(_finite(np.moveaxis(maps.emissive_linear, -1, 0)), 0.0)
    emissive_luminance = _luminance(emissive)[mask]
    values = {
        **_albedo_stats(maps, mask),
        "roughness_mean": float(roughness.mean()),
        "roughness_std": float(roughness.std()),
        "metallic_mean": float(metallic.mean()),
        "metallic_coverage": float(np.count_nonzero(metallic > 0.5) / metallic.size),
        **_relief_stats(maps, mask),
        **{f"{name}_mean": float(inside(name).mean()) for name in _PLAIN_MEANS},
        "emissive_mean": float(emissive_luminance.mean()),
    }
    return {name: values[name] for name in STAT_NAMES}


def stat_label(name: str) -> str:
    """Display label: underscores to spaces, AO/IOR/RMS upper-cased, first letter capitalised."""
    words = [w.upper() if w in _UPPERCASE_WORDS else w for w in name.split("_")]
    label = " ".join(words)
    return label[:1].upper() + label[1:]


def format_stat_value(value: float) -> str:
    """0 -> "0"; |v| >= 100 -> 1 decimal; |v| >= 10 -> 2 decimals; otherwise 3 decimals."""
    if value == 0:
        return "0"
    magnitude = abs(value)
    if magnitude >= 100:
        return f"{value:.1f}"
    if magnitude >= 10:
        return f"{value:.2f}"
    return f"{value:.3f}"


STATS_HEADING: str = f"Appearance scalars (computed on a {STATS_GRID}x{STATS_GRID} grid):"


def format_stats(stats: dict[str, float]) -> str:
    """The critic's statistics block: the heading, then one "- Label: value — definition" line
    per statistic present in ``stats``, in reporting order."""
    lines = [STATS_HEADING]
    for name in STAT_NAMES:
        if name in stats:
            value = format_stat_value(stats[name])
            lines.append(f"- {stat_label(name)}: {value} — {STAT_DEFINITIONS[name]}")
    return "\n".join(lines)
