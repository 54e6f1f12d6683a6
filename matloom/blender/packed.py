"""Packed AO / roughness / metallic textures that an exported folder's presets wrote.

``matloom render --preset gltf|godot|unreal|mtlx`` writes an ORM texture (R AO, G roughness,
B metallic) and ``--preset unity`` an HDRP mask map (R metallic, G AO, A smoothness =
1 - roughness). When a source folder holds one, the Blender material reads that texture once
and splits it with a Separate Color node (``worker_material.split_packed``), as an artist
wiring the engine texture set would.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from matloom.blender.listed import UnlistedFileError, listed_file

_ORM_TEXT = "R AO, G roughness, B metallic"
_ORM = {"ao": ("R", False), "roughness": ("G", False), "metallic": ("B", False)}
_MASK_TEXT = "R metallic, G AO, B detail mask (1), A smoothness = 1 - roughness"
_MASK = {"metallic": ("R", False), "ao": ("G", False), "roughness": ("A", True)}
#: (preset, file role, the manifest's channel text, map -> (channel, 1 - value?)), preferred
#: first. A preset whose channel text differs is skipped (its packing is not this one).
PACKINGS: tuple[tuple[str, str, str, dict[str, tuple[str, bool]]], ...] = (
    ("gltf", "orm", _ORM_TEXT, _ORM),
    ("godot", "orm", _ORM_TEXT, _ORM),
    ("unreal", "orm", _ORM_TEXT, _ORM),
    ("mtlx", "orm", _ORM_TEXT, _ORM),
    ("unity", "maskmap", _MASK_TEXT, _MASK),
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
    for preset, role, text, channels in PACKINGS:
        entry = presets.get(preset)
        if not isinstance(entry, dict):
            continue
        files = entry.get("files")
        item = files.get(role) if isinstance(files, dict) else None
        if not isinstance(item, dict) or not isinstance(item.get("file"), str):
            continue  # constant AO/roughness/metallic: written as values, no texture
        if item.get("channels") != text:
            continue
        sub = entry.get("folder") if isinstance(entry.get("folder"), str) else preset
        try:  # only a file inside the folder, listed with its SHA-256, is ever read
            path = listed_file(folder, f"{sub}/{item['file']}", manifest)
        except UnlistedFileError as err:
            raise PackedTextureError(str(err)) from None
        return {
            "preset": preset,
            "role": role,
            "file": str(path),
            "channels": {
                name: {"channel": channel, "invert": invert}
                for name, (channel, invert) in channels.items()
            },
        }
    return None
