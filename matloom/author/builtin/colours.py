"""Colour vocabulary of the offline author: named colours, tone modifiers and colour arithmetic.

Colours are sRGB triples on the 0-255 scale, the scale `.basecolor(...)` takes. The table holds
everyday names, paint/textile names ("cornflower", "mustard", "charcoal") and material-derived
names ("rust", "copper", "terracotta"), because prompts describe colour with all three.
"""

from __future__ import annotations

import colorsys

RGB = tuple[int, int, int]

NAMED_COLOURS: dict[str, RGB] = {
    # neutrals
    "white": (236, 236, 232),
    "black": (22, 22, 24),
    "grey": (128, 128, 128),
    "gray": (128, 128, 128),
    "silver": (192, 194, 198),
    "charcoal": (54, 56, 60),
    "graphite": (70, 72, 76),
    "ivory": (240, 234, 214),
    "cream": (238, 226, 196),
    "beige": (212, 196, 164),
    "offwhite": (232, 228, 216),
    "eggshell": (236, 230, 212),
    "bone": (226, 218, 198),
    "ecru": (206, 194, 162),
    "taupe": (140, 126, 112),
    "khaki": (190, 176, 130),
    "tan": (200, 164, 118),
    "sand": (214, 190, 150),
    "stone": (150, 144, 134),
    "ash": (170, 168, 162),
    "slate": (88, 96, 106),
    "pewter": (140, 144, 146),
    "smoke": (120, 122, 126),
    "oatmeal": (216, 204, 180),
    "linen": (226, 216, 196),
    "pearl": (232, 228, 220),
    "snow": (246, 248, 250),
    "jet": (16, 16, 18),
    "ebony": (40, 32, 28),
    "onyx": (30, 30, 32),
    # reds / pinks
    "red": (186, 32, 36),
    "crimson": (170, 20, 50),
    "scarlet": (222, 40, 30),
    "maroon": (110, 24, 32),
    "burgundy": (118, 26, 44),
    "wine": (114, 30, 48),
    "cherry": (170, 24, 44),
    "ruby": (158, 16, 52),
    "brick": (160, 70, 52),
    "rust": (160, 74, 36),
    "terracotta": (190, 96, 66),
    "coral": (240, 120, 100),
    "salmon": (236, 138, 114),
    "pink": (236, 150, 176),
    "rose": (220, 120, 140),
    "blush": (232, 178, 176),
    "magenta": (200, 30, 140),
    "fuchsia": (214, 40, 160),
    "raspberry": (190, 30, 84),
    "candy": (226, 40, 50),
    "vermilion": (220, 60, 36),
    "oxblood": (96, 26, 28),
    "mauve": (178, 130, 150),
    "peach": (246, 184, 148),
    # oranges / yellows
    "orange": (232, 118, 30),
    "tangerine": (240, 128, 20),
    "amber": (220, 140, 30),
    "apricot": (244, 170, 110),
    "copper": (184, 110, 66),
    "bronze": (164, 118, 60),
    "yellow": (236, 204, 40),
    "lemon": (244, 226, 80),
    "mustard": (206, 164, 40),
    "gold": (212, 168, 60),
    "golden": (212, 164, 64),
    "honey": (214, 150, 50),
    "ochre": (200, 140, 50),
    "saffron": (240, 180, 40),
    "straw": (226, 206, 140),
    "butter": (246, 230, 150),
    "brass": (190, 160, 80),
    "caramel": (190, 120, 60),
    # browns
    "brown": (116, 72, 42),
    "chocolate": (92, 56, 36),
    "coffee": (100, 70, 50),
    "mocha": (120, 90, 70),
    "walnut": (92, 60, 38),
    "mahogany": (112, 46, 30),
    "chestnut": (130, 64, 40),
    "umber": (100, 76, 50),
    "sienna": (160, 82, 45),
    "cinnamon": (170, 98, 50),
    "hazel": (150, 110, 60),
    "camel": (190, 150, 100),
    "fawn": (200, 170, 130),
    "cognac": (150, 72, 30),
    "sepia": (112, 66, 20),
    "russet": (128, 70, 27),
    "auburn": (140, 50, 30),
    "bronzed": (160, 110, 60),
    # greens
    "green": (60, 130, 60),
    "olive": (112, 112, 50),
    "lime": (150, 210, 60),
    "emerald": (20, 140, 90),
    "jade": (70, 150, 110),
    "sage": (150, 170, 130),
    "mint": (160, 220, 180),
    "forest": (34, 80, 40),
    "moss": (90, 110, 50),
    "pine": (30, 80, 60),
    "chartreuse": (180, 220, 40),
    "teal": (20, 120, 120),
    "seafoam": (140, 210, 180),
    "army": (80, 90, 50),
    "hunter": (40, 84, 50),
    "avocado": (110, 130, 40),
    "pistachio": (170, 200, 130),
    "celadon": (170, 210, 170),
    "verdigris": (70, 160, 140),
    "malachite": (20, 130, 80),
    "khakigreen": (120, 120, 80),
    # blues
    "blue": (40, 80, 170),
    "navy": (24, 34, 80),
    "cobalt": (20, 70, 170),
    "royal": (50, 80, 200),
    "sky": (130, 190, 230),
    "azure": (40, 130, 220),
    "cyan": (40, 190, 210),
    "turquoise": (50, 190, 190),
    "aqua": (80, 210, 210),
    "cornflower": (100, 140, 230),
    "denim": (60, 90, 140),
    "indigo": (50, 40, 120),
    "sapphire": (20, 50, 140),
    "steel": (110, 130, 150),
    "powder": (176, 206, 230),
    "periwinkle": (150, 160, 230),
    "cerulean": (40, 120, 190),
    "petrol": (20, 80, 100),
    "ice": (200, 228, 240),
    "baby": (170, 210, 236),
    "midnight": (24, 26, 56),
    "ultramarine": (30, 50, 180),
    "prussian": (20, 50, 80),
    # purples
    "purple": (110, 50, 140),
    "violet": (130, 70, 180),
    "lavender": (190, 170, 220),
    "lilac": (200, 160, 210),
    "plum": (110, 50, 90),
    "eggplant": (70, 30, 60),
    "aubergine": (70, 30, 60),
    "amethyst": (150, 100, 200),
    "orchid": (200, 120, 200),
    "grape": (100, 40, 110),
}

