"""Quick fixed-light preview: the reference's numpy shading of composited maps, reproduced.

The reference (``fixed_light_preview``, spec §6) shades a head-on swatch with Blinn-Phong, a
constant-F0 Fresnel term, a coat lobe, wrap-lit subsurface, sheen, a 0.2 ambient term, soft-knee
emissive and a transmission / coverage mix over 0.5 grey. :func:`shade` applies exactly that
shading to a :class:`~matloom.engine.maps.MaterialMaps`. The seed sweep calls it ~1000 times per
prompt, so it has two implementations with the same results:

* ``numba`` (used when asked for, or when the session's policy picks it: numba loaded or a
  large image, :meth:`matloom.engine.session.Session.choose_shader`; kernels in
  :mod:`matloom.engine.kernels.shade_numba`): per-texel kernels, no full-size temporaries. The
  three pow-like steps are vectorised numpy calls between the kernels (numpy's SIMD ``pow`` is
  several times faster than a scalar libm call in a loop), and so is the anisotropy rotation
  (only when some angle is not 0; it is the numpy path's own function, so both agree).
* ``numpy`` (a short command's, the fallback without numba, or ``MATLOOM_BACKEND=numpy``): the
  formulas on whole arrays.

Precision: the maps are float32 (the reference blends them in float64, a ~1e-7 relative
difference). Both implementations shade in float64 as the reference does; the numba path only
takes v^(1/2.4) of the albedo and of the soft-knee emissive in float32, which moved 2 of about
2 million values by one level against the numpy path in a random stress test
(``benchmarks/preview.py``). Both reproduce all 30 reference previews of the parity fixtures
byte for byte.

Anisotropy: the reference widens the Blinn-Phong lobe by 1 / (1 + 4 anisotropy); we read that
as brush lines along +x, the highlight stretched across them, along +y (as real grooves stretch
it). ``anisotropy_angle`` (the brushing direction, degrees counter-clockwise from +x) turns the
stretch to angle + 90: the exponent is then multiplied by :func:`anisotropy_direction_factor`,
the ratio of the Ashikhmin-Shirley exponents with the turned and the unturned stretch. It is
exactly 1 where the angle is 0 (so every preview without the channel is unchanged, byte for
byte) and where the anisotropy is 0; otherwise the highlight dims or brightens as the stretch turns
across or along the half vector's in-plane direction. Angles are axial (180 = 0).

Non-finite inputs never raise. They follow the reference's arithmetic (NaN propagates through
clamps and ``pow`` as in numpy, so e.g. 1^NaN = 1; non-finite normal components are replaced by
nx, ny = 0 and nz = 1), and a texel whose final value is NaN is written as 0, which is what the
reference's float-to-uint8 cast produced on its platform (e.g. +inf emissive gives
inf / (1 + inf) = NaN -> 0; NaN albedo -> 0; see the ``nan_inf_fields`` fixture).
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable, Collection
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from matloom.engine.colour import fast_linear_to_srgb, linear_to_srgb
from matloom.engine.maps import ARRAY_FIELDS, MaterialMaps
from matloom.vocab.layout import LAYOUT

if TYPE_CHECKING:
    from matloom.engine.session import Session

#: Composited maps only other maps are derived from (height -> normal, AO).
_RELIEF_SOURCES = frozenset(LAYOUT[d.source].field for d in LAYOUT.derived)
#: The anisotropy amount and direction maps (see the module docstring).
_ANISOTROPY = LAYOUT["anisotropy"].field
_ANISOTROPY_ANGLE = LAYOUT["anisotropy_angle"].field

#: The reference's fixed light direction, normalize(0.5, 0.5, 1), as exact float64 components.
_REFERENCE_LIGHT: tuple[float, float, float] = tuple(
    # math.sqrt(1.5) is exactly the np.linalg.norm([0.5, 0.5, 1.0]) the reference divides by
    float(c)
    for c in np.array([0.5, 0.5, 1.0]) / math.sqrt(1.5)
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


@dataclass(frozen=True, eq=False)
class ShadeParams:
    """The flat preview's shading parameters for one light: the light, its unit vector L
    (``direction``) and the half vector H = normalize(L + V), V = (0, 0, 1), float64 3-vectors.

    Public so that the seed sweep (:func:`matloom.engine.schedules.sweep.run_sweep`, an engine
    schedule whose float32 kernel shades its candidates) shades with the same vectors, and
    previews what its kernel cannot take with :meth:`shade`.
    """

    light: Light
    direction: np.ndarray
    half: np.ndarray

    @classmethod
    def of(cls, light: Light | None = None) -> ShadeParams:
        """The parameters of ``light`` (default: the reference's light)."""
        light = light or DEFAULT_LIGHT
        direction = np.array(light.direction(), dtype=np.float64)
        half = direction + np.array([0.0, 0.0, 1.0])
        norm = math.sqrt(half.dot(half))  # what np.linalg.norm computes, without linalg
        # A light straight from below (L = -V) has no half vector; any unit H is as good.
        half = half / norm if norm > 0.0 else np.array([0.0, 0.0, 1.0])
        return cls(light, direction, half)

    def shade(self, maps: MaterialMaps, backend: str = "auto") -> np.ndarray:
        """:func:`shade` of ``maps`` with this light."""
        return shade(maps, light=self.light, backend=backend)


_SRGB_EXPONENT = 1.0 / 2.4
_SRGB_KNEE = 0.0031308


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


def anisotropy_direction_factor(
    angle_deg: np.ndarray, anisotropy: np.ndarray, half: np.ndarray
) -> np.ndarray:
    """Per texel, the factor that turns the reference's exponent (brushing along +x, stretch
    along +y) into the exponent with the brushing along ``angle_deg`` (degrees counter-clockwise
    from +x), the stretch across it.

    With the stretch t = (cos(angle + 90), sin(angle + 90)) = (-sin angle, cos angle), the
    in-plane half vector h = (H_x, H_y) and k = 1 / (1 + 4 a) (``anisotropy`` a, already
    clamped to [0, 1]), the Ashikhmin-Shirley exponent is proportional to
    k (h.t)^2 + (h.b)^2 = |h|^2 - (1 - k) (h.t)^2; the factor is its value at the angle over
    its value at 0. It is exactly 1 where the angle is 0, where
    a = 0 and when h = 0 (a head-on half vector has no direction to compare with). NaN
    angles give NaN, as every other NaN map does. float64, shared by both shaders.
    """
    hx, hy = float(half[0]), float(half[1])
    in_plane = hx * hx + hy * hy
    with np.errstate(all="ignore"):
        theta = np.radians(np.asarray(angle_deg, dtype=np.float64))
        along = hy * np.cos(theta) - hx * np.sin(theta)  # h.t, t across the brushing
        quadrupled = 4.0 * np.asarray(anisotropy, dtype=np.float64)
        stretch = quadrupled / (1.0 + quadrupled)  # 1 - k
        at_zero = in_plane - stretch * (hy * hy)
        factor = (in_plane - stretch * (along * along)) / at_zero
    return np.where((angle_deg == 0) | (at_zero == 0), 1.0, factor)


#: The maps the shading reads: every map of the layout but the height (the shading reads the
#: normal and AO derived from it), with their component counts (1: (H, W), 3: (H, W, 3)).
_INPUTS: dict[str, int] = {
    name: LAYOUT.components(name) for name in ARRAY_FIELDS if name not in _RELIEF_SOURCES
}


def _kernel_inputs(maps: MaterialMaps) -> dict[str, np.ndarray]:
    """C-contiguous float32 views of the maps the shading reads, with their shapes checked.

    The kernels run without bounds checks, so a mis-shaped map must be refused here. Float32
    C-contiguous maps (the normal case) are passed through without copying, and every call
    then hits the same compiled kernel signature.
    """
    rows, cols = maps.alpha.shape
    inputs: dict[str, np.ndarray] = {}
    for name, components in _INPUTS.items():
        array = np.ascontiguousarray(getattr(maps, name), dtype=np.float32)
        expected = (rows, cols) if components == 1 else (rows, cols, components)
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
    from matloom.engine.kernels.shade_numba import _shade_kernel, _specular_base_kernel

    _specular_base_kernel(m["normal"], m["roughness"], m[_ANISOTROPY], half, n_dot_h, spec)
    angle = m[_ANISOTROPY_ANGLE]
    if angle.any():  # NaN counts: it propagates as in the numpy path
        anisotropy = np.clip(m[_ANISOTROPY].astype(np.float64), 0.0, 1.0)
        spec *= anisotropy_direction_factor(angle, anisotropy, half)
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
    """Whole-array float64 path, the reference's formulas in the reference's order.

    The sRGB encodes take numpy's fast ``power`` (its last bit depends on the CPU); a texel
    whose value lies within :data:`_LEVEL_MARGIN` of a quantisation boundary, where that bit
    could move it by a level, is shaded again with the portable power, so the image is the
    same on every CPU and equal to the all-portable shading."""
    with np.errstate(all="ignore"):
        scaled = _scaled_levels(_shade_values(m, direction, half, fast_linear_to_srgb))
        levels = np.floor(scaled)
        frac = scaled - levels
        near = ((frac < _LEVEL_MARGIN) | (frac > 1.0 - _LEVEL_MARGIN)).any(axis=-1)
        if near.any():
            subset = {name: values[near] for name, values in m.items()}
            exact = _shade_values(subset, direction, half, linear_to_srgb)
            levels[near] = np.floor(_scaled_levels(exact))
        levels[np.isnan(levels)] = 0.0
    return levels.astype(np.uint8)


#: Distance from a quantisation boundary (in levels) within which :func:`_shade_numpy`
#: recomputes a texel with the portable power: far above the few-ulp difference of numpy's
#: ``power`` from it, carried through the shading (< 1e-11 levels).
_LEVEL_MARGIN = 1e-7


def _scaled_levels(out: np.ndarray) -> np.ndarray:
    """255 x clip(out, 0, 1) + 0.5: the value the 8-bit quantisation floors."""
    return 255.0 * np.clip(out, 0.0, 1.0) + 0.5


def _shade_values(
    m: dict[str, np.ndarray],
    direction: np.ndarray,
    half: np.ndarray,
    encode: Callable[[np.ndarray], np.ndarray],
) -> np.ndarray:
    """The shaded float64 RGB before quantisation (any leading shape: an image or the texels
    of a mask), with ``encode`` as the sRGB encode."""
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
            1.0 + 4.0 * clipped[_ANISOTROPY]
        )
        angle = m[_ANISOTROPY_ANGLE]
        if angle.any():
            shininess *= anisotropy_direction_factor(angle, clipped[_ANISOTROPY], half)
        albedo = encode(m["basecolor_linear"].astype(np.float64))
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
            shaded += encode(emissive / (1.0 + emissive))
        material = shaded * (1.0 - trans)[..., None] + 0.5 * trans[..., None]
        return material * cover[..., None] + 0.5 * (1.0 - cover)[..., None]


