"""Engine and interchange presets: each writes a self-contained subfolder beside
``material.json`` (inside the render's staged batch) and returns its manifest entry.

| preset | files (``<name>`` = material name) |
|---|---|
| ``gltf`` | ``<name>.gltf`` + ``.bin`` + PNGs, and ``<name>.glb`` (a textured quad) |
| ``mtlx`` | ``<name>.mtlx`` (``open_pbr_surface`` + displacement) + PNGs |
| ``usd`` | ``<name>.usda`` (``UsdPreviewSurface`` on a quad) + PNGs |
| ``unreal`` | ``T_<name>_BC``, ``_N_dx`` (DirectX), ``_ORM``, ``_H`` (16-bit), ``_E`` |
| ``unity`` | HDRP ``<name>_maskmap`` (R metallic, G AO, B detail mask, A smoothness), ``_normal_gl``, ... |
| ``godot`` | ``<name>_orm``, ``_normal_gl``, ... |

A registry entry is a :class:`Preset`; add one module and one entry for a new target.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from matloom.io.presets import engines, gltf, mtlx, usd
from matloom.io.presets.common import PresetInput


@dataclass(frozen=True)
class Preset:
    name: str
    summary: str
    write: Callable[[PresetInput, Path], dict[str, Any]]


#: Every preset by name (the CLI's ``--preset`` choices, in this order).
PRESETS: dict[str, Preset] = {
    p.name: p
    for p in (
        Preset("gltf", "glTF 2.0 material (.gltf + .glb quad), ORM, normal +Y", gltf.write),
        Preset("mtlx", "MaterialX open_pbr_surface with displacement", mtlx.write),
        Preset("usd", "USD (.usda) UsdPreviewSurface on a quad", usd.write),
        Preset("unreal", "Unreal: T_<name>_BC/_N_dx (DirectX)/_ORM/_H (16-bit)", engines.unreal),
        Preset("unity", "Unity HDRP: mask map + OpenGL normal", engines.unity),
        Preset("godot", "Godot 4: ORM + OpenGL normal", engines.godot),
    )
}

__all__ = ["PRESETS", "Preset", "PresetInput"]
