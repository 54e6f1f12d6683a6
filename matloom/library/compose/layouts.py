"""The composer's layouts: how a surface is divided (tiles and joints, planks, stripes, cells)
and where motifs go. :data:`LAYOUTS` (read through :mod:`matloom.library.compose.tables`) holds
the data; :func:`build_layout` writes a layout's Defines.

Every layout is drawn in program units where one repeat (a tile, a brick, a plank, a stripe
pair, a motif step) is ``cell_w`` units wide; the View is ``side`` units, a whole number of
repeats, starting at ``origin`` (inside the cells, so that no joint runs along the wrap edge).
To add a layout: a :class:`LayoutSpec` in ``_ALL`` and its builder in ``_BUILDERS``.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from types import MappingProxyType

from matloom.library.compose.writer import Writer, num


@dataclass(frozen=True)
class Lattice:
    """Where motifs are centred: the cells of ``Tile(motif, width, height, offset=offset)``
    moved by ``shift``, plus a second such lattice moved by ``second`` (herringbone's upright
    planks); ``fit`` is the motif diameter (units) that fills one place."""

    width: float = 1.0
    height: float = 1.0
    offset: float = 0.0
    shift: tuple[float, float] = (0.0, 0.0)
    fit: float = 1.0
    second: tuple[float, float] | None = None


@dataclass(frozen=True)
class LayoutSpec:
    """A layout. ``joints``: it has joints (grout, mortar, seams) between its cells, as wide
    as the ``grout_width`` Define (``grout``, units); ``gaps``: gaps of its own between its
    cells (woven strips);
    ``two_colour``: its cells alternate between two colours; ``alt_contrast``: how far the
    default second colour is from the base colour (0 the same, 1 a strong contrast);
    ``holes``: the motif is cut through the surface (perforations); ``cell_m``: the size of one
    repeat in metres when the request gives none (None: the base's ``cell_m``);
    ``default_motif``: the motif it shows when none is asked for."""

    name: str
    noun: str
    words: tuple[str, ...]
    side: float
    lattice: Lattice
    origin: tuple[float, float] = (0.25, 0.25)
    cell_w: float = 1.0
    joints: bool = True
    grout: float = 0.04
    two_colour: bool = False
    alt_contrast: float = 0.0
    holes: bool = False
    gaps: bool = False
    cell_m: float | None = None
    default_motif: str | None = None
    unit: str = "tile"
    alt_slot: str = "second"

    @property
    def shows_ground(self) -> bool:
        """The ground (grout, gaps, the void under holes) shows between its cells."""
        return self.joints or self.holes or self.gaps


@dataclass(frozen=True)
class LayoutParts:
    """Define names a layout wrote (None: it has none). ``cells``: 1 on the tiles, 0 in the
    joints; ``edge``: distance to the tile border (units, for bevels); ``pick``: a random value
    per tile; ``alt``: 1 where the second colour goes; ``upright``: 1 on upright planks;
    ``height``: a height shape of its own (units: quilted puffs, woven strips)."""

    cells: str | None = None
    edge: str | None = None
    pick: str | None = None
    alt: str | None = None
    upright: str | None = None
    height: str | None = None


def _l(name: str, noun: str, words: str, side: float, lattice: Lattice, **kw: object) -> LayoutSpec:
    return LayoutSpec(name, noun, tuple(words.split()), side, lattice, **kw)  # type: ignore[arg-type]


_ALL = (
    _l("grid", "square tiles in a grid", "grid tiled tiles squares", 4, Lattice()),
    _l(
        "rows", "rectangular tiles in stacked rows", "rows row stacked", 4, Lattice(1, 0.5, fit=0.5)
    ),  # fmt: skip
    _l(
        "brick",
        "running bond bricks",
        "brick bricks bond staggered offset",
        4,
        Lattice(1, 0.5, 0.5, fit=0.5),
        unit="brick",
    ),  # fmt: skip
    _l(
        "boards",
        "long boards in staggered rows",
        "boards floorboards lapped",
        2,
        Lattice(1, 0.125, 0.5, fit=0.12),
        cell_w=0.125,
        grout=0.006,
        cell_m=0.15,
        unit="board",
    ),  # fmt: skip
    _l(
        "herringbone",
        "herringbone planks",
        "herringbone",
        4,
        Lattice(2, 0.5, -0.25, (-0.5, 0), 0.5, second=(-0.75, 1.25)),
        unit="plank",
    ),  # fmt: skip
    _l(
        "basketweave",
        "basketweave pairs of planks",
        "basketweave basket-weave parquet",
        4,
        Lattice(fit=0.9),
        grout=0.03,
        unit="block",
    ),  # fmt: skip
    _l(
        "hexagons",
        "hexagonal tiles",
        "hexagons hexagon hexagonal hex honeycomb",
        7,
        Lattice(1, 0.875, 0.5, fit=0.95),
        origin=(0.125, 0.0625),
    ),  # fmt: skip
    _l(
        "stripes",
        "stripes",
        "stripes striped stripe bands banded pinstripe",
        4,
        Lattice(),
        joints=False,
        two_colour=True,
        alt_contrast=1.0,
        unit="stripe",
        alt_slot="stripe",
    ),  # fmt: skip
    _l(
        "checks",
        "a checkerboard",
        "checks checked checker checkered checkerboard chequered gingham",
        4,
        Lattice(),
        grout=0.012,
        two_colour=True,
        alt_contrast=1.0,
        alt_slot="check",
    ),  # fmt: skip
    _l(
        "scatter",
        "scattered motifs",
        "scatter scattered random sprinkled strewn",
        4,
        Lattice(),
        joints=False,
        default_motif="dot",
        unit="motif",
    ),  # fmt: skip
    _l(
        "perforations",
        "perforations",
        "perforations perforated holes punched pierced",
        7,
        Lattice(1, 0.875, 0.5, fit=0.95),
        origin=(0.0625, 0.0625),
        joints=False,
        holes=True,
        cell_m=0.015,
        default_motif="circle",
        unit="hole",
    ),  # fmt: skip
    _l(
        "quilting",
        "quilted diamonds",
        "quilting quilted padded tufted",
        4,
        Lattice(1, 0.5, 0.5, (0, -0.25), 0.7),
        grout=0.012,
        cell_m=0.12,
        unit="quilt",
    ),  # fmt: skip
    _l(
        "diamonds",
        "diamond tiles",
        "diamonds harlequin argyle lozenge rhombus",
        4,
        Lattice(1, 0.5, 0.5, (0, -0.25), 0.7),
        two_colour=True,
        alt_contrast=0.6,
        alt_slot="diamond",
    ),  # fmt: skip
    _l(
        "chevron",
        "chevron stripes",
        "chevron chevrons zigzag zig-zag",
        4,
        Lattice(),
        joints=False,
        two_colour=True,
        alt_contrast=1.0,
        unit="chevron",
        alt_slot="band",
    ),  # fmt: skip
    _l(
        "weave",
        "woven strips",
        "weave woven interwoven wicker",
        4,
        Lattice(),
        joints=False,
        gaps=True,
        two_colour=True,
        alt_contrast=0.15,
        cell_m=0.04,
        unit="strip",
        alt_slot="weft",
    ),  # fmt: skip
)

#: layout name -> spec (read-only)
LAYOUTS: MappingProxyType[str, LayoutSpec] = MappingProxyType({s.name: s for s in _ALL})

_FEATHER = 0.006  # joint edge softening, units


def _joint(w: Writer, edge: str) -> str:
    """Coverage of the tiles from the distance to their border and ``grout_width``."""
    f = num(_FEATHER)
    return w.define("tiles", f"Smoothstep((grout_width * 0.5), ((grout_width * 0.5) + {f}), "
                    f"{edge})", "1 on the tiles, 0 in the joints")  # fmt: skip


def _bricks(w: Writer, height: float, offset: float) -> LayoutParts:
    args = f"brick_height={num(height)}, offset={num(offset)}, mortar=grout_width"
    tiles = w.define("tiles", f"Bricks({args}, feather={num(_FEATHER)})",
                     "1 on the tiles, 0 in the joints")  # fmt: skip
    edge = w.define("tile_edge", f'Bricks({args}, output="edge")', "distance to the joint")
    pick = w.define("tile_pick", f'Bricks({args}, output="cell_value", seed={w.seed()})',
                    "one random value per tile")  # fmt: skip
    return LayoutParts(cells=tiles, edge=edge, pick=pick)


def grid(w: Writer, spec: LayoutSpec) -> LayoutParts:
    return _bricks(w, 1, 0)


def rows(w: Writer, spec: LayoutSpec) -> LayoutParts:
    return _bricks(w, 0.5, 0)


def brick(w: Writer, spec: LayoutSpec) -> LayoutParts:
    return _bricks(w, 0.5, 0.5)


def boards(w: Writer, spec: LayoutSpec) -> LayoutParts:
    """Boards eight times as long as they are wide, each row's joints half a board along
    (siding, floorboards, laminate)."""
    return _bricks(w, 0.125, 0.5)


def checks(w: Writer, spec: LayoutSpec) -> LayoutParts:
    """Squares of two colours; tiles with joints on hard bases, printed squares without."""
    if not spec.joints:
        alt = w.define("checker", "Mod((Floor(X()) + Floor(Y())), 2)", "1 on every other square")
        return LayoutParts(alt=alt)
    parts = _bricks(w, 1, 0)
    args = "brick_height=1, offset=0, mortar=grout_width"
    alt = w.define("checker", f'Mod((Bricks({args}, output="row") + Bricks({args}, '
                   'output="column")), 2)', "1 on every other square")  # fmt: skip
    return LayoutParts(cells=parts.cells, edge=parts.edge, pick=parts.pick, alt=alt)


def herringbone(w: Writer, spec: LayoutSpec) -> LayoutParts:
    """Planks two cells long and one wide on a half-unit grid: cells whose (column + row)
    mod 4 is 0 or 1 belong to flat planks, 2 or 3 to upright ones."""
    w.define("hb_col", "Floor((X() * 2))")
    w.define("hb_row", "Floor((Y() * 2))")
    w.define("hb_step", "Mod((hb_col + hb_row), 4)", "place along the plank's staircase")
    up = w.define("upright", "Clamp((hb_step - 1), 0, 1)", "1 on upright planks")
    w.define("hb_along", "Mix(((hb_step + Fract((X() * 2))) / 2), (((hb_step - 2) + "
             "Fract((Y() * 2))) / 2), upright)", "0 to 1 along the plank")  # fmt: skip
    w.define("hb_across", "Mix(Fract((Y() * 2)), Fract((X() * 2)), upright)")
    edge = w.define("tile_edge", "Min((Min(hb_along, (1 - hb_along)) * 1), (Min(hb_across, "
                    "(1 - hb_across)) * 0.5))", "distance to the joint")  # fmt: skip
    tiles = _joint(w, edge)
    pick = w.define("tile_pick", f"Hash(((hb_col - (hb_step * (1 - upright))) + 0.5), "
                    f"((hb_row - ((hb_step - 2) * upright)) + 0.5), seed={w.seed()})",
                    "one random value per plank")  # fmt: skip
    return LayoutParts(cells=tiles, edge=edge, pick=pick, upright=up)


def basketweave(w: Writer, spec: LayoutSpec) -> LayoutParts:
    """Unit blocks of two planks each, flat and upright blocks alternating."""
    up = w.define("upright", "Mod((Floor(X()) + Floor(Y())), 2)", "1 in upright blocks")
    w.define("bw_along", "Mix(Fract(X()), Fract(Y()), upright)")
    w.define("bw_across", "Mix(Fract((Y() * 2)), Fract((X() * 2)), upright)")
    edge = w.define("tile_edge", "Min(Min(bw_along, (1 - bw_along)), (Min(bw_across, "
                    "(1 - bw_across)) * 0.5))", "distance to the joint")  # fmt: skip
    tiles = _joint(w, edge)
    s = w.seed()
    pick = w.define("tile_pick", f"Mix(Hash(X(), (Y() * 2), seed={s}), Hash((X() * 2), Y(), "
                    f"seed={s}), upright)", "one random value per plank")  # fmt: skip
    return LayoutParts(cells=tiles, edge=edge, pick=pick, upright=up)


_HEX_R = 0.875 / 1.5  # centre to the top vertex: rows 0.875 apart tile exactly


def hexagons(w: Writer, spec: LayoutSpec) -> LayoutParts:
    """Hexagons one unit across the flats in rows 0.875 apart (7 across and 8 rows per View:
    within 1 % of regular), from Tile's per-instance frame."""
    r, h = num(_HEX_R), num(_HEX_R / 2)
    hexagon = w.define("hex_cell", f"Fill(Path(0, {r}, LineTo(0.5, {h}), LineTo(0.5, -{h}), "
                       f"LineTo(0, -{r}), LineTo(-0.5, -{h}), LineTo(-0.5, {h})))")  # fmt: skip
    s = w.seed()
    grid_ = f"1, 0.875, offset=0.5, seed={s}"
    w.define("hex_u", f'Tile({hexagon}, {grid_}, output="u")', "position in the hexagon")
    w.define("hex_v", f'Tile({hexagon}, {grid_}, output="v")')
    w.define("hex_d", f"Max((Abs(hex_u) * 2), (Abs(hex_u) + (Abs(hex_v) / {r})))",
             "1 on the hexagon's border")  # fmt: skip
    edge = w.define("tile_edge", "(1 - hex_d) * 0.5", "distance to the joint")
    tiles = _joint(w, edge)
    pick = w.define("tile_pick", f'Tile({hexagon}, {grid_}, output="instance_value")',
                    "one random value per tile")  # fmt: skip
    return LayoutParts(cells=tiles, edge=edge, pick=pick)


def stripes(w: Writer, spec: LayoutSpec) -> LayoutParts:
    w.define("stripe_share", 0.5, "share of each repeat in the stripe colour")
    alt = w.define("stripes", "1 - Smoothstep((stripe_share - 0.01), (stripe_share + 0.01), "
                   "Fract(X()))", "1 on the stripes")  # fmt: skip
    return LayoutParts(alt=alt)


def chevron(w: Writer, spec: LayoutSpec) -> LayoutParts:
    w.define("zigzag", "Fract((Y() + Abs((Fract(X()) - 0.5))))", "0 to 1 across each band")
    alt = w.define("chevron_band", "Smoothstep(0.49, 0.51, zigzag)", "1 on every other band")
    return LayoutParts(alt=alt)


def _diagonal(w: Writer) -> str:
    """Distance (units) to the nearest diagonal line x + y or x - y = whole number."""
    w.define("diag_a", "Abs((Fract((X() + Y())) - 0.5))")
    w.define("diag_b", "Abs((Fract((X() - Y())) - 0.5))")
    return w.define("tile_edge", "(0.5 - Max(diag_a, diag_b)) * 0.7071", "distance to the seam")


def diamonds(w: Writer, spec: LayoutSpec) -> LayoutParts:
    edge = _diagonal(w)
    tiles = _joint(w, edge)
    alt = w.define("harlequin", "Mod((Floor((X() + Y())) + Floor((X() - Y()))), 2)",
                   "1 on every other diamond")  # fmt: skip
    pick = w.define("tile_pick", f"Hash((X() + Y()), (X() - Y()), seed={w.seed()})",
                    "one random value per diamond")  # fmt: skip
    return LayoutParts(cells=tiles, edge=edge, pick=pick, alt=alt)


def quilting(w: Writer, spec: LayoutSpec) -> LayoutParts:
    edge = _diagonal(w)
    tiles = _joint(w, edge)
    puff = w.define("puff", f"Sqrt(Clamp((tile_edge / 0.3536))) * {num(w.units(0.012))}",
                    "padding puffed up between the stitches")  # fmt: skip
    return LayoutParts(cells=tiles, edge=edge, height=puff)


def weave(w: Writer, spec: LayoutSpec) -> LayoutParts:
    args = "base_freq=1, warp_width=0.8"
    tiles = w.define("strips", f"Weave({args}, feather=0.02)", "1 on the strips")
    along = w.define("strip_along", f'Weave({args}, output="along")')
    pick = w.define("tile_pick", f'Weave({args}, output="thread_value", seed={w.seed()})',
                    "one random value per strip")  # fmt: skip
    alt = w.define("weft_strips", f'Weave({args}, output="weft")', "1 on the crossing strips")
    over = w.define("over_under", f"Sin(({along} * 3.141593)) * {num(w.units(0.004))}",
                    "strips rise over and dip under")  # fmt: skip
    return LayoutParts(cells=tiles, pick=pick, alt=alt, height=over)


def scatter(w: Writer, spec: LayoutSpec) -> LayoutParts:
    return LayoutParts()


def perforations(w: Writer, spec: LayoutSpec) -> LayoutParts:
    return LayoutParts()


_BUILDERS: MappingProxyType[str, Callable[[Writer, LayoutSpec], LayoutParts]] = MappingProxyType(
    {
        "grid": grid,
        "rows": rows,
        "brick": brick,
        "boards": boards,
        "checks": checks,
        "herringbone": herringbone,
        "basketweave": basketweave,
        "hexagons": hexagons,
        "stripes": stripes,
        "chevron": chevron,
        "diamonds": diamonds,
        "quilting": quilting,
        "weave": weave,
        "scatter": scatter,
        "perforations": perforations,
    }
)


def build_layout(w: Writer, spec: LayoutSpec) -> LayoutParts:
    """Write ``spec``'s Defines (``grout_width`` first when it has joints)."""
    if spec.joints:
        w.define("grout_width", spec.grout, "joint width (units)")
    return _BUILDERS[spec.name](w, spec)
