"""Hints for names that mean something elsewhere: function and channel aliases (parser hints)."""

from __future__ import annotations

_FUNCTION_ALIASES = {
    "noise": "fBm",
    "perlin": "fBm",
    "simplex": "fBm",
    "fbm": "fBm",
    "turbulence": "fBm",
    "voronoi": "Worley",
    "cellular": "Worley",
    "cells": "Worley",
    "brick": "Bricks",
    "tiles": "Bricks",
    "tile": "Bricks",
    "grid": "Bricks",
    "checker": "Bricks",
    "circle": "Ellipse",
    "rectangle": "Rect",
    "box": "Rect",
    "square": "Rect",
    "line": "Stroke",
    "clamp": "Threshold",
    "step": "Threshold",
    "smoothstep": "Threshold",
    "mix": "Add",
    "lerp": "Add",
    "power": "Pow",
    "exp": "Pow",
    "ln": "Log",
    "round": "Floor",
    "translate": "Translate",
    "rotate": "Rotate",
    "scale": "Scale",
}


def function_alias(name: str) -> str | None:
    """A hint naming the vocabulary function that does what ``name`` usually means elsewhere."""
    target = _FUNCTION_ALIASES.get(name.lower())
    return f"did you mean `{target}(...)`?" if target else None


def name_alias(name: str) -> str | None:
    target = _FUNCTION_ALIASES.get(name.lower())
    if target:
        return f"there is no name '{name}'; call a function such as {target}(...)"
    return None


def channel_alias(name: str) -> str | None:
    aliases = {
        "color": "basecolor",
        "colour": "basecolor",
        "albedo": "basecolor",
        "base_color": "basecolor",
        "rough": "roughness",
        "metal": "metallic",
        "metalness": "metallic",
        "emission": "emissive",
        "normal": "height",
        "bump": "height",
        "displacement": "height",
        "opacity": "alpha",
        "clearcoat": "coat",
        "specular": "roughness",
        "glossiness": "roughness",
        "gloss": "roughness",
        "smoothness": "roughness",
        "transparency": "transmission",
        "refraction": "ior",
        "glow": "emissive",
        "emit": "emissive",
        "sss": "subsurface",
    }
    if name.lower() in aliases:
        return f"did you mean `.{aliases[name.lower()]}`?"
    return None


__all__ = ["channel_alias", "function_alias", "name_alias"]
