"""Packed AO / roughness / metallic textures that an exported folder's presets wrote.

``matloom render --preset gltf|godot|unreal|mtlx`` writes an ORM texture (R AO, G roughness,
B metallic) and ``--preset unity`` an HDRP mask map (R metallic, G AO, A smoothness =
1 - roughness). When a source folder holds one, the Blender material reads that texture once
and splits it with a Separate Color node (``worker_material.split_packed``), as an artist
wiring the engine texture set would. Which channel holds which map is the preset's
:class:`~matloom.vocab.packing.Packing`, shared with the writer.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from matloom.blender.listed import UnlistedFileError, listed_file
from matloom.vocab.packing import MASK_MAP, ORM, Packing

#: (preset, the packed texture it writes), preferred first. The texture is the preset
#: entry's file of the packing's role; its layout comes from the packing, not the manifest.
PACKINGS: tuple[tuple[str, Packing], ...] = (
    ("gltf", ORM),
    ("godot", ORM),
    ("unreal", ORM),
    ("mtlx", ORM),
    ("unity", MASK_MAP),
)


class PackedTextureError(Exception):
    """A packed texture listed in the manifest is missing; the message is one line."""


def packed_texture(manifest: dict[str, Any], folder: Path) -> dict[str, Any] | None:
    """The job entry of the first packed texture the manifest's presets list, or None.

    ``{"preset", "role", "file" (absolute), "channels": {map: {"channel", "invert"}}}``.
    """
    presets = manifest.get("presets")
    if not isinstance(presets, dict):
        return None
    for preset, packing in PACKINGS:
        entry = presets.get(preset)
        if not isinstance(entry, dict):
            continue
        files = entry.get("files")
        item = files.get(packing.role) if isinstance(files, dict) else None
        if not isinstance(item, dict) or not isinstance(item.get("file"), str):
            continue  # constant AO/roughness/metallic: written as values, no texture
        sub = entry.get("folder") if isinstance(entry.get("folder"), str) else preset
        try:  # only a file inside the folder, listed with its SHA-256, is ever read
            path = listed_file(folder, f"{sub}/{item['file']}", manifest)
        except UnlistedFileError as err:
            raise PackedTextureError(str(err)) from None
        return {
            "preset": preset,
            "role": packing.role,
            "file": str(path),
            "channels": {
                packed.map: {"channel": packed.channel, "invert": packed.inverted}
                for packed in packing.maps
            },
        }
    return None
