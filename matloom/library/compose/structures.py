"""Structure builders of the hard bases (ceramic, stone, concrete, wood, metal, glass, minerals).

Each builder writes the Defines of one base's structure through its :class:`Ctx` and returns a
:class:`Structure`. Sizes come from the base (metres) and become whole numbers of features per
View (:meth:`~matloom.library.compose.writer.Writer.freq`), so every structure tiles.
:data:`STRUCTURES` maps ``BaseSpec.structure`` to its builder (the soft bases are in
:mod:`matloom.library.compose.structures_soft`).
"""

from __future__ import annotations

from types import MappingProxyType

from matloom.library.compose.structure import Builder, Ctx, Structure
from matloom.library.compose.structures_soft import SOFT
from matloom.library.compose.writer import TAU, num, share_threshold


def glaze(c: Ctx) -> Structure:
    """A smooth glaze or moulded surface: soft pooling, a faint ripple, optional speckles."""
    f = c.base.feature_m
    pool = c.d("pool", c.w.fbm(3, f * 3), "glaze pooling")
    ripple = c.d("ripple", c.w.fbm(2, f), "faint ripple")
    speck = c.specks("speckle", 0.003)
    return Structure(
        tone=c.d("tone", f"Smoothstep(0.3, 0.75, {pool})"),
        bump=c.d("bump", f"(({pool} * 0.6) + ({ripple} * 0.4)) * {c.amp}"),
        accent=speck,
        rough=c.d("rough_var", f"({ripple} - 0.5) * 0.04"),
    )


def stone(c: Ctx) -> Structure:
    """Natural stone: cloudy mottling, a fine grain and lighter grains."""
    f = c.base.feature_m
    mottle = c.d("mottle", c.w.fbm(4, f), "cloudy mottling")
    grain = c.d("grain", c.w.fbm(3, f / 25), "fine grain")
    return Structure(
        tone=c.d("tone", f"Clamp((({mottle} - 0.5) * 2.2) + 0.5 + (({grain} - 0.5) * 0.6))"),
        bump=c.d("bump", f"(({mottle} * 0.6) + ({grain} * 0.4)) * {c.amp}"),
        accent=c.specks("grains", f / 40),
        rough=c.d("rough_var", f"({grain} - 0.5) * 0.15"),
    )


def marble(c: Ctx) -> Structure:
    """Marble: soft clouds and thin warped veins (the zero lines of a warped noise)."""
    f = c.base.feature_m
    cloud = c.d("cloud", c.w.fbm(4, f), "soft clouds")
    warp = c.d("warp", c.w.fbm(3, f * 1.5, to_01=False), "vein warp")
    field = c.w.fbm(5, f * 1.2, to_01=False)
    veins = c.d(
        "veins",
        f"Smoothstep(0.045, 0.005, Abs(Translate({field}, ({warp} * {num(0.25 * c.w.side / 4)}), "
        "0)))",
        "thin veins",
    )
    return Structure(
        tone=c.d("tone", f"Smoothstep(0.35, 0.7, {cloud})"),
        bump=c.d("bump", f"{cloud} * {c.amp}"),
        accent=veins,
    )


def granite(c: Ctx) -> Structure:
    """Granite: crystals of three colours (Worley cells of uniform random values)."""
    cells = c.w.worley(c.base.feature_m, 'output="cell_value"', hi=128)
    crystal = c.d("crystal", cells, "one random value per crystal")
    share = c.base.accent_share
    dark = c.d("dark_grains", f"Smoothstep({num(1 - share - 0.004)}, {num(1 - share + 0.004)}, "
               f"{crystal})")  # fmt: skip
    sheen = c.d("sheen_var", c.w.fbm(3, 0.2), "polish variation")
    return Structure(
        tone=c.d("tone", f"Smoothstep(0.3, 0.34, {crystal}) * (1 - {dark})"),
        bump=c.d("bump", f"{crystal} * {c.amp}"),
        accent=dark,
        rough=c.d("rough_var", f"({sheen} - 0.5) * 0.08"),
    )


