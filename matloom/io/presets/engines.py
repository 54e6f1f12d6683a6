"""Game-engine presets: Unreal, Unity (HDRP) and Godot texture sets (no material file; the
manifest entry lists each texture's role, colour space and the constant values)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from matloom.io.presets.common import (
    LINEAR,
    PresetFiles,
    PresetInput,
    write_basecolor,
    write_emissive,
    write_height,
    write_normal,
    write_orm,
)
from matloom.vocab.packing import MASK_MAP


def unreal(src: PresetInput, folder: Path) -> dict[str, Any]:
    """``T_<name>_BC`` (sRGB), ``_N_dx`` (DirectX normal: Unreal's ``_N`` suffix with the
    convention, as every normal map's name carries it), ``_ORM`` (R AO, G roughness,
    B metallic), ``_H`` (16-bit height), ``_E`` (emissive, when used)."""
    out = PresetFiles(folder)
    prefix = f"T_{src.name}"
    write_basecolor(src, out, f"{prefix}_BC.png", src.bits)
    write_normal(src, out, f"{prefix}_N_dx.png", "dx", src.bits)
    write_orm(src, out, f"{prefix}_ORM.png", src.bits)
    write_height(src, out, f"{prefix}_H.png")
    write_emissive(src, out, f"{prefix}_E.png", src.bits)
    return out.entry(
        src,
        import_settings="_N_dx: normal map (DirectX, no green flip); _ORM and _H: sRGB off",
    )


def unity(src: PresetInput, folder: Path) -> dict[str, Any]:
    """HDRP: base colour, mask map (R metallic, G AO, B detail mask = 1, A smoothness =
    1 - roughness), OpenGL normal, 16-bit height, emissive (when used)."""
    out = PresetFiles(folder)
    write_basecolor(src, out, f"{src.name}_basecolor.png", src.bits)
    write_normal(src, out, f"{src.name}_normal_gl.png", "gl", src.bits)
    if src.orm_constant:
        for f in ("metallic", "ao", "roughness"):
            out.values[f] = src.constant(f)
        out.values["smoothness"] = 1.0 - float(src.constant("roughness") or 0.0)
    else:
        m = src.maps
        mask = np.stack(
            [m.metallic, m.ao, np.ones_like(m.ao), 1.0 - np.asarray(m.roughness)], axis=2
        )
        out.png(
            MASK_MAP.role,
            f"{src.name}_maskmap.png",
            mask,
            src.bits,
            colour_space=LINEAR,
            channels=MASK_MAP.description,
        )
    write_height(src, out, f"{src.name}_height.png")
    write_emissive(src, out, f"{src.name}_emissive.png", src.bits)
    return out.entry(
        src,
        import_settings="maskmap, normal and height: sRGB off; normal: Texture Type Normal map",
    )


def godot(src: PresetInput, folder: Path) -> dict[str, Any]:
    """Godot 4 ORMMaterial3D: albedo, ORM (R AO, G roughness, B metallic), OpenGL normal,
    16-bit height, emissive (when used)."""
    out = PresetFiles(folder)
    write_basecolor(src, out, f"{src.name}_basecolor.png", src.bits)
    write_orm(src, out, f"{src.name}_orm.png", src.bits)
    write_normal(src, out, f"{src.name}_normal_gl.png", "gl", src.bits)
    write_height(src, out, f"{src.name}_height.png")
    write_emissive(src, out, f"{src.name}_emissive.png", src.bits)
    return out.entry(src, import_settings="normal: Normal Map import, no Y inversion")
