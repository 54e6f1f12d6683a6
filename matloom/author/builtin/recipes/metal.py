"""Metal family: brushed, polished, hammered, galvanized, anodized, corrugated, diamond plate,
rusted, copper patina, heat-tinted, grid / grating, perforated, riveted panels, foil and cast
iron, plus iridescent ore.

The head-on preview lights a flat metal only through its ambient term, so metal recipes keep
roughness moderate and put visible structure into the height (dents, streaks, ridges): tilted
normals are what catch the fixed light and read as metal.
"""

from __future__ import annotations

from matloom.author.builtin.recipes.base import recipe, roles

METAL_PRESETS = {
    "aluminum": {"metal": (200, 202, 206)},
    "aluminium": {"metal": (200, 202, 206)},
    "steel": {"metal": (172, 174, 178)},
    "stainless": {"metal": (184, 186, 190)},
    "chrome": {"metal": (222, 224, 228)},
    "silver": {"metal": (210, 210, 214)},
    "copper": {"metal": (196, 120, 84)},
    "brass": {"metal": (204, 170, 92)},
    "bronze": {"metal": (170, 120, 70)},
    "gold": {"metal": (226, 180, 80)},
    "golden": {"metal": (226, 180, 80)},
    "titanium": {"metal": (150, 150, 156)},
    "iron": {"metal": (110, 110, 112)},
    "zinc": {"metal": (176, 180, 184)},
    "nickel": {"metal": (196, 192, 180)},
    "pewter": {"metal": (150, 152, 152)},
    "tin": {"metal": (190, 192, 194)},
    "platinum": {"metal": (214, 214, 216)},
    "lead": {"metal": (110, 112, 118)},
    "gunmetal": {"metal": (80, 84, 90)},
    "rose gold": {"metal": (214, 150, 130)},
}
METAL_WORDS = {"metal": 2.0, "metallic": 1.5, "sheet": 1.0, **{w: 2.0 for w in METAL_PRESETS}}
METAL_ROLES = roles(("metal", (186, 188, 192)))

recipe(
    "brushed-metal",
    "metal",
    "brushed metal: fine directional streaks, anisotropic sheen",
    """
View(0, 0, {view}, {view})
Define(brush, fBm(octaves=5, base_freq_x={mf:3}, base_freq_y={mf:180}, to_01=True, seed={seed:brush}))
Define(swirl, fBm(octaves=3, base_freq_x=0.6, base_freq_y=3, to_01=True, seed={seed:swirl}))
Material(
  Layer(1)
    .basecolor({mix:metal~-0.25,metal,((brush * 0.7) + (swirl * 0.3))})
    .metallic(0.9)
    .roughness(({rough} + (brush * 0.12)))
    .anisotropy(0.75)
    .height((brush * {hv:0.004}))
)""",
    tags={"brushed": 4, "satin metal": 3, "stainless": 1, **METAL_WORDS},
    colours=METAL_ROLES,
    slots={"view": 1, "rough": 0.45},
    presets=METAL_PRESETS,
    unit_m=0.3,
)

recipe(
    "polished-metal",
    "metal",
    "polished / chrome metal: mirror-smooth with soft reflected clouds",
    """
View(0, 0, {view}, {view})
Define(reflect, fBm(octaves=3, base_freq_x=0.8, base_freq_y=1.6, to_01=True, seed={seed:reflect}))
Define(sweep, Abs(Sin((((X() * 0.6) + (Y() * 1.2)) + (reflect * 2)))))
Material(
  Layer(1)
    .basecolor({mix:metal~-0.45,metal~0.2,((sweep * 0.6) + (reflect * 0.4))})
    .metallic(0.85)
    .roughness({rough})
    .coat(0.5)
    .height((sweep * {h:0.01}))
)""",
    tags={
        "polished": 2.5,
        "chrome": 4,
        "chromed": 4,
        "mirror": 3,
        "shiny metal": 3,
        "reflective": 1.5,
        **METAL_WORDS,
    },
    colours=METAL_ROLES,
    slots={"view": 2, "rough": 0.12},
    presets=METAL_PRESETS,
    unit_m=0.5,
)

