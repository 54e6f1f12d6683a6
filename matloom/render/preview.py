"""Quick fixed-light preview: the reference's numpy shading of composited maps, reproduced.

The reference (``fixed_light_preview``, spec §6) shades a head-on swatch with Blinn-Phong, a
constant-F0 Fresnel term, a coat lobe, wrap-lit subsurface, sheen, a 0.2 ambient term, soft-knee
emissive and a transmission / coverage mix over 0.5 grey. :func:`shade` applies exactly that
shading to a :class:`~matloom.engine.maps.MaterialMaps`. The seed sweep calls it ~1000 times per
prompt, so it has two implementations with the same results:

* ``numba`` (used when numba is installed): per-texel kernels, no full-size temporaries. The
  three pow-like steps are vectorised numpy calls between the kernels (numpy's SIMD ``pow`` is
  several times faster than a scalar libm call in a loop).
* ``numpy`` (fallback without numba, or ``MATLOOM_BACKEND=numpy``): the formulas on whole arrays.

Precision: the maps are float32 (the reference blends them in float64, a ~1e-7 relative
difference). Both implementations shade in float64 as the reference does; the numba path only
takes v^(1/2.4) of the albedo and of the soft-knee emissive in float32, which moved 2 of about
2 million values by one level against the numpy path in a random stress test
(``benchmarks/preview.py``). Both reproduce all 30 reference previews of the parity fixtures
byte for byte.

Non-finite inputs never raise. They follow the reference's arithmetic (NaN propagates through
clamps and ``pow`` as in numpy, so e.g. 1^NaN = 1; non-finite normal components are replaced by
nx, ny = 0 and nz = 1), and a texel whose final value is NaN is written as 0, which is what the
reference's float-to-uint8 cast produced on its platform (e.g. +inf emissive gives
inf / (1 + inf) = NaN -> 0; NaN albedo -> 0; see the ``nan_inf_fields`` fixture).
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from matloom.engine.colour import linear_to_srgb
from matloom.engine.maps import MaterialMaps

try:
    import numba
except ImportError:  # numba is the optional "fast" extra
    numba = None

#: The reference's fixed light direction, normalize(0.5, 0.5, 1), as exact float64 components.
_REFERENCE_LIGHT: tuple[float, float, float] = tuple(
    float(c) for c in np.array([0.5, 0.5, 1.0]) / np.linalg.norm([0.5, 0.5, 1.0])
)


@dataclass(frozen=True)
class Light:
    """A directional light seen from an orthographic head-on camera at V = (0, 0, 1).

    ``azimuth_deg`` is measured in the surface plane from +x (right) toward +y (up, toward image
    row 0); ``elevation_deg`` is the angle above the surface plane (90 = straight on).
    """

    azimuth_deg: float = 45.0
    elevation_deg: float = math.degrees(math.atan2(1.0, math.sqrt(0.5)))

    def __post_init__(self) -> None:
        if not (math.isfinite(self.azimuth_deg) and math.isfinite(self.elevation_deg)):
            raise ValueError(f"light angles must be finite, got {self}")

    def direction(self) -> tuple[float, float, float]:
        """Unit light vector L. The default light returns the reference's exact vector."""
        if self == DEFAULT_LIGHT:
            return _REFERENCE_LIGHT
        az = math.radians(self.azimuth_deg)
        el = math.radians(self.elevation_deg)
        return (math.cos(el) * math.cos(az), math.cos(el) * math.sin(az), math.sin(el))


#: The reference's light: azimuth 45 deg, elevation atan(1/sqrt(0.5)) ~ 54.7356 deg, i.e. the
#: direction normalize(0.5, 0.5, 1). :meth:`Light.direction` returns that vector exactly.
DEFAULT_LIGHT: Light = Light()


def _light_and_half_vectors(light: Light | None) -> tuple[np.ndarray, np.ndarray]:
    """Return (L, H) as float64 3-vectors, with H = normalize(L + V) and V = (0, 0, 1)."""
    direction = np.array((light or DEFAULT_LIGHT).direction(), dtype=np.float64)
    half = direction + np.array([0.0, 0.0, 1.0])
    norm = np.linalg.norm(half)
    # A light straight from below (L = -V) has no half vector; any unit H is as good as another.
    half = half / norm if norm > 0.0 else np.array([0.0, 0.0, 1.0])
    return direction, half