#: multi-word names, matched before single words (keys are space-separated lowercase words).
PHRASE_COLOURS: dict[str, RGB] = {
    "off white": (232, 228, 216),
    "rose gold": (214, 150, 130),
    "milk chocolate": (132, 86, 56),
    "dark chocolate": (70, 42, 28),
    "steel blue": (90, 130, 170),
    "light steel blue": (176, 196, 222),
    "sky blue": (130, 190, 230),
    "royal blue": (50, 80, 200),
    "navy blue": (24, 34, 80),
    "baby blue": (170, 210, 236),
    "powder blue": (176, 206, 230),
    "forest green": (34, 80, 40),
    "army green": (80, 90, 50),
    "olive green": (112, 112, 50),
    "hunter green": (40, 84, 50),
    "lime green": (150, 210, 60),
    "sea green": (50, 140, 100),
    "kelly green": (40, 160, 70),
    "bottle green": (20, 80, 50),
    "burnt orange": (200, 90, 30),
    "burnt sienna": (150, 70, 40),
    "burnt umber": (90, 56, 36),
    "brick red": (160, 60, 45),
    "fire engine red": (210, 30, 30),
    "blood red": (130, 10, 16),
    "candy red": (226, 40, 50),
    "hot pink": (240, 80, 160),
    "baby pink": (244, 194, 206),
    "dusty pink": (210, 160, 160),
    "dusty rose": (200, 140, 140),
    "blue green": (30, 140, 130),
    "blue-green": (30, 140, 130),
    "gun metal": (70, 76, 82),
    "gunmetal": (70, 76, 82),
    "stainless steel": (180, 182, 184),
    "dingy gold": (176, 146, 70),
    "old gold": (176, 146, 60),
    "mustard yellow": (206, 164, 40),
    "lemon yellow": (244, 226, 80),
    "sand color": (214, 190, 150),
    "natural wood": (186, 146, 100),
    "oatmeal color": (216, 204, 180),
    "cafe au lait": (166, 123, 91),
    "midnight blue": (24, 26, 56),
    "electric blue": (40, 120, 250),
    "neon green": (60, 255, 80),
    "neon pink": (255, 60, 180),
    "neon blue": (40, 140, 255),
    "wine red": (114, 30, 48),
    "cherry red": (170, 24, 44),
    "sage green": (150, 170, 130),
    "mint green": (160, 220, 180),
    "emerald green": (20, 140, 90),
    "jade green": (70, 150, 110),
    "pale gold": (226, 200, 130),
    "champagne": (230, 210, 170),
    "sea foam": (140, 210, 180),
    "camel brown": (190, 150, 100),
    "chocolate brown": (92, 56, 36),
    "coffee brown": (100, 70, 50),
    "rust red": (150, 60, 30),
    "rust orange": (190, 90, 40),
    "ice blue": (200, 228, 240),
    "charcoal grey": (54, 56, 60),
    "charcoal gray": (54, 56, 60),
    "slate grey": (88, 96, 106),
    "slate gray": (88, 96, 106),
    "dove grey": (170, 168, 166),
    "dove gray": (170, 168, 166),
}

