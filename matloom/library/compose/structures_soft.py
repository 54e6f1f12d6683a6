"""Structure builders of the soft and loose bases: polymers, ground covers, plants, textiles,
paper and plaster (see :mod:`matloom.library.compose.structures` for the contract)."""

from __future__ import annotations

from types import MappingProxyType

from matloom.library.compose.structure import Builder, Ctx, Structure
from matloom.library.compose.writer import TAU, num


def leather(c: Ctx) -> Structure:
    """Leather: a pebbled grain (creases along Worley cell borders) and a soft patina."""
    f = c.base.feature_m
    cells = c.w.worley(f, 'combination="F2-F1"', 128)
    crease = c.d("crease", f"Smoothstep(0, 0.25, {cells})", "pebble grain")
    patina = c.d("patina", c.w.fbm(4, 0.08), "patina")
    return Structure(
        tone=c.d("tone", f"Clamp((({patina} - 0.5) * 1.8) + 0.5 + ((1 - {crease}) * 0.25))"),
        bump=c.d("bump", f"{crease} * {c.amp}"),
        rough=c.d("rough_var", f"({patina} - 0.5) * 0.15"),
    )


def rubber(c: Ctx) -> Structure:
    """Rubber: a fine matte texture and a few flecks."""
    grain = c.d("grain", c.w.fbm(3, c.base.feature_m / 10), "matte grain")
    return Structure(
        tone=c.d("tone", f"{grain} * 0.5"),
        bump=c.d("bump", f"{grain} * {c.amp}"),
        accent=c.specks("flecks", 0.003),
    )


def foam(c: Ctx) -> Structure:
    """Foam: open pores (pits around Worley feature points) in a soft mass."""
    f = c.base.feature_m
    cells = c.d("cells", c.w.worley(f, hi=96), "foam cells")
    pore = c.d("pores", f"Smoothstep(0.42, 0.12, {cells})", "open pores")
    return Structure(
        tone=c.d("tone", pore),
        bump=c.d("bump", f"(1 - {pore}) * {c.amp}"),
    )


def soil(c: Ctx) -> Structure:
    """Soil: crumbly clods, fine crumbs and a few small stones."""
    f = c.base.feature_m
    clods = c.d("clods", c.w.fbm(5, f), "clods")
    crumbs = c.d("crumbs", c.w.fbm(2, 0.004), "crumbs")
    stones = c.specks("stones", 0.01)
    return Structure(
        tone=c.d("tone", f"Clamp(((0.5 - {clods}) * 2) + 0.5 + (({crumbs} - 0.5) * 0.6))"),
        bump=c.d("bump", f"(({clods} * 0.7) + ({crumbs} * 0.3)) * {c.amp}"),
        accent=stones,
    )


def sand(c: Ctx) -> Structure:
    """Sand: wind ripples across it and fine grains, a few darker ones."""
    wave = c.d("wave", c.w.fbm(2, 0.3, to_01=False), "ripple warp")
    k = c.w.cycles(c.w.per_view(0.06, hi=40), TAU)
    ripple = c.d("ripples", f"(Sin(((Y() * {k}) + ({wave} * 3))) * 0.5) + 0.5",
                 "wind ripples")  # fmt: skip
    grain = c.d("grain", c.w.fbm(2, c.base.feature_m), "grains")
    return Structure(
        tone=c.d("tone", f"Clamp(((1 - {ripple}) * 0.4) + (({grain} - 0.5) * 1.2) + 0.3)"),
        bump=c.d("bump", f"(({ripple} * 0.8) + ({grain} * 0.2)) * {c.amp}"),
        accent=c.specks("dark_grains", 0.002),
    )


def gravel(c: Ctx) -> Structure:
    """Gravel: rounded stones (smooth Worley domes), each of its own tone."""
    f = c.base.feature_m
    freq = c.w.freq(f, hi=48)
    seed = c.w.seed()
    dome = c.d("dome", f"Clamp(1 - (Worley(base_freq={freq}, seed={seed}) "
               "* 1.6))", "stones")  # fmt: skip
    value = c.d("stone_value", f'Worley(base_freq={freq}, seed={seed}, output="cell_value")')
    share = c.base.accent_share
    return Structure(
        tone=c.d("tone", f"Clamp(({value} * 1.4) - ((1 - Sqrt({dome})) * 0.8))"),
        bump=c.d("bump", f"Sqrt({dome}) * {c.amp}"),
        accent=c.d(
            "light_stones",
            f"Smoothstep({num(1 - share - 0.004)}, "
            f"{num(1 - share + 0.004)}, {value}) * Smoothstep(0, 0.2, {dome})",
        ),  # fmt: skip
    )


