"""numba kernel for sweep previews: normals + cavity AO + fixed-light shading in one pass.

Input is the planar (N_PLANES, H, W) output of the compositing kernel in preview mode (alpha,
the scalars, height, basecolor r g b, emissive r g b; plane indices from
:mod:`matloom.vocab.layout`); output is the uint8 RGB preview. The
relief follows :mod:`matloom.engine.relief` (same float32 formulas) and the shading follows
:func:`matloom.render.preview.shade`, but in float32 with vectorised approximations of log2 and
exp2 for the powers (relative error about 1e-5), so a sweep preview may differ from
``matloom.preview`` by one level at a few texels. It is serial and
``nogil``: the sweep shades several candidates at once on threads.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from matloom.engine.kernels.register_numba import _jit
from matloom.engine.kernels.relief_numba import _box_row, tap_weights
from matloom.engine.relief import DEFAULT_AO_RADIUS_TEXELS
from matloom.vocab.layout import LAYOUT, RELIEF_SOURCE

# Planes of the channels the shading reads (numba freezes them as constants at compile time).
_ALPHA = LAYOUT.plane(LAYOUT.coverage.name)
_METALLIC, _ROUGHNESS = LAYOUT.plane("metallic"), LAYOUT.plane("roughness")
_SHEEN, _COAT = LAYOUT.plane("sheen"), LAYOUT.plane("coat")
_TRANSMISSION, _SUBSURFACE = LAYOUT.plane("transmission"), LAYOUT.plane("subsurface")
_ANISOTROPY, _IOR = LAYOUT.plane("anisotropy"), LAYOUT.plane("ior")
_ANISOTROPY_ANGLE = LAYOUT.plane("anisotropy_angle")
_HEIGHT = LAYOUT.plane(RELIEF_SOURCE)
_BASECOLOR, _EMISSIVE = LAYOUT.plane("basecolor"), LAYOUT.plane("emissive")  # r; g, b follow

_LN2 = math.log(2.0)
#: Taylor coefficients of 2**f = exp(f ln 2) on [0, 1) (relative error < 1e-6).
_EXP2 = tuple(_LN2**k / math.factorial(k) for k in range(8))
_SRGB_KNEE = np.float32(0.0031308)


@_jit(inline=True)
def _clip01(v: np.float32) -> np.float32:
    if v < np.float32(0.0):
        return np.float32(0.0)
    if v > np.float32(1.0):
        return np.float32(1.0)
    return v


@_jit()
def log2_row(x, out, bits):  # type: ignore[no-untyped-def]
    """out = log2(x) for x >= 0 (0 gives -127, NaN stays NaN) to about 2e-6, vectorised:
    exponent from the bits, log2 of the mantissa m in [1, 2) by the atanh series."""
    xi = x.view(np.int32)
    for j in range(x.size):
        bits[j] = (xi[j] & 0x7FFFFF) | 0x3F800000
    mantissa = bits.view(np.float32)
    one = np.float32(1.0)
    for j in range(x.size):
        m = mantissa[j]
        z = (m - one) / (m + one)
        z2 = z * z
        poly = np.float32(1.0 / 11.0)
        poly = poly * z2 + np.float32(1.0 / 9.0)
        poly = poly * z2 + np.float32(1.0 / 7.0)
        poly = poly * z2 + np.float32(1.0 / 5.0)
        poly = poly * z2 + np.float32(1.0 / 3.0)
        poly = poly * z2 + one
        value = np.float32((xi[j] >> 23) - 127) + np.float32(2.0 / _LN2) * z * poly
        out[j] = value if x[j] == x[j] else x[j]


@_jit()
def exp2_row(y, out, bits):  # type: ignore[no-untyped-def]
    """out = 2**y for y <= 127 (0 below 2**-126, NaN stays NaN) to about 1e-6 relative,
    vectorised."""
    for j in range(y.size):
        n = np.floor(y[j])
        bits[j] = (np.int32(max(n, np.float32(-127.0))) + 127) << 23
    scale = bits.view(np.float32)
    for j in range(y.size):
        n = np.floor(y[j])
        f = y[j] - n
        poly = np.float32(_EXP2[7])
        for k in range(6, -1, -1):
            poly = poly * f + np.float32(_EXP2[k])
        value = poly * scale[j] if n >= np.float32(-126.0) else np.float32(0.0)
        out[j] = value if y[j] == y[j] else y[j]


def encode_coefficients() -> np.ndarray:
    """float32 coefficients (ascending) of a degree-5 fit of w ** (10 / 3) on
    [0.0031308 ** (1 / 8), 1], so that v ** (1 / 2.4) = P(v ** (1 / 8)) within 2e-7."""
    low = float(_SRGB_KNEE) ** 0.125
    nodes = np.cos(np.pi * (np.arange(64) + 0.5) / 64) * (1 - low) / 2 + (1 + low) / 2
    coefs = np.polynomial.polynomial.polyfit(nodes, nodes ** (10 / 3), 5)
    return coefs.astype(np.float32)


@_jit()
def encode_row(v, out, coefs):  # type: ignore[no-untyped-def]
    """out = linear -> sRGB of v (>= 0; NaN stays NaN): 12.92 v, or 1.055 v^(1/2.4) - 0.055
    with v^(1/2.4) = P(v^(1/8)) (three square roots and a polynomial: vectorises)."""
    c0, c1, c2, c3, c4, c5 = coefs[0], coefs[1], coefs[2], coefs[3], coefs[4], coefs[5]
    for j in range(v.size):
        x = v[j]
        w = np.sqrt(np.sqrt(np.sqrt(x)))
        power = ((((c5 * w + c4) * w + c3) * w + c2) * w + c1) * w + c0
        encoded = np.float32(1.055) * power - np.float32(0.055)
        out[j] = x * np.float32(12.92) if x <= _SRGB_KNEE else encoded


@_jit(inline=True)
def _quantise(v: np.float32) -> np.uint8:
    """Clip to [0, 1] and round half up to 8 bits; NaN becomes 0 (the reference's cast).
    Branch-free (truncation equals floor for the non-negative value) so that it vectorises."""
    q = np.float32(255.0) * _clip01(v) + np.float32(0.5)
    return np.uint8(np.int32(q if q == q else np.float32(0.0)))


@_jit()
def _normals_row(h, i, dx1, dx2, dy1, dy2, sx, sy):  # type: ignore[no-untyped-def]
    """Slopes of row i as :func:`relief_numba.normals_kernel` computes them."""
    rows, cols = h.shape
    row = h[i]
    sx[:] = np.float32(0.0)
    sy[:] = np.float32(0.0)
    if cols > 2:
        right, left, mid = row[2:], row[:-2], sx[1:-1]
        for j in range(cols - 2):
            mid[j] = (right[j] - left[j]) / dx2
    if cols > 1:
        sx[0] = (row[1] - row[0]) / dx1
        sx[cols - 1] = (row[cols - 1] - row[cols - 2]) / dx1
    if rows > 1:
        below, above = h[min(i + 1, rows - 1)], h[max(i - 1, 0)]
        div = dy2 if (0 < i < rows - 1) else dy1
        for j in range(cols):
            sy[j] = (below[j] - above[j]) / div


@_jit()
def _ao_row(h, mean, i, wy, div_y, depth, out):  # type: ignore[no-untyped-def]
    """out = AO of row i from the horizontally box-filtered ``mean``."""
    rows = h.shape[0]
    reach = (wy.size - 1) // 2
    out[:] = np.float32(0.0)
    for o in range(wy.size):
        src = mean[min(max(i + o - reach, 0), rows - 1)]
        w = wy[o]
        for j in range(out.size):
            out[j] += src[j] * w
    for j in range(out.size):
        cavity = _clip01((out[j] / div_y - h[i, j]) / depth)
        out[j] = _clip01(np.float32(1.0) - cavity)


@_jit()
def _rotate_stretch(shininess, anisotropy, angle, half):  # type: ignore[no-untyped-def]
    """shininess *= :func:`matloom.render.preview.anisotropy_direction_factor` (in float64 per
    texel; texels with angle 0 are left as they are)."""
    hx, hy = np.float64(half[0]), np.float64(half[1])
    in_plane = hx * hx + hy * hy
    for j in range(shininess.size):
        degrees = np.float64(angle[j])
        if degrees != 0.0:  # NaN too: it propagates
            quadrupled = 4.0 * np.float64(_clip01(anisotropy[j]))
            stretch = quadrupled / (1.0 + quadrupled)
            theta = degrees * (math.pi / 180.0)
            along = hy * math.cos(theta) - hx * math.sin(theta)  # across the brushing
            at_zero = in_plane - stretch * (hy * hy)
            if at_zero != 0.0:
                factor = (in_plane - stretch * (along * along)) / at_zero
                shininess[j] = np.float32(np.float64(shininess[j]) * factor)


@_jit()
def _shade_row(p, i, sx, sy, ao, light, half, coefs, has_emissive, has_angle, rows, bits, out):  # type: ignore[no-untyped-def]
    """The preview shading of row i (see :func:`matloom.render.preview.shade`) in float32.

    ``rows`` (12, W) float32 scratch. The work is split into short branch-free loops over 1-D
    rows with few arrays each (so that they vectorise), and the powers run as vectorised
    log2/exp2 passes.
    """
    one, zero, three = np.float32(1.0), np.float32(0.0), np.float32(3.0)
    n_dot_l, n_dot_h, nz_row, spec, tmp = rows[0], rows[1], rows[2], rows[3], rows[4]
    gain, rim, f0, coat_lobe, albedo, glow, metal = (
        rows[5],
        rows[6],
        rows[7],
        rows[8],
        rows[9],
        rows[10],
        rows[11],
    )
    l0, l1, l2, h0, h1, h2 = light[0], light[1], light[2], half[0], half[1], half[2]
    for j in range(sx.size):
        inv = one / np.sqrt(sx[j] * sx[j] + sy[j] * sy[j] + one)
        nx, ny, nz = -sx[j] * inv, sy[j] * inv, inv
        finite = (nx - nx == zero) and (ny - ny == zero) and (nz - nz == zero)
        nx = nx if finite else zero
        ny = ny if finite else zero
        nz = nz if finite else one
        n_dot_l[j] = _clip01(nx * l0 + ny * l1 + nz * l2)
        n_dot_h[j] = _clip01(nx * h0 + ny * h1 + nz * h2)
        nz_row[j] = nz
    roughness, anisotropy = p[_ROUGHNESS, i], p[_ANISOTROPY, i]
    for j in range(sx.size):
        smooth = one - _clip01(roughness[j])
        tmp[j] = (smooth * smooth * np.float32(100.0) + np.float32(2.0)) / (
            one + np.float32(4.0) * _clip01(anisotropy[j])
        )
    if has_angle:
        _rotate_stretch(tmp, anisotropy, p[_ANISOTROPY_ANGLE, i], half)
    log2_row(n_dot_h, spec, bits)
    for j in range(sx.size):
        tmp[j] *= spec[j]
    exp2_row(tmp, spec, bits)
    for j in range(sx.size):  # numpy's pow: 1 ** NaN = 1
        spec[j] = one if n_dot_h[j] == one else spec[j]
    coat = p[_COAT, i]
    for j in range(sx.size):
        nh = n_dot_h[j]
        nh2 = nh * nh
        nh16 = nh2 * nh2
        nh16 *= nh16
        nh16 *= nh16
        coat_lobe[j] = (
            np.float32(0.04)
            * _clip01(coat[j])
            * (np.float32(0.5) + np.float32(0.5) * nh16 * nh16 * nh16 * nh2)
        )
    metallic, ior = p[_METALLIC, i], p[_IOR, i]
    for j in range(sx.size):
        m = _clip01(metallic[j])
        metal[j] = m
        eta = ior[j]
        eta = one if eta < one else (three if eta > three else eta)
        r0 = (one - eta) / (one + eta)
        f0[j] = r0 * r0 * (one - m)
    sheen, subsurface = p[_SHEEN, i], p[_SUBSURFACE, i]
    for j in range(sx.size):
        shn = _clip01(sheen[j])
        ss = _clip01(subsurface[j])
        wrap = _clip01((n_dot_l[j] + ss) / (one + ss))
        gain[j] = np.float32(0.2) + (one - metal[j]) * wrap * ao[j] + shn * np.float32(0.1)
        tilt = one - nz_row[j]
        rim[j] = np.float32(0.5) * shn * (tilt * tilt) * (tilt * tilt) * tilt
    transmission, alpha = p[_TRANSMISSION, i], p[_ALPHA, i]
    for c in range(3):
        encode_row(p[_BASECOLOR + c, i], albedo, coefs)
        for j in range(sx.size):
            a = albedo[j]
            tmp[j] = a * gain[j] + rim[j] + (f0[j] + a * metal[j]) * spec[j] + coat_lobe[j]
        if has_emissive:
            emissive = p[_EMISSIVE + c, i]
            for j in range(sx.size):
                glow[j] = emissive[j] / (one + emissive[j])
            encode_row(glow, albedo, coefs)
            for j in range(sx.size):
                tmp[j] += albedo[j] if emissive[j] != zero else zero
        for j in range(sx.size):
            trans = _clip01(transmission[j])
            cover = _clip01(alpha[j])
            material = tmp[j] * (one - trans) + np.float32(0.5) * trans
            out[i, j, c] = _quantise(material * cover + np.float32(0.5) * (one - cover))


@_jit()
def relief_shade(planes, spacing, wx, div_x, wy, div_y, depth, light, half, coefs, mean, out):  # type: ignore[no-untyped-def]
    """Shade the composited ``planes`` (N_PLANES, H, W) into ``out`` (H, W, 3) uint8.

    ``spacing`` = float32 (dx, 2 dx, dy, 2 dy); ``wx``/``wy`` and ``div_x``/``div_y`` are the AO
    box taps and divisors, ``depth`` the AO depth scale; ``mean`` is (H, W) float32 scratch.
    ``light`` and ``half`` are float32 unit vectors, ``coefs`` = :func:`encode_coefficients`.
    """
    h = planes[_HEIGHT]
    rows, cols = h.shape
    for i in range(rows):
        _box_row(h[i], wx, div_x, mean[i])
    has_emissive = False
    for c in range(_EMISSIVE, _EMISSIVE + 3):
        for i in range(rows):
            for j in range(cols):
                has_emissive |= planes[c, i, j] != np.float32(0.0)
    has_angle = False
    for i in range(rows):
        for j in range(cols):
            has_angle |= planes[_ANISOTROPY_ANGLE, i, j] != np.float32(0.0)
    sx = np.empty(cols, np.float32)
    sy = np.empty(cols, np.float32)
    ao = np.empty(cols, np.float32)
    scratch = np.empty((12, cols), np.float32)
    bits = np.empty(cols, np.int32)
    for i in range(rows):
        _normals_row(h, i, spacing[0], spacing[1], spacing[2], spacing[3], sx, sy)
        _ao_row(h, mean, i, wy, div_y, depth, ao)
        _shade_row(
            planes, i, sx, sy, ao, light, half, coefs, has_emissive, has_angle, scratch, bits, out
        )


@dataclass(frozen=True)
class ShadeInputs:
    """The constant inputs of :func:`relief_shade` for one grid and one light, by name (in the
    kernel's argument order); built once per sweep by :meth:`build`, read by every thread."""

    #: float32 (dx, 2 dx, dy, 2 dy): the normals' central differences.
    spacing: np.ndarray
    #: AO box taps and divisor along x and along y (the reference's default radius).
    wx: np.ndarray
    div_x: np.float32
    wy: np.ndarray
    div_y: np.float32
    #: The AO depth scale (radius x dx).
    depth: np.float32
    #: float32 unit light and half vectors.
    light: np.ndarray
    half: np.ndarray
    #: :func:`encode_coefficients`.
    coefs: np.ndarray

    @classmethod
    def build(cls, dx: float, dy: float, light: np.ndarray, half: np.ndarray) -> ShadeInputs:
        """Inputs for texel size (``dx``, ``dy``) and the (float64) light and half vectors."""
        radius = DEFAULT_AO_RADIUS_TEXELS
        taps, divisor = tap_weights(radius) or (np.ones(17, np.float32), np.float32(17))
        return cls(
            spacing=np.array([dx, 2.0 * dx, dy, 2.0 * dy], dtype=np.float32),
            wx=taps,
            div_x=divisor,
            wy=taps,
            div_y=divisor,
            depth=np.float32(radius * dx),
            light=np.asarray(light).astype(np.float32),
            half=np.asarray(half).astype(np.float32),
            coefs=encode_coefficients(),
        )

    def shade(self, planes: np.ndarray, mean: np.ndarray, out: np.ndarray) -> None:
        """:func:`relief_shade` of ``planes`` into ``out`` with these inputs (``mean``: scratch)."""
        relief_shade(
            planes,
            self.spacing,
            self.wx,
            self.div_x,
            self.wy,
            self.div_y,
            self.depth,
            self.light,
            self.half,
            self.coefs,
            mean,
            out,
        )
