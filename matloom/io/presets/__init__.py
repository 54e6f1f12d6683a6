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

from dataclasses import dataclass
from importlib import import_module
from pathlib import Path
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from matloom.io.presets.common import PresetInput


@dataclass(frozen=True)
class Preset:
    """One target: its name, a one-line summary and its writer, ``"module:function"`` in this
    package. The writer's module is imported when the preset is written, so the registry (the
    CLI's ``--preset`` choices) costs nothing to import."""

    name: str
    summary: str
    writer: str

    def write(self, source: PresetInput, folder: Path) -> dict[str, Any]:
        """Write the preset's files for ``source`` into ``folder``; its manifest entry."""
        module, function = self.writer.split(":")
        return getattr(import_module(f"{__name__}.{module}"), function)(source, folder)


#: Every preset by name (the CLI's ``--preset`` choices, in this order).
PRESETS: dict[str, Preset] = {
    p.name: p
    for p in (
        Preset("gltf", "glTF 2.0 material (.gltf + .glb quad), ORM, normal +Y", "gltf:write"),
        Preset("mtlx", "MaterialX open_pbr_surface with displacement", "mtlx:write"),
        Preset("usd", "USD (.usda) UsdPreviewSurface on a quad", "usd:write"),
        Preset("unreal", "Unreal: T_<name>_BC/_N_dx (DirectX)/_ORM/_H (16-bit)", "engines:unreal"),
        Preset("unity", "Unity HDRP: mask map + OpenGL normal", "engines:unity"),
        Preset("godot", "Godot 4: ORM + OpenGL normal", "engines:godot"),
    )
}

__all__ = ["PRESETS", "Preset"]
