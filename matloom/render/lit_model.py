"""The ``lit`` preview's studio and shading formulas, shared by its numpy and numba paths.

Every function here is branch-free arithmetic on numpy ufuncs (``np.sqrt``, ``np.exp``,
``np.minimum``, ...), so the one source runs on whole arrays (the numpy path of
:mod:`matloom.render.lit`) and on per-texel floats compiled by numba
(:mod:`matloom.render.lit_numba` registers these functions with ``register_jitable``). The two
paths therefore agree up to floating-point rounding.

Frame: x right, y up (toward image row 0), z out of the swatch toward the camera, i.e. the
normal map's OpenGL convention. Swatch coordinates (px, py) put the longer side of the (tiled)
image on [-1, 1]; the camera looks straight down -z from :data:`CAMERA_DISTANCE` above the
centre (a mild perspective, so that a flat mirror reflects a band of the studio rather than one
point of it).

The studio (linear radiance; "albedo units": a white Lambert surface facing a light of
intensity I receives I):

* an environment: a sky gradient from :data:`GROUND` (below, image bottom) to :data:`SKY`
  (above, image top) along the reflected direction's y, a large softbox above the camera and a
  thin strip light below it, prefiltered analytically by roughness (the boxes' edges widen and
  the gradient flattens toward its mean as the lobe widens);
* a grazing key light (from the upper left, :data:`KEY_ELEVATION_DEG` above the surface) and a
  weak fill light from the lower right.

Shading: GGX microfacets with height-correlated Smith visibility and Schlick Fresnel (anisotropic
for the base lobe, stretched along the tangent, which is across the brushing direction
``anisotropy_angle``, at angle + 90, as real grooves stretch it), F0 from the ior
for dielectrics and from the base colour for metals, Karis' analytic split-sum term for the
environment; a clear coat (second GGX lobe, ior 1.5, :data:`COAT_ROUGHNESS`) attenuating what
is under it; a Charlie sheen lobe (roughness 0.5) with its directional albedo, coloured white
mixed with the base colour's hue (:data:`SHEEN_TINT`), so that it rims steep relief even on a
dark cloth; wrap-lit diffuse for subsurface; transmission shows a checker backdrop, refracted by
the normal and tinted by the base colour; uncovered texels show the same backdrop. Display: a soft shoulder above
:data:`TONE_KNEE`, then sRGB through :data:`SRGB_LUT`.
"""

from __future__ import annotations

import math

import numpy as np

#: What the formulas take and return: whole arrays (numpy path) or one texel's float (numba).
Value = np.ndarray | float
Vector = tuple[Value, Value, Value]
#: A directional light: (lx, ly, lz, intensity).
LightVector = tuple[float, float, float, float]

# --- camera and lights ---------------------------------------------------------------------

#: Camera height over the swatch centre, in swatch half-widths (about 44 degrees field of view).
CAMERA_DISTANCE = 2.5
#: Grazing key light: from the upper left, low over the surface, so that relief reads.
KEY_AZIMUTH_DEG = 135.0
KEY_ELEVATION_DEG = 25.0
KEY_INTENSITY = 1.0
#: Fill light from the lower right.
FILL_AZIMUTH_DEG = -45.0
FILL_ELEVATION_DEG = 50.0
FILL_INTENSITY = 0.2
#: Directional lights are treated as small discs: GGX alpha never goes below this for them.
LIGHT_SPREAD = 0.03

# --- environment ---------------------------------------------------------------------------

