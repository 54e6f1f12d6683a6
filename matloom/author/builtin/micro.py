"""Micro-textures: the surface grain that pattern recipes lay their colours on.

A pattern (checker, stripes, plaid, dots ...) says where colours go; the material says what the
surface looks like up close (woven threads, knit loops, glossy glaze, marble veins, vinyl ...).
Pattern recipes therefore take a micro-texture slot: its Define line(s), a height expression,
a roughness expression, extra channel lines and a way to shade any colour with its field. The
author picks the micro from material words in the prompt ("knit", "vinyl", "marble" ...), or
keeps the recipe's default. Frequencies use ``{mf:N}`` (N features across the View), so the
grain stays a few pixels wide however large the pattern is.
"""

from __future__ import annotations

from dataclasses import dataclass

from matloom.author.builtin import colours as C
from matloom.author.builtin.template import mix_expr


@dataclass(frozen=True)
class Micro:
    """One micro-texture: Define lines, height, roughness, extra channels and colour shading."""

    name: str
    defines: str
    field: str
    contrast: float
    height: str
    rough: str
    extra: str = ""
    metallic: bool = False

    def parts(self) -> dict[str, str]:
        """The ``{micro:...}`` parts a template can reference."""
        return {
            "def": self.defines,
            "h": self.height,
            "rough": self.rough,
            "extra": self.extra,
            "field": self.field,
        }

    def colour(self, _ref: str, rgb: C.RGB) -> str:
        """Channel expressions shading ``rgb`` by the micro field (dark in its valleys)."""
        amount = abs(self.contrast)
        if C.luminance(rgb) < 0.2 and self.name in {"marble", "stone", "wood"}:
            other = C.shade(rgb, amount * 0.6)  # dark colours get light veins / grain instead
        else:
            other = C.shade(rgb, -amount)
        if self.contrast >= 0:
            return mix_expr(other, rgb, self.field)
        return mix_expr(rgb, other, self.field)


MICROS: dict[str, Micro] = {
    "weave": Micro(
        "weave",
        "Define(weave, Weave(base_freq={mf:64}, warp_width=0.86, feather=0.45))\n"
        "Define(fuzz, fBm(octaves=3, base_freq={mf:90}, to_01=True, seed={seed:fuzz}))",
        "(weave * (0.8 + (fuzz * 0.4)))",
        0.32,
        "(weave * {hv:0.006})",
        "({rough} + (fuzz * 0.1))",
        ".sheen(0.25)",
    ),
    "twill": Micro(
        "twill",
        "Define(weave, Weave(over=2, under=2, base_freq={mf:72}, warp_width=0.9, feather=0.4))\n"
        "Define(fuzz, fBm(octaves=3, base_freq={mf:90}, to_01=True, seed={seed:fuzz}))",
        "(weave * (0.8 + (fuzz * 0.4)))",
        0.3,
        "(weave * {hv:0.005})",
        "({rough} + (fuzz * 0.1))",
        ".sheen(0.2)",
    ),
    "knit": Micro(
        "knit",
        "Define(col, (X() * {mf:36}))\n"
        "Define(knit, Abs(Sin((((Y() * {mf:44}) + (Abs(((col - Floor(col)) - 0.5)) * 1.2)) * 3.1416))))",
        "(knit * Abs(Sin((col * 3.1416))))",
        0.4,
        "(knit * Abs(Sin((col * 3.1416))) * {hv:0.008})",
        "{rough}",
        ".sheen(0.3)",
    ),
    "fleece": Micro(
        "fleece",
        "Define(fuzz, fBm(octaves=5, base_freq={mf:60}, to_01=True, seed={seed:fuzz}))",
        "fuzz",
        0.25,
        "(fuzz * {hv:0.01})",
        "0.95",
        ".sheen(0.6)",
    ),
    "smooth": Micro(
        "smooth",
        "Define(grain, fBm(octaves=3, base_freq={mf:24}, to_01=True, seed={seed:grain}))",
        "grain",
        0.06,
        "(grain * {hv:0.002})",
        "({rough} + (grain * 0.05))",
        ".coat(0.3)",
    ),
    "glaze": Micro(
        "glaze",
        "Define(glaze, fBm(octaves=3, base_freq={mf:8}, to_01=True, seed={seed:glaze}))",
        "glaze",
        0.08,
        "(glaze * {hv:0.002})",
        "({rough} + (glaze * 0.04))",
        ".coat(0.8)",
    ),
    "marble": Micro(
        "marble",
        "Define(warp, fBm(octaves=5, base_freq={mf:2}, seed={seed:warp}))\n"
        "Define(vein, Threshold((Abs(Sin(((((X() + Y()) * {mf:2.2}) + (warp * 5)) * 3.1416))) * 6), "
        "above_at=1))",
        "vein",
        0.45,
        "0",
        "({rough} + (vein * 0.03))",
        ".coat(0.6)",
    ),
    "leather": Micro(
        "leather",
        "Define(pebble, Worley(base_freq={mf:34}, to_01=True, seed={seed:pebble}))",
        "pebble",
        -0.22,
        "((1 - pebble) * {hv:0.006})",
        "({rough} + (pebble * 0.15))",
        "",
    ),
    "paper": Micro(
        "paper",
        "Define(fibre, fBm(octaves=4, base_freq_x={mf:60}, base_freq_y={mf:20}, to_01=True, "
        "seed={seed:fibre}))",
        "fibre",
        0.08,
        "(fibre * {hv:0.002})",
        "0.9",
        "",
    ),
    "felt": Micro(
        "felt",
        "Define(fuzz, fBm(octaves=5, base_freq={mf:70}, to_01=True, seed={seed:fuzz}))",
        "fuzz",
        0.18,
        "(fuzz * {hv:0.004})",
        "0.95",
        ".sheen(0.35)",
    ),
    "metal": Micro(
        "metal",
        "Define(brush, fBm(octaves=4, base_freq_x={mf:6}, base_freq_y={mf:160}, to_01=True, "
        "seed={seed:brush}))",
        "brush",
        0.2,
        "(brush * {hv:0.003})",
        "({rough} + (brush * 0.1))",
        ".metallic(0.85)\n.anisotropy(0.6)",
        True,
    ),
    "wood": Micro(
        "wood",
        "Define(grain, fBm(octaves=5, base_freq_x={mf:3}, base_freq_y={mf:40}, to_01=True, "
        "seed={seed:grain}))",
        "grain",
        0.3,
        "(grain * {hv:0.003})",
        "({rough} + (grain * 0.1))",
        "",
    ),
    "stone": Micro(
        "stone",
        "Define(speck, fBm(octaves=5, base_freq={mf:40}, to_01=True, seed={seed:speck}))",
        "speck",
        0.3,
        "(speck * {hv:0.004})",
        "({rough} + (speck * 0.1))",
        "",
    ),
    "rubber": Micro(
        "rubber",
        "Define(grain, fBm(octaves=4, base_freq={mf:70}, to_01=True, seed={seed:grain}))",
        "grain",
        0.1,
        "(grain * {hv:0.002})",
        "0.85",
        "",
    ),
}

