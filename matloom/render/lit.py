"""The ``lit`` quick preview: physically based shading of the composited maps in a small studio.

The ``flat`` preview (:func:`matloom.render.preview.shade`) is the reference's fixed-light
Blinn-Phong swatch, kept byte for byte. :func:`shade_lit` shades the same maps with GGX
microfacets, a clear coat, a sheen lobe, transmission over a checker backdrop and anisotropy, lit
by an analytic studio (a sky gradient with a softbox and a strip light, a grazing key light and a
fill light); the model and its numbers are in :mod:`matloom.render.lit_model`.
:data:`LIT_LAYOUT_NOTE` and :data:`FLAT_LAYOUT_NOTE` say in words what each layout shows (for
prompts and docs).

Two implementations of the same formulas (``lit_model``'s functions run on arrays here and are
compiled per texel by numba in :mod:`matloom.render.lit_numba`):

* ``numba`` (when installed): one pass per texel, no temporaries, rows split over threads;
* ``numpy``: the formulas on bands of rows (bounded memory at any size or tile count).

They agree within one 8-bit level except at rare texels on a backdrop checker edge or a light
box edge (float rounding; ``tests/render/test_lit.py`` bounds it). Non-finite map values never
raise: NaN becomes the channel's neutral value (0; ao 1, ior 1.5), infinities clamp.
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from typing import TYPE_CHECKING

import numpy as np

from matloom.engine.maps import ARRAY_FIELDS, MaterialMaps
from matloom.render import lit_model as M
from matloom.render.preview import DEFAULT_LIGHT, Light, pick_shader
from matloom.vocab.layout import LAYOUT

if TYPE_CHECKING:
    from matloom.engine.session import Session

#: The maps the lit shading reads, in the kernel's order (every array field but the height,
#: which shows through the normal and AO derived from it).
LIT_MAPS: tuple[str, ...] = (
    LAYOUT["basecolor"].field,
    LAYOUT.coverage.field,
    *(
        LAYOUT[name].field
        for name in (
            "metallic",
            "roughness",
            "sheen",
            "coat",
            "transmission",
            "subsurface",
            "anisotropy",
            "ior",
            "anisotropy_angle",
            "emissive",
        )
    ),
    "normal",
    "ao",
)
#: Maps shown only through others (the height, through the normal and AO).
NOT_READ: frozenset[str] = frozenset(ARRAY_FIELDS) - frozenset(LIT_MAPS)

#: Texels per band of the numpy path (~150 float64 temporaries each).
_BAND_TEXELS = 1 << 15

LIT_LAYOUT_NOTE: str = (
    "lit preview: the swatch seen head-on by a camera "
    f"{M.CAMERA_DISTANCE:g} half-widths above it, shaded with GGX microfacets "
    "(metallic/roughness; F0 from ior for dielectrics, base colour for metals), a clear coat "
    f"(roughness {M.COAT_ROUGHNESS:g}), a sheen lobe (white mixed with the base colour's hue: "
    "a soft lift on flat cloth, a bright rim where the relief slopes steeply), subsurface wrap "
    "and anisotropy (brush "
    "lines along anisotropy_angle, the highlight stretched across them). Studio: a sky "
    "gradient (bright at the top, dark at the bottom), a large "
    "softbox above the camera and a thin strip light below it, which smooth and metallic "
    "surfaces reflect as a gradient with a bright band in the upper part of the swatch (rough "
    "ones as a soft glow); a grazing key light from the upper left at "
    f"{M.KEY_ELEVATION_DEG:g} degrees elevation and a fill light from the lower right at "
    f"{M.FILL_ELEVATION_DEG:g} degrees. Relief (height) shows through the normals it produces "
    "(slopes facing the upper left are lit, the others shaded, with highlights and a sheen rim "
    "on slopes) and through ambient occlusion in cavities; there are no cast shadows. "
    "Transmission shows a grey checker backdrop through the surface (shifted by the normals as "
    "refraction, blurred by roughness, tinted by the base colour); uncovered areas (alpha < 1) "
    "show the plain checker; emissive adds light."
)

FLAT_LAYOUT_NOTE: str = (
    "flat preview (the reference's): Blinn-Phong under one directional light (azimuth "
    f"{DEFAULT_LIGHT.azimuth_deg:g} degrees from the upper right, elevation "
    f"{DEFAULT_LIGHT.elevation_deg:.1f} degrees) plus a constant ambient of 0.2 x base colour; "
    "there is no environment to reflect, so metallic surfaces show only that ambient and a "
    "small highlight (a flat polished metal is dark) and roughness shows only as highlight "
    "width; coat adds a near-uniform lift of at most 0.04; sheen only brightens the base colour "
    "by 10 % plus a rim on steep slopes; transmission and uncovered areas fade to flat 50 % grey "
    "(no backdrop, no refraction); subsurface widens the diffuse wrap; anisotropy only widens "
    "or narrows the single highlight. Relief shows through the normals and AO."
)


def _lights(key_light: Light | None) -> np.ndarray:
    """[[lx, ly, lz, intensity]] of the key (``key_light`` or the studio's) and the fill."""
    key = M.KEY_DIRECTION if key_light is None else key_light.direction()
    return np.array([(*key, M.KEY_INTENSITY), (*M.FILL_DIRECTION, M.FILL_INTENSITY)], np.float64)


def _inputs(maps: MaterialMaps) -> tuple[np.ndarray, ...]:
    """C-contiguous float32 maps in :data:`LIT_MAPS` order, shapes checked (the kernel runs
    without bounds checks)."""
    rows, cols = maps.alpha.shape
    arrays = []
    for name in LIT_MAPS:
        array = np.ascontiguousarray(getattr(maps, name), dtype=np.float32)
        components = LAYOUT.components(name)
        expected = (rows, cols) if components == 1 else (rows, cols, components)
        if array.shape != expected:
            raise ValueError(f"map {name!r} has shape {array.shape}, expected {expected}")
        arrays.append(array)
    return tuple(arrays)


def _unit(a: np.ndarray, nan: float = 0.0) -> np.ndarray:
    a = a.astype(np.float64)
    return np.where(np.isnan(a), nan, np.clip(a, 0.0, 1.0))


def _range(a: np.ndarray, lo: float, hi: float, nan: float) -> np.ndarray:
    a = a.astype(np.float64)
    return np.where(np.isnan(a), nan, np.clip(a, lo, hi))


def _normal(n: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The reference's sanitising (non-finite x, y -> 0, z -> 1; z in [-1, 1]), normalised."""
    n = n.astype(np.float64)
    finite = np.isfinite(n)
    nx = np.where(finite[..., 0], n[..., 0], 0.0)
    ny = np.where(finite[..., 1], n[..., 1], 0.0)
    nz = np.where(finite[..., 2], np.clip(n[..., 2], -1.0, 1.0), 1.0)
    length = np.sqrt(nx * nx + ny * ny + nz * nz)
    ok = length > 1e-12
    safe = np.where(ok, length, 1.0)
    return np.where(ok, nx / safe, 0.0), np.where(ok, ny / safe, 0.0), np.where(ok, nz / safe, 1.0)


def _shade_band(
    m: tuple[np.ndarray, ...], px: np.ndarray, py: np.ndarray, lights: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """lit_model.shade_texel on a band of gathered maps (numpy path)."""
    basecolor, alpha, metallic, rough, sheen, coat, trans, ss, aniso, ior, angle, glow = m[:12]
    normal, ao = m[12:]
    aniso = _unit(aniso)
    degrees = angle.astype(np.float64)
    rotated = (aniso > 0.0) & (degrees != 0.0) & np.isfinite(degrees)
    theta = np.radians(np.where(rotated, degrees, 0.0))
    # the angle is the brushing direction; the GGX tangent (larger alpha: the stretch) is across
    # it, at angle + 90 (ANISOTROPY_STRETCH_OFFSET_DEG): (cos, sin) of that is (-sin, cos)
    tangent = (np.where(rotated, -np.sin(theta), 0.0), np.where(rotated, np.cos(theta), 1.0))
    scalars = (
        _unit(alpha),
        _unit(metallic),
        _unit(rough),
        _unit(sheen),
        _unit(coat),
        _unit(trans),
        _unit(ss),
        aniso,
        _range(ior, 1.0, 3.0, 1.5),
        _unit(ao, 1.0),
    )
    base = tuple(_unit(basecolor[..., c]) for c in range(3))
    emissive = tuple(_range(glow[..., c], 0.0, 1e4, 0.0) for c in range(3))
    key, fill = tuple(lights[0]), tuple(lights[1])
    with np.errstate(all="ignore"):
        return M.shade_texel(px, py, base, emissive, scalars, _normal(normal), tangent, key, fill)


def _shade_numpy(m: tuple[np.ndarray, ...], lights: np.ndarray, tile: int) -> np.ndarray:
    rows, cols = m[1].shape
    out_rows, out_cols = rows * tile, cols * tile
    scale = 2.0 / max(out_rows, out_cols)
    out = np.empty((out_rows, out_cols, 3), dtype=np.uint8)
    col_index = np.arange(out_cols) % cols
    px = ((np.arange(out_cols) + 0.5) * scale - 0.5 * out_cols * scale)[None, :]
    band = max(1, _BAND_TEXELS // out_cols)
    top = M.LUT_SIZE - 1
    for first in range(0, out_rows, band):
        index = np.arange(first, min(first + band, out_rows))
        gather = np.ix_(index % rows, col_index)
        py = (0.5 * out_rows * scale - (index + 0.5) * scale)[:, None]
        shaded = _shade_band(tuple(a[gather] for a in m), px, py, lights)
        for c, value in enumerate(shaded):
            level = np.nan_to_num(np.clip(value, 0.0, 1.0), nan=0.0) * top + 0.5
            out[first : first + len(index), :, c] = M.SRGB_LUT[level.astype(np.int64)]
    return out


def _shade_numba(m: tuple[np.ndarray, ...], lights: np.ndarray, tile: int) -> np.ndarray:
    from matloom.engine.kernels.threads import parallel_rows
    from matloom.render.lit_numba import lit_rows

    rows, cols = m[1].shape
    out = np.empty((rows * tile, cols * tile, 3), dtype=np.uint8)
    lut = M.SRGB_LUT

    def work(first: int, last: int) -> None:
        lit_rows(m, lights, lut, tile, out, first, last)

    parallel_rows(out.shape[0], out.shape[1], work)
    return out


_SHADERS: dict[str, Callable[[tuple[np.ndarray, ...], np.ndarray, int], np.ndarray]] = {
    "numpy": _shade_numpy,
    "numba": _shade_numba,
}


@functools.cache
def _numba_importable() -> bool:
    try:
        import matloom.render.lit_numba  # noqa: F401
    except ImportError:
        return False
    return True


def available_backends() -> list[str]:
    """Backends :func:`shade_lit` accepts here (``numba`` only when numba is installed)."""
    return sorted(name for name in _SHADERS if name != "numba" or _numba_importable())


def _resolve_backend(backend: str, texels: int = 0, session: Session | None = None) -> str:
    """As :func:`matloom.render.preview.shade` resolves it (:func:`pick_shader`)."""
    return pick_shader(backend, _SHADERS, _numba_importable, texels=texels, session=session)


def shade_lit(
    maps: MaterialMaps,
    *,
    key_light: Light | None = None,
    tile: int = 1,
    backend: str = "auto",
    session: Session | None = None,
) -> np.ndarray:
    """Shade ``maps`` in the lit studio; uint8 (tile H, tile W, 3) sRGB, like
    :func:`~matloom.render.preview.shade`.

    ``key_light`` replaces the studio's grazing key light (azimuth 135, elevation 25 degrees).
    ``tile`` > 1 shades the maps repeated n x n as one surface (the camera's view of the studio
    spans the whole image, so the tiling adds no seams of its own). ``backend``: ``auto``
    (``session``'s choice), ``numba`` or ``numpy`` (the same formulas). Raises ValueError on
    mis-shaped maps.
    """
    if tile < 1:
        raise ValueError(f"tile count must be >= 1, got {tile}")
    shader = _resolve_backend(backend, int(np.size(maps.alpha)) * tile * tile, session)
    return _SHADERS[shader](_inputs(maps), _lights(key_light), tile)
