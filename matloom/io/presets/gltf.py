"""glTF 2.0 preset: ``<name>.gltf`` (+ ``<name>.bin`` and PNG textures) and ``<name>.glb``
(the same quad and material with the textures embedded), written with the standard library
and numpy.

Mapping: ``baseColorTexture`` (sRGB, alpha = coverage when not opaque) ; ``metallicRoughness``
and ``occlusion`` read one ORM texture (R AO, G roughness, B metallic, linear); ``normalTexture``
(+Y, OpenGL); emissive as an sRGB texture times ``emissiveFactor`` with
``KHR_materials_emissive_strength`` above 1; ``KHR_materials_clearcoat``, ``_sheen``,
``_transmission``, ``_ior`` and ``_anisotropy`` only where the program uses the channel (its
direction is the highlight's stretch: ``anisotropy_angle``, the brushing, + 90 degrees). Constant
maps become factors. The physical size is in the material's and the asset's ``extras``. The
quad lies in the XY plane facing +Z, sized in metres (1 m wide when the size is unknown).
"""

from __future__ import annotations

import json
import math
import struct
from pathlib import Path
from typing import Any

import numpy as np

from matloom.io.presets.common import (
    LINEAR,
    PresetFiles,
    PresetInput,
    write_basecolor,
    write_emissive,
    write_normal,
    write_orm,
)
from matloom.vocab.channels import ANISOTROPY_STRETCH_OFFSET_DEG

_ARRAY_BUFFER, _ELEMENT_ARRAY_BUFFER = 34962, 34963
_FLOAT, _UNSIGNED_SHORT = 5126, 5123
_REPEAT, _LINEAR, _LINEAR_MIPMAP_LINEAR = 10497, 9729, 9987


def _quad(width: float, height: float) -> list[tuple[np.ndarray, str, int, int]]:
    """(data, accessor type, component type, target) for POSITION, NORMAL, TANGENT,
    TEXCOORD_0 and the indices of a quad centred on the origin."""
    w, h = width / 2, height / 2
    position = np.array([[-w, h, 0], [w, h, 0], [w, -h, 0], [-w, -h, 0]], np.float32)
    normal = np.tile(np.array([0, 0, 1], np.float32), (4, 1))
    tangent = np.tile(np.array([1, 0, 0, 1], np.float32), (4, 1))
    uv = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], np.float32)  # glTF: (0, 0) = top left
    indices = np.array([0, 3, 2, 0, 2, 1], np.uint16)
    return [
        (position, "VEC3", _FLOAT, _ARRAY_BUFFER),
        (normal, "VEC3", _FLOAT, _ARRAY_BUFFER),
        (tangent, "VEC4", _FLOAT, _ARRAY_BUFFER),
        (uv, "VEC2", _FLOAT, _ARRAY_BUFFER),
        (indices, "SCALAR", _UNSIGNED_SHORT, _ELEMENT_ARRAY_BUFFER),
    ]


def _material(src: PresetInput, out: PresetFiles, textures: list[str]) -> dict[str, Any]:
    """The glTF material; ``textures`` collects the PNG file of each texture index."""

    def texture(file: str | None) -> dict[str, int] | None:
        if file is None:
            return None
        if file not in textures:
            textures.append(file)
        return {"index": textures.index(file)}

    name = src.name
    pbr: dict[str, Any] = {}
    material: dict[str, Any] = {"name": name, "pbrMetallicRoughness": pbr}
    extensions: dict[str, Any] = {}
    base = texture(write_basecolor(src, out, f"{name}_basecolor.png"))
    if base is not None:
        pbr["baseColorTexture"] = base
    else:
        pbr["baseColorFactor"] = [*out.values["basecolor_linear"], 1.0]
    if not src.opaque:
        material["alphaMode"] = "BLEND"
    orm = texture(write_orm(src, out, f"{name}_orm.png"))
    if orm is not None:
        pbr["metallicRoughnessTexture"] = orm
        if src.constant("ao") != 1.0:
            material["occlusionTexture"] = dict(orm)
    else:
        pbr["metallicFactor"] = out.values["metallic"]
        pbr["roughnessFactor"] = out.values["roughness"]
    normal = texture(write_normal(src, out, f"{name}_normal_gl.png", "gl"))
    if normal is not None:
        material["normalTexture"] = normal
    emissive = texture(write_emissive(src, out, f"{name}_emissive.png"))
    if src.emissive is not None:
        scale = src.emissive[1]
        colour = src.constant("emissive_linear")
        rgb = [1.0, 1.0, 1.0] if colour is None else [c / scale for c in colour[:3]]
        material["emissiveFactor"] = [c * min(scale, 1.0) for c in rgb]
        if emissive is not None:
            material["emissiveTexture"] = emissive
        if scale > 1.0:
            extensions["KHR_materials_emissive_strength"] = {"emissiveStrength": scale}
    _extensions(src, out, extensions, texture)
    if extensions:
        material["extensions"] = extensions
    material["extras"] = {"matloom": {"physical_size": src.physical()}}
    return material


