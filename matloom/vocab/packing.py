"""Packed textures: which map each colour channel of an ORM texture or a mask map holds.

The presets write them (:mod:`matloom.io.presets`; a packed file's ``channels`` text in the
manifest is its :attr:`Packing.description`); ``matloom blender`` reads them back
(:mod:`matloom.blender.packed`), finding the file by its :attr:`Packing.role` in the preset's
manifest entry and splitting it by :attr:`Packing.maps`. This module imports no numpy.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class PackedMap:
    """One map stored in one channel of a packed texture."""

    #: The map's ``MaterialMaps`` field (``ao``, ``roughness``, ``metallic``).
    map: str
    #: The texture channel holding it: ``R``, ``G``, ``B`` or ``A``.
    channel: str
    #: Stored as 1 - value (Unity's smoothness = 1 - roughness).
    inverted: bool = False


@dataclass(frozen=True)
class Packing:
    """The layout of one packed texture."""

    #: The file's role in the preset's manifest entry (``files[role]``).
    role: str
    #: The maps it holds, in the order the job lists them.
    maps: tuple[PackedMap, ...]
    #: The manifest's ``channels`` text of the file (for people and engines' importers).
    description: str


#: R ambient occlusion, G roughness, B metallic (glTF, Godot, Unreal, MaterialX, USD).
ORM = Packing(
    "orm",
    (PackedMap("ao", "R"), PackedMap("roughness", "G"), PackedMap("metallic", "B")),
    "R AO, G roughness, B metallic",
)

#: Unity HDRP's mask map: R metallic, G ambient occlusion, B detail mask (written as 1),
#: A smoothness = 1 - roughness.
MASK_MAP = Packing(
    "maskmap",
    (
        PackedMap("metallic", "R"),
        PackedMap("ao", "G"),
        PackedMap("roughness", "A", inverted=True),
    ),
    "R metallic, G AO, B detail mask (1), A smoothness = 1 - roughness",
)