#: Linear radiance of the gradient's ends (image top: sky; bottom: ground).
SKY = (0.62, 0.67, 0.76)
GROUND = (0.05, 0.045, 0.04)
#: Sky mix t = 0.5 + SKY_SLOPE * r_y (clamped), for the reflected direction r.
SKY_SLOPE = 1.25
#: The softbox above the camera (centre r_y, half-height, half-width in direction space).
SOFTBOX_Y, SOFTBOX_HALF_HEIGHT, SOFTBOX_HALF_WIDTH, SOFTBOX_RADIANCE = 0.2, 0.08, 0.3, 3.5
#: The thin strip light below the camera.
STRIP_Y, STRIP_HALF_HEIGHT, STRIP_HALF_WIDTH, STRIP_RADIANCE = -0.24, 0.025, 0.6, 2.0
#: Edge softness of the light boxes: BOX_SOFT + BOX_BLUR * alpha (direction-space units).
BOX_SOFT, BOX_BLUR = 0.015, 1.5
#: The gradient flattens toward its mean by min(1, GRADIENT_BLUR * alpha).
GRADIENT_BLUR = 1.5
#: The diffuse (irradiance) lookup: the environment at the normal, blurred as this alpha.
DIFFUSE_BLUR = 1.2

# --- layers --------------------------------------------------------------------------------

#: Perceptual roughness of the clear coat (there is no coat roughness channel).
COAT_ROUGHNESS = 0.05
#: Lowest perceptual roughness of the base lobe (alpha = 0.002, a mirror).
MIN_ROUGHNESS = 0.045
#: Share of the base colour's hue in the sheen colour (0: white sheen, 1: the hue at full
#: brightness, the base colour divided by its largest component, as Blender's sheen tint): a
#: dark velvet keeps a bright, coloured rim instead of a sheen as dark as its base.
SHEEN_TINT = 0.5
#: Added to the base colour and its largest component before the hue is taken (a black base
#: gets a white sheen; no division by zero).
SHEEN_HUE_FLOOR = 1e-3
#: Subsurface widens the diffuse wrap by up to this much.
SUBSURFACE_WRAP = 0.5

# --- backdrop (transmission, uncovered texels) and display ---------------------------------

#: Checker cell size in swatch units (8 cells across the longer side) and its two radiances.
CHECKER_CELL = 0.25
CHECKER_DARK, CHECKER_LIGHT = 0.05, 0.45
#: How far the normal shifts the backdrop seen through a transmissive texel, times 1 - 1/ior.
REFRACTION = 0.4
#: Linear values above this are compressed smoothly toward 1 (a soft shoulder, slope 1 at it).
TONE_KNEE = 0.8
#: Entries of the linear -> 8-bit sRGB table (steps of 6e-5 in linear light).
LUT_SIZE = 16384


def _unit_vector(azimuth_deg: float, elevation_deg: float) -> tuple[float, float, float]:
    az, el = math.radians(azimuth_deg), math.radians(elevation_deg)
    return (math.cos(el) * math.cos(az), math.cos(el) * math.sin(az), math.sin(el))


KEY_DIRECTION = _unit_vector(KEY_AZIMUTH_DEG, KEY_ELEVATION_DEG)
FILL_DIRECTION = _unit_vector(FILL_AZIMUTH_DEG, FILL_ELEVATION_DEG)


def _srgb_lut() -> np.ndarray:
    """uint8 sRGB levels of LUT_SIZE evenly spaced linear values on [0, 1] (round half up)."""
    v = np.linspace(0.0, 1.0, LUT_SIZE)
    encoded = np.where(v <= 0.0031308, 12.92 * v, 1.055 * np.power(v, 1.0 / 2.4) - 0.055)
    return np.floor(255.0 * encoded + 0.5).astype(np.uint8)


SRGB_LUT: np.ndarray = _srgb_lut()


# --- formulas (arrays or floats) -----------------------------------------------------------


def clamp(v: Value, lo: Value, hi: Value) -> Value:
    return np.minimum(np.maximum(v, lo), hi)


def trapezoid(x: Value, half: float, soft: Value) -> Value:
    """A box of half-width ``half`` blurred by a box of width ``soft`` (area kept)."""
    peak = np.minimum(1.0, 2.0 * half / soft)
    return clamp((half + 0.5 * soft - np.abs(x)) / soft, 0.0, peak)