def grass(c: Ctx) -> Structure:
    """Grass: blades (noise stretched upright), clumps and dry patches."""
    f = c.base.feature_m
    blades = c.d("blades", c.w.fbm(3, f, stretch=(f, f * 8)), "blades")
    clumps = c.d("clumps", c.w.fbm(3, 0.15), "clumps")
    return Structure(
        tone=c.d("tone", f"Clamp(((1 - {blades}) * 1.2) - 0.1 + (({clumps} - 0.5) * 0.8))"),
        bump=c.d("bump", f"(({blades} * 0.7) + ({clumps} * 0.3)) * {c.amp}"),
        accent=c.d("dry", f"Smoothstep(0.66, 0.72, {clumps}) * {blades}", "dry patches"),
    )


def moss(c: Ctx) -> Structure:
    """Moss: soft cushions (rounded Worley cells) with fine fuzz."""
    f = c.base.feature_m
    cushion = c.d("cushion", f"Clamp(1 - {c.w.worley(f * 4, hi=48)})",
                  "cushions")  # fmt: skip
    fuzz = c.d("fuzz", c.w.fbm(3, f / 3), "fuzz")
    return Structure(
        tone=c.d("tone", f"Clamp(((1 - {cushion}) * 0.8) + (({fuzz} - 0.5) * 1.2))"),
        bump=c.d("bump", f"(({cushion} * 0.7) + ({fuzz} * 0.3)) * {c.amp}"),
        accent=c.d("tips", f"Smoothstep(0.62, 0.7, {fuzz}) * {cushion}", "light tips"),
    )


def bark(c: Ctx) -> Structure:
    """Bark: deep furrows between upright ridges, with patches of lichen."""
    f = c.base.feature_m
    ridge = c.d("ridge", c.w.fbm(4, f, stretch=(f, f * 6), to_01=False), "ridges")
    furrow = c.d("furrow", f"Smoothstep(0.02, 0.3, Abs({ridge}))", "furrows")
    lichen = c.d("lichen", c.w.fbm(4, 0.1), "lichen")
    t = 0.5 + 0.144 * 1.4
    return Structure(
        tone=c.d("tone", f"1 - {furrow}"),
        bump=c.d("bump", f"{furrow} * {c.amp}"),
        accent=c.d("lichen_patches", f"Smoothstep({num(t)}, {num(t + 0.04)}, {lichen}) * {furrow}"),
    )


def weave(c: Ctx) -> Structure:
    """Woven cloth: warp and weft threads, each of its own shade, rounded across."""
    n = c.w.cycles(2 * max(1, c.w.per_view(c.base.feature_m * 4, hi=48)))  # plain weave: pairs
    seed = c.w.seed()
    mask = c.d("threads", f"Weave(base_freq={n}, warp_width=0.85, feather=0.08)", "threads")
    across = c.d("across", f'Weave(base_freq={n}, warp_width=0.85, output="across")')
    shade = c.d("thread_shade",
                f'Weave(base_freq={n}, warp_width=0.85, output="thread_value", seed={seed})')  # fmt: skip
    round_ = c.d("round", f"Sin(({across} * 3.141593)) * {mask}", "rounded threads")
    return Structure(
        tone=c.d("tone", f"Clamp(({shade} * 0.5) + ((1 - {round_}) * 0.6))"),
        bump=c.d("bump", f"{round_} * {c.amp}"),
    )