def _jit(**options: Any) -> Callable[[Callable[..., Any]], Any]:
    """``numba.njit(cache=True, **options)``; uncached when numba finds no writable cache
    directory (it raises at decoration time then); the plain function without numba (the numpy
    path is used then, so these are never called uncompiled)."""

    def decorate(func: Callable[..., Any]) -> Any:
        if numba is None:
            return func
        try:
            return numba.njit(cache=True, **options)(func)
        except RuntimeError:
            return numba.njit(cache=False, **options)(func)

    return decorate


#: Options of the two per-texel kernels. ``nogil`` lets callers shade previews on threads;
#: ``error_model="numpy"`` makes x/0 give inf/NaN instead of raising. The fast-math subset only
#: allows reassociation, contraction (FMA) and reciprocal division: results move by a few float64
#: ulps at most, and NaN/inf semantics (no ``nnan``/``ninf``) are kept.
_KERNEL_OPTIONS: dict[str, Any] = {
    "nogil": True,
    "error_model": "numpy",
    "fastmath": {"nsz", "arcp", "contract", "reassoc"},
}


@_jit(inline="always")
def _clip01(v: float) -> float:
    """Clamp to [0, 1] keeping NaN, like ``np.clip``."""
    if v < 0.0:
        return 0.0
    if v > 1.0:
        return 1.0
    return v


_SRGB_EXPONENT = 1.0 / 2.4
_SRGB_KNEE = 0.0031308


@_jit(inline="always")
def _srgb_from_power(v: float, v_pow: float) -> float:
    """Linear -> sRGB given v^(1/2.4) precomputed: 12.92 v at or below 0.0031308."""
    if v <= _SRGB_KNEE:
        return 12.92 * v
    return 1.055 * v_pow - 0.055


@_jit(inline="always")
def _quantise(v: float) -> np.uint8:
    """Clip to [0, 1] and round half up to 8 bits; NaN becomes 0 (the reference's cast)."""
    if v != v:
        return np.uint8(0)
    return np.uint8(math.floor(255.0 * _clip01(v) + 0.5))


@_jit(inline="always")
def _finite_or(v: float, fallback: float) -> float:
    return v if math.isfinite(v) else fallback


@_jit(inline="always")
def _clean_normal(normal: np.ndarray, i: int, j: int) -> tuple[float, float, float]:
    """The reference's normal sanitising: non-finite nx, ny -> 0 and nz -> 1; nz in [-1, 1]."""
    nx = _finite_or(np.float64(normal[i, j, 0]), 0.0)
    ny = _finite_or(np.float64(normal[i, j, 1]), 0.0)
    nz = _finite_or(np.float64(normal[i, j, 2]), 1.0)
    return nx, ny, (-1.0 if nz < -1.0 else (1.0 if nz > 1.0 else nz))


@_jit(**_KERNEL_OPTIONS)
def _specular_base_kernel(
    normal: np.ndarray,
    roughness: np.ndarray,
    anisotropy: np.ndarray,
    half: np.ndarray,
    n_dot_h: np.ndarray,
    shininess: np.ndarray,
) -> None:
    """Pass 1: clamped N.H and the Blinn-Phong exponent per texel (float64), for one pow."""
    rows, cols = n_dot_h.shape
    for i in range(rows):
        for j in range(cols):
            nx, ny, nz = _clean_normal(normal, i, j)
            n_dot_h[i, j] = _clip01(nx * half[0] + ny * half[1] + nz * half[2])
            rough = _clip01(np.float64(roughness[i, j]))
            aniso = _clip01(np.float64(anisotropy[i, j]))
            shininess[i, j] = ((1.0 - rough) ** 2 * 100.0 + 2.0) / (1.0 + 4.0 * aniso)