recipe(
    "hammered-metal",
    "metal",
    "hand-hammered metal: overlapping round dents catching the light",
    """
View(0, 0, {view}, {view})
Define(dent, Worley(base_freq={mf:7}, to_01=True, seed={seed:dent}))
Define(patina, fBm(octaves=4, base_freq=1.5, to_01=True, seed={seed:patina}))
Material(
  Layer(1)
    .basecolor({mix:metal~-0.35,metal,((dent * 0.6) + (patina * 0.4))})
    .metallic(0.85)
    .roughness(({rough} + (patina * 0.1)))
    .height(((dent * dent) * {hv:0.08}))
)""",
    tags={
        "hammered": 6,
        "beaten": 4,
        "dimpled": 4,
        "planished": 5,
        "forged": 2,
        "handmade": 1,
        **METAL_WORDS,
    },
    colours=roles(("metal", (186, 124, 86))),
    slots={"view": 1, "rough": 0.35},
    presets=METAL_PRESETS,
    unit_m=0.2,
)

recipe(
    "galvanized-metal",
    "metal",
    "galvanized steel: crystalline zinc spangle in silvery patches",
    """
View(0, 0, {view}, {view})
Define(warpU, fBm(octaves=3, base_freq={mf:8}, seed={seed:warpU}))
Define(warpV, fBm(octaves=3, base_freq={mf:8}, seed={seed:warpV}))
Define(grainHash, (Sin(((Floor(((X() * {mf:7}) + (warpU * 0.6))) * 12.9898) + (Floor(((Y() * {mf:7}) + (warpV * 0.6))) * 78.233))) * 43758.5453))
Define(spangle, (grainHash - Floor(grainHash)))
Define(feather, fBm(octaves=4, base_freq_x={mf:40}, base_freq_y={mf:8}, to_01=True, seed={seed:feather}))
Material(
  Layer(1)
    .basecolor({mix:metal~-0.2,metal~0.15,((spangle * 0.75) + (feather * 0.25))})
    .metallic(0.6)
    .roughness(({rough} + (spangle * 0.15)))
    .height(((spangle * {hv:0.002}) + (feather * {hv:0.002})))
)""",
    tags={"galvanized": 6, "galvanised": 6, "zinc": 3, "spangle": 5, "hot dip": 4, **METAL_WORDS},
    colours=roles(("metal", (184, 188, 192))),
    slots={"view": 1, "rough": 0.4},
    presets=METAL_PRESETS,
    unit_m=0.3,
)

recipe(
    "anodized-metal",
    "metal",
    "anodized aluminium: saturated satin colour with fine grain",
    """
View(0, 0, {view}, {view})
Define(grain, fBm(octaves=4, base_freq_x={mf:10}, base_freq_y={mf:90}, to_01=True, seed={seed:grain}))
Define(tone, fBm(octaves=3, base_freq=0.8, to_01=True, seed={seed:tone}))
Material(
  Layer(1)
    .basecolor({mix:metal~-0.25,metal,((grain * 0.5) + (tone * 0.5))})
    .metallic(0.7)
    .roughness(({rough} + (grain * 0.08)))
    .anisotropy(0.3)
    .coat(0.4)
    .height((grain * {hv:0.002}))
)""",
    tags={"anodized": 6, "anodised": 6, **METAL_WORDS},
    colours=roles(("metal", (70, 118, 186))),
    slots={"view": 1, "rough": 0.35},
    unit_m=0.3,
)

recipe(
    "corrugated-metal",
    "metal",
    "corrugated sheet metal: regular sinusoidal ridges",
    """
View(0, 0, {view}, {view})
Define(wave, Sin((X() * {freq})))
Define(streak, fBm(octaves=4, base_freq_x=2, base_freq_y=12, to_01=True, seed={seed:streak}))
Material(
  Layer(1)
    .basecolor({mix:metal~-0.3,metal,((((wave * 0.5) + 0.5) * 0.5) + (streak * 0.5))})
    .metallic(0.8)
    .roughness(({rough} + (streak * 0.1)))
    .height((wave * {h:0.05}))
)""",
    tags={
        "corrugated": 6,
        "ribbed": 2,
        "roofing": 3,
        "roof": 2,
        "shed": 2,
        "ridges": 1.5,
        "tin roof": 5,
        "wavy": 1,
        **METAL_WORDS,
    },
    colours=roles(("metal", (176, 180, 184))),
    slots={"view": 2, "rough": 0.45, "freq": 18},
    patterns=("rows", "waves"),
    presets=METAL_PRESETS,
    unit_m=0.5,
)

