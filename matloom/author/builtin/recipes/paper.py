"""Paper family: plain paper, crumpled paper, cardboard, wrapping paper, shoji screens,
wallpaper, parchment and newsprint.
"""

from __future__ import annotations

from matloom.author.builtin.recipes.base import recipe, roles

PAPER = {"paper": 3, "sheet": 0.5}

recipe(
    "paper",
    "paper",
    "paper sheet: soft off-white with visible fibres and tooth",
    """
View(0, 0, {view}, {view})
Define(fibre, fBm(octaves=4, base_freq={mf:70}, to_01=True, seed={seed:fibre}))
Define(cloud, fBm(octaves=4, base_freq=1.5, to_01=True, seed={seed:cloud}))
Material(
  Layer(1)
    .basecolor({mix:base~-0.08,base,((fibre * 0.5) + (cloud * 0.5))})
    .roughness(0.9)
    .height((fibre * {hv:0.002}))
)""",
    tags={
        **PAPER,
        "stationery": 3,
        "printer paper": 7,
        "watercolor paper": 7,
        "cotton paper": 6,
        "handmade paper": 7,
        "card": 2,
        "cardstock": 6,
        "construction paper": 7,
    },
    colours=roles(("base", (240, 236, 226))),
    slots={"view": 1, "rough": 0.9},
    unit_m=0.2,
)

recipe(
    "crumpled-paper",
    "paper",
    "crumpled paper: sharp creases and facets from crushing",
    """
View(0, 0, {view}, {view})
Define(facet, Worley(base_freq=2.5, to_01=True, seed={seed:facet}))
Define(crease, Worley(combination="F2-F1", base_freq=2.5, to_01=True, seed={seed:facet}))
Define(small, Worley(combination="F2-F1", base_freq=6, to_01=True, seed={seed:small}))
Define(fibre, fBm(octaves=3, base_freq={mf:70}, to_01=True, seed={seed:fibre}))
Material(
  Layer(1)
    .basecolor({mix:base~-0.15,base,((Min((crease * 3), 1) * 0.6) + (fibre * 0.4))})
    .roughness(0.9)
    .height((((facet * {h:0.06}) + (Min((crease * 3), 1) * {h:0.03})) + (small * {h:0.01})))
)""",
    tags={"crumpled": 7, "crinkled": 4, "wrinkled": 4, "crushed": 3, "scrunched": 6, **PAPER},
    colours=roles(("base", (236, 232, 222))),
    slots={"view": 2, "rough": 0.9},
    unit_m=0.2,
)

recipe(
    "cardboard",
    "paper",
    "cardboard: brown kraft liner with corrugated flutes showing through",
    """
View(0, 0, {view}, {view})
Define(flute, Abs(Sin((X() * {mf:14} * 3.1416))))
Define(fibre, fBm(octaves=4, base_freq={mf:60}, to_01=True, seed={seed:fibre}))
Define(blotch, fBm(octaves=3, base_freq=1.5, to_01=True, seed={seed:blotch}))
Material(
  Layer(1)
    .basecolor({mix:base~-0.15,base,(((flute * 0.3) + (fibre * 0.4)) + (blotch * 0.3))})
    .roughness(0.9)
    .height(((flute * {hv:0.006}) + (fibre * {hv:0.002})))
)""",
    tags={
        "cardboard": 8,
        "corrugated cardboard": 10,
        "carton": 6,
        "kraft": 5,
        "box": 3,
        "paperboard": 7,
        "packaging": 2,
    },
    colours=roles(("base", (190, 150, 104))),
    slots={"view": 1, "rough": 0.9},
    unit_m=0.1,
)

recipe(
    "wrapping-paper",
    "paper",
    "holiday wrapping paper: glossy print of diagonal stripes and stars",
    """
View(0, 0, {view}, {view})
Define(diag, (((X() + Y()) * 1.5) - Floor(((X() + Y()) * 1.5))))
Define(lx, ((X() - Floor(X())) - 0.5))
Define(ly, ((Y() - Floor(Y())) - 0.5))
Define(star, Threshold(((0.11 - (Min(Abs(lx), Abs(ly)) + (Max(Abs(lx), Abs(ly)) * 0.22))) * 40), below_at=0, above_at=1))
Define(sheen, fBm(octaves=3, base_freq=1, to_01=True, seed={seed:sheen}))
Material(
  Layer(1)
    .basecolor({mix:base~-0.15,base,sheen})
    .roughness(0.3)
    .coat(0.6),
  Layer(Threshold(((diag - 0.75) * 60), below_at=0, above_at=1))
    .basecolor({rgb:stripe})
    .roughness(0.3),
  Layer(star)
    .basecolor({rgb:star_col})
    .metallic(0.3)
    .roughness(0.3)
)""",
    tags={
        "wrapping paper": 10,
        "gift wrap": 10,
        "giftwrap": 10,
        "wrapping": 5,
        "holiday": 4,
        "christmas": 5,
        "festive": 5,
        "gift": 3,
        "present": 2,
        "birthday": 3,
    },
    colours=roles(
        ("base", (180, 30, 40)),
        ("stripe", (30, 110, 60), "accent"),
        ("star_col", (230, 190, 80), "accent"),
    ),
    slots={"view": 4, "rough": 0.3},
    patterns=("stripes",),
    unit_m=0.05,
)