#: ``-ish`` / ``-y`` adjective forms mapped to their base colour name.
ISH_FORMS: dict[str, str] = {
    "reddish": "red",
    "brownish": "brown",
    "greenish": "green",
    "bluish": "blue",
    "blueish": "blue",
    "yellowish": "yellow",
    "greyish": "grey",
    "grayish": "gray",
    "pinkish": "pink",
    "purplish": "purple",
    "orangish": "orange",
    "orangey": "orange",
    "blackish": "black",
    "whitish": "white",
    "goldish": "gold",
    "rusty-red": "rust",
}

#: tone modifiers: name -> (lightness multiplier or target shift, saturation multiplier).
TONE_MODIFIERS: dict[str, tuple[float, float]] = {
    "light": (1.35, 0.8),
    "pale": (1.55, 0.55),
    "dark": (0.55, 1.0),
    "deep": (0.6, 1.2),
    "bright": (1.15, 1.35),
    "vivid": (1.05, 1.4),
    "dull": (0.85, 0.6),
    "muted": (0.9, 0.55),
    "dusty": (0.95, 0.55),
    "faded": (1.15, 0.5),
    "rich": (0.8, 1.25),
    "soft": (1.2, 0.75),
    "dingy": (0.8, 0.6),
    "washed": (1.2, 0.5),
    "neon": (1.1, 1.6),
    "pastel": (1.45, 0.55),
    "medium": (1.0, 1.0),
    "warm": (1.0, 1.0),
    "cool": (1.0, 1.0),
    "burnt": (0.7, 1.1),
    "dirty": (0.8, 0.6),
    "hot": (1.05, 1.3),
    "icy": (1.3, 0.6),
    "earthy": (0.85, 0.7),
}


def clamp_rgb(rgb: tuple[float, float, float]) -> RGB:
    """Round and clamp a colour to integers in 0-255."""
    return (
        max(0, min(255, round(rgb[0]))),
        max(0, min(255, round(rgb[1]))),
        max(0, min(255, round(rgb[2]))),
    )


def apply_tone(rgb: RGB, modifier: str) -> RGB:
    """Apply one tone modifier ("dark", "pale", "warm" ...) to ``rgb`` in HLS space."""
    light_mul, sat_mul = TONE_MODIFIERS[modifier]
    h, l_, s = colorsys.rgb_to_hls(rgb[0] / 255, rgb[1] / 255, rgb[2] / 255)
    if light_mul >= 1.0:
        l_ = l_ + (1.0 - l_) * min(0.8, (light_mul - 1.0) * 1.1)
    else:
        l_ = l_ * light_mul
    s = min(1.0, s * sat_mul)
    r, g, b = colorsys.hls_to_rgb(h, l_, s)
    out = (r * 255, g * 255, b * 255)
    if modifier == "warm":
        out = (out[0] * 1.08, out[1] * 1.0, out[2] * 0.88)
    elif modifier == "cool":
        out = (out[0] * 0.9, out[1] * 0.98, out[2] * 1.1)
    elif modifier == "burnt":
        out = (out[0] * 1.0, out[1] * 0.8, out[2] * 0.7)
    return clamp_rgb(out)


def mix(a: RGB, b: RGB, t: float) -> RGB:
    """Linear mix of two colours in sRGB space: ``t=0`` gives ``a``, ``t=1`` gives ``b``."""
    return clamp_rgb(tuple(a[i] + (b[i] - a[i]) * t for i in range(3)))  # type: ignore[arg-type]


def scale(rgb: RGB, factor: float) -> RGB:
    """Multiply a colour by ``factor`` (darken below 1, lighten above 1, clamped)."""
    return clamp_rgb((rgb[0] * factor, rgb[1] * factor, rgb[2] * factor))


def shade(rgb: RGB, amount: float) -> RGB:
    """Lighten (amount > 0, toward white) or darken (amount < 0, toward black) a colour."""
    if amount >= 0:
        return mix(rgb, (255, 255, 255), amount)
    return mix(rgb, (0, 0, 0), -amount)


def luminance(rgb: RGB) -> float:
    """Rec.709 luminance of the sRGB-encoded colour in [0, 1] (as the preview statistics use)."""
    return (0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]) / 255.0


def desaturate(rgb: RGB, amount: float) -> RGB:
    """Move a colour toward its own grey by ``amount`` in [0, 1]."""
    grey = luminance(rgb) * 255
    return mix(rgb, (round(grey), round(grey), round(grey)), amount)


def lookup(name: str) -> RGB | None:
    """The colour for a single word or phrase, or ``None`` when it is not a colour name."""
    key = name.lower().strip()
    if key in PHRASE_COLOURS:
        return PHRASE_COLOURS[key]
    if key in NAMED_COLOURS:
        return NAMED_COLOURS[key]
    if key in ISH_FORMS:
        return NAMED_COLOURS[ISH_FORMS[key]]
    return None