def environment(rx: Value, ry: Value, rz: Value, alpha: Value) -> tuple[Value, Value]:
    """(t, boxes) seen along the unit direction r by a lobe of GGX width ``alpha``: the sky mix
    t (0 ground .. 1 sky) and the light boxes' radiance."""
    t = clamp(0.5 + SKY_SLOPE * ry, 0.0, 1.0) * clamp(1.0 + 3.0 * rz, 0.0, 1.0)
    t = t + (0.5 - t) * np.minimum(GRADIENT_BLUR * alpha, 1.0)
    soft = BOX_SOFT + BOX_BLUR * alpha
    softbox = trapezoid(ry - SOFTBOX_Y, SOFTBOX_HALF_HEIGHT, soft) * trapezoid(
        rx, SOFTBOX_HALF_WIDTH, soft
    )
    strip = trapezoid(ry - STRIP_Y, STRIP_HALF_HEIGHT, soft) * trapezoid(rx, STRIP_HALF_WIDTH, soft)
    boxes = (SOFTBOX_RADIANCE * softbox + STRIP_RADIANCE * strip) * clamp(4.0 * rz, 0.0, 1.0)
    return t, boxes


def env_brdf(roughness: Value, nov: Value) -> tuple[Value, Value]:
    """Karis' analytic split-sum terms (A, B): reflectance = F0 * A + B."""
    r0 = 1.0 - roughness
    r1 = 0.0425 - 0.0275 * roughness
    # exp2(-9.28 nov) = exp(-z)^8, z = 0.804 nov <= 0.81: Taylor to z^4 (0.6 % at nov = 1),
    # no libm call, so that numba vectorises the texel loop
    z = -0.8040514 * nov
    e = 1.0 + z * (1.0 + z * (0.5 + z * (1.0 / 6.0 + z * (1.0 / 24.0))))
    e = e * e
    e = e * e
    a004 = np.minimum(r0 * r0, e * e) * r0 + r1
    return -1.04 * a004 + 1.04 - 0.572 * roughness, 1.04 * a004 - 0.04 + 0.022 * roughness


def ggx_aniso(
    noh: Value,
    toh: Value,
    boh: Value,
    nol: Value,
    tol: Value,
    bol: Value,
    nov: Value,
    tov: Value,
    bov: Value,
    at: Value,
    ab: Value,
) -> Value:
    """pi * D * V of anisotropic GGX (alpha ``at`` along the tangent, ``ab`` across) with
    height-correlated Smith visibility."""
    d = toh * toh / (at * at) + boh * boh / (ab * ab) + noh * noh
    lv = nol * np.sqrt(at * at * tov * tov + ab * ab * bov * bov + nov * nov)
    ll = nov * np.sqrt(at * at * tol * tol + ab * ab * bol * bol + nol * nol)
    return 0.5 / (at * ab * d * d * (lv + ll) + 1e-12)


def ggx(noh: Value, nol: Value, nov: Value, a: Value) -> Value:
    """pi * D * V of isotropic GGX with height-correlated Smith visibility."""
    a2 = a * a
    d = noh * noh * (a2 - 1.0) + 1.0
    lv = nol * np.sqrt(nov * nov * (1.0 - a2) + a2)
    ll = nov * np.sqrt(nol * nol * (1.0 - a2) + a2)
    return 0.5 * a2 / (d * d * (lv + ll) + 1e-12)


def sheen_lobe(noh: Value, nol: Value, nov: Value) -> Value:
    """pi * D * V of the Charlie sheen lobe at alpha 0.25 (sin^4) with Neubelt's visibility."""
    s2 = 1.0 - noh * noh
    return 3.0 * s2 * s2 / (4.0 * (nol + nov - nol * nov) + 1e-12)


