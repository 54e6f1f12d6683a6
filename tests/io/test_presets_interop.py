"""MaterialX and USD presets read by the real consumers (the ``interop`` extra: MaterialX and
usd-core, in their own venv: ``make test-interop``). Skipped with a message when missing."""

from __future__ import annotations

import pytest

from matloom.runtime.export import export_maps

try:
    import MaterialX as mx
except ImportError:  # pragma: no cover - depends on the extra
    mx = None
try:
    from pxr import Usd, UsdShade
except ImportError:  # pragma: no cover - depends on the extra
    Usd = UsdShade = None

pytestmark = pytest.mark.interop
NEEDS_MTLX = pytest.mark.skipif(mx is None, reason="needs the interop extra (MaterialX)")
NEEDS_USD = pytest.mark.skipif(Usd is None, reason="needs the interop extra (usd-core)")


def _load_mtlx(path):  # noqa: ANN001, ANN202
    doc = mx.createDocument()
    mx.readFromXmlFile(doc, str(path))
    lib = mx.createDocument()
    mx.loadLibraries(mx.getDefaultDataLibraryFolders(), mx.getDefaultDataSearchPath(), lib)
    doc.importLibrary(lib)
    return doc


def _source(doc, shader, name: str) -> tuple[str, int | None]:  # noqa: ANN001
    """(file, channel) feeding a surface input (channel None: the whole image)."""
    node = doc.getNode(shader.getInput(name).getNodeName())
    channel = None
    if node.getCategory() in ("extract", "normalmap", "remap"):
        if node.getCategory() == "extract":
            channel = int(node.getInput("index").getValueString())
        node = doc.getNode(node.getInput("in").getNodeName())
    assert node.getCategory() == "image", name
    return node.getInput("file").getValueString(), channel


@NEEDS_MTLX
@pytest.mark.parametrize("program", ["full", "plain", "flat"])
def test_materialx_validates_and_inputs_read_the_right_files(render_presets, program) -> None:
    _, result = render_presets(program, presets=["mtlx"], unit_m=0.25)
    doc = _load_mtlx(result.out_dir / "mtlx" / f"{program}.mtlx")
    valid, message = doc.validate()
    assert valid, message
    (material,) = doc.getMaterialNodes()
    shader = doc.getNode(material.getInput("surfaceshader").getNodeName())
    assert shader.getCategory() == "open_pbr_surface"
    if program == "flat":
        assert shader.getInputValue("specular_roughness") == pytest.approx(0.25)
        return
    base = doc.getNode(shader.getInput("base_color").getNodeName()).getInput("file")
    assert base.getValueString() == f"{program}_basecolor.png"
    assert base.getColorSpace() == "srgb_texture"
    assert _source(doc, shader, "specular_roughness") == (f"{program}_orm.png", 1)
    assert _source(doc, shader, "base_metalness") == (f"{program}_orm.png", 2)
    assert _source(doc, shader, "geometry_normal") == (f"{program}_normal_gl.png", None)
    disp = doc.getNode(material.getInput("displacementshader").getNodeName())
    entry = result.manifest["presets"]["mtlx"]["files"]["height"]
    assert float(disp.getInputValue("scale")) == pytest.approx(entry["displacement_scale_m"])
    if program == "full":
        for name, channel in (("coat_weight", "coat"), ("fuzz_weight", "sheen"),
                              ("transmission_weight", "transmission")):  # fmt: skip
            assert _source(doc, shader, name) == (f"full_{channel}.png", None)
        assert _source(doc, shader, "emission_color") == ("full_emissive.png", None)


@NEEDS_USD
@pytest.mark.parametrize("program", ["full", "plain"])
def test_usd_stage_has_a_preview_surface(render_presets, program) -> None:
    _, result = render_presets(program, presets=["usd"], unit_m=0.25)
    stage = Usd.Stage.Open(str(result.out_dir / "usd" / f"{program}.usda"))
    shaders = [UsdShade.Shader(p) for p in stage.Traverse() if p.IsA(UsdShade.Shader)]
    ids = {s.GetIdAttr().Get() for s in shaders}
    assert {"UsdPreviewSurface", "UsdUVTexture", "UsdPrimvarReader_float2"} <= ids
    material = UsdShade.Material(stage.GetPrimAtPath(f"/{program}/Looks/{program}_material"))
    surface = material.ComputeSurfaceSource()[0]
    assert surface.GetIdAttr().Get() == "UsdPreviewSurface"
    sources = {}
    for shader_input in surface.GetInputs():
        connected = shader_input.GetConnectedSources()[0]
        if connected:
            reader = UsdShade.Shader(connected[0].source.GetPrim())
            file = reader.GetInput("file").Get().path
            sources[shader_input.GetBaseName()] = (file, connected[0].sourceName)
    assert sources["roughness"] == (f"./{program}_orm.png", "g")
    assert sources["metallic"] == (f"./{program}_orm.png", "b")
    assert sources["occlusion"] == (f"./{program}_orm.png", "r")
    assert sources["normal"] == (f"./{program}_normal_gl.png", "rgb")
    assert sources["diffuseColor"][0] == f"./{program}_basecolor.png"
    custom = material.GetPrim().GetCustomDataByKey("matloom_physical_size")
    assert custom["unit_m"] == pytest.approx(0.25)


#: Ordinary names that are not identifiers: a file's stem starting with a digit, a leading '-'.
ODD_NAMES = ["01_bricks", "-lead"]


@NEEDS_USD
@pytest.mark.parametrize("name", ODD_NAMES)
def test_usd_opens_a_layer_named_like_a_file(preset_maps, tmp_path, name: str) -> None:
    result = export_maps(preset_maps("full"), tmp_path, presets=["usd"], unit_m=0.25, name=name)
    stage = Usd.Stage.Open(str(result.out_dir / "usd" / f"{name}.usda"))
    assert stage is not None and stage.GetDefaultPrim().IsValid()
    (material,) = [p for p in stage.Traverse() if p.IsA(UsdShade.Material)]
    surface = UsdShade.Material(material).ComputeSurfaceSource()[0]
    assert surface.GetIdAttr().Get() == "UsdPreviewSurface"
    reader = UsdShade.Shader(surface.GetInput("diffuseColor").GetConnectedSources()[0][0].source)
    assert reader.GetInput("file").Get().path == f"./{name}_basecolor.png"


@NEEDS_MTLX
@pytest.mark.parametrize("name", ODD_NAMES)
def test_materialx_validates_a_document_named_like_a_file(preset_maps, tmp_path, name) -> None:
    result = export_maps(preset_maps("full"), tmp_path, presets=["mtlx"], unit_m=0.25, name=name)
    doc = _load_mtlx(result.out_dir / "mtlx" / f"{name}.mtlx")
    valid, message = doc.validate()
    assert valid, message
    (material,) = doc.getMaterialNodes()
    shader = doc.getNode(material.getInput("surfaceshader").getNodeName())
    base = doc.getNode(shader.getInput("base_color").getNodeName()).getInput("file")
    assert base.getValueString() == f"{name}_basecolor.png"
