"""The material node graph of MatLoom's Blender worker; runs INSIDE Blender (``bpy`` passed in).

Principled BSDF wired the way an artist would: one Image Texture per map (colour spaces from
the manifest), a Normal Map node (OpenGL), Bump, a Displacement node at the physical scale,
the coverage alpha, and, when the source was exported with a preset that packs AO, roughness
and metallic into one texture (``job["packed"]``), that texture read once and split with a
Separate Color node. Every node is named and sits in a frame (Maps, ORM split, Surface, Relief).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from worker_common import try_set, try_use_nodes, working

#: anisotropy_angle is the brushing direction; Blender's tangent is the highlight's stretch,
#: across it (matloom.vocab.channels.ANISOTROPY_STRETCH_OFFSET_DEG = 90 degrees, in turns).
_BRUSHING_TO_STRETCH_TURN = 0.25
#: Separate Color outputs by channel letter (A is the image's own Alpha output)
_CHANNELS = {"R": "Red", "G": "Green", "B": "Blue"}


def build_material(bpy: Any, job: dict[str, Any]) -> Any:
    """Principled BSDF wired the way an artist would: named nodes in frames."""
    mat = bpy.data.materials.new(job["name"])
    try_use_nodes(mat)
    tree = mat.node_tree
    nodes, links = tree.nodes, tree.links
    for node in list(nodes):
        nodes.remove(node)
    packed = job.get("packed")
    frames = {}
    for label in ("Maps", "Surface", "Relief") + (("ORM split",) if packed else ()):
        frame = nodes.new("NodeFrame")
        frame.name = frame.label = label
        frames[label] = frame

    def add(kind: str, name: str, frame: str, x: float, y: float) -> Any:
        node = nodes.new(kind)
        node.name = node.label = name
        node.location = (x, y)
        node.parent = frames[frame]
        return node

    out = add("ShaderNodeOutputMaterial", "Material Output", "Surface", 400, 0)
    bsdf = add("ShaderNodeBsdfPrincipled", "Principled BSDF", "Surface", 0, 0)
    links.new(bsdf.outputs["BSDF"], out.inputs["Surface"])
    maps = job["maps"]
    split = set(packed["channels"]) if packed else set()
    sockets: dict[str, Any] = {}  # map name -> the output socket that carries it
    textures: dict[str, Any] = {}
    y = 600.0
    for name, item in maps.items():
        if item.get("file") is None or name in split:
            continue
        tex = add("ShaderNodeTexImage", f"{name} map", "Maps", -900, y)
        y -= 300
        tex.image = load_image(bpy, item["file"], item["colour_space"], bool(item.get("alpha")))
        textures[name] = tex
        sockets[name] = tex.outputs["Color"]
    if packed:
        sockets.update(split_packed(bpy, tree, add, packed, y))

    def constant(name: str) -> Any:
        return maps.get(name, {}).get("constant")

    # base colour (x AO, like the reference) and, fixed, the coverage alpha
    base = textures.get("basecolor")
    if base is not None:
        colour_out = base.outputs["Color"]
        if "ao" in sockets:
            mix = add("ShaderNodeMix", "Base x AO", "Surface", -400, 400)
            mix.data_type = "RGBA"
            mix.blend_type = "MULTIPLY"
            mix.inputs["Factor"].default_value = 1.0
            links.new(colour_out, mix.inputs[6])
            links.new(sockets["ao"], mix.inputs[7])
            colour_out = mix.outputs[2]
        links.new(colour_out, bsdf.inputs["Base Color"])
        if maps["basecolor"].get("alpha"):
            links.new(base.outputs["Alpha"], bsdf.inputs["Alpha"])
    elif isinstance(constant("basecolor"), list):
        bsdf.inputs["Base Color"].default_value = (*working(constant("basecolor")), 1.0)
    bsdf.inputs["IOR"].default_value = float(job["defaults"]["ior"])  # fixed: not 1.0
    for name, socket in job["scalar_inputs"].items():
        if name in sockets:
            links.new(sockets[name], bsdf.inputs[socket])
        elif isinstance(constant(name), (int, float)):
            bsdf.inputs[socket].default_value = float(constant(name))
    wire_anisotropy(tree, add, bsdf, maps, textures)
    # emission
    if "emissive" in textures:
        links.new(textures["emissive"].outputs["Color"], bsdf.inputs["Emission Color"])
        bsdf.inputs["Emission Strength"].default_value = 1.0
    elif isinstance(constant("emissive"), list) and any(constant("emissive")):
        bsdf.inputs["Emission Color"].default_value = (*working(constant("emissive")), 1.0)
        bsdf.inputs["Emission Strength"].default_value = 1.0
    wire_relief(tree, add, bsdf, out, job, textures)
    method = {"true": "BOTH", "bump": "BUMP", "off": "BUMP"}[job["displacement"]]
    if not try_set(mat, "displacement_method", method):
        try_set(mat.cycles, "displacement_method", method)
    return mat


def load_image(bpy: Any, path: str, colour_space: str, alpha: bool) -> Any:
    image = bpy.data.images.load(path, check_existing=True)
    image.colorspace_settings.name = colour_space
    if alpha:
        image.alpha_mode = "CHANNEL_PACKED"  # the alpha is data, not premultiplied coverage
    return image


def split_packed(
    bpy: Any, tree: Any, add: Callable[..., Any], packed: dict[str, Any], y: float
) -> dict[str, Any]:
    """Read the packed AO/roughness/metallic texture once and split it into its channels.

    ``packed["channels"]`` maps a map name to ``{"channel": "R"|"G"|"B"|"A", "invert": bool}``
    (Unity's mask map stores smoothness = 1 - roughness in A). Returns the socket per map.
    """
    mask = packed["role"] == "maskmap"
    tex = add("ShaderNodeTexImage", "Mask map" if mask else "ORM map", "Maps", -900, y)
    uses_alpha = any(c["channel"] == "A" for c in packed["channels"].values())
    tex.image = load_image(bpy, packed["file"], "Non-Color", uses_alpha)
    separate = add(
        "ShaderNodeSeparateColor", "Split mask map" if mask else "Split ORM", "ORM split", -650, y
    )
    separate.mode = "RGB"
    tree.links.new(tex.outputs["Color"], separate.inputs["Color"])
    sockets: dict[str, Any] = {}
    for k, (name, spec) in enumerate(sorted(packed["channels"].items())):
        channel = spec["channel"]
        socket = tex.outputs["Alpha"] if channel == "A" else separate.outputs[_CHANNELS[channel]]
        if spec.get("invert"):
            invert = add("ShaderNodeMath", f"{name} = 1 - {channel}", "ORM split", -450, y - 80 * k)
            invert.operation = "SUBTRACT"
            invert.inputs[0].default_value = 1.0
            tree.links.new(socket, invert.inputs[1])
            socket = invert.outputs["Value"]
        sockets[name] = socket
    return sockets


def wire_anisotropy(
    tree: Any, add: Callable[..., Any], bsdf: Any, maps: dict[str, Any], textures: dict[str, Any]
) -> None:
    """Anisotropy across the brushing: Blender stretches the highlight along its tangent (the
    UV tangent turned by Anisotropic Rotation, 1 = 360 degrees), and anisotropy_angle is the
    direction of the brush lines, so the rotation is the angle plus a quarter turn."""
    links = tree.links
    if "anisotropy" in maps:
        tangent = add("ShaderNodeTangent", "UV Tangent", "Surface", -400, -700)
        tangent.direction_type = "UV_MAP"
        links.new(tangent.outputs["Tangent"], bsdf.inputs["Tangent"])
    angle = maps.get("anisotropy_angle")
    if angle is None:
        return
    if "anisotropy_angle" in textures:
        turn = add("ShaderNodeMath", "Angle to rotation", "Surface", -400, -550)
        turn.operation = "MULTIPLY_ADD"  # value * scale + a quarter turn
        turn.inputs[1].default_value = float(angle.get("scale", 1.0 / 360.0))
        turn.inputs[2].default_value = _BRUSHING_TO_STRETCH_TURN
        links.new(textures["anisotropy_angle"].outputs["Color"], turn.inputs[0])
        links.new(turn.outputs["Value"], bsdf.inputs["Anisotropic Rotation"])
    elif isinstance(angle.get("constant"), (int, float)):
        degrees = float(angle["constant"]) % 180.0
        rotation = degrees / 360.0 + _BRUSHING_TO_STRETCH_TURN
        bsdf.inputs["Anisotropic Rotation"].default_value = rotation


def wire_relief(
    tree: Any,
    add: Callable[..., Any],
    bsdf: Any,
    out: Any,
    job: dict[str, Any],
    textures: dict[str, Any],
) -> None:
    """Normal Map (tangent space, OpenGL) -> Bump -> BSDF Normal; height -> Displacement."""
    links = tree.links
    bump = add("ShaderNodeBump", "Bump", "Relief", -300, -300)
    links.new(bump.outputs["Normal"], bsdf.inputs["Normal"])
    if "normal" in textures:
        normal_map = add("ShaderNodeNormalMap", "Normal Map (OpenGL)", "Relief", -550, -300)
        normal_map.space = "TANGENT"
        normal_map.inputs["Strength"].default_value = 1.0
        colour = textures["normal"].outputs["Color"]
        if job["maps"]["normal"].get("flip_green"):
            colour = flip_green(tree, add, colour)
        links.new(colour, normal_map.inputs["Color"])
        links.new(normal_map.outputs["Normal"], bump.inputs["Normal"])
    geometry = job["surface"]
    if "height" in textures:
        disp = add("ShaderNodeDisplacement", "Displacement", "Relief", 100, -450)
        disp.space = "OBJECT"
        disp.inputs["Midlevel"].default_value = float(geometry["midlevel"])
        disp.inputs["Scale"].default_value = float(geometry["displacement_scale"])
        links.new(textures["height"].outputs["Color"], disp.inputs["Height"])
        if job["displacement"] != "off":
            links.new(disp.outputs["Displacement"], out.inputs["Displacement"])


def flip_green(tree: Any, add: Callable[..., Any], colour: Any) -> Any:
    """DirectX normal map -> OpenGL: green = 1 - green."""
    split = add("ShaderNodeSeparateColor", "Split DX normal", "Relief", -800, -700)
    invert = add("ShaderNodeMath", "1 - green", "Relief", -650, -700)
    invert.operation = "SUBTRACT"
    invert.inputs[0].default_value = 1.0
    join = add("ShaderNodeCombineColor", "OpenGL normal", "Relief", -500, -700)
    tree.links.new(colour, split.inputs["Color"])
    tree.links.new(split.outputs["Red"], join.inputs["Red"])
    tree.links.new(split.outputs["Green"], invert.inputs[1])
    tree.links.new(invert.outputs["Value"], join.inputs["Green"])
    tree.links.new(split.outputs["Blue"], join.inputs["Blue"])
    return join.outputs["Color"]