def slate(c: Ctx) -> Structure:
    """Slate: cleft layers (noise stretched along the cleavage) and a fine grit."""
    f = c.base.feature_m
    layers = c.d("layers", c.w.fbm(4, f, stretch=(f * 3, f / 3)), "cleft layers")
    grit = c.d("grit", c.w.fbm(2, f / 30), "fine grit")
    return Structure(
        tone=c.d("tone", f"Clamp((({layers} - 0.5) * 2) + 0.5)"),
        bump=c.d("bump", f"(({layers} * 0.8) + ({grit} * 0.2)) * {c.amp}"),
        rough=c.d("rough_var", f"({grit} - 0.5) * 0.1"),
    )


def strata(c: Ctx) -> Structure:
    """Sandstone: wavy strata across the stone, sandy grain, scattered light grains."""
    f = c.base.feature_m
    wave = c.d("wave", c.w.fbm(3, f * 8, to_01=False), "warp of the strata")
    k = c.w.cycles(c.w.per_view(f * 3, hi=48), TAU)
    layers = c.d(
        "strata",
        f"(Sin(((Y() * {k}) + ({wave} * 2.5))) * 0.5) + 0.5",
        "layers of sediment",
    )
    sand = c.d("sand", c.w.fbm(2, 0.002), "sand grains")
    return Structure(
        tone=c.d("tone", f"Clamp(({layers} * 0.75) + (({sand} - 0.5) * 0.8))"),
        bump=c.d("bump", f"(({layers} * 0.4) + ({sand} * 0.6)) * {c.amp}"),
        accent=c.specks("light_grains", 0.002),
    )


def concrete(c: Ctx) -> Structure:
    """Concrete: mottled cement, fine sand and small air pores."""
    f = c.base.feature_m
    mottle = c.d("mottle", c.w.fbm(4, f), "cement mottling")
    sand = c.d("sand", c.w.fbm(2, 0.003), "fine sand")
    pores = c.d("pores", f"Smoothstep(0.1, 0.05, {c.w.worley(0.012, hi=96)})", "air pores")
    return Structure(
        tone=c.d("tone", f"Clamp((({mottle} - 0.5) * 2) + 0.5 + (({sand} - 0.5) * 0.5))"),
        bump=c.d("bump", f"((({mottle} * 0.6) + ({sand} * 0.4)) - ({pores} * 0.8)) * {c.amp}"),
        accent=pores,
        rough=c.d("rough_var", f"({sand} - 0.5) * 0.1"),
    )


def terrazzo(c: Ctx) -> Structure:
    """Terrazzo: chips (Worley cells shrunk from their borders) in a cement matrix; a chip is
    the secondary or the accent colour by its random value."""
    f = c.base.feature_m
    freq = c.w.freq(f, hi=64)
    seed = c.w.seed()
    value = c.d("chip_value", f'Worley(base_freq={freq}, seed={seed}, output="cell_value")')
    edge = f'Worley(base_freq={freq}, seed={seed}, output="edge")'
    gap = num(0.18 / float(freq))
    chip = c.d("chip", f"Smoothstep({gap}, {num(float(gap) * 1.3)}, {edge})", "stone chips")
    share = c.base.accent_share
    matrix = c.d("matrix", c.w.fbm(3, 0.1), "cement matrix")
    return Structure(
        tone=c.d(
            "tone",
            f"{chip} * Smoothstep({num(share - 0.004)}, {num(share + 0.004)}, "
            f"{value}) + (({matrix} - 0.5) * 0.3)",
        ),  # fmt: skip
        bump=c.d("bump", f"{chip} * {c.amp}"),
        accent=c.d(
            "accent_chips",
            f"{chip} * (1 - Smoothstep({num(share - 0.004)}, {num(share + 0.004)}, {value}))",
        ),  # fmt: skip
    )