recipe(
    "diamond-plate",
    "metal",
    "diamond tread plate: raised lugs alternating in a checker",
    """
View(0, 0, {view}, {view})
Define(lx, ((X() - Floor(X())) - 0.5))
Define(ly, ((Y() - Floor(Y())) - 0.5))
Define(flip, Threshold((Sin((X() * 3.1416)) * Sin((Y() * 3.1416))), below_at=0, above_at=0, above_to=1))
Define(along, (((lx + (ly * ((2 * flip) - 1))) * 0.7071)))
Define(across, (((ly - (lx * ((2 * flip) - 1))) * 0.7071)))
Define(lug, Threshold(((1 - (((along / 0.36) * (along / 0.36)) + ((across / 0.08) * (across / 0.08)))) * 3), below_at=0, above_at=1))
Define(scuff, fBm(octaves=4, base_freq={mf:50}, to_01=True, seed={seed:scuff}))
Material(
  Layer(1)
    .basecolor({mix:metal~-0.3,metal,scuff})
    .metallic(0.85)
    .roughness(({rough} + (scuff * 0.15)))
    .height((lug * {h:0.04}))
)""",
    tags={
        "diamond plate": 8,
        "tread plate": 8,
        "checker plate": 8,
        "checkered plate": 8,
        "treadplate": 8,
        "floor plate": 5,
        "non slip": 3,
        "anti slip": 3,
        **METAL_WORDS,
    },
    colours=roles(("metal", (176, 178, 182))),
    slots={"view": 4, "rough": 0.4},
    presets=METAL_PRESETS,
    unit_m=0.03,
)

recipe(
    "rusted-metal",
    "metal",
    "heavily rusted steel: flaking orange-brown rust over dark metal",
    """
View(0, 0, {view}, {view})
Define(rustBlob, fBm(octaves=6, base_freq=1.6, to_01=True, seed={seed:rustBlob}))
Define(pit, fBm(octaves=4, base_freq={mf:60}, to_01=True, seed={seed:pit}))
Define(rust, Threshold(((((rustBlob + (pit * 0.3)) - 0.75) + ({wear} * 0.5)) * 8), below_at=0, above_at=1))
Define(flake, Threshold(((pit - 0.62) * 20), below_at=0, above_at=1))
Material(
  Layer(1)
    .basecolor({mix:metal~-0.3,metal,pit})
    .metallic(0.8)
    .roughness(0.5)
    .height((pit * {hv:0.002})),
  Layer(rust)
    .basecolor({mix:rust_dark,rust_col,((pit * 0.7) + (rustBlob * 0.3))})
    .roughness(0.95)
    .height((rust * ({h:0.004} + (flake * {hv:0.006}))))
)""",
    tags={
        "rusted": 4,
        "rusty": 4,
        "rust": 4,
        "corroded": 4,
        "corrosion": 4,
        "oxidized": 3,
        "weathered steel": 4,
        "corten": 6,
        "iron": 1.5,
        "steel": 1.5,
        "metal": 1.5,
    },
    colours=roles(
        ("metal", (120, 118, 116)),
        ("rust_col", (170, 84, 38), "accent"),
        ("rust_dark", (90, 44, 24), "accent", ("rust_col", -0.45)),
    ),
    slots={"view": 2, "rough": 0.9, "wear": 0.6},
    absorbs=("rusty", "weathered"),
    unit_m=0.5,
)

recipe(
    "copper-patina",
    "metal",
    "copper with blue-green verdigris patina blooms",
    """
View(0, 0, {view}, {view})
Define(bloom, fBm(octaves=6, base_freq=1.4, to_01=True, seed={seed:bloom}))
Define(fine, fBm(octaves=4, base_freq={mf:50}, to_01=True, seed={seed:fine}))
Define(patina, Threshold(((((bloom + (fine * 0.25)) - 0.72) + ({wear} * 0.4)) * 7), below_at=0, above_at=1))
Material(
  Layer(1)
    .basecolor({mix:metal~-0.35,metal,((bloom * 0.6) + (fine * 0.4))})
    .metallic(0.85)
    .roughness(0.4)
    .height((fine * {hv:0.002})),
  Layer(patina)
    .basecolor({mix:patina_col,patina_col~0.3,fine})
    .roughness(0.9)
    .height((patina * {hv:0.003}))
)""",
    tags={
        "patina": 6,
        "verdigris": 7,
        "oxidized copper": 7,
        "copper": 2.5,
        "bronze": 1.5,
        "statue": 2,
        "weathered copper": 6,
        "green copper": 5,
    },
    colours=roles(("metal", (182, 108, 70)), ("patina_col", (78, 160, 140), "accent")),
    slots={"view": 2, "rough": 0.5, "wear": 0.5},
    absorbs=("weathered",),
    presets={"bronze": {"metal": (160, 112, 66)}},
    unit_m=0.5,
)