#: Channels the reference clamps to [0, 1] before shading: coverage and the [0, 1] scalars.
_UNIT_CHANNELS: tuple[str, ...] = tuple(c.field for c in (LAYOUT.coverage, *LAYOUT.unit_scalars))

#: Shading implementations by backend name (see the module docstring).
_SHADERS: dict[str, Callable[[dict[str, np.ndarray], np.ndarray, np.ndarray], np.ndarray]] = {
    "numpy": _shade_numpy,
    "numba": _shade_numba,
}


@functools.cache
def _numba_importable() -> bool:
    """True when the numba shading kernels can be imported (imports numba; asked once, since
    ``auto`` asks on every shade and a failed import is not cached by Python)."""
    try:
        import matloom.engine.kernels.shade_numba  # noqa: F401
    except ImportError:
        return False
    return True


def available_shaders() -> list[str]:
    """Backend names :func:`shade` accepts here (``numba`` only when numba is installed)."""
    return sorted(name for name in _SHADERS if name != "numba" or _numba_importable())


def pick_shader(
    backend: str,
    names: Collection[str],
    numba_ok: Callable[[], bool],
    *,
    texels: int = 0,
    session: Session | None = None,
) -> str:
    """The shader to use among ``names`` (``numba`` counts only when ``numba_ok()``): ``auto``
    -> the session's choice for an image of ``texels`` texels
    (:meth:`~matloom.engine.session.Session.choose_shader`: numpy for a short command, numba
    where numba is loaded or the image is large), numpy where numba is not installed; an
    explicit name must be available (ValueError otherwise). Shared by every preview layout.
    ``session`` defaults to the process's default session.

    The numpy and numba shaders may differ by one level on rare texels (see the module
    docstring), so ``auto``'s preview of a small image in a fresh process (numpy) and in one
    that has loaded numba may differ there; a cold and a warm start of one command do not.
    """
    if backend == "auto":
        from matloom.engine.session import default_session

        backend = (session or default_session()).choose_shader("auto", texels)
        if backend not in names or (backend == "numba" and not numba_ok()):
            return "numpy"
        return backend
    if backend not in names or (backend == "numba" and not numba_ok()):
        have = sorted(name for name in names if name != "numba" or numba_ok())
        raise ValueError(f"unknown or unavailable shader {backend!r}; have {have}")
    return backend


