"""The composition contract: what the parts reader asks the composer to build.

A :class:`CompositionSpec` is made from a request's :class:`~matloom.library.parts.Parts` when
no library entry covers it (or to add a motif or layout a retrieved entry lacks). The composer
(:func:`matloom.library.compose.build.compose`) turns it into a tileable program with named
parameters and reports which requested things it showed and which it could not.

Names (``base``, ``layout``, ``motif.shape``) are keys of the composer's tables
(:data:`matloom.library.compose.tables.BASES`, ``LAYOUTS``, ``MOTIFS``), which the parts
reader reads too: one vocabulary, no copies.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from matloom.lang import ast as A
from matloom.library.colour import RGB


@dataclass(frozen=True)
class Finish:
    """Surface finish asked for; ``None`` keeps the base's own."""

    roughness: float | None = None
    metallic: float | None = None
    #: 0..1 (glass, resin, jelly); mapped to what the language can show
    translucency: float | None = None
    #: the words it came from ("glossy", "matte", "brushed"), for the explanation
    words: tuple[str, ...] = ()


@dataclass(frozen=True)
class MotifSpec:
    """A motif placed by the layout (or scattered): a key of ``MOTIFS``."""

    shape: str
    colour: RGB | None = None
    #: size of one motif relative to its cell (0.2 .. 0.95)
    scale: float = 0.6
    words: tuple[str, ...] = ()


@dataclass(frozen=True)
class CompositionSpec:
    """What to build. ``colours`` are (role, rgb): roles ``base``, ``secondary``, ``accent``,
    ``grout`` (joints, mortar, gaps), ``motif``, ``stripe``; the first ``base`` is the ground.
    ``size_m`` is the physical size of one repeat (a tile, a cell, a motif step); ``None`` lets
    the base or layout choose. ``named`` is a named material the colour and finish came from
    (``"malachite"``), for the explanation."""

    base: str
    colours: tuple[tuple[str, RGB], ...] = ()
    finish: Finish = field(default_factory=Finish)
    layout: str | None = None
    motif: MotifSpec | None = None
    size_m: float | None = None
    named: str | None = None
    seed: int = 0


@dataclass(frozen=True)
class ComposedProgram:
    """The composer's result: the program, its text (canonical, with a header comment), whether
    it tiles, the physical size of its View side, what it showed (``shown``: short phrases,
    "layout: hexagons", "motif: star") and what it could not (``dropped``, with the reason)."""

    program: A.Program
    text: str
    tileable: bool
    unit_m: float
    shown: tuple[str, ...] = ()
    dropped: tuple[str, ...] = ()
    #: (address, label) of its named parameters (``("define:base", "base colour")``), as
    #: ``matloom params`` labels them from the front matter at the top of ``text``
    labels: tuple[tuple[str, str], ...] = ()
    #: the library category of its base ("stone") and a one-line description, for the result
    category: str = ""
    description: str = ""