@_jit(**_KERNEL_OPTIONS)
def _shade_kernel(
    maps: tuple,
    basecolor_pow: np.ndarray,
    emissive_pow: np.ndarray,
    has_emissive: bool,
    spec: np.ndarray,
    light: np.ndarray,
    n_dot_h: np.ndarray,
    out: np.ndarray,
) -> None:
    """Pass 2: the rest of the reference's shading per texel, in float64, into uint8 ``out``.

    ``maps`` holds (basecolor, alpha, metallic, sheen, coat, transmission, subsurface, ior,
    emissive, normal, ao); ``basecolor_pow`` / ``emissive_pow`` hold v^(1/2.4) of the linear
    colour and of the soft-knee emissive; ``spec`` = (N.H)^shininess.
    """
    basecolor, alpha, metallic, sheen, coat, transmission, subsurface, ior, emissive, normal, ao = (
        maps
    )
    rows, cols = alpha.shape
    for i in range(rows):
        for j in range(cols):
            cover = _clip01(np.float64(alpha[i, j]))
            metal = _clip01(np.float64(metallic[i, j]))
            trans = _clip01(np.float64(transmission[i, j]))
            shn = _clip01(np.float64(sheen[i, j]))
            ss = _clip01(np.float64(subsurface[i, j]))
            eta = np.float64(ior[i, j])
            eta = 1.0 if eta < 1.0 else (3.0 if eta > 3.0 else eta)
            nx, ny, nz = _clean_normal(normal, i, j)
            n_dot_l = _clip01(nx * light[0] + ny * light[1] + nz * light[2])

            nh2 = n_dot_h[i, j] * n_dot_h[i, j]  # (N.H)^50 by squaring, no pow
            nh16 = nh2 * nh2
            nh16 *= nh16
            nh16 *= nh16
            nh50 = nh16 * nh16 * nh16 * nh2
            coat_lobe = 0.04 * _clip01(np.float64(coat[i, j])) * (0.5 + 0.5 * nh50)
            f0_dielectric = ((1.0 - eta) / (1.0 + eta)) ** 2 * (1.0 - metal)
            wrap = _clip01((n_dot_l + ss) / (1.0 + ss))
            # ambient 0.2 + wrap diffuse * AO + sheen tint 0.1, all multiplying the albedo.
            albedo_gain = 0.2 + (1.0 - metal) * wrap * np.float64(ao[i, j]) + shn * 0.1
            sheen_rim = 0.5 * shn * (1.0 - nz) ** 5
            spec_ij = spec[i, j]

            for c in range(3):
                albedo = _srgb_from_power(np.float64(basecolor[i, j, c]), basecolor_pow[i, j, c])
                shaded = (
                    albedo * albedo_gain
                    + sheen_rim
                    + (f0_dielectric + albedo * metal) * spec_ij
                    + coat_lobe
                )
                if has_emissive:
                    glow = np.float64(emissive[i, j, c])
                    if glow != 0.0:
                        shaded += _srgb_from_power(glow / (1.0 + glow), emissive_pow[i, j, c])
                material = shaded * (1.0 - trans) + 0.5 * trans
                out[i, j, c] = _quantise(material * cover + 0.5 * (1.0 - cover))


def _srgb_power(values: np.ndarray, out: np.ndarray | None = None) -> np.ndarray:
    """v^(1/2.4) of float32 ``values`` with numpy's SIMD pow, into ``out`` (may be ``values``).

    The result only feeds the v > 0.0031308 branch of the sRGB curve, so values at or below the
    knee are raised to the knee instead: that keeps zeros and negatives off numpy's slow
    special-case path (about 5x slower) and changes nothing that is used. NaN stays NaN.
    """
    out = np.maximum(values, np.float32(_SRGB_KNEE), out=out)
    return np.power(out, np.float32(_SRGB_EXPONENT), out=out)


def _basecolor_power(basecolor: np.ndarray) -> np.ndarray:
    """v^(1/2.4) of the linear base colour, float32, for the albedo's sRGB encoding."""
    return _srgb_power(basecolor)


def _soft_knee_power(emissive: np.ndarray) -> np.ndarray:
    """(E / (1 + E))^(1/2.4) in float32, the power part of the emissive sRGB encoding."""
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        ratio = emissive / (np.float32(1.0) + emissive)
        return _srgb_power(ratio, out=ratio)


