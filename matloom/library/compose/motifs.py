"""The composer's motifs: silhouettes drawn with the language's shapes (Ellipse, Rect, Path under
Fill and Stroke) in a frame centred on (0, 0) that fits a circle of radius 0.5, placed by a
layout's lattice through ``Tile`` (which repeats with the View). ``maze`` and ``wave`` are
patterns of the lattice's cells rather than silhouettes. A hole (an eye, a midrib) is a shape
subtracted, never a product with ``1 - shape``: a product has no bounded support, and Tile then
evaluates the motif everywhere (four times slower).

To add a motif: a :class:`MotifShape` in ``_ALL`` (its expression in the unit frame and the
words that name it); the grid test composes it with every base and layout.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from types import MappingProxyType

from matloom.library.compose.layouts import Lattice
from matloom.library.compose.writer import Writer, num


@dataclass(frozen=True)
class MotifShape:
    """A motif: ``expr`` in the unit frame (coverage 0..1), or a lattice pattern
    (``kind`` ``"maze"`` or ``"wave"``, no ``expr``)."""

    name: str
    noun: str
    words: tuple[str, ...]
    expr: str = ""
    kind: str = "shape"


def _c(v: float) -> str:
    """A shape coordinate: three decimals (0, not -0 or 1e-17)."""
    return num(round(v, 3) + 0.0, 3)


def _poly(points: list[tuple[float, float]]) -> str:
    """``Fill(Path(...))`` of a closed polygon."""
    (x0, y0), rest = points[0], points[1:]
    segs = ", ".join(f"LineTo({_c(x)}, {_c(y)})" for x, y in rest)
    return f"Fill(Path({_c(x0)}, {_c(y0)}, {segs}))"


def _star(points: int, outer: float, inner: float) -> str:
    pts = []
    for k in range(points * 2):
        r = outer if k % 2 == 0 else inner
        a = math.pi / 2 + k * math.pi / points
        pts.append((r * math.cos(a), r * math.sin(a)))
    return _poly(pts)


def _regular(sides: int, radius: float, turn: float = 90.0) -> str:
    return _poly(
        [
            (
                radius * math.cos(math.radians(turn + k * 360 / sides)),
                radius * math.sin(math.radians(turn + k * 360 / sides)),
            )  # fmt: skip
            for k in range(sides)
        ]
    )


def _plus(length: float, half: float, turn: float = 0.0) -> str:
    arm = [(half, half), (half, length), (-half, length), (-half, half)]
    pts: list[tuple[float, float]] = []
    for q in range(4):
        a = math.radians(turn + 90 * q)
        c, s = math.cos(a), math.sin(a)
        pts += [(x * c - y * s, x * s + y * c) for x, y in arm[:3]]
    return _poly(pts)


def _spiral(turns: float = 2.5, radius: float = 0.45, steps: int = 30) -> str:
    pts = []
    for k in range(steps + 1):
        t = k / steps
        a = t * turns * 2 * math.pi
        pts.append((radius * t * math.cos(a), radius * t * math.sin(a)))
    (x0, y0), rest = pts[0], pts[1:]
    segs = ", ".join(f"LineTo({_c(x)}, {_c(y)})" for x, y in rest)
    return f"Stroke(Path({_c(x0)}, {_c(y0)}, {segs}), 0.06)"


def _m(name: str, noun: str, words: str, expr: str = "", kind: str = "shape") -> MotifShape:
    return MotifShape(name, noun, tuple(words.split()), expr, kind)


#: five round petals around the centre (plain Ellipses keep Tile's support box: no Rotate)
_PETALS = [
    f"Fill(Ellipse({_c(0.28 * math.sin(a))}, {_c(0.28 * math.cos(a))}, 0.19, 0.19))"
    for a in (k * 2 * math.pi / 5 for k in range(5))
]
_CUBE = (
    "Max(Stroke(Path(0, 0.5, LineTo(0.433, 0.25), LineTo(0.433, -0.25), LineTo(0, -0.5), "
    "LineTo(-0.433, -0.25), LineTo(-0.433, 0.25), LineTo(0, 0.5)), 0.06), Stroke(Path(-0.433, "
    "0.25, LineTo(0, 0), LineTo(0.433, 0.25)), 0.06), Stroke(Path(0, 0, LineTo(0, -0.5)), 0.06))"
)
_ALL = (
    _m(
        "circle",
        "circles",
        "circle circles disc discs disk disks round coin coins",
        "Fill(Ellipse(0, 0, 0.5, 0.5))",
    ),  # fmt: skip
    _m(
        "ellipse",
        "ovals",
        "ellipse ellipses oval ovals elliptical ovoid",
        "Fill(Ellipse(0, 0, 0.5, 0.3))",
    ),  # fmt: skip
    _m(
        "dot", "dots", "dot dots dotted polka spot spots spotted", "Fill(Ellipse(0, 0, 0.25, 0.25))"
    ),
    _m("ring", "rings", "ring rings hoop hoops annulus", "Stroke(Ellipse(0, 0, 0.42, 0.42), 0.12)"),
    _m(
        "square", "squares", "square squares block blocks", "Fill(Rect(-0.4, -0.4, 0.8, 0.8, 0.03))"
    ),  # fmt: skip
    _m("box", "boxes", "box boxes frame frames outline", "Stroke(Rect(-0.4, -0.4, 0.8, 0.8), 0.1)"),
    _m("cube", "cubes", "cube cubes isometric tumbling", _CUBE),
    _m(
        "triangle",
        "triangles",
        "triangle triangles triangular",
        _poly([(0, 0.45), (0.5, -0.42), (-0.5, -0.42)]),
    ),  # fmt: skip
    _m(
        "diamond",
        "diamonds",
        "diamond diamonds lozenges rhombi",
        _poly([(0, 0.5), (0.34, 0), (0, -0.5), (-0.34, 0)]),
    ),  # fmt: skip
    _m("hexagon", "hexagons", "hexagon hexagons", _regular(6, 0.5)),
    _m("star", "stars", "star stars starry", _star(5, 0.5, 0.2)),
    _m(
        "heart",
        "hearts",
        "heart hearts",
        "Fill(Path(0, -0.45, CubicTo(-0.1, -0.3, -0.5, -0.05, -0.5, 0.18), CubicTo(-0.5, 0.45, "
        "-0.12, 0.52, 0, 0.28), CubicTo(0.12, 0.52, 0.5, 0.45, 0.5, 0.18), CubicTo(0.5, -0.05, "
        "0.1, -0.3, 0, -0.45)))",
    ),  # fmt: skip
    _m(
        "chevron",
        "chevrons",
        "arrowhead arrowheads",
        _poly([(-0.5, 0.05), (0, 0.45), (0.5, 0.05), (0.5, -0.25), (0, 0.15), (-0.5, -0.25)]),
    ),  # fmt: skip
    _m("cross", "crosses", "cross crosses saltire", _plus(0.48, 0.11, 45)),
    _m("plus", "plus signs", "plus pluses", _plus(0.45, 0.12)),
    _m(
        "arrow",
        "arrows",
        "arrow arrows",
        _poly(
            [(-0.5, -0.1), (0.1, -0.1), (0.1, -0.3), (0.5, 0), (0.1, 0.3), (0.1, 0.1), (-0.5, 0.1)]
        ),
    ),  # fmt: skip
    _m(
        "crescent",
        "crescents",
        "crescent crescents moon moons",
        "Fill(Path(0.1, 0.44, CubicTo(-0.45, 0.5, -0.6, -0.5, 0.1, -0.44), CubicTo(-0.25, -0.3, "
        "-0.25, 0.3, 0.1, 0.44)))",
    ),
    _m(
        "drop",
        "drops",
        "drop drops droplet droplets teardrop teardrops raindrop raindrops",
        "Fill(Path(0, 0.5, CubicTo(0.1, 0.25, 0.35, 0.05, 0.35, -0.15), CubicTo(0.35, -0.36, "
        "0.18, -0.5, 0, -0.5), CubicTo(-0.18, -0.5, -0.35, -0.36, -0.35, -0.15), CubicTo(-0.35, "
        "0.05, -0.1, 0.25, 0, 0.5)))",
    ),  # fmt: skip
    _m("spiral", "spirals", "spiral spirals swirl swirls", _spiral()),
    _m(
        "snowflake",
        "snowflakes",
        "snowflake snowflakes",
        "Max(Stroke(Path(0, -0.5, LineTo(0, 0.5)), 0.07), Stroke(Path(-0.433, -0.25, "
        "LineTo(0.433, 0.25)), 0.07), Stroke(Path(-0.433, 0.25, LineTo(0.433, -0.25)), 0.07))",
    ),
    _m(
        "leaf",
        "leaves",
        "leaf leaves foliage",
        "(Fill(Path(0, -0.5, CubicTo(0.38, -0.3, 0.34, 0.28, 0, 0.5), CubicTo(-0.34, 0.28, -0.38, "
        "-0.3, 0, -0.5))) - Fill(Rect(-0.015, -0.42, 0.03, 0.82)))",
    ),  # fmt: skip
    _m(
        "flower",
        "flowers",
        "flower flowers floral blossom blossoms daisy daisies",
        "(Max(" + ", ".join(_PETALS) + ", Fill(Ellipse(0, 0, 0.13, 0.13))) - "
        "Stroke(Ellipse(0, 0, 0.13, 0.13), 0.025))",
    ),  # fmt: skip
    _m(
        "tree",
        "trees",
        "tree trees",
        "Max(Fill(Rect(-0.06, -0.5, 0.12, 0.32, 0.02)), Fill(Ellipse(0, 0.12, 0.36, 0.36)))",
    ),
    _m(
        "pine",
        "pine trees",
        "pine pines fir firs conifer conifers",
        "Max(Fill(Rect(-0.05, -0.5, 0.1, 0.2)), "
        + _poly([(0, 0.5), (0.3, 0.04), (-0.3, 0.04)])
        + ", "
        + _poly([(0, 0.22), (0.4, -0.32), (-0.4, -0.32)])
        + ")",
    ),  # fmt: skip
    _m(
        "fish",
        "fish",
        "fish fishes",
        "(Max(Fill(Ellipse(-0.06, 0, 0.34, 0.2)), Fill(Path(0.2, 0, LineTo(0.5, 0.2), "
        "LineTo(0.5, -0.2)))) - Fill(Ellipse(-0.24, 0.05, 0.04, 0.04)))",
    ),  # fmt: skip
    _m(
        "bird",
        "birds",
        "bird birds sparrow sparrows",
        "(Max(Fill(Ellipse(-0.04, -0.04, 0.27, 0.19)), Fill(Ellipse(0.2, 0.14, 0.12, 0.12)), "
        "Fill(Path(0.3, 0.17, LineTo(0.45, 0.12), LineTo(0.3, 0.09))), Fill(Path(-0.22, 0.02, "
        "LineTo(-0.5, 0.16), LineTo(-0.46, 0), LineTo(-0.2, -0.1))), Fill(Rect(-0.03, -0.42, "
        "0.025, 0.22)), Fill(Rect(0.06, -0.42, 0.025, 0.22))) - Fill(Ellipse(0.23, 0.17, 0.025, "
        "0.025)))",
    ),  # fmt: skip
    _m(
        "cat",
        "cats",
        "cat cats kitten kittens kitty",
        "Max(Fill(Ellipse(0, -0.2, 0.26, 0.28)), Fill(Ellipse(0, 0.18, 0.19, 0.16)), "
        "Fill(Path(-0.17, 0.24, LineTo(-0.15, 0.45), LineTo(-0.04, 0.32))), Fill(Path(0.17, 0.24, "
        "LineTo(0.15, 0.45), LineTo(0.04, 0.32))), Stroke(Path(0.2, -0.42, CubicTo(0.48, -0.42, "
        "0.48, -0.1, 0.36, 0)), 0.06))",
    ),  # fmt: skip
    _m(
        "dog",
        "dogs",
        "dog dogs puppy puppies hound",
        "Max(Fill(Rect(-0.32, -0.12, 0.5, 0.24, 0.1)), Fill(Rect(0.1, 0, 0.16, 0.2)), "
        "Fill(Ellipse(0.25, 0.16, 0.14, 0.13)), Fill(Rect(0.3, 0.06, 0.18, 0.1, 0.04)), "
        "Fill(Path(0.17, 0.25, LineTo(0.22, 0.4), LineTo(0.28, 0.27))), "
        "Fill(Rect(-0.3, -0.42, 0.08, 0.32)), Fill(Rect(-0.16, -0.42, 0.08, 0.32)), "
        "Fill(Rect(0.02, -0.42, 0.08, 0.32)), Fill(Rect(0.14, -0.42, 0.08, 0.32)), "
        "Stroke(Path(-0.3, 0.06, CubicTo(-0.42, 0.12, -0.45, 0.25, -0.42, 0.32)), 0.05))",
    ),  # fmt: skip
    _m(
        "rabbit",
        "rabbits",
        "rabbit rabbits bunny bunnies hare hares",
        "Max(Fill(Ellipse(-0.05, -0.22, 0.3, 0.22)), Fill(Ellipse(0.22, 0.02, 0.14, 0.13)), "
        "Fill(Ellipse(0.18, 0.3, 0.05, 0.18)), Fill(Ellipse(0.28, 0.28, 0.05, 0.17)), "
        "Fill(Ellipse(-0.36, -0.14, 0.08, 0.08)))",
    ),  # fmt: skip
    _m(
        "butterfly",
        "butterflies",
        "butterfly butterflies moth moths",
        "Max(Fill(Ellipse(-0.22, 0.16, 0.22, 0.18)), Fill(Ellipse(0.22, 0.16, 0.22, 0.18)), "
        "Fill(Ellipse(-0.16, -0.2, 0.14, 0.16)), Fill(Ellipse(0.16, -0.2, 0.14, 0.16)), "
        "Fill(Rect(-0.03, -0.35, 0.06, 0.65, 0.03)))",
    ),  # fmt: skip
    _m(
        "paw",
        "paw prints",
        "paw paws pawprint pawprints",
        "Max(Fill(Ellipse(0, -0.17, 0.22, 0.18)), Fill(Ellipse(-0.28, 0.08, 0.09, 0.12)), "
        "Fill(Ellipse(-0.1, 0.26, 0.09, 0.12)), Fill(Ellipse(0.1, 0.26, 0.09, 0.12)), "
        "Fill(Ellipse(0.28, 0.08, 0.09, 0.12)))",
    ),  # fmt: skip
    _m("maze", "a maze", "maze mazes labyrinth labyrinthine", kind="maze"),
    _m("wave", "waves", "wave waves wavy squiggle squiggles", kind="wave"),
)

#: motif name -> shape (read-only)
MOTIFS: MappingProxyType[str, MotifShape] = MappingProxyType({m.name: m for m in _ALL})


def place_motif(w: Writer, motif: MotifShape, lattice: Lattice, scatter: bool) -> str:
    """Write the motif's Defines (its shape, then ``motifs``: the placed coverage, sized by
    the ``motif_size`` Define) and return ``"motifs"``."""
    if motif.kind == "maze":
        return _maze(w, lattice)
    if motif.kind == "wave":
        return _wave(w, lattice)
    shape = w.define(f"{motif.name}_shape", motif.expr, f"one {motif.name}, drawn in a unit circle")
    fit = "" if lattice.fit == 1 else f" * {num(lattice.fit)}"
    grid = f"{num(lattice.width)}, {num(lattice.height)}"
    if lattice.offset:
        grid += f", offset={num(lattice.offset)}"
    if scatter:
        size = f"scale_min=(motif_size * {num(lattice.fit * 0.7)}), scale_max=(motif_size{fit})"
        tile = f"Tile({shape}, {grid}, jitter=0.3, rotate=180, {size}, probability=0.85, seed={w.seed()})"
    else:
        size = f"scale_min=(motif_size{fit}), scale_max=(motif_size{fit})"
        tile = f"Tile({shape}, {grid}, {size}, seed={w.seed()})"
    placed = _moved(tile, lattice.shift)
    if lattice.second is not None:
        placed = f"Max({placed}, {_moved(tile, lattice.second)})"
    return w.define("motifs", placed, "the motifs, one per cell")


def _moved(expr: str, shift: tuple[float, float]) -> str:
    if shift == (0.0, 0.0):
        return expr
    return f"Translate({expr}, {num(shift[0])}, {num(shift[1])})"


def _maze(w: Writer, lattice: Lattice) -> str:
    """A diagonal wall in every cell of the lattice, one way or the other at random."""
    cw, ch = lattice.width, lattice.height
    w.define("maze_u", f"Fract((X() / {num(cw)}))")
    w.define("maze_v", f"Fract((Y() / {num(ch)}))")
    w.define("maze_turn", f"Smoothstep(0.499, 0.501, Hash((X() / {num(cw)}), (Y() / {num(ch)}), "
             f"seed={w.seed()}))", "which way each wall runs")  # fmt: skip
    w.define("maze_d", "Mix(Abs((maze_u - maze_v)), Abs(((maze_u + maze_v) - 1)), maze_turn) "
             "* 0.7071", "distance to the wall (cells)")  # fmt: skip
    return w.define("motifs", "Smoothstep((motif_size * 0.12), (motif_size * 0.09), maze_d)",
                    "maze walls")  # fmt: skip


def _wave(w: Writer, lattice: Lattice) -> str:
    """A wavy line through every row of the lattice."""
    cw, ch = lattice.width, lattice.height
    k = num(2 * math.pi / cw, 10)
    w.define("wave_d", f"Abs(((Fract((Y() / {num(ch)})) - 0.5) - ((motif_size * 0.4) * "
             f"Sin((X() * {k})))))", "distance to the wave line (cells)")  # fmt: skip
    return w.define("motifs", "Smoothstep(0.07, 0.045, wave_d)", "wavy lines")