def _scalar_texture(
    src: PresetInput, out: PresetFiles, channel: str, texture: Any
) -> tuple[float, dict[str, int] | None]:
    """(factor, texture info) of a [0, 1] channel: its constant, or 1 and a grey texture."""
    value = src.constant(channel)
    if value is not None:
        out.values[channel] = value
        return float(value), None  # type: ignore[arg-type]
    file = out.png(channel, f"{src.name}_{channel}.png", getattr(src.maps, channel), 8)
    out.files[channel]["colour_space"] = LINEAR
    return 1.0, texture(file)


def _extensions(src: PresetInput, out: PresetFiles, ext: dict[str, Any], texture: Any) -> None:
    if src.used("coat"):
        factor, tex = _scalar_texture(src, out, "coat", texture)
        ext["KHR_materials_clearcoat"] = {
            "clearcoatFactor": factor,
            "clearcoatRoughnessFactor": 0.0,
        }
        if tex:
            ext["KHR_materials_clearcoat"]["clearcoatTexture"] = tex
    if src.used("sheen"):
        value = src.constant("sheen")
        sheen: dict[str, Any] = {"sheenRoughnessFactor": 0.5}
        if value is not None:
            out.values["sheen"] = value
            sheen["sheenColorFactor"] = [float(value)] * 3  # type: ignore[arg-type]
        else:
            grey = np.repeat(np.asarray(src.maps.sheen)[..., None], 3, axis=2)
            from matloom.engine.colour import linear_to_srgb

            file = out.png("sheen", f"{src.name}_sheen.png", linear_to_srgb(grey), 8)
            out.files["sheen"]["colour_space"] = "sRGB"
            sheen["sheenColorFactor"] = [1.0, 1.0, 1.0]
            sheen["sheenColorTexture"] = texture(file)
        ext["KHR_materials_sheen"] = sheen
    if src.used("transmission"):
        factor, tex = _scalar_texture(src, out, "transmission", texture)
        ext["KHR_materials_transmission"] = {"transmissionFactor": factor}
        if tex:
            ext["KHR_materials_transmission"]["transmissionTexture"] = tex
    if src.used("ior"):
        ior = np.asarray(src.maps.ior, dtype=np.float64)
        finite = ior[np.isfinite(ior)]
        mean = float(finite.mean()) if finite.size else 1.5
        ext["KHR_materials_ior"] = {"ior": mean}
        if src.constant("ior") is None:
            out.notes.append(f"KHR_materials_ior has no texture: the mean ior {mean:.4g} is used")
    if src.used("anisotropy"):
        strength = src.constant("anisotropy")
        angle = src.constant("anisotropy_angle")
        aniso: dict[str, Any] = {}
        if strength is not None and angle is not None:
            aniso["anisotropyStrength"] = float(strength)  # type: ignore[arg-type]
            # glTF's anisotropy direction is the stretch; ours is the brushing, 90 degrees off
            stretch = float(angle) + ANISOTROPY_STRETCH_OFFSET_DEG  # type: ignore[arg-type]
            stretch = stretch % 180.0 if math.isfinite(stretch) else 90.0  # as the previews
            aniso["anisotropyRotation"] = math.radians(stretch)
        else:
            brushing = np.asarray(src.maps.anisotropy_angle, dtype=np.float64)
            theta = np.radians(brushing + ANISOTROPY_STRETCH_OFFSET_DEG)
            rgb = np.stack(
                [np.cos(theta) * 0.5 + 0.5, np.sin(theta) * 0.5 + 0.5, src.maps.anisotropy],
                axis=2,
            )
            file = out.png("anisotropy", f"{src.name}_anisotropy.png", rgb, 8)
            out.files["anisotropy"].update(
                colour_space=LINEAR,
                channels="RG stretch direction (tangent space: the brushing + 90 degrees), "
                "B strength",
            )
            aniso["anisotropyStrength"] = 1.0
            aniso["anisotropyTexture"] = texture(file)
        ext["KHR_materials_anisotropy"] = aniso
    if src.used("subsurface"):
        out.notes.append("subsurface has no glTF equivalent and is left out")


