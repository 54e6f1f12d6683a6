"""USD preset: ``<name>.usda``, a text layer with a quad ``Mesh`` (sized in metres,
``metersPerUnit = 1``) bound to a ``Material`` whose ``UsdPreviewSurface`` reads the maps
through ``UsdUVTexture`` nodes: base colour (sRGB), ORM (raw: r occlusion, g roughness,
b metallic), the OpenGL normal (raw, scale 2 bias -1), emissive (sRGB), opacity (the base
colour's alpha) and displacement from the 16-bit height, scaled to metres. Constant maps are
input values; the physical size is in the material's ``customData``. Written as plain text:
usd-core is only needed to read it (the tests do).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from matloom.io.presets.common import (
    IOR_SPAN,
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


def _f(value: float) -> str:
    return f"{float(value):.9g}"


def _tuple(values: Any) -> str:
    return "(" + ", ".join(_f(v) for v in values) + ")"


class _Material:
    def __init__(self, name: str) -> None:
        self.path = f"/{name}/Looks/{name}_material"
        self.readers: list[str] = []
        self.inputs: list[str] = []

    def texture(
        self,
        node: str,
        file: str,
        colour_space: str,
        output: str,
        scale: tuple[float, ...] | None = None,
        bias: tuple[float, ...] | None = None,
    ) -> str:
        lines = [
            f'        def Shader "{node}"',
            "        {",
            '            uniform token info:id = "UsdUVTexture"',
            f"            asset inputs:file = @./{file}@",
            f'            token inputs:sourceColorSpace = "{colour_space}"',
            f"            float2 inputs:st.connect = <{self.path}/st_reader.outputs:result>",
            '            token inputs:wrapS = "repeat"',
            '            token inputs:wrapT = "repeat"',
        ]
        if scale is not None:
            lines.append(f"            float4 inputs:scale = {_tuple(scale)}")
        if bias is not None:
            lines.append(f"            float4 inputs:bias = {_tuple(bias)}")
        for out_name, out_type in (("rgb", "float3"), ("r", "float"), ("g", "float"),
                                   ("b", "float"), ("a", "float")):  # fmt: skip
            lines.append(f"            {out_type} outputs:{out_name}")
        lines.append("        }")
        self.readers.append("\n".join(lines))
        kind = "float3" if output == "rgb" else "float"
        return f"{kind}|{self.path}/{node}.outputs:{output}"

    def connect(self, name: str, type_: str, source: str) -> None:
        self.inputs.append(f"            {type_} inputs:{name}.connect = <{source.split('|')[1]}>")

    def set(self, name: str, type_: str, value: str) -> None:
        self.inputs.append(f"            {type_} inputs:{name} = {value}")


def write(src: PresetInput, folder: Path) -> dict[str, Any]:
    """Write the USD preset into ``folder``; returns its manifest entry."""
    out = PresetFiles(folder)
    name = src.name  # file names keep the name; prims take it as a USD identifier
    mat = _Material(src.identifier)
    base = write_basecolor(src, out, f"{name}_basecolor.png", src.bits)
    if base is None:
        mat.set("diffuseColor", "color3f", _tuple(out.values["basecolor_linear"]))
    else:
        mat.connect("diffuseColor", "color3f", mat.texture("basecolor", base, "sRGB", "rgb"))
        if not src.opaque:
            mat.connect("opacity", "float", f"float|{mat.path}/basecolor.outputs:a")
    orm = write_orm(src, out, f"{name}_orm.png", src.bits)
    if orm is None:
        mat.set("occlusion", "float", _f(out.values["ao"]))
        mat.set("roughness", "float", _f(out.values["roughness"]))
        mat.set("metallic", "float", _f(out.values["metallic"]))
    else:
        mat.connect("occlusion", "float", mat.texture("orm", orm, "raw", "r"))
        mat.connect("roughness", "float", f"float|{mat.path}/orm.outputs:g")
        mat.connect("metallic", "float", f"float|{mat.path}/orm.outputs:b")
    normal = write_normal(src, out, f"{name}_normal_gl.png", "gl", src.bits)
    if normal is not None:
        reader = mat.texture("normal", normal, "raw", "rgb", (2, 2, 2, 1), (-1, -1, -1, 0))
        mat.connect("normal", "normal3f", reader)
    if src.used("coat"):
        coat = src.constant("coat")
        if coat is None:
            reader = mat.texture("coat", _grey(src, out, "coat"), "raw", "r")
            mat.connect("clearcoat", "float", reader)
        else:
            mat.set("clearcoat", "float", _f(coat))  # type: ignore[arg-type]
    if src.used("ior"):
        ior = src.constant("ior")
        if ior is None:
            file = write_ior(src, out, f"{name}_ior.png")
            reader = mat.texture("ior", file, "raw", "r", (IOR_SPAN,) * 4, (1.0,) * 4)
            mat.connect("ior", "float", reader)
        else:
            mat.set("ior", "float", _f(ior))  # type: ignore[arg-type]
    emissive = write_emissive(src, out, f"{name}_emissive.png", src.bits)
    if src.emissive is not None:
        scale = src.emissive[1]
        colour = src.constant("emissive_linear")
        if emissive is not None:
            reader = mat.texture("emissive", emissive, "sRGB", "rgb", (scale, scale, scale, 1))
            mat.connect("emissiveColor", "color3f", reader)
        else:
            mat.set("emissiveColor", "color3f", _tuple(colour[:3]))
    height = write_height(src, out, f"{name}_height.png")
    if height is not None:
        low, high = src.height_range
        unit = src.unit_m if src.unit_m is not None else 1.0
        span = float32_input((high - low) * unit, "the displacement scale", out.notes)
        bias = float32_input(low * unit, "the displacement bias", out.notes)
        reader = mat.texture("height", height, "raw", "r", (span,) * 4, (bias,) * 4)
        mat.connect("displacement", "float", reader)
    for channel in ("sheen", "transmission", "subsurface", "anisotropy"):
        if src.used(channel):
            out.notes.append(f"{channel} has no UsdPreviewSurface input and is left out")
    out.write_text("usda", f"{name}.usda", _layer(src, mat), meaning="USD ASCII layer")
    return out.entry(src)


def _grey(src: PresetInput, out: PresetFiles, channel: str) -> str:
    return out.png(channel, f"{src.name}_{channel}.png", getattr(src.maps, channel), src.bits)


def _layer(src: PresetInput, mat: _Material) -> str:
    name = src.identifier  # prim names must be identifiers ("01_bricks" is not)
    width, height = src.quad_size
    w, h = width / 2, height / 2
    physical = src.physical()
    custom = "\n".join(
        f"                double {k} = {_f(v)}"
        for k, v in physical.items()
        if isinstance(v, (int, float)) and not isinstance(v, bool)
    )
    inputs = "\n".join(mat.inputs)
    readers = "\n\n".join(mat.readers)
    return f'''#usda 1.0
(
    defaultPrim = "{name}"
    doc = "MatLoom material {name}"
    metersPerUnit = 1
    upAxis = "Y"
)

def Xform "{name}" (
    kind = "component"
)
{{
    def Mesh "quad" (
        prepend apiSchemas = ["MaterialBindingAPI"]
    )
    {{
        float3[] extent = [({_f(-w)}, {_f(-h)}, 0), ({_f(w)}, {_f(h)}, 0)]
        int[] faceVertexCounts = [4]
        int[] faceVertexIndices = [0, 1, 2, 3]
        point3f[] points = [({_f(-w)}, {_f(-h)}, 0), ({_f(w)}, {_f(-h)}, 0), ({_f(w)}, {_f(h)}, 0), ({_f(-w)}, {_f(h)}, 0)]
        normal3f[] normals = [(0, 0, 1), (0, 0, 1), (0, 0, 1), (0, 0, 1)] (
            interpolation = "vertex"
        )
        texCoord2f[] primvars:st = [(0, 0), (1, 0), (1, 1), (0, 1)] (
            interpolation = "vertex"
        )
        uniform token subdivisionScheme = "none"
        rel material:binding = <{mat.path}>
    }}

    def Scope "Looks"
    {{
        def Material "{name}_material" (
            customData = {{
                dictionary matloom_physical_size = {{
{custom}
                }}
            }}
        )
        {{
            token outputs:surface.connect = <{mat.path}/preview_surface.outputs:surface>
            token outputs:displacement.connect = <{mat.path}/preview_surface.outputs:displacement>

            def Shader "preview_surface"
            {{
                uniform token info:id = "UsdPreviewSurface"
{inputs}
                token outputs:surface
                token outputs:displacement
            }}

            def Shader "st_reader"
            {{
                uniform token info:id = "UsdPrimvarReader_float2"
                string inputs:varname = "st"
                float2 outputs:result
            }}

{readers}
        }}
    }}
}}
'''
