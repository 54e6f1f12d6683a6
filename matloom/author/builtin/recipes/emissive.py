"""Emissive family: neon tubes, glow-in-the-dark specks, electroluminescent wire, lava and LED
panels.

Emission is added after shading and soft-knee tone-mapped, so a dark, rough base keeps the
glow readable; glowing elements are thin masks with their own emissive colour and strength.
"""

from __future__ import annotations

from matloom.author.builtin.recipes.base import recipe, roles

recipe(
    "neon-tubes",
    "emissive",
    "neon tubes: bright glowing lines with a soft halo on a dark wall",
    """
View(0, 0, {view}, {view})
Define(wall, fBm(octaves=4, base_freq=2, to_01=True, seed={seed:wall}))
Define(tubeA, Abs(Sin((((Y() * 1.2) + (Sin((X() * 2.5)) * 0.3)) * 3.1416))))
Define(tubeB, Abs(Sin(((X() * 0.9) * 3.1416))))
Define(core, Max(Threshold(((0.05 - tubeA) * 40), below_at=0, above_at=1), Threshold(((0.04 - tubeB) * 40), below_at=0, above_at=1)))
Define(halo, Max(Threshold(((0.3 - tubeA) * 4), below_at=0, above_at=1), Threshold(((0.25 - tubeB) * 4), below_at=0, above_at=1)))
Material(
  Layer(1)
    .basecolor({mix:back~-0.3,back,wall})
    .roughness(0.9),
  Layer((halo * 0.5))
    .basecolor({rgb:glow~-0.4})
    .roughness(0.9)
    .emissive({rgb:glow}, 0.6),
  Layer(core)
    .basecolor({rgb:glow~0.5})
    .roughness(0.2)
    .emissive({rgb:glow}, 4)
    .height((core * {h:0.01}))
)""",
    tags={
        "neon": 8,
        "neon sign": 10,
        "neon lights": 9,
        "tube": 2,
        "tubes": 2,
        "cyberpunk": 4,
        "glowing lines": 6,
        "light tubes": 6,
        "synthwave": 5,
        "vaporwave": 5,
    },
    colours=roles(("glow", (255, 40, 200)), ("back", (30, 28, 36), "base")),
    slots={"view": 3, "rough": 0.9},
    unit_m=0.3,
)

recipe(
    "glow-in-dark",
    "emissive",
    "glow-in-the-dark material: phosphorescent green specks and blobs",
    """
View(0, 0, {view}, {view})
Define(matrix, fBm(octaves=4, base_freq={mf:40}, to_01=True, seed={seed:matrix}))
Define(speck, Worley(base_freq={mf:12}, to_01=True, seed={seed:speck}))
Define(blob, fBm(octaves=4, base_freq=1.2, to_01=True, seed={seed:blob}))
Material(
  Layer(1)
    .basecolor({mix:base~-0.2,base,matrix})
    .roughness(0.85)
    .height((matrix * {hv:0.003})),
  Layer(Max(Threshold(((0.15 - speck) * 25), below_at=0, above_at=1), Threshold(((blob - 0.62) * 8), below_at=0, above_at=0.7)))
    .basecolor({rgb:glow~-0.3})
    .roughness(0.6)
    .emissive({rgb:glow}, 1.8)
)""",
    tags={
        "glow in the dark": 10,
        "phosphorescent": 8,
        "luminescent": 6,
        "bioluminescent": 7,
        "luminous": 4,
        "glowing": 3,
        "glow": 3,
        "fluorescent": 4,
        "radioactive": 4,
    },
    colours=roles(("base", (70, 74, 80)), ("glow", (110, 255, 150), "accent")),
    slots={"view": 2, "rough": 0.85},
    unit_m=0.3,
)