_SCALAR_INPUTS: tuple[str, ...] = (
    "alpha",
    "metallic",
    "roughness",
    "sheen",
    "coat",
    "transmission",
    "subsurface",
    "anisotropy",
    "ior",
    "ao",
)
_COLOUR_INPUTS: tuple[str, ...] = ("basecolor_linear", "emissive_linear", "normal")


def _kernel_inputs(maps: MaterialMaps) -> dict[str, np.ndarray]:
    """C-contiguous float32 views of the maps the shading reads, with their shapes checked.

    The kernels run without bounds checks, so a mis-shaped map must be refused here. Float32
    C-contiguous maps (the normal case) are passed through without copying, and every call
    then hits the same compiled kernel signature.
    """
    rows, cols = maps.alpha.shape
    inputs: dict[str, np.ndarray] = {}
    for name in _SCALAR_INPUTS + _COLOUR_INPUTS:
        array = np.ascontiguousarray(getattr(maps, name), dtype=np.float32)
        expected = (rows, cols) if name in _SCALAR_INPUTS else (rows, cols, 3)
        if array.shape != expected:
            raise ValueError(f"map {name!r} has shape {array.shape}, expected {expected}")
        inputs[name] = array
    return inputs


def _shade_numba(m: dict[str, np.ndarray], direction: np.ndarray, half: np.ndarray) -> np.ndarray:
    """Kernel path: N.H and exponent (kernel), (N.H)^exponent and the sRGB powers (numpy SIMD),
    then everything else per texel (kernel)."""
    rows, cols = m["alpha"].shape
    n_dot_h = np.empty((rows, cols), dtype=np.float64)
    spec = np.empty((rows, cols), dtype=np.float64)
    _specular_base_kernel(m["normal"], m["roughness"], m["anisotropy"], half, n_dot_h, spec)
    with np.errstate(invalid="ignore", over="ignore"):
        np.power(n_dot_h, spec, out=spec)  # spec = (N.H)^shininess, float64
    emissive = m["emissive_linear"]
    has_emissive = bool(emissive.any())
    emissive_pow = _soft_knee_power(emissive) if has_emissive else np.empty((1, 1, 3), np.float32)
    channels = tuple(m[name] for name in _KERNEL_CHANNELS)
    out = np.empty((rows, cols, 3), dtype=np.uint8)
    basecolor_pow = _basecolor_power(m["basecolor_linear"])
    _shade_kernel(
        channels, basecolor_pow, emissive_pow, has_emissive, spec, direction, n_dot_h, out
    )
    return out


#: Maps passed to :func:`_shade_kernel`, in its unpacking order.
_KERNEL_CHANNELS: tuple[str, ...] = (
    "basecolor_linear",
    "alpha",
    "metallic",
    "sheen",
    "coat",
    "transmission",
    "subsurface",
    "ior",
    "emissive_linear",
    "normal",
    "ao",
)