recipe(
    "heat-tinted-metal",
    "metal",
    "heat-tinted metal: flame-coloured bands of gold, purple and blue",
    """
View(0, 0, {view}, {view})
Define(flame, fBm(octaves=5, base_freq=0.9, to_01=True, seed={seed:flame}))
Define(heat, ((flame * 3) + (Y() * 0.3)))
Define(fine, fBm(octaves=4, base_freq={mf:40}, to_01=True, seed={seed:fine}))
Material(
  Layer(1)
    .basecolor({mix:metal~-0.25,metal~0.1,((fine * 0.5) + (flame * 0.5))})
    .metallic(0.6)
    .roughness(({rough} + (fine * 0.1)))
    .height((fine * {hv:0.003})),
  Layer((Threshold((Sin((heat * 3.1416)) * 3), below_at=0, above_at=1) * 0.75))
    .basecolor({mix:tint_a,tint_b,flame})
    .metallic(0.5)
    .roughness({rough}),
  Layer((Threshold(((Sin(((heat * 3.1416) + 2)) * 3) - 1.5), below_at=0, above_at=1) * 0.7))
    .basecolor({mix:tint_c,tint_a,flame})
    .metallic(0.5)
    .roughness({rough})
)""",
    tags={
        "heat tinted": 6,
        "heat tint": 6,
        "fire treated": 6,
        "flame": 3,
        "torched": 5,
        "flamed": 5,
        "heat treated": 5,
        "burnished": 2,
        "blued": 4,
        **METAL_WORDS,
    },
    colours=roles(
        ("metal", (200, 120, 76), "material"),
        ("tint_a", (70, 110, 190), "accent"),
        ("tint_b", (70, 170, 140), "accent"),
        ("tint_c", (160, 80, 160), "accent"),
    ),
    slots={"view": 2, "rough": 0.35},
    presets={"titanium": {"metal": (160, 150, 130)}},
    unit_m=0.3,
)


recipe(
    "painted-metal",
    "metal",
    "painted steel: an enamel coat chipped away to bare metal and rust underneath",
    """
View(0, 0, {view}, {view})
Define(chipN, fBm(octaves=6, base_freq=1.8, to_01=True, seed={seed:chip}))
Define(paint, Threshold(((chipN - (0.35 + ({wear} * 0.25))) * 25), below_at=0, above_at=1))
Define(rustN, fBm(octaves=5, base_freq={mf:8}, to_01=True, seed={seed:rust}))
Define(rust, Threshold(((rustN - 0.45) * 6), below_at=0, above_at=1))
Material(
  Layer(1)
    .basecolor({mix:metal~-0.3,metal,rustN})
    .metallic(0.7)
    .roughness(0.5)
    .height((rustN * {hv:0.003})),
  Layer((rust * (1 - paint)))
    .basecolor({mix:rust_col~-0.35,rust_col,rustN})
    .roughness(0.95),
  Layer(paint)
    .basecolor({mix:paint_col~-0.1,paint_col,chipN})
    .roughness({rough})
    .height((paint * {h:0.006}))
)""",
    tags={
        "painted metal": 7,
        "painted steel": 7,
        "painted iron": 7,
        "enamel": 2.5,
        "paint": 3,
        "painted": 3,
        "chipped": 2,
        "peeling": 1.5,
        "steel": 1.5,
        "metal": 1.5,
        "rusted": 1.5,
        "rusty": 1.5,
        "iron": 1,
        "locker": 4,
        "machinery": 3,
        "container": 3,
    },
    colours=roles(
        ("paint_col", (50, 96, 160)),
        ("metal", (120, 118, 116), "material"),
        ("rust_col", (160, 80, 36), "material"),
    ),
    slots={"view": 2, "rough": 0.45, "wear": 0.45},
    absorbs=("chipped", "rusty", "worn"),
    unit_m=0.5,
)