def _resolve_backend(backend: str, texels: int = 0, session: Session | None = None) -> str:
    return pick_shader(backend, _SHADERS, _numba_importable, texels=texels, session=session)


def shade(
    maps: MaterialMaps,
    *,
    light: Light | None = None,
    backend: str = "auto",
    session: Session | None = None,
) -> np.ndarray:
    """Shade ``maps`` with the reference's fixed-light preview; uint8 (H, W, 3) RGB.

    ``light`` defaults to the reference's light normalize(0.5, 0.5, 1); any other light only
    changes L (and the half vector), never the formulas. The result does not depend on the
    maps' View: the reference previews whatever window the maps were evaluated on. ``backend``
    is ``auto`` (``session``'s choice, :func:`pick_shader`), ``numba`` or ``numpy`` (the same
    images but for one level on rare texels). Never raises on non-finite values (see the module
    docstring); raises ValueError on mis-shaped maps.
    """
    params = ShadeParams.of(light)
    shader = _resolve_backend(backend, int(np.size(maps.alpha)), session)
    return _SHADERS[shader](_kernel_inputs(maps), params.direction, params.half)


def tile_image(img: np.ndarray, n: int = 2) -> np.ndarray:
    """Repeat ``img`` n x n times (rows and columns) so that tiling seams become visible."""
    if n < 1:
        raise ValueError(f"tile count must be >= 1, got {n}")
    reps = (n, n) + (1,) * (img.ndim - 2)
    return np.tile(img, reps)