def _shade_numpy(m: dict[str, np.ndarray], direction: np.ndarray, half: np.ndarray) -> np.ndarray:
    """Whole-array float64 path, the reference's formulas in the reference's order."""
    with np.errstate(all="ignore"):
        clipped = {name: np.clip(m[name].astype(np.float64), 0.0, 1.0) for name in _UNIT_CHANNELS}
        eta = np.clip(m["ior"].astype(np.float64), 1.0, 3.0)
        normal = m["normal"].astype(np.float64)
        finite = np.isfinite(normal)
        nx = np.where(finite[..., 0], normal[..., 0], 0.0)
        ny = np.where(finite[..., 1], normal[..., 1], 0.0)
        nz = np.clip(np.where(finite[..., 2], normal[..., 2], 1.0), -1.0, 1.0)
        n_dot_l = np.clip(nx * direction[0] + ny * direction[1] + nz * direction[2], 0.0, 1.0)
        n_dot_h = np.clip(nx * half[0] + ny * half[1] + nz * half[2], 0.0, 1.0)

        metal, sheen = clipped["metallic"], clipped["sheen"]
        ss, trans, cover = clipped["subsurface"], clipped["transmission"], clipped["alpha"]
        shininess = ((1.0 - clipped["roughness"]) ** 2 * 100.0 + 2.0) / (
            1.0 + 4.0 * clipped["anisotropy"]
        )
        albedo = linear_to_srgb(m["basecolor_linear"].astype(np.float64))
        f0_dielectric = ((1.0 - eta) / (1.0 + eta)) ** 2 * (1.0 - metal)
        f0 = f0_dielectric[..., None] + albedo * metal[..., None]
        specular = f0 * (n_dot_h**shininess)[..., None]
        specular += (0.04 * clipped["coat"] * (0.5 + 0.5 * n_dot_h**50))[..., None]
        wrap = np.clip((n_dot_l + ss) / (1.0 + ss), 0.0, 1.0)
        diffuse = albedo * ((1.0 - metal) * wrap * m["ao"].astype(np.float64))[..., None]
        diffuse += albedo * (sheen * 0.1)[..., None] + (0.5 * sheen * (1.0 - nz) ** 5)[..., None]
        shaded = 0.2 * albedo + diffuse + specular
        emissive = m["emissive_linear"].astype(np.float64)
        if emissive.any():
            shaded += linear_to_srgb(emissive / (1.0 + emissive))
        material = shaded * (1.0 - trans)[..., None] + 0.5 * trans[..., None]
        out = material * cover[..., None] + 0.5 * (1.0 - cover)[..., None]
        levels = np.floor(255.0 * np.clip(out, 0.0, 1.0) + 0.5)
        levels[np.isnan(levels)] = 0.0
    return levels.astype(np.uint8)


#: Channels the reference clamps to [0, 1] before shading.
_UNIT_CHANNELS: tuple[str, ...] = (
    "alpha",
    "metallic",
    "roughness",
    "sheen",
    "coat",
    "transmission",
    "subsurface",
    "anisotropy",
)

#: Shading implementations by backend name (see the module docstring).
_SHADERS: dict[str, Callable[[dict[str, np.ndarray], np.ndarray, np.ndarray], np.ndarray]] = {
    "numpy": _shade_numpy,
}
if numba is not None:
    _SHADERS["numba"] = _shade_numba


def available_shaders() -> list[str]:
    """Backend names :func:`shade` accepts here (``numba`` only when numba is installed)."""
    return sorted(_SHADERS)


def _resolve_backend(backend: str) -> str:
    """``auto`` -> $MATLOOM_BACKEND if it names a shader here, else numba if installed, else
    numpy; an explicit name must be available."""
    if backend == "auto":
        wanted = os.environ.get("MATLOOM_BACKEND", "auto")
        if wanted in _SHADERS:
            return wanted
        return "numba" if "numba" in _SHADERS else "numpy"
    if backend not in _SHADERS:
        raise ValueError(f"unknown or unavailable shader {backend!r}; have {available_shaders()}")
    return backend


def shade(maps: MaterialMaps, *, light: Light | None = None, backend: str = "auto") -> np.ndarray:
    """Shade ``maps`` with the reference's fixed-light preview; uint8 (H, W, 3) RGB.

    ``light`` defaults to the reference's light normalize(0.5, 0.5, 1); any other light only
    changes L (and the half vector), never the formulas. The result does not depend on the
    maps' View: the reference previews whatever window the maps were evaluated on. ``backend``
    is ``auto``, ``numba`` or ``numpy`` (identical results). Never raises on non-finite values
    (see the module docstring); raises ValueError on mis-shaped maps.
    """
    direction, half = _light_and_half_vectors(light)
    return _SHADERS[_resolve_backend(backend)](_kernel_inputs(maps), direction, half)


def tile_image(img: np.ndarray, n: int = 2) -> np.ndarray:
    """Repeat ``img`` n x n times (rows and columns) so that tiling seams become visible."""
    if n < 1:
        raise ValueError(f"tile count must be >= 1, got {n}")
    reps = (n, n) + (1,) * (img.ndim - 2)
    return np.tile(img, reps)
