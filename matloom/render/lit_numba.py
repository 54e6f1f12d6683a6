"""numba kernel of the ``lit`` preview (:func:`matloom.render.lit.shade_lit`).

The formulas are :mod:`matloom.render.lit_model`'s, compiled inline per texel: its functions are
registered with ``register_jitable``, so the numpy path calls the same source on arrays. This
module only adds the per-texel input sanitising (the numpy path's ``_sanitise`` does the same on
arrays), the swatch coordinates and the sRGB table look-up. Importing it imports numba.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numba.extending import register_jitable

from matloom.engine.kernels.jit import jit
from matloom.render import lit_model as M

#: ``error_model="numpy"``: x / 0 gives inf / NaN instead of raising. The fast-math subset only
#: reassociates, contracts (FMA) and uses reciprocals: results move by a few ulps, which the
#: tests bound against the numpy path.
_OPTIONS: dict[str, Any] = {
    "error_model": "numpy",
    "fastmath": {"nsz", "arcp", "contract", "reassoc"},
}

#: Inlined at numba IR level, so that the whole texel is one loop body LLVM can vectorise (the
#: small leaf functions LLVM inlines by itself). Inlining everything at IR level compiled about
#: 2x longer; inlining nothing left the loop scalar (about 5x slower).
_INLINED = frozenset({M.shade_texel, M.direct_light, M._channel, M.environment})

for _function in M.SHARED_FUNCTIONS:
    _inline = "always" if _function in _INLINED else "never"
    register_jitable(inline=_inline, **_OPTIONS)(_function)


@jit(inline=True)
def _unit(v: float, nan: float) -> float:
    """Clamp to [0, 1]; NaN becomes ``nan``."""
    if v != v:
        return nan
    return 0.0 if v < 0.0 else (1.0 if v > 1.0 else v)


@jit(inline=True)
def _range(v: float, lo: float, hi: float, nan: float) -> float:
    """Clamp to [lo, hi]; NaN becomes ``nan``."""
    if v != v:
        return nan
    return lo if v < lo else (hi if v > hi else v)


#: Rows of the per-row input scratch of :func:`_shade_row` (see :func:`_load_row`).
_FIELDS = 21


@jit(**_OPTIONS)
def _load_row(maps: tuple, i: int, s: np.ndarray) -> None:
    """Sanitised float64 inputs of source row ``i`` into ``s`` (_FIELDS, W): coverage .. ao
    (0-9), base colour (10-12), emissive (13-15), unit normal (16-18), tangent (19-20)."""
    (basecolor, alpha, metallic, roughness, sheen, coat, transmission, subsurface) = maps[:8]
    (anisotropy, ior, angle, emissive, normal, ao) = maps[8:]
    for j in range(alpha.shape[1]):
        s[0, j] = _unit(np.float64(alpha[i, j]), 0.0)
        s[1, j] = _unit(np.float64(metallic[i, j]), 0.0)
        s[2, j] = _unit(np.float64(roughness[i, j]), 0.0)
        s[3, j] = _unit(np.float64(sheen[i, j]), 0.0)
        s[4, j] = _unit(np.float64(coat[i, j]), 0.0)
        s[5, j] = _unit(np.float64(transmission[i, j]), 0.0)
        s[6, j] = _unit(np.float64(subsurface[i, j]), 0.0)
        s[7, j] = _unit(np.float64(anisotropy[i, j]), 0.0)
        s[8, j] = _range(np.float64(ior[i, j]), 1.0, 3.0, 1.5)
        s[9, j] = _unit(np.float64(ao[i, j]), 1.0)
    for j in range(alpha.shape[1]):  # separate loops: one big loop ran ~3x slower
        for c in range(3):
            s[10 + c, j] = _unit(np.float64(basecolor[i, j, c]), 0.0)
            s[13 + c, j] = _range(np.float64(emissive[i, j, c]), 0.0, 1e4, 0.0)
    for j in range(alpha.shape[1]):
        nx, ny = np.float64(normal[i, j, 0]), np.float64(normal[i, j, 1])
        nz = np.float64(normal[i, j, 2])
        nx = nx if math.isfinite(nx) else 0.0
        ny = ny if math.isfinite(ny) else 0.0
        nz = _range(nz, -1.0, 1.0, 1.0) if math.isfinite(nz) else 1.0
        length = math.sqrt(nx * nx + ny * ny + nz * nz)
        if length > 1e-12:
            nx, ny, nz = nx / length, ny / length, nz / length
        else:
            nx, ny, nz = 0.0, 0.0, 1.0
        s[16, j], s[17, j], s[18, j] = nx, ny, nz
    for j in range(alpha.shape[1]):
        degrees = np.float64(angle[i, j])
        s[19, j], s[20, j] = 0.0, 1.0  # the stretch is across the brushing (angle + 90)
        if s[7, j] > 0.0 and degrees != 0.0 and math.isfinite(degrees):
            theta = math.radians(degrees)
            s[19, j], s[20, j] = -math.sin(theta), math.cos(theta)


@jit(**_OPTIONS)
def _shade_row(
    s: np.ndarray, px0: float, py: float, scale: float, lights: np.ndarray, o: np.ndarray
) -> None:
    """Display values of one row of texels into ``o`` (3, W); branch-free, so that LLVM
    vectorises it. ``px0``: swatch x of the first texel's centre."""
    key = (lights[0, 0], lights[0, 1], lights[0, 2], lights[0, 3])
    fill = (lights[1, 0], lights[1, 1], lights[1, 2], lights[1, 3])
    for j in range(s.shape[1]):
        scalars = (s[0, j], s[1, j], s[2, j], s[3, j], s[4, j])
        scalars = scalars + (s[5, j], s[6, j], s[7, j], s[8, j], s[9, j])
        base = (s[10, j], s[11, j], s[12, j])
        glow = (s[13, j], s[14, j], s[15, j])
        normal = (s[16, j], s[17, j], s[18, j])
        px = px0 + j * scale
        r, g, b = M.shade_texel(
            px, py, base, glow, scalars, normal, (s[19, j], s[20, j]), key, fill
        )
        o[0, j], o[1, j], o[2, j] = r, g, b


@jit(nogil=True, **_OPTIONS)
def lit_rows(
    maps: tuple,
    lights: np.ndarray,
    lut: np.ndarray,
    tile: int,
    out: np.ndarray,
    first: int,
    last: int,
) -> None:
    """Shade output rows ``first`` .. ``last`` - 1 of ``out`` ((tile H, tile W, 3) uint8).

    ``maps`` = (basecolor, alpha, metallic, roughness, sheen, coat, transmission, subsurface,
    anisotropy, ior, anisotropy_angle, emissive, normal, ao), float32, (H, W) or (H, W, 3);
    ``lights`` = [[lx, ly, lz, intensity] of the key, of the fill]; ``lut`` =
    :data:`~matloom.render.lit_model.SRGB_LUT`.
    """
    rows, cols = maps[1].shape
    out_rows, out_cols = rows * tile, cols * tile
    scale = 2.0 / max(out_rows, out_cols)
    top = lut.size - 1
    s = np.empty((_FIELDS, cols), np.float64)
    o = np.empty((3, cols), np.float64)
    for oi in range(first, last):
        _load_row(maps, oi % rows, s)
        py = (0.5 * out_rows - (oi + 0.5)) * scale
        for k in range(tile):
            _shade_row(s, (k * cols + 0.5 - 0.5 * out_cols) * scale, py, scale, lights, o)
            for j in range(cols):
                for c in range(3):
                    out[oi, k * cols + j, c] = lut[int(_unit(o[c, j], 0.0) * top + 0.5)]