recipe(
    "shoji-screen",
    "paper",
    "shoji screen: translucent rice paper in a light wooden lattice",
    """
View(0, 0, {view}, {view})
Define(lattice, (1 - Bricks(brick_width=1, brick_height=1.4, offset=0, mortar=0.06, feather=0.01)))
Define(fibre, fBm(octaves=4, base_freq={mf:60}, to_01=True, seed={seed:fibre}))
Define(glow, fBm(octaves=3, base_freq=0.8, to_01=True, seed={seed:glow}))
Define(grain, fBm(octaves=4, base_freq_x=30, base_freq_y=30, to_01=True, seed={seed:grain}))
Material(
  Layer(1)
    .basecolor({mix:paper~-0.12,paper,((fibre * 0.6) + (glow * 0.4))})
    .roughness(0.9)
    .transmission(0.3)
    .height((fibre * {hv:0.003})),
  Layer(lattice)
    .basecolor({mix:frame~-0.25,frame,grain})
    .roughness(0.6)
    .height((lattice * {h:0.02}))
)""",
    tags={
        "shoji": 10,
        "rice paper": 7,
        "washi": 7,
        "japanese": 2,
        "paper screen": 8,
        "screen": 2,
        "screens": 2,
        "sliding doors": 3,
        "lattice": 2,
        "wood frame": 2,
        "frame": 1,
        "paper": 1.5,
    },
    colours=roles(("paper", (240, 234, 216)), ("frame", (150, 104, 64), "frame")),
    slots={"view": 3, "rough": 0.9},
    patterns=("grid",),
    unit_m=0.3,
)

recipe(
    "wallpaper",
    "paper",
    "damask wallpaper: repeating ornamental motif in tone-on-tone",
    """
View(0, 0, {view}, {view})
Define(lx, ((X() - Floor(X())) - 0.5))
Define(ly, ((Y() - Floor(Y())) - 0.5))
Define(petal, Threshold(((0.3 - ((Abs(lx) * 1.8) + Abs((ly + (Abs(lx) * 0.8))))) * 30), below_at=0, above_at=1))
Define(lozenge, Threshold(((0.03 - Abs(((Abs(lx) + Abs(ly)) - 0.48))) * 40), below_at=0, above_at=1))
Define(paperTex, fBm(octaves=3, base_freq={mf:60}, to_01=True, seed={seed:paperTex}))
Material(
  Layer(1)
    .basecolor({mix:base~-0.05,base,paperTex})
    .roughness(0.8)
    .height((paperTex * {hv:0.001})),
  Layer(Max(petal, lozenge))
    .basecolor({rgb:motif})
    .roughness(0.5)
    .sheen(0.3)
    .height((Max(petal, lozenge) * {h:0.004}))
)""",
    tags={
        "wallpaper": 8,
        "wall paper": 8,
        "damask": 8,
        "victorian": 4,
        "brocade": 5,
        "ornate": 3,
        "baroque": 4,
    },
    colours=roles(("base", (170, 150, 110)), ("motif", (200, 180, 130), "accent", ("base", 0.25))),
    slots={"view": 3, "rough": 0.8},
    patterns=("floral", "diamonds"),
    unit_m=0.1,
)

recipe(
    "parchment",
    "paper",
    "old parchment: mottled yellowed sheet with stains and darker edges",
    """
View(0, 0, {view}, {view})
Define(mottle, fBm(octaves=5, base_freq=1.4, to_01=True, seed={seed:mottle}))
Define(fibre, fBm(octaves=4, base_freq={mf:60}, to_01=True, seed={seed:fibre}))
Define(stainN, fBm(octaves=4, base_freq=2.2, to_01=True, seed={seed:stain}))
Material(
  Layer(1)
    .basecolor({mix:base~-0.3,base,((mottle * 0.7) + (fibre * 0.3))})
    .roughness(0.9)
    .height(((mottle * {h:0.01}) + (fibre * {hv:0.002}))),
  Layer(Threshold(((stainN - 0.6) * 6), below_at=0, above_at=0.6))
    .basecolor({rgb:base~-0.4})
    .roughness(0.9)
)""",
    tags={
        "parchment": 9,
        "old paper": 8,
        "aged paper": 8,
        "vellum": 7,
        "papyrus": 7,
        "manuscript": 5,
        "scroll": 4,
        "antique paper": 8,
        **PAPER,
    },
    colours=roles(("base", (226, 204, 156))),
    slots={"view": 2, "rough": 0.9},
    unit_m=0.3,
)

recipe(
    "newsprint",
    "paper",
    "newsprint: grey paper covered in columns of small text lines",
    """
View(0, 0, {view}, {view})
Define(line, Translate(Bricks(brick_width=0.3, brick_height=0.06, offset=0.37, mortar=0.025, feather=0.005), 0.01, 0))
Define(column, Threshold(((0.44 - Abs(((X() - Floor(X())) - 0.5))) * 40), below_at=0, above_at=1))
Define(fibre, fBm(octaves=3, base_freq={mf:70}, to_01=True, seed={seed:fibre}))
Material(
  Layer(1)
    .basecolor({mix:base~-0.1,base,fibre})
    .roughness(0.9),
  Layer(((line * column) * 0.85))
    .basecolor({rgb:ink})
    .roughness(0.9)
)""",
    tags={
        "newspaper": 9,
        "newsprint": 9,
        "text": 2,
        "printed text": 5,
        "magazine": 4,
        "book page": 6,
        "typography": 4,
        "letters": 2,
    },
    colours=roles(("base", (216, 212, 200)), ("ink", (40, 40, 44), "accent")),
    slots={"view": 3, "rough": 0.9},
    patterns=("rows", "stripes"),
    unit_m=0.1,
)
