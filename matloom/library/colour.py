"""Colour arithmetic of the library adapter: sRGB triples on the 0-255 scale ``.basecolor`` takes.

Tone modifiers ("pale", "dark", "bright" ...) come from ``data/colours.toml`` as a lightness and
a saturation multiplier applied in HLS space.
"""

from __future__ import annotations

import colorsys

RGB = tuple[int, int, int]


def clamp_rgb(rgb: tuple[float, float, float]) -> RGB:
    """Round and clamp a colour to integers in 0-255."""
    return (
        max(0, min(255, round(rgb[0]))),
        max(0, min(255, round(rgb[1]))),
        max(0, min(255, round(rgb[2]))),
    )


def apply_tone(rgb: RGB, modifier: str, tone: tuple[float, float]) -> RGB:
    """Apply a tone modifier (its ``(lightness, saturation)`` multipliers) to ``rgb``."""
    light_mul, sat_mul = tone
    h, light, s = colorsys.rgb_to_hls(rgb[0] / 255, rgb[1] / 255, rgb[2] / 255)
    if light_mul >= 1.0:
        light = light + (1.0 - light) * min(0.8, (light_mul - 1.0) * 1.1)
    else:
        light = light * light_mul
    s = min(1.0, s * sat_mul)
    r, g, b = colorsys.hls_to_rgb(h, light, s)
    out = (r * 255, g * 255, b * 255)
    if modifier == "warm":
        out = (out[0] * 1.08, out[1], out[2] * 0.88)
    elif modifier == "cool":
        out = (out[0] * 0.9, out[1] * 0.98, out[2] * 1.1)
    elif modifier == "burnt":
        out = (out[0], out[1] * 0.8, out[2] * 0.7)
    return clamp_rgb(out)


def mix(a: RGB, b: RGB, t: float) -> RGB:
    """Linear mix in sRGB: ``t = 0`` gives ``a``, ``t = 1`` gives ``b``."""
    return clamp_rgb((a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t, a[2] + (b[2] - a[2]) * t))


def luminance(rgb: RGB) -> float:
    """Rec.709 luminance of the sRGB-encoded colour, in [0, 1]."""
    return (0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]) / 255.0


def saturation(rgb: RGB) -> float:
    """HSV saturation in [0, 1]."""
    return colorsys.rgb_to_hsv(rgb[0] / 255, rgb[1] / 255, rgb[2] / 255)[1]


def hue_distance(a: RGB, b: RGB) -> float:
    """Angle between the hues of two colours, in degrees (0-180)."""
    ha = colorsys.rgb_to_hsv(a[0] / 255, a[1] / 255, a[2] / 255)[0]
    hb = colorsys.rgb_to_hsv(b[0] / 255, b[1] / 255, b[2] / 255)[0]
    d = abs(ha - hb)
    return min(d, 1 - d) * 360


def lightness(rgb: RGB) -> float:
    """HLS lightness in [0, 1]."""
    return colorsys.rgb_to_hls(rgb[0] / 255, rgb[1] / 255, rgb[2] / 255)[1]


def with_lightness(rgb: RGB, light: float) -> RGB:
    """``rgb`` with its HLS lightness set to ``light`` (hue and saturation kept)."""
    h, _, s = colorsys.rgb_to_hls(rgb[0] / 255, rgb[1] / 255, rgb[2] / 255)
    r, g, b = colorsys.hls_to_rgb(h, max(0.0, min(1.0, light)), s)
    return clamp_rgb((r * 255, g * 255, b * 255))