#: prompt words -> micro-texture (first match in prompt order wins).
MICRO_WORDS: dict[str, str] = {
    "knit": "knit",
    "knitted": "knit",
    "jersey": "knit",
    "knitting": "knit",
    "sweater": "knit",
    "fleece": "fleece",
    "fur": "fleece",
    "plush": "fleece",
    "velvet": "fleece",
    "velour": "fleece",
    "terry": "fleece",
    "vinyl": "smooth",
    "pvc": "smooth",
    "plastic": "smooth",
    "laminate": "smooth",
    "acrylic": "smooth",
    "rubber": "rubber",
    "silicone": "rubber",
    "ceramic": "glaze",
    "porcelain": "glaze",
    "glazed": "glaze",
    "tile": "glaze",
    "tiles": "glaze",
    "enamel": "glaze",
    "marble": "marble",
    "leather": "leather",
    "faux": "leather",
    "paper": "paper",
    "cardboard": "paper",
    "wallpaper": "paper",
    "felt": "felt",
    "wool": "felt",
    "metal": "metal",
    "steel": "metal",
    "aluminum": "metal",
    "aluminium": "metal",
    "wood": "wood",
    "wooden": "wood",
    "stone": "stone",
    "granite": "stone",
    "concrete": "stone",
    "twill": "twill",
    "denim": "twill",
    "gabardine": "twill",
    "cotton": "weave",
    "linen": "weave",
    "woven": "weave",
    "canvas": "weave",
    "silk": "weave",
    "polyester": "weave",
    "nylon": "weave",
    "satin": "weave",
    "fabric": "weave",
    "cloth": "weave",
    "textile": "weave",
    "walnut": "wood",
    "oak": "wood",
    "maple": "wood",
    "cherry": "wood",
    "mahogany": "wood",
    "birch": "wood",
    "pine": "wood",
    "teak": "wood",
}

#: broad words that only say "cloth" / "tile": any more specific word in the prompt wins.
GENERIC_MICRO_WORDS: frozenset[str] = frozenset(
    {
        "fabric",
        "cloth",
        "textile",
        "cotton",
        "polyester",
        "nylon",
        "woven",
        "tile",
        "tiles",
        "wool",
        "silk",
        "satin",
        "linen",
    }
)