def wood(c: Ctx) -> Structure:
    """Wood: growth rings along the grain (a sawtooth of the across coordinate, warped), pores
    and fibres stretched along it."""
    f = c.base.feature_m
    ax = c.axes
    warp = c.d("warp", c.w.fbm(3, f, stretch=ax.stretch(f * 40, f * 4), to_01=False))
    rings = c.w.cycles(c.w.per_view(f * 3, hi=96))
    ring = c.d(
        "rings",
        f"Fract((({ax.across} * {rings}) + ({warp} * 1.6)) + ({c.phase} * 7))",
        "growth rings",
    )
    fibre = c.d("fibre", c.w.fbm(2, f, stretch=ax.stretch(f * 20, f / 6)), "fibres")
    return Structure(
        tone=c.d("tone", f"Clamp((Smoothstep(0.55, 0.95, {ring}) * 0.7) + ({fibre} - 0.35))"),
        bump=c.d("bump", f"((Smoothstep(0.55, 0.95, {ring}) * 0.3) + ({fibre} * 0.7)) * {c.amp}"),
        rough=c.d("rough_var", f"({fibre} - 0.5) * 0.1"),
    )


def bamboo(c: Ctx) -> Structure:
    """Bamboo: dense fibres along the stalk and darker nodes across it."""
    f = c.base.feature_m
    ax = c.axes
    fibre = c.d("fibre", c.w.fbm(2, f, stretch=ax.stretch(f * 40, f)), "fibres")
    nodes = c.w.cycles(c.w.per_view(0.2, hi=16))
    node = c.d(
        "nodes",
        f"Smoothstep(0.04, 0.0, Abs(Fract(({ax.along} * {nodes}) + ({c.phase} * 3)) - 0.5))",
        "stalk nodes",
    )
    return Structure(
        tone=c.d("tone", f"Clamp((({fibre} - 0.5) * 1.5) + 0.5)"),
        bump=c.d("bump", f"(({fibre} * 0.5) + ({node} * 0.5)) * {c.amp}"),
        accent=node,
    )


def cork(c: Ctx) -> Structure:
    """Cork: pressed granules of varied tone with dark pits between some of them."""
    f = c.base.feature_m
    granule = c.d("granule", c.w.worley(f, 'output="cell_value"', hi=128), "granules")
    pits = c.specks("pits", f * 1.5)
    return Structure(
        tone=c.d("tone", granule),
        bump=c.d("bump", f"{granule} * {c.amp}"),
        accent=pits,
    )


def metal(c: Ctx) -> Structure:
    """Bare metal: faint smudges that vary the roughness more than the colour."""
    smudge = c.d("smudge", c.w.fbm(3, c.base.feature_m), "smudges")
    return Structure(
        tone=c.d("tone", f"{smudge} * 0.3"),
        bump=c.d("bump", f"{smudge} * {c.amp}"),
        rough=c.d("rough_var", f"({smudge} - 0.5) * 0.2"),
    )


def brushed(c: Ctx) -> Structure:
    """Brushed metal: fine streaks along the brushing direction."""
    f = c.base.feature_m
    streak = c.d("streak", c.w.fbm(3, f, stretch=c.axes.stretch(0.2, f)), "brush streaks")
    return Structure(
        tone=c.d("tone", f"{streak} * 0.5"),
        bump=c.d("bump", f"{streak} * {c.amp}"),
        rough=c.d("rough_var", f"({streak} - 0.5) * 0.12"),
    )


def rust(c: Ctx) -> Structure:
    """Rust: blotches of dark and bright oxide, flaking, the steel showing where it is thin."""
    f = c.base.feature_m
    blotch = c.d("blotch", c.w.fbm(5, f), "oxide blotches")
    flake = c.d("flake", c.w.fbm(3, f / 6), "flaking")
    t = share_threshold(c.base.accent_share)
    return Structure(
        tone=c.d("tone", f"Smoothstep(0.4, 0.65, {blotch})"),
        bump=c.d("bump", f"(({blotch} * 0.5) + ({flake} * 0.5)) * {c.amp}"),
        accent=c.d("bright_rust", f"Smoothstep({num(t - 0.03)}, {num(t + 0.03)}, {flake})"),
        metal=c.d("bare_steel", f"Smoothstep(0.35, 0.2, {blotch})"),
    )