def sheen_albedo(nov: Value) -> Value:
    """Directional albedo of :func:`sheen_lobe` (a cubic fit, within 0.04)."""
    x = 1.0 - nov
    return ((0.965460 * x - 0.613483) * x + 0.472778) * x + 0.018710


def fresnel_weight(voh: Value) -> Value:
    """Schlick's (1 - V.H)^5: F = F0 + (1 - F0) * weight."""
    w = 1.0 - voh
    w2 = w * w
    return w2 * w2 * w


def direct_light(
    light: LightVector,
    n: Vector,
    t: Vector,
    b: Vector,
    v: Vector,
    nov: Value,
    tov: Value,
    bov: Value,
    at: Value,
    ab: Value,
    wrap: Value,
) -> tuple[Value, Value, Value, Value, Value]:
    """One directional light ``light`` = (lx, ly, lz, intensity) on the frame (n, t, b) seen
    along v: (diffuse, specular, fresnel weight, coat, sheen), each already times N.L and the
    intensity except the Fresnel weight."""
    lx, ly, lz, intensity = light
    nx, ny, nz = n
    vx, vy, vz = v
    nol_raw = nx * lx + ny * ly + nz * lz
    nol = np.maximum(nol_raw, 0.0)
    hx, hy, hz = lx + vx, ly + vy, lz + vz
    inv = 1.0 / np.sqrt(hx * hx + hy * hy + hz * hz + 1e-12)
    hx, hy, hz = hx * inv, hy * inv, hz * inv
    noh = clamp(nx * hx + ny * hy + nz * hz, 0.0, 1.0)
    voh = clamp(vx * hx + vy * hy + vz * hz, 0.0, 1.0)
    toh = t[0] * hx + t[1] * hy + t[2] * hz
    boh = b[0] * hx + b[1] * hy + b[2] * hz
    tol = t[0] * lx + t[1] * ly + t[2] * lz
    bol = b[0] * lx + b[1] * ly + b[2] * lz
    lit = intensity * nol
    diffuse = intensity * np.maximum(nol_raw + wrap, 0.0) / ((1.0 + wrap) * (1.0 + wrap))
    spread = LIGHT_SPREAD * LIGHT_SPREAD
    at_l, ab_l = np.sqrt(at * at + spread), np.sqrt(ab * ab + spread)
    specular = lit * ggx_aniso(noh, toh, boh, nol, tol, bol, nov, tov, bov, at_l, ab_l)
    coat_alpha = COAT_ROUGHNESS * COAT_ROUGHNESS
    coat = lit * ggx(noh, nol, nov, math.sqrt(coat_alpha * coat_alpha + spread))
    return diffuse, specular, fresnel_weight(voh), coat, lit * sheen_lobe(noh, nol, nov)


def checker(qx: Value, qy: Value, blur: Value) -> Value:
    """Backdrop radiance at swatch point q, flattened toward its mean by ``blur`` in [0, 1]."""
    cells = np.floor(qx / CHECKER_CELL) + np.floor(qy / CHECKER_CELL)
    odd = cells - 2.0 * np.floor(0.5 * cells)
    value = CHECKER_DARK + (CHECKER_LIGHT - CHECKER_DARK) * odd
    return value + (0.5 * (CHECKER_DARK + CHECKER_LIGHT) - value) * blur


def tone(x: Value) -> Value:
    """Identity up to TONE_KNEE, then a shoulder approaching 1 (x >= 0)."""
    y = np.maximum(x - TONE_KNEE, 0.0) / (1.0 - TONE_KNEE)
    return np.minimum(x, TONE_KNEE) + (1.0 - TONE_KNEE) * y / (1.0 + y)