def _document(
    src: PresetInput, material: dict[str, Any], textures: list[str], embed: dict[str, bytes] | None
) -> tuple[dict[str, Any], bytes]:
    """The glTF JSON and its binary buffer (with the PNGs when ``embed`` holds their bytes)."""
    blob = bytearray()
    views: list[dict[str, Any]] = []
    accessors: list[dict[str, Any]] = []

    def add_view(data: bytes, target: int | None) -> int:
        while len(blob) % 4:
            blob.append(0)
        view: dict[str, Any] = {"buffer": 0, "byteOffset": len(blob), "byteLength": len(data)}
        if target is not None:
            view["target"] = target
        blob.extend(data)
        views.append(view)
        return len(views) - 1

    for data, kind, component, target in _quad(*src.quad_size):
        accessor: dict[str, Any] = {
            "bufferView": add_view(data.tobytes(), target),
            "componentType": component,
            "count": int(data.shape[0]),
            "type": kind,
        }
        if kind == "VEC3" and len(accessors) == 0:
            accessor["min"] = [float(v) for v in data.min(axis=0)]
            accessor["max"] = [float(v) for v in data.max(axis=0)]
        accessors.append(accessor)
    images: list[dict[str, Any]] = []
    for file in textures:
        if embed is None:
            images.append({"uri": file, "name": file})
        else:
            images.append(
                {"bufferView": add_view(embed[file], None), "mimeType": "image/png", "name": file}
            )
    while len(blob) % 4:
        blob.append(0)
    used = sorted(material.get("extensions", {}))
    doc: dict[str, Any] = {
        "asset": {
            "version": "2.0",
            "generator": "MatLoom",
            "extras": {"matloom": {"physical_size": src.physical()}},
        },
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0, "name": src.name}],
        "meshes": [
            {
                "name": f"{src.name}_quad",
                "primitives": [
                    {
                        "attributes": {"POSITION": 0, "NORMAL": 1, "TANGENT": 2, "TEXCOORD_0": 3},
                        "indices": 4,
                        "material": 0,
                    }
                ],
            }
        ],
        "materials": [material],
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": len(blob)}],
    }
    if used:
        doc["extensionsUsed"] = used
    if textures:
        doc["samplers"] = [
            {
                "magFilter": _LINEAR,
                "minFilter": _LINEAR_MIPMAP_LINEAR,
                "wrapS": _REPEAT,
                "wrapT": _REPEAT,
            }
        ]
        doc["images"] = images
        doc["textures"] = [{"sampler": 0, "source": i} for i in range(len(textures))]
    return doc, bytes(blob)


def _glb(doc: dict[str, Any], blob: bytes) -> bytes:
    text = json.dumps(doc, separators=(",", ":")).encode("utf-8")
    text += b" " * (-len(text) % 4)
    chunks = struct.pack("<I4s", len(text), b"JSON") + text
    chunks += struct.pack("<I4s", len(blob), b"BIN\x00") + blob
    return struct.pack("<4sII", b"glTF", 2, 12 + len(chunks)) + chunks


def write(src: PresetInput, folder: Path) -> dict[str, Any]:
    """Write the glTF preset into ``folder``; returns its manifest entry."""
    out = PresetFiles(folder)
    textures: list[str] = []
    material = _material(src, out, textures)
    doc, blob = _document(src, material, textures, None)
    doc["buffers"][0]["uri"] = f"{src.name}.bin"
    out.write_bytes("buffer", f"{src.name}.bin", blob)
    text = json.dumps(doc, indent=1, allow_nan=False) + "\n"
    out.write_text("gltf", f"{src.name}.gltf", text, meaning="glTF 2.0, external textures")
    glb_doc, glb_blob = _document(src, material, textures, out.png_bytes)
    out.write_bytes(
        "glb", f"{src.name}.glb", _glb(glb_doc, glb_blob), meaning="binary glTF, embedded"
    )
    return out.entry(src, extensions=doc.get("extensionsUsed", []))