def glass(c: Ctx) -> Structure:
    """Glass and resin: a faint ripple, clouding and a few bubbles."""
    f = c.base.feature_m
    ripple = c.d("ripple", c.w.fbm(3, f), "ripple")
    return Structure(
        tone=c.d("tone", f"Smoothstep(0.35, 0.7, {ripple})"),
        bump=c.d("bump", f"{ripple} * {c.amp}"),
        accent=c.specks("bubbles", 0.004),
    )


def crystal(c: Ctx) -> Structure:
    """Crystals: faceted cells (Worley F1 as pyramids), bright facet edges, varied tone."""
    f = c.base.feature_m
    freq = c.w.freq(f, hi=48)
    seed = c.w.seed()
    facet = c.d("facet", f"Worley(base_freq={freq}, seed={seed})", "facets")
    value = c.d("facet_value", f'Worley(base_freq={freq}, seed={seed}, output="cell_value")')
    edges = c.d(
        "facet_edges",
        f"Smoothstep({num(0.05 / float(freq))}, 0, Worley(base_freq={freq}, seed={seed}, "
        'output="edge"))',
    )
    return Structure(
        tone=c.d("tone", f"Clamp(({value} * 0.7) + ({facet} * 0.4))"),
        bump=c.d("bump", f"(1 - Clamp({facet})) * {c.amp}"),
        accent=edges,
    )


def banded(c: Ctx) -> Structure:
    """Banded minerals (malachite, agate): concentric bands around nodules, warped."""
    f = c.base.feature_m
    warp = c.d("warp", c.w.fbm(3, f * 12, to_01=False), "band warp")
    dist = c.d("nodules", c.w.worley(f * 14, hi=24), "distance to the nodule centres")
    bands = c.d("bands", f"(Sin((({dist} * 26) + ({warp} * 3))) * 0.5) + 0.5", "growth bands")
    return Structure(
        tone=c.d("tone", f"Smoothstep(0.35, 0.65, {bands})"),
        bump=c.d("bump", f"{bands} * {c.amp}"),
        accent=c.d(
            "light_bands", f"Smoothstep(0.93, 0.99, {bands}) * {num(c.base.accent_share * 8)}"
        ),
    )


def ice(c: Ctx) -> Structure:
    """Ice: clouding, white cracks along cell borders and trapped bubbles."""
    f = c.base.feature_m
    cloud = c.d("cloud", c.w.fbm(4, f), "clouding")
    crack_cells = c.w.worley(f * 2, 'output="edge"', hi=24)
    crack = c.d("cracks", f"Smoothstep({num(c.w.units(0.002))}, 0, {crack_cells})", "cracks")
    return Structure(
        tone=c.d("tone", f"Smoothstep(0.3, 0.75, {cloud})"),
        bump=c.d("bump", f"({cloud} - ({crack} * 0.5)) * {c.amp}"),
        accent=crack,
    )


#: ``BaseSpec.structure`` -> builder
STRUCTURES: MappingProxyType[str, Builder] = MappingProxyType(
    {
        "glaze": glaze,
        "stone": stone,
        "marble": marble,
        "granite": granite,
        "slate": slate,
        "strata": strata,
        "concrete": concrete,
        "terrazzo": terrazzo,
        "wood": wood,
        "bamboo": bamboo,
        "cork": cork,
        "metal": metal,
        "brushed": brushed,
        "rust": rust,
        "glass": glass,
        "crystal": crystal,
        "banded": banded,
        "ice": ice,
        **SOFT,
    }
)