def _channel(
    base: Value, emissive: Value, sky: float, ground: float, s: tuple[Value, ...]
) -> Value:
    """One colour channel of the shading; ``s`` holds the colour-independent terms."""
    (metal, f0d, trans, cover, sheen, spec_a, spec_b, occlusion, t_spec, box_spec) = s[:10]
    (t_coat, box_coat, coat_f, t_diff, box_diff, ao, diffuse_in) = s[10:17]
    (spec0, spec1, coat_in, sheen_e, sheen_in, backdrop, seen_through, peak) = s[17:]
    f0 = f0d * (1.0 - metal) + base * metal
    env_spec = ground + (sky - ground) * t_spec + box_spec
    specular = env_spec * (f0 * spec_a + spec_b) * occlusion + f0 * spec0 + spec1
    env_diff = (ground + (sky - ground) * t_diff + box_diff) * ao
    diffuse = base * (env_diff + diffuse_in)
    body = diffuse + (base * backdrop - diffuse) * trans
    body = body * (1.0 - metal) * (1.0 - (f0d * spec_a + spec_b))
    hue = (base + SHEEN_HUE_FLOOR) / (peak + SHEEN_HUE_FLOOR)
    sheen_colour = sheen * (1.0 - SHEEN_TINT + SHEEN_TINT * hue)
    layer = (body + specular) * (1.0 - sheen * sheen_e)
    layer = layer + sheen_colour * (env_diff * sheen_e + sheen_in)
    env_coat = ground + (sky - ground) * t_coat + box_coat
    surface = layer * (1.0 - coat_f) + env_coat * coat_f * occlusion + coat_in + emissive
    return tone(surface * cover + seen_through * (1.0 - cover))


