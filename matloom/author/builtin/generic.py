"""The generic fallback material used when no recipe matches a request.

It is built only from what the interpreter recognised: the first colour becomes the base, a
second colour mottles it, finish words set roughness and relief. It is deliberately plain, so
that an unknown request still yields a sensible, editable starting point.
"""

from __future__ import annotations

from matloom.author.builtin.recipes.base import ColourRole, Recipe

GENERIC = Recipe(
    name="generic-surface",
    family="concrete",
    summary="plain surface with soft two-tone mottling and fine grain",
    template="""
View(0, 0, {view}, {view})
Define(mottle, fBm(octaves=4, base_freq=1.5, to_01=True, seed={seed:mottle}))
Define(grain, fBm(octaves=4, base_freq={mf:40}, to_01=True, seed={seed:grain}))
Material(
  Layer(1)
    .basecolor({mix:base,second,mottle})
    .roughness(({rough} + (grain * 0.1)))
    .height((grain * {hv:0.003}))
)""".strip("\n"),
    tags={},
    colours=(
        ColourRole("base", (150, 148, 142)),
        ColourRole("second", (150, 148, 142), "accent", ("base", -0.12)),
    ),
    slots={"view": 2.0, "rough": 0.6, "relief": 1.0},
)
