"""The built-in recipe library: hand-written, parameterised MatLoom programs by family.

Importing this package registers every recipe in :data:`REGISTRY` (name -> :class:`Recipe`),
in a fixed module order (everyday materials first), which is also the scorer's tie-break order.
"""

from __future__ import annotations

import importlib

from matloom.author.builtin.recipes.base import FAMILIES, REGISTRY, ColourRole, Recipe

#: modules in registration order (earlier recipes win score ties).
MODULES: tuple[str, ...] = (
    "wood",
    "stone",
    "stone_worked",
    "masonry",
    "concrete",
    "metal",
    "metal_sheet",
    "fabric",
    "fabric_special",
    "fabric_prints",
    "fabric_motifs",
    "leather",
    "ground",
    "glass",
    "plastic",
    "paper",
    "organic",
    "emissive",
    "scifi",
)

for _module in MODULES:
    importlib.import_module(f"{__name__}.{_module}")

__all__ = ["FAMILIES", "MODULES", "REGISTRY", "ColourRole", "Recipe"]
