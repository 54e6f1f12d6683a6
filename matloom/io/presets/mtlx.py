"""MaterialX preset: ``<name>.mtlx``, an ``open_pbr_surface`` reading the maps, a
``normalmap`` node, ``displacement`` from the 16-bit height with its scale in metres, and a
``surfacematerial``; written with the standard library (``xml.etree``).

Colour spaces: the document is ``lin_rec709``; base colour and emissive images are
``srgb_texture``; every other map is read as ``float`` or ``vector3`` (never colour-managed).
The ORM file is read once as a ``vector3`` and split with ``extract`` (0 AO, 1 roughness,
2 metallic); AO has no OpenPBR input and is recorded, not connected. Constant maps are input
values. The physical size and the displacement scale in metres are in the material's ``doc``
string; the displacement node's ``scale`` is in metres when ``unit_m`` is known.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any
from xml.etree import ElementTree as ET

import numpy as np

from matloom.io.presets.common import (
    IOR_SPAN,
    LINEAR,
    PresetFiles,
    PresetInput,
    float32_input,
    write_basecolor,
    write_emissive,
    write_height,
    write_ior,
    write_normal,
    write_orm,
)
from matloom.vocab.channels import ANISOTROPY_STRETCH_OFFSET_DEG

MTLX_VERSION = "1.39"
#: What a clamped displacement scale is called in the preset's notes.
_SCALE = "the displacement scale (height range x unit_m)"


def _fmt(value: float) -> str:
    return f"{float(value):.9g}"


class _Doc:
    def __init__(self, name: str) -> None:
        self.root = ET.Element("materialx", version=MTLX_VERSION, colorspace="lin_rec709")
        self.name = name
        self.shader = ET.Element("open_pbr_surface", name=f"{name}_surface", type="surfaceshader")
        self.inputs: dict[str, Any] = {}

    def node(self, kind: str, name: str, type_: str, **inputs: tuple[str, str, dict]) -> str:
        element = ET.SubElement(self.root, kind, name=name, type=type_)
        for key, (itype, value, attrs) in inputs.items():
            ET.SubElement(element, "input", name=key, type=itype, **attrs, **value_attr(value))
        return name

    def image(self, name: str, type_: str, file: str, colorspace: str | None = None) -> str:
        attrs = {"colorspace": colorspace} if colorspace else {}
        return self.node("image", name, type_, file=("filename", file, attrs))

    def extract(self, name: str, source: str, index: int) -> str:
        return self.node(
            "extract", name, "float", **{"in": ("vector3", "@" + source, {})},
            index=("integer", str(index), {}),
        )  # fmt: skip

    def connect(self, input_name: str, itype: str, node: str) -> None:
        self.inputs[input_name] = (itype, "@" + node)

    def set(self, input_name: str, itype: str, value: str) -> None:
        self.inputs[input_name] = (itype, value)


def value_attr(value: str) -> dict[str, str]:
    return {"nodename": value[1:]} if value.startswith("@") else {"value": value}


def _scalar(doc: _Doc, src: PresetInput, out: PresetFiles, channel: str, target: str) -> None:
    value = src.constant(channel)
    if value is not None:
        doc.set(target, "float", _fmt(value))  # type: ignore[arg-type]
        out.values[channel] = value
        return
    file = out.png(channel, f"{src.name}_{channel}.png", getattr(src.maps, channel), src.bits)
    out.files[channel]["colour_space"] = LINEAR
    doc.connect(target, "float", doc.image(f"{channel}_image", "float", file))


def _stretch_tangent(doc: _Doc, src: PresetInput, out: PresetFiles) -> None:
    """``geometry_tangent`` turned to the highlight's stretch: open_pbr_surface stretches the
    anisotropic highlight along its tangent, ``anisotropy_angle`` is the brushing direction, so
    the tangent is T cos(a + 90) + B sin(a + 90) (T, B: the UV tangent and bitangent)."""
    world = {"space": ("string", "world", {})}
    tangent = doc.node("tangent", "uv_tangent", "vector3", **world)
    bitangent = doc.node("bitangent", "uv_bitangent", "vector3", **world)
    offset = math.radians(ANISOTROPY_STRETCH_OFFSET_DEG)
    brushing = src.constant("anisotropy_angle")
    if isinstance(brushing, float):
        stretch = math.radians(brushing) + offset if math.isfinite(brushing) else offset
        cos_in = ("float", _fmt(math.cos(stretch)), {})
        sin_in = ("float", _fmt(math.sin(stretch)), {})
    else:
        degrees = np.asarray(src.maps.anisotropy_angle, dtype=np.float64)
        unit = np.where(np.isfinite(degrees), np.mod(degrees, 180.0) / 180.0, 0.0)
        file = out.png("anisotropy_angle", f"{src.name}_anisotropy_angle.png", unit, 16)
        out.files["anisotropy_angle"].update(
            colour_space=LINEAR, decode="brushing angle_degrees = value / 65535 * 180 (axial)"
        )
        image = doc.image("anisotropy_angle_image", "float", file)
        radians = doc.node(
            "multiply", "brushing_radians", "float", in1=("float", "@" + image, {}),
            in2=("float", _fmt(math.pi), {}),
        )  # fmt: skip
        turned = doc.node(
            "add", "stretch_radians", "float", in1=("float", "@" + radians, {}),
            in2=("float", _fmt(offset), {}),
        )  # fmt: skip
        cos_in = (
            "float",
            "@" + doc.node("cos", "stretch_cos", "float", **{"in": ("float", "@" + turned, {})}),
            {},
        )
        sin_in = (
            "float",
            "@" + doc.node("sin", "stretch_sin", "float", **{"in": ("float", "@" + turned, {})}),
            {},
        )
    along = doc.node(
        "multiply", "stretch_along_t", "vector3", in1=("vector3", "@" + tangent, {}), in2=cos_in
    )
    across = doc.node(
        "multiply", "stretch_along_b", "vector3", in1=("vector3", "@" + bitangent, {}), in2=sin_in
    )
    total = doc.node(
        "add", "stretch_sum", "vector3", in1=("vector3", "@" + along, {}),
        in2=("vector3", "@" + across, {}),
    )  # fmt: skip
    direction = doc.node(
        "normalize", "stretch_tangent", "vector3", **{"in": ("vector3", "@" + total, {})}
    )
    doc.connect("geometry_tangent", "vector3", direction)


def write(src: PresetInput, folder: Path) -> dict[str, Any]:
    """Write the MaterialX preset into ``folder``; returns its manifest entry."""
    out = PresetFiles(folder)
    name = src.name  # file names keep the name; elements take it as an identifier
    doc = _Doc(src.identifier)
    doc.set("base_weight", "float", "1")
    base = write_basecolor(src, out, f"{name}_basecolor.png", src.bits)
    if base is None:
        doc.set("base_color", "color3", ", ".join(_fmt(v) for v in out.values["basecolor_linear"]))
    else:
        doc.connect(
            "base_color", "color3", doc.image("basecolor_image", "color3", base, "srgb_texture")
        )
        if not src.opaque:
            rgba = doc.image("basecolor_alpha_image", "vector4", base)
            doc.connect(
                "geometry_opacity",
                "float",
                doc.node("extract", "opacity", "float", **{"in": ("vector4", "@" + rgba, {})},
                         index=("integer", "3", {})),
            )  # fmt: skip
    orm = write_orm(src, out, f"{name}_orm.png", src.bits)
    if orm is None:
        doc.set("base_metalness", "float", _fmt(out.values["metallic"]))
        doc.set("specular_roughness", "float", _fmt(out.values["roughness"]))
    else:
        image = doc.image("orm_image", "vector3", orm)
        doc.extract("occlusion", image, 0)
        doc.connect("specular_roughness", "float", doc.extract("roughness", image, 1))
        doc.connect("base_metalness", "float", doc.extract("metallic", image, 2))
        out.notes.append(
            "AO (ORM red) has no open_pbr_surface input: the node 'occlusion' reads it"
        )
    normal = write_normal(src, out, f"{name}_normal_gl.png", "gl", src.bits)
    if normal is not None:
        image = doc.image("normal_image", "vector3", normal)
        doc.connect(
            "geometry_normal",
            "vector3",
            doc.node("normalmap", "normalmap", "vector3", **{"in": ("vector3", "@" + image, {})}),
        )
    for channel, target in (
        ("coat", "coat_weight"),
        ("sheen", "fuzz_weight"),
        ("transmission", "transmission_weight"),
        ("subsurface", "subsurface_weight"),
        ("anisotropy", "specular_roughness_anisotropy"),
    ):
        if src.used(channel):
            _scalar(doc, src, out, channel, target)
    if src.used("anisotropy"):
        _stretch_tangent(doc, src, out)
    if src.used("ior"):
        ior = src.constant("ior")
        if ior is not None:
            doc.set("specular_ior", "float", _fmt(ior))  # type: ignore[arg-type]
        else:
            image = doc.image("ior_image", "float", write_ior(src, out, f"{name}_ior.png"))
            remap = doc.node(
                "remap", "ior", "float", **{"in": ("float", "@" + image, {})},
                outlow=("float", "1", {}), outhigh=("float", _fmt(1 + IOR_SPAN), {}),
            )  # fmt: skip
            doc.connect("specular_ior", "float", remap)
    emissive = write_emissive(src, out, f"{name}_emissive.png", src.bits)
    if src.emissive is not None:
        scale = src.emissive[1]
        colour = src.constant("emissive_linear")
        if emissive is not None:
            image = doc.image("emissive_image", "color3", emissive, "srgb_texture")
            doc.connect("emission_color", "color3", image)
        else:
            doc.set("emission_color", "color3", ", ".join(_fmt(c / scale) for c in colour[:3]))
        doc.set("emission_luminance", "float", _fmt(scale))
    shader = doc.shader
    for key, (itype, value) in doc.inputs.items():
        ET.SubElement(shader, "input", name=key, type=itype, **value_attr(value))
    doc.root.append(shader)
    material = ET.SubElement(doc.root, "surfacematerial", name=doc.name, type="material")
    ET.SubElement(
        material, "input", name="surfaceshader", type="surfaceshader", nodename=shader.get("name")
    )
    height = write_height(src, out, f"{name}_height.png")
    physical = src.physical()
    if height is not None:
        low, high = src.height_range
        unit = src.unit_m if src.unit_m is not None else 1.0
        image = doc.image("height_image", "float", height)
        disp = doc.node(
            "displacement",
            f"{doc.name}_displacement",
            "displacementshader",
            displacement=("float", "@" + image, {}),
            scale=("float", _fmt(float32_input((high - low) * unit, _SCALE, out.notes)), {}),
        )
        ET.SubElement(
            material, "input", name="displacementshader", type="displacementshader", nodename=disp
        )
        doc.root.remove(material)
        doc.root.append(material)
    units = "metres" if src.unit_m is not None else "coordinate units (physical size unknown)"
    material.set("doc", _describe(physical, units))
    ET.indent(doc.root, space="  ")
    text = '<?xml version="1.0"?>\n' + ET.tostring(doc.root, encoding="unicode") + "\n"
    out.write_text("mtlx", f"{name}.mtlx", text, meaning=f"MaterialX {MTLX_VERSION}")
    return out.entry(src, displacement_units=units)


def _describe(physical: dict[str, Any], units: str) -> str:
    if physical.get("unit_m") is None:
        return f"MatLoom material; displacement scale in {units}"
    return (
        f"MatLoom material; physical size {physical['width_m']:.6g} m x "
        f"{physical['height_m']:.6g} m; displacement scale "
        f"{physical['displacement_scale_m']:.6g} m"
    )