recipe(
    "el-wire",
    "emissive",
    "electroluminescent wire: thin glowing cables looping over a dark base",
    """
View(0, 0, {view}, {view})
Define(warpA, fBm(octaves=3, base_freq=0.7, seed={seed:warpA}))
Define(warpB, fBm(octaves=3, base_freq=0.7, seed={seed:warpB}))
Define(wireA, Abs(Sin((((Y() * 1.1) + (warpA * 2.5)) * 3.1416))))
Define(wireB, Abs(Sin((((X() * 0.8) + (warpB * 2.5)) * 3.1416))))
Define(wire, Max(Threshold(((0.06 - wireA) * 40), below_at=0, above_at=1), Threshold(((0.06 - wireB) * 40), below_at=0, above_at=1)))
Define(halo, Max(Threshold(((0.25 - wireA) * 4), below_at=0, above_at=1), Threshold(((0.25 - wireB) * 4), below_at=0, above_at=1)))
Material(
  Layer(1)
    .basecolor({rgb:back})
    .roughness(0.9),
  Layer((halo * 0.45))
    .basecolor({rgb:glow~-0.5})
    .roughness(0.9)
    .emissive({rgb:glow}, 0.5),
  Layer(wire)
    .basecolor({rgb:glow~0.3})
    .roughness(0.3)
    .emissive({rgb:glow}, 3)
    .height((wire * {h:0.01}))
)""",
    tags={
        "electroluminescent": 9,
        "el wire": 10,
        "wire": 3,
        "wires": 3,
        "cable": 2,
        "light strip": 5,
        "led strip": 5,
        "emits light": 4,
        "glowing wire": 9,
        "lighting": 1.5,
    },
    colours=roles(("glow", (40, 220, 255)), ("back", (20, 22, 28), "base")),
    slots={"view": 3, "rough": 0.9},
    unit_m=0.3,
)

recipe(
    "lava",
    "emissive",
    "lava: black cooled crust split by glowing molten cracks",
    """
View(0, 0, {view}, {view})
Define(crust, Worley(base_freq=2, to_01=True, seed={seed:crust}))
Define(crack, Worley(combination="F2-F1", base_freq=2, to_01=True, seed={seed:crust}))
Define(heat, fBm(octaves=4, base_freq=1.5, to_01=True, seed={seed:heat}))
Define(molten, Threshold((((0.1 + (heat * 0.1)) - crack) * 15), below_at=0, above_at=1))
Material(
  Layer(1)
    .basecolor({mix:crust_col~-0.4,crust_col,heat})
    .roughness(0.9)
    .height((((1 - crust) * {h:0.05}) + (heat * {h:0.02}))),
  Layer(molten)
    .basecolor({mix:glow~-0.3,glow,heat})
    .roughness(0.6)
    .emissive({mix:glow,glow2,heat}, 3)
)""",
    tags={
        "lava": 7,
        "magma": 8,
        "molten": 8,
        "lava flow": 10,
        "volcano": 4,
        "eruption": 5,
        "hot": 1,
        "fire": 2,
        "inferno": 5,
        "embers": 5,
    },
    colours=roles(
        ("crust_col", (40, 34, 32)),
        ("glow", (255, 90, 20), "accent"),
        ("glow2", (255, 200, 60), "accent"),
    ),
    slots={"view": 2, "rough": 0.9},
    unit_m=0.5,
)

recipe(
    "led-panel",
    "emissive",
    "LED panel: a grid of small glowing diodes on a black board",
    """
View(0, 0, {view}, {view})
Define(dx, ((X() - Floor(X())) - 0.5))
Define(dy, ((Y() - Floor(Y())) - 0.5))
Define(led, Threshold(((0.22 - Sqrt(((dx * dx) + (dy * dy)))) * 30), below_at=0, above_at=1))
Define(flicker, fBm(octaves=2, base_freq=0.8, to_01=True, seed={seed:flicker}))
Material(
  Layer(1)
    .basecolor({rgb:back})
    .roughness(0.6),
  Layer(led)
    .basecolor({rgb:glow~0.3})
    .roughness(0.2)
    .emissive({mix:glow,glow2,flicker}, 2.5)
    .height((led * {h:0.05}))
)""",
    tags={
        "led": 6,
        "leds": 6,
        "led panel": 9,
        "pixels": 4,
        "pixel": 3,
        "display": 2,
        "matrix": 2,
        "diode": 6,
        "scoreboard": 6,
        "screen": 2,
    },
    colours=roles(
        ("glow", (255, 60, 40)), ("glow2", (255, 160, 60), "accent"), ("back", (16, 16, 18), "base")
    ),
    slots={"view": 12, "rough": 0.6},
    patterns=("dots", "grid"),
    unit_m=0.005,
)