def shade_texel(
    px: Value,
    py: Value,
    base: Vector,
    emissive: Vector,
    scalars: tuple[Value, ...],
    normal: Vector,
    tangent: tuple[Value, Value],
    key: LightVector,
    fill: LightVector,
) -> Vector:
    """Display values (r, g, b) in [0, 1] (before sRGB) of one texel or of arrays of texels.

    ``px, py``: swatch coordinates; ``base``/``emissive``: linear (r, g, b), base in [0, 1],
    emissive >= 0; ``scalars`` = (coverage, metallic, roughness, sheen, coat, transmission,
    subsurface, anisotropy, ior, ao), already finite and clamped (ior to [1, 3]); ``normal``:
    unit (x, y, z); ``tangent``: unit in-plane (cos, sin) of the stretch (anisotropy angle +
    90); ``key`` and ``fill``: (lx, ly, lz, intensity) of the two lights.
    """
    cover, metal, rough, sheen, coat, trans, ss, aniso, eta, ao = scalars
    nx, ny, nz = normal
    # view vector toward the camera over the swatch centre
    vx, vy, vz = -px, -py, CAMERA_DISTANCE
    inv = 1.0 / np.sqrt(vx * vx + vy * vy + vz * vz)
    vx, vy, vz = vx * inv, vy * inv, vz * inv
    nov = np.maximum(nx * vx + ny * vy + nz * vz, 1e-4)
    # tangent frame: the in-plane tangent made orthogonal to n, and b = n x t
    along = nx * tangent[0] + ny * tangent[1]
    tx, ty, tz = tangent[0] - nx * along, tangent[1] - ny * along, -nz * along
    inv = 1.0 / np.sqrt(tx * tx + ty * ty + tz * tz + 1e-12)
    tx, ty, tz = tx * inv, ty * inv, tz * inv
    bx, by, bz = ny * tz - nz * ty, nz * tx - nx * tz, nx * ty - ny * tx
    tov = tx * vx + ty * vy + tz * vz
    bov = bx * vx + by * vy + bz * vz
    rough = clamp(rough, MIN_ROUGHNESS, 1.0)
    alpha = rough * rough
    at, ab = np.maximum(alpha * (1.0 + aniso), 0.002), np.maximum(alpha * (1.0 - aniso), 0.002)
    # the environment is reflected off the normal bent (by aniso / 2) toward the view's part
    # across b: that scales the reflection's tangent component by 1 - aniso, i.e. stretches the
    # reflected studio along the tangent
    bend = 0.5 * aniso * clamp(5.0 * rough, 0.0, 1.0)
    ux, uy, uz = vx - bx * bov, vy - by * bov, vz - bz * bov
    inv = 1.0 / np.sqrt(ux * ux + uy * uy + uz * uz + 1e-12)
    mx, my, mz = (
        nx + (ux * inv - nx) * bend,
        ny + (uy * inv - ny) * bend,
        nz + (uz * inv - nz) * bend,
    )
    inv = 1.0 / np.sqrt(mx * mx + my * my + mz * mz + 1e-12)
    mx, my, mz = mx * inv, my * inv, mz * inv
    mov = 2.0 * (mx * vx + my * vy + mz * vz)
    t_spec, box_spec = environment(mov * mx - vx, mov * my - vy, mov * mz - vz, alpha)
    nov2 = 2.0 * nov
    rx, ry, rz = nov2 * nx - vx, nov2 * ny - vy, nov2 * nz - vz
    coat_alpha = COAT_ROUGHNESS * COAT_ROUGHNESS
    t_coat, box_coat = environment(rx, ry, rz, coat_alpha)
    t_diff, box_diff = environment(nx, ny, nz, DIFFUSE_BLUR)
    spec_a, spec_b = env_brdf(rough, nov)
    coat_a, coat_b = env_brdf(COAT_ROUGHNESS, nov)
    coat_f = coat * (0.04 * coat_a + coat_b)
    occlusion = 1.0 - (1.0 - ao) * (0.5 + 0.5 * rough)
    # the two lights
    n, t, b, v = (nx, ny, nz), (tx, ty, tz), (bx, by, bz), (vx, vy, vz)
    wrap = SUBSURFACE_WRAP * ss
    k_diff, k_spec, k_f, k_coat, k_sheen = direct_light(
        key, n, t, b, v, nov, tov, bov, at, ab, wrap
    )
    f_diff, f_spec, f_f, f_coat, f_sheen = direct_light(
        fill, n, t, b, v, nov, tov, bov, at, ab, wrap
    )
    spec0 = k_spec * (1.0 - k_f) + f_spec * (1.0 - f_f)
    spec1 = k_spec * k_f + f_spec * f_f
    coat_in = coat * (k_coat * (0.04 + 0.96 * k_f) + f_coat * (0.04 + 0.96 * f_f))
    # backdrop: refracted and frosted through transmission, plain where uncovered
    shift = REFRACTION * (1.0 - 1.0 / eta)
    backdrop = checker(px - nx * shift, py - ny * shift, clamp(2.0 * rough, 0.0, 1.0))
    seen_through = checker(px, py, 0.0)
    f0d = (eta - 1.0) / (eta + 1.0)
    s = (metal, f0d * f0d, trans, cover, sheen, spec_a, spec_b, occlusion, t_spec, box_spec)
    s = s + (t_coat, box_coat, coat_f, t_diff, box_diff, ao, k_diff + f_diff)
    peak = np.maximum(np.maximum(base[0], base[1]), base[2])  # the sheen's hue: base / peak
    s = s + (spec0, spec1, coat_in, sheen_albedo(nov), k_sheen + f_sheen, backdrop, seen_through)
    s = s + (peak,)
    r = _channel(base[0], emissive[0], SKY[0], GROUND[0], s)
    g = _channel(base[1], emissive[1], SKY[1], GROUND[1], s)
    return r, g, _channel(base[2], emissive[2], SKY[2], GROUND[2], s)


#: The functions the numba kernel calls, registered by :mod:`matloom.render.lit_numba`.
SHARED_FUNCTIONS = (
    clamp,
    trapezoid,
    environment,
    env_brdf,
    ggx_aniso,
    ggx,
    sheen_lobe,
    sheen_albedo,
    fresnel_weight,
    direct_light,
    checker,
    tone,
    _channel,
    shade_texel,
)
