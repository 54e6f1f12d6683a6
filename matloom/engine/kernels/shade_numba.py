"""numba kernels of the exact preview shading (:func:`matloom.render.preview.shade`).

Moved out of :mod:`matloom.render.preview` so that importing the preview module does not import
numba (about 0.4 s): the numpy shader is used unless numba is already loaded or asked for.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from matloom.engine.kernels.jit import jit

#: Options of the two per-texel kernels. ``nogil`` lets callers shade previews on threads;
#: ``error_model="numpy"`` makes x/0 give inf/NaN instead of raising. The fast-math subset only
#: allows reassociation, contraction (FMA) and reciprocal division: results move by a few float64
#: ulps at most, and NaN/inf semantics (no ``nnan``/``ninf``) are kept.
_KERNEL_OPTIONS: dict[str, Any] = {
    "nogil": True,
    "error_model": "numpy",
    "fastmath": {"nsz", "arcp", "contract", "reassoc"},
}


@jit(inline=True)
def _clip01(v: float) -> float:
    """Clamp to [0, 1] keeping NaN, like ``np.clip``."""
    if v < 0.0:
        return 0.0
    if v > 1.0:
        return 1.0
    return v


_SRGB_EXPONENT = 1.0 / 2.4
_SRGB_KNEE = 0.0031308


@jit(inline=True)
def _srgb_from_power(v: float, v_pow: float) -> float:
    """Linear -> sRGB given v^(1/2.4) precomputed: 12.92 v at or below 0.0031308."""
    if v <= _SRGB_KNEE:
        return 12.92 * v
    return 1.055 * v_pow - 0.055


@jit(inline=True)
def _quantise(v: float) -> np.uint8:
    """Clip to [0, 1] and round half up to 8 bits; NaN becomes 0 (the reference's cast)."""
    if v != v:
        return np.uint8(0)
    return np.uint8(math.floor(255.0 * _clip01(v) + 0.5))


@jit(inline=True)
def _finite_or(v: float, fallback: float) -> float:
    return v if math.isfinite(v) else fallback


@jit(inline=True)
def _clean_normal(normal: np.ndarray, i: int, j: int) -> tuple[float, float, float]:
    """The reference's normal sanitising: non-finite nx, ny -> 0 and nz -> 1; nz in [-1, 1]."""
    nx = _finite_or(np.float64(normal[i, j, 0]), 0.0)
    ny = _finite_or(np.float64(normal[i, j, 1]), 0.0)
    nz = _finite_or(np.float64(normal[i, j, 2]), 1.0)
    return nx, ny, (-1.0 if nz < -1.0 else (1.0 if nz > 1.0 else nz))


@jit(**_KERNEL_OPTIONS)
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


@jit(**_KERNEL_OPTIONS)
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
