"""The composer's vocabulary, one place for the composer and the parts reader: the bases
(:data:`BASES`), layouts (:data:`LAYOUTS`) and motifs (:data:`MOTIFS`), each a read-only
mapping name -> spec whose ``words`` are the request words that name it.

The data lives beside its builders (``bases.py``, ``layouts.py``, ``motifs.py``); this module
only gathers it and answers word look-ups (:func:`base_for`, :func:`layout_for`,
:func:`motif_for`). Words are unique within each table (a test keeps them so); one word may
name a layout and a motif ("diamonds", "chevron"): the reader decides by its place in the
request.
"""

from __future__ import annotations

import functools
from collections.abc import Mapping
from types import MappingProxyType

from matloom.library.compose.bases import BASES, BaseSpec
from matloom.library.compose.layouts import LAYOUTS, Lattice, LayoutSpec
from matloom.library.compose.motifs import MOTIFS, MotifShape

__all__ = [
    "BASES",
    "LAYOUTS",
    "MOTIFS",
    "BaseSpec",
    "Lattice",
    "LayoutSpec",
    "MotifShape",
    "base_for",
    "layout_for",
    "motif_for",
    "word_index",
]


@functools.cache
def word_index(table: str) -> Mapping[str, str]:
    """Word -> name for ``table`` (``"bases"``, ``"layouts"`` or ``"motifs"``); each name is
    also a word of its own entry (``brushed_metal`` as ``"brushed metal"`` too)."""
    specs: Mapping[str, BaseSpec | LayoutSpec | MotifShape] = {
        "bases": BASES,
        "layouts": LAYOUTS,
        "motifs": MOTIFS,
    }[table]
    out: dict[str, str] = {}
    for name, spec in specs.items():
        for word in (name, name.replace("_", " "), *spec.words):
            out.setdefault(word.lower(), name)
    return MappingProxyType(out)


def base_for(word: str) -> str | None:
    """The base a word names (``"timber"`` -> ``"wood"``), else None."""
    return word_index("bases").get(word.lower())


def layout_for(word: str) -> str | None:
    """The layout a word names (``"herringbone"``), else None."""
    return word_index("layouts").get(word.lower())


def motif_for(word: str) -> str | None:
    """The motif a word names (``"ovals"`` -> ``"ellipse"``), else None."""
    return word_index("motifs").get(word.lower())