def knit(c: Ctx) -> Structure:
    """Knit: columns of V-shaped stitches (two slanted loops per stitch)."""
    n = c.w.per_view(c.base.feature_m, hi=64)
    cols, rows = c.w.cycles(n), c.w.cycles(round(n * 1.25))
    u = c.d("stitch_u", f"Fract((X() * {cols}))")
    loop = c.d(
        "loops",
        f"Sin((Fract((Y() * {rows}) + (Abs(({u} - 0.5)) * 1.1)) * 3.141593))",
        "V-shaped loops",
    )
    gap = c.d("gaps", f"Smoothstep(0.5, 0.42, Abs(({u} - 0.5)))", "between the columns")
    fuzz = c.d("fuzz", c.w.fbm(2, c.base.feature_m / 8), "yarn fuzz")
    return Structure(
        tone=c.d("tone", f"Clamp(((1 - ({loop} * {gap})) * 0.8) + (({fuzz} - 0.5) * 0.5))"),
        bump=c.d("bump", f"(({loop} * {gap} * 0.85) + ({fuzz} * 0.15)) * {c.amp}"),
    )


def felt(c: Ctx) -> Structure:
    """Felt: matted fibres, fine and even."""
    fibre = c.d("fibre", c.w.fbm(3, c.base.feature_m), "matted fibres")
    cloud = c.d("cloud", c.w.fbm(3, 0.05), "density")
    return Structure(
        tone=c.d("tone", f"Clamp((({fibre} - 0.5) * 1.5) + (({cloud} - 0.5) * 0.8) + 0.5)"),
        bump=c.d("bump", f"{fibre} * {c.amp}"),
    )


def paper(c: Ctx) -> Structure:
    """Paper: a fibrous cloud, fine tooth and a few darker fibres."""
    cloud = c.d("cloud", c.w.fbm(4, 0.03), "fibre cloud")
    tooth = c.d("tooth", c.w.fbm(2, c.base.feature_m), "tooth")
    return Structure(
        tone=c.d("tone", f"Clamp((({cloud} - 0.5) * 1.6) + 0.5)"),
        bump=c.d("bump", f"(({cloud} * 0.4) + ({tooth} * 0.6)) * {c.amp}"),
        accent=c.specks("fibres", 0.0015),
    )


def plaster(c: Ctx) -> Structure:
    """Plaster: trowel marks (soft patches) over a fine sandy tooth."""
    f = c.base.feature_m
    trowel = c.d("trowel", c.w.fbm(4, f), "trowel marks")
    tooth = c.d("tooth", c.w.fbm(2, 0.002), "sandy tooth")
    return Structure(
        tone=c.d("tone", f"Smoothstep(0.35, 0.65, {trowel})"),
        bump=c.d("bump", f"((Smoothstep(0.4, 0.6, {trowel}) * 0.6) + ({tooth} * 0.4)) * {c.amp}"),
        rough=c.d("rough_var", f"(0.5 - {trowel}) * 0.15"),
    )


def asphalt(c: Ctx) -> Structure:
    """Asphalt: aggregate stones in dark binder, some of them light."""
    f = c.base.feature_m
    freq = c.w.freq(f, hi=96)
    seed = c.w.seed()
    dome = c.d("aggregate", f"Clamp(1 - (Worley(base_freq={freq}, seed={seed}) * 1.5))",
               "aggregate")  # fmt: skip
    value = c.d("stone_value", f'Worley(base_freq={freq}, seed={seed}, output="cell_value")')
    share = c.base.accent_share
    return Structure(
        tone=c.d("tone", f"Clamp((1 - {dome}) * 1.5)"),
        bump=c.d("bump", f"{dome} * {c.amp}"),
        accent=c.d(
            "light_stones",
            f"Smoothstep({num(1 - share - 0.004)}, "
            f"{num(1 - share + 0.004)}, {value}) * Smoothstep(0.1, 0.3, {dome})",
        ),  # fmt: skip
    )


#: soft ``BaseSpec.structure`` keys -> builder
SOFT: MappingProxyType[str, Builder] = MappingProxyType(
    {
        "leather": leather,
        "rubber": rubber,
        "foam": foam,
        "soil": soil,
        "sand": sand,
        "gravel": gravel,
        "grass": grass,
        "moss": moss,
        "bark": bark,
        "weave": weave,
        "knit": knit,
        "felt": felt,
        "paper": paper,
        "plaster": plaster,
        "asphalt": asphalt,
    }
)
