"""Sci-fi family: hull panels with greebles and lights, circuit boards, carbon fibre and a
hexagonal energy-armour plating.
"""

from __future__ import annotations

from matloom.author.builtin.recipes.base import recipe, roles
from matloom.author.builtin.recipes.snippets import HEX

SCIFI = {
    "sci fi": 6,
    "scifi": 6,
    "futuristic": 5,
    "spaceship": 5,
    "space": 1.5,
    "tech": 2,
    "cyber": 3,
    "robot": 3,
    "mech": 3,
}

recipe(
    "scifi-panel",
    "scifi",
    "sci-fi hull panels: inset plates, seams, vents and small lights",
    """
View(0, 0, {view}, {view})
Define(plate, Bricks(brick_width=2, brick_height=1, offset=0.5, mortar=0.04, feather=0.01))
Define(inset, Bricks(brick_width=1, brick_height=0.5, offset=0, mortar=0.16, feather=0.02))
Define(vent, (Threshold(((0.5 - Abs(((Y() * 10) - Floor((Y() * 10))) - 0.5)) * 10 - 3), below_at=0, above_at=1) * Threshold(((0.2 - Abs(((X() - Floor(X())) - 0.75))) * 40), below_at=0, above_at=1)))
Define(light, Threshold(((0.05 - Sqrt(((((X() - Floor(X())) - 0.15) * ((X() - Floor(X())) - 0.15)) + (((Y() - Floor(Y())) - 0.8) * ((Y() - Floor(Y())) - 0.8))))) * 60), below_at=0, above_at=1))
Define(wear, fBm(octaves=4, base_freq=2, to_01=True, seed={seed:wear}))
Material(
  Layer(1)
    .basecolor({rgb:base~-0.6})
    .metallic(0.7)
    .roughness(0.6),
  Layer(plate)
    .basecolor({mix:base~-0.2,base,wear})
    .metallic(0.6)
    .roughness(({rough} + (wear * 0.2)))
    .height((plate * ({h:0.02} + (inset * {h:0.01})))),
  Layer((vent * plate))
    .basecolor({rgb:base~-0.5})
    .metallic(0.6)
    .roughness(0.6),
  Layer(light)
    .basecolor({rgb:glow~0.3})
    .emissive({rgb:glow}, 3)
    .roughness(0.2)
)""",
    tags={
        **SCIFI,
        "panel": 1.5,
        "panels": 1.5,
        "hull": 3,
        "greeble": 7,
        "greebles": 7,
        "spacecraft": 6,
        "starship": 6,
        "station": 2,
        "bulkhead": 5,
    },
    colours=roles(("base", (170, 176, 184)), ("glow", (60, 200, 255), "accent")),
    slots={"view": 4, "rough": 0.4},
    unit_m=0.5,
)

recipe(
    "circuit-board",
    "scifi",
    "circuit board: green solder mask with copper traces and pads",
    """
View(0, 0, {view}, {view})
Define(traceH, Threshold(((0.04 - Abs(((Y() * 4) - Floor(((Y() * 4) + 0.5))))) * 40), below_at=0, above_at=1))
Define(traceV, Threshold(((0.04 - Abs(((X() * 4) - Floor(((X() * 4) + 0.5))))) * 40), below_at=0, above_at=1))
Define(routeH, Threshold(((fBm(octaves=2, base_freq_x=0.5, base_freq_y=8, to_01=True, seed={seed:routeH}) - 0.55) * 20), below_at=0, above_at=1))
Define(routeV, Threshold(((fBm(octaves=2, base_freq_x=8, base_freq_y=0.5, to_01=True, seed={seed:routeV}) - 0.55) * 20), below_at=0, above_at=1))
Define(pad, Threshold(((0.09 - Max(Abs(((X() * 4) - Floor(((X() * 4) + 0.5)))), Abs(((Y() * 4) - Floor(((Y() * 4) + 0.5)))))) * 40), below_at=0, above_at=1))
Define(chip, Threshold(((fBm(octaves=1, base_freq=1.5, to_01=True, seed={seed:chip}) - 0.62) * 40), below_at=0, above_at=1))
Material(
  Layer(1)
    .basecolor({rgb:board})
    .roughness(0.4)
    .coat(0.5),
  Layer(Max(Max((traceH * routeH), (traceV * routeV)), (pad * Max(routeH, routeV))))
    .basecolor({rgb:copper})
    .metallic(0.9)
    .roughness(0.35)
    .height({h:0.005}),
  Layer(chip)
    .basecolor({rgb:chip_col})
    .roughness(0.5)
    .height((chip * {h:0.05}))
)""",
    tags={
        "circuit": 8,
        "circuit board": 10,
        "pcb": 10,
        "motherboard": 9,
        "electronics": 6,
        "electronic": 5,
        "traces": 3,
        "microchip": 6,
        "computer": 3,
        **SCIFI,
    },
    colours=roles(
        ("board", (30, 100, 50)),
        ("copper", (210, 170, 90), "accent"),
        ("chip_col", (24, 24, 26), "accent"),
    ),
    slots={"view": 2, "rough": 0.4},
    patterns=("grid",),
    unit_m=0.05,
)

recipe(
    "carbon-fibre",
    "scifi",
    "carbon fibre: glossy 2x2 twill of black tows under clear coat",
    """
View(0, 0, {view}, {view})
Define(tow, Weave(over=2, under=2, base_freq=6, warp_width=0.96, feather=0.5))
Define(tc, Floor((X() * 6)))
Define(tr, Floor((Y() * 6)))
Define(warpTop, Threshold(((1.5 - ((tc - tr) - (4 * Floor(((tc - tr) / 4))))) * 10), below_at=0, above_at=1))
Material(
  Layer(1)
    .basecolor({mix:base~-0.5,base,((tow * 0.6) + (warpTop * 0.4))})
    .roughness({rough})
    .coat(1)
    .anisotropy(0.5)
    .height((tow * {h:0.01}))
)""",
    tags={
        "carbon fiber": 10,
        "carbon fibre": 10,
        "carbon": 4,
        "kevlar": 7,
        "composite": 4,
        "cfrp": 9,
        "racing": 2,
    },
    colours=roles(("base", (70, 72, 78))),
    slots={"view": 2, "rough": 0.2},
    patterns=("weave", "checker"),
    presets={"kevlar": {"base": (210, 180, 60)}},
    unit_m=0.05,
)

recipe(
    "hex-armor",
    "scifi",
    "hexagonal armour plating with glowing energy seams",
    "View(0, 0, {view}, {view})\n"
    + HEX
    + """
Define(seam, Threshold(((hexD - 0.45) * 40), below_at=0, above_at=1))
Define(wear, fBm(octaves=4, base_freq=1.5, to_01=True, seed={seed:wear}))
Material(
  Layer(1)
    .basecolor({mix:base~-0.3,base,wear})
    .metallic(0.7)
    .roughness(({rough} + (wear * 0.2)))
    .height(((0.5 - hexD) * {h:0.06})),
  Layer(seam)
    .basecolor({rgb:glow~0.3})
    .roughness(0.3)
    .emissive({rgb:glow}, 2.5)
)""",
    tags={
        "hex armor": 9,
        "armor": 3,
        "armour": 3,
        "shield": 3,
        "force field": 8,
        "energy": 3,
        "plating": 4,
        "hexagonal plates": 7,
        **SCIFI,
    },
    colours=roles(("base", (90, 96, 104)), ("glow", (60, 200, 255), "accent")),
    slots={"view": 4, "rough": 0.35},
    patterns=("hexagon",),
    unit_m=0.1,
)
