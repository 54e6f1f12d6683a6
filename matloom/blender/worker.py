"""MatLoom's Blender worker: runs INSIDE Blender, never imported by ``matloom``.

Run as ``blender -b --factory-startup --python worker.py -- job.json`` or, with the ``bpy``
module importable, as ``python worker.py job.json``. It uses only ``bpy`` (with ``bmesh`` and
``mathutils``, which ship with it) and the standard library. It reads the JSON job written by
``matloom.blender.job``, builds one Blender scene per layout around one material, renders every
requested view with Cycles and optionally saves the scenes (``save_blend``) or the material
alone (``save_material``). Every file is written under a temporary name and renamed at the end,
so a killed render never leaves a half-written file under its final name.

Progress and errors are JSON lines on stdout prefixed with ``MATLOOM-JSON `` (Blender prints its
own lines there too): ``start``, ``device``, ``render_start`` and ``render`` (per view),
``saved``, ``warning``, ``error`` and ``done``. The material's node graph is built by
``worker_material.py`` and the helpers are in ``worker_common.py`` (siblings of this file).
"""

from __future__ import annotations

import json
import math
import os
import sys
import time
import traceback
from typing import Any

# Blender's own Python does not put the script's folder on sys.path; the sibling worker_*
# modules live there (appended, so nothing of Blender's is shadowed)
_HERE = os.path.dirname(os.path.abspath(__file__))
if _HERE not in sys.path:
    sys.path.append(_HERE)

from worker_common import (  # noqa: E402
    emit,
    exit_with_parent,
    srgb8,
    state,
    temp_name,
    try_set,
    try_use_nodes,
)
from worker_material import build_material  # noqa: E402

MIN_VERSION = (4, 2)


def job_path(argv: list[str]) -> str:
    rest = argv[argv.index("--") + 1 :] if "--" in argv else argv[1:]
    if len(rest) != 1:
        raise SystemExit(
            "usage: worker.py job.json  (or: blender -b --python worker.py -- job.json)"
        )
    return rest[0]


# ------------------------------------------------------------------------ settings


def setup_common(bpy: Any, common: dict[str, Any]) -> None:
    """The reference switches the file's working space to Linear Rec.2020 (Blender 5.0+)."""
    space = common.get("working_space")
    colorspace = getattr(bpy.data, "colorspace", None)
    if not space or colorspace is None or not hasattr(bpy.ops.wm, "set_working_color_space"):
        emit("warning", message=f"this Blender has no working colour space setting ({space})")
        return
    try:
        bpy.ops.wm.set_working_color_space(working_space=space, convert_colors=False)
    except (RuntimeError, TypeError) as err:
        emit("warning", message=f"cannot set the working colour space {space}: {err}")
    state["working_space"] = colorspace.working_space


def setup_scene(bpy: Any, scene: Any, common: dict[str, Any], layout: dict[str, Any]) -> None:
    scene.render.engine = "CYCLES"
    cyc = scene.cycles
    cyc.samples = int(layout["samples"])
    try_set(cyc, "use_adaptive_sampling", common["adaptive_sampling"])
    try_set(cyc, "adaptive_threshold", common["adaptive_threshold"])
    try_set(cyc, "adaptive_min_samples", common["adaptive_min_samples"])
    try_set(cyc, "use_denoising", common["denoise"])
    try_set(cyc, "denoising_input_passes", common["denoise_passes"])
    try_set(cyc, "use_light_tree", common["light_tree"])
    try_set(cyc, "pixel_filter_type", common["pixel_filter"])
    try_set(cyc, "filter_width", common["filter_width"])
    try_set(cyc, "film_exposure", common["film_exposure"])
    try_set(cyc, "debug_use_spatial_splits", common["spatial_splits"])
    scene.render.film_transparent = bool(layout["film_transparent"])
    try_set(scene.view_settings, "view_transform", common["view_transform"])
    img = scene.render.image_settings
    img.file_format = common["file_format"]
    img.color_mode = common["color_mode"]
    img.color_depth = common["color_depth"]
    img.compression = int(common["compression"])
    scene.render.resolution_x = scene.render.resolution_y = int(layout["resolution"])
    scene.render.resolution_percentage = int(common["resolution_percentage"])
    scene.render.use_file_extension = False


def choose_device(bpy: Any, scenes: list[Any], order: list[str], wanted: str) -> str:
    """The reference's order (OPTIX, CUDA, HIP, METAL), all GPUs on and the CPU off; the CPU
    when no GPU is found or ``wanted`` is "cpu"."""
    chosen = "CPU"
    if wanted != "cpu":
        try:
            prefs = bpy.context.preferences.addons["cycles"].preferences
        except (KeyError, AttributeError):
            prefs = None
        for kind in order:
            if prefs is None or kind == "NONE":
                break
            try:
                prefs.compute_device_type = kind
                prefs.get_devices()
            except (TypeError, ValueError, AttributeError):
                continue
            gpus = [d for d in prefs.devices if d.type == kind]
            if not gpus:
                continue
            for device in prefs.devices:
                device.use = device.type == kind
            chosen = kind
            break
    for scene in scenes:
        scene.cycles.device = "CPU" if chosen == "CPU" else "GPU"
        try_set(scene.cycles, "denoiser", "OPTIX" if chosen == "OPTIX" else "OPENIMAGEDENOISE")
        try_set(scene.cycles, "denoising_use_gpu", chosen != "CPU")
    emit("device", device=chosen)
    return chosen


# ------------------------------------------------------------------------ geometry


def plane_mesh(bpy: Any, name: str, width: float, height: float) -> Any:
    """A single quad facing +Z with UVs: (0, 0) at the smallest X and Y (the map's bottom-left,
    since row 0 of every map is its top)."""
    mesh = bpy.data.meshes.new(name)
    w, h = width / 2.0, height / 2.0
    mesh.from_pydata([(-w, -h, 0.0), (w, -h, 0.0), (w, h, 0.0), (-w, h, 0.0)], [], [(0, 1, 2, 3)])
    uv = mesh.uv_layers.new(name="UVMap")
    for loop, coords in zip(mesh.loops, ((0, 0), (1, 0), (1, 1), (0, 1)), strict=True):
        uv.data[loop.index].uv = coords
    mesh.update()
    return mesh


def prop_mesh(bpy: Any, prop: dict[str, Any]) -> Any:
    import bmesh

    size = prop.get("size") or {}
    kind = prop["kind"]
    if kind == "plane":
        return plane_mesh(bpy, prop["name"], 2.0, 2.0)
    bm = bmesh.new()
    if kind == "uv_sphere":
        bmesh.ops.create_uvsphere(bm, u_segments=48, v_segments=24, radius=size["radius"])
    elif kind == "cube":
        bmesh.ops.create_cube(bm, size=size["size"])
    elif kind == "cone":
        bmesh.ops.create_cone(
            bm,
            cap_ends=True,
            segments=int(size.get("vertices", 3)),
            radius1=size["radius"],
            radius2=0.0,
            depth=size["depth"],
        )
    elif kind == "torus":
        torus(bm, size["major_radius"], size["minor_radius"])
    else:
        raise ValueError(f"unknown prop kind {kind!r}")
    if kind in ("uv_sphere", "torus"):
        for face in bm.faces:
            face.smooth = True
    mesh = bpy.data.meshes.new(prop["name"])
    bm.to_mesh(mesh)
    bm.free()
    return mesh


def torus(bm: Any, major: float, minor: float, segments: int = 48, rings: int = 12) -> None:
    grid = []
    for i in range(segments):
        u = 2 * math.pi * i / segments
        row = []
        for j in range(rings):
            v = 2 * math.pi * j / rings
            r = major + minor * math.cos(v)
            row.append(bm.verts.new((r * math.cos(u), r * math.sin(u), minor * math.sin(v))))
        grid.append(row)
    for i in range(segments):
        for j in range(rings):
            a, b = grid[i][j], grid[(i + 1) % segments][j]
            c, d = grid[(i + 1) % segments][(j + 1) % rings], grid[i][(j + 1) % rings]
            bm.faces.new((a, b, c, d))


def place(obj: Any, location: list[float], rotation_deg: list[float], scale: Any = None) -> None:
    obj.location = location
    obj.rotation_euler = [math.radians(a) for a in rotation_deg]
    if scale is not None:
        obj.scale = scale


def simple_material(bpy: Any, name: str, colour: list[int], roughness: float) -> Any:
    mat = bpy.data.materials.new(name)
    try_use_nodes(mat)
    bsdf = mat.node_tree.nodes.get("Principled BSDF")
    bsdf.inputs["Base Color"].default_value = (*srgb8(colour), 1.0)
    bsdf.inputs["Roughness"].default_value = roughness
    return mat


# ------------------------------------------------------------------------ scenes


def build_scene(bpy: Any, scene: Any, job: dict[str, Any], name: str, material: Any) -> Any:
    from mathutils import Vector

    layout = job["layouts"][name]
    geometry = job["surface"]
    setup_scene(bpy, scene, job["common"], layout)
    coll = scene.collection
    mesh = plane_mesh(bpy, f"{job['name']} surface", *geometry["size"])
    mesh.materials.append(material)
    panel = bpy.data.objects.new(f"{job['name']} ({name})", mesh)
    coll.objects.link(panel)
    place(
        panel,
        layout["panel_location"],
        layout["panel_rotation_deg"],
        [geometry["object_scale"]] * 3,
    )
    if job["displacement"] == "true" and "height" in job["maps"]:
        mod = panel.modifiers.new("Displacement subdivision", "SUBSURF")
        mod.subdivision_type = "SIMPLE"
        mod.levels = mod.render_levels = 6
        try_set(mod, "quality", 6)
        try_set(mod, "use_adaptive_subdivision", True)
    for prop in layout["props"]:
        obj = bpy.data.objects.new(prop["name"], prop_mesh(bpy, prop))
        obj.data.materials.append(
            simple_material(bpy, prop["name"], prop["colour"], prop["roughness"])
        )
        place(obj, prop["location"], prop["rotation_deg"], prop["scale"])
        coll.objects.link(obj)
    target = Vector(layout["camera"]["target"])
    for spec in layout["lights"]:
        light = bpy.data.lights.new(f"{spec['name']} light", "AREA")
        light.shape = spec["shape"]
        light.size = spec["size"]
        light.energy = spec["power_w"]
        try_set(light, "spread", math.radians(spec["spread_deg"]))
        try_set(light, "use_shadow", spec["shadow"])
        obj = bpy.data.objects.new(f"{spec['name']} light", light)
        obj.location = spec["location"]
        direction = target - Vector(spec["location"])
        obj.rotation_euler = direction.to_track_quat("-Z", "Y").to_euler()
        coll.objects.link(obj)
    if not layout.get("shadow", True):
        for obj in coll.objects:
            if obj.type == "MESH":
                try_set(obj, "visible_shadow", False)
    cam_data = bpy.data.cameras.new(f"{name} camera")
    camera = bpy.data.objects.new(f"{name} camera", cam_data)
    coll.objects.link(camera)
    scene.camera = camera
    scene.world = build_world(bpy, name, layout)
    return camera


def build_world(bpy: Any, name: str, layout: dict[str, Any]) -> Any:
    world = bpy.data.worlds.new(f"{name} world")
    try_use_nodes(world)
    nodes, links = world.node_tree.nodes, world.node_tree.links
    background = nodes.get("Background") or nodes.new("ShaderNodeBackground")
    background.inputs["Strength"].default_value = float(layout["world_strength"])
    if layout["world"] == "hdri":
        folder, _, file = layout["hdri"].rpartition("/")
        path = os.path.join(bpy.utils.system_resource("DATAFILES", path=folder) or "", file)
        if not os.path.isfile(path):
            raise RuntimeError(f"Blender's bundled studio light {layout['hdri']} is missing")
        env = nodes.new("ShaderNodeTexEnvironment")
        env.name = env.label = "Studio HDRI"
        env.image = bpy.data.images.load(path, check_existing=True)
        mapping = nodes.new("ShaderNodeMapping")
        mapping.name = mapping.label = "HDRI turn"
        coords = nodes.new("ShaderNodeTexCoord")
        links.new(coords.outputs["Generated"], mapping.inputs["Vector"])
        links.new(mapping.outputs["Vector"], env.inputs["Vector"])
        links.new(env.outputs["Color"], background.inputs["Color"])
    else:
        background.inputs["Color"].default_value = (*srgb8(layout["world_colour"]), 1.0)
    return world


def aim(camera: Any, view: dict[str, Any]) -> None:
    cam = view["camera"]
    camera.location = cam["location"]
    camera.rotation_euler = [math.radians(a) for a in cam["rotation_deg"]]
    camera.data.lens = cam["lens_mm"]
    camera.data.sensor_width = cam["sensor_mm"]
    camera.data.clip_start = cam["clip_start"]


def render(bpy: Any, scene: Any, camera: Any, view: dict[str, Any]) -> float:
    aim(camera, view)
    if scene.world is not None and "HDRI turn" in scene.world.node_tree.nodes:
        rotation = scene.world.node_tree.nodes["HDRI turn"].inputs["Rotation"]
        rotation.default_value = (0.0, 0.0, math.radians(view["world_turn_deg"]))
    final = view["output"]
    temp = temp_name(final)
    scene.render.filepath = temp
    t0 = time.perf_counter()
    try:
        bpy.ops.render.render(write_still=True, scene=scene.name)
        if not os.path.isfile(temp):
            raise RuntimeError(f"Blender wrote no image for the {view['layout']} view")
        os.replace(temp, final)
    finally:
        if os.path.exists(temp):
            os.unlink(temp)
    return time.perf_counter() - t0


def save_files(bpy: Any, job: dict[str, Any], material: Any) -> None:
    if not (job.get("save_blend") or job.get("save_material")):
        return
    for image in bpy.data.images:
        if image.source == "FILE" and image.filepath and not image.packed_file:
            image.pack()
    if job.get("save_blend"):
        final = job["save_blend"]
        temp = temp_name(final)
        try:
            bpy.ops.wm.save_as_mainfile(filepath=temp, compress=True, copy=True)
            os.replace(temp, final)
        finally:
            if os.path.exists(temp):
                os.unlink(temp)
        emit("saved", path=final, kind="scene")
    if job.get("save_material"):
        final = job["save_material"]
        temp = temp_name(final)
        material.use_fake_user = True
        if hasattr(material, "asset_mark"):
            material.asset_mark()
        try:
            bpy.data.libraries.write(temp, {material}, fake_user=True, compress=True)
            os.replace(temp, final)
        finally:
            if os.path.exists(temp):
                os.unlink(temp)
        emit("saved", path=final, kind="material")


def run(job: dict[str, Any]) -> None:
    import bpy

    bpy.ops.wm.read_factory_settings(use_empty=True)
    setup_common(bpy, job["common"])
    material = build_material(bpy, job)
    scenes, cameras = {}, {}
    first = bpy.data.scenes[0]
    for i, name in enumerate(job["layouts"]):
        scene = first if i == 0 else bpy.data.scenes.new(name)
        scene.name = name
        scenes[name] = scene
        cameras[name] = build_scene(bpy, scene, job, name, material)
    choose_device(bpy, list(scenes.values()), job["common"]["device_order"], job["device"])
    total = len(job["renders"])
    for k, view in enumerate(job["renders"]):
        name = view["layout"]
        emit("render_start", layout=name, view=view["view"], index=k, total=total)
        seconds = render(bpy, scenes[name], cameras[name], view)
        emit(
            "render",
            layout=name,
            view=view["view"],
            index=k,
            total=total,
            seconds=round(seconds, 3),
            output=view["output"],
        )
    save_files(bpy, job, material)


def main(argv: list[str]) -> int:
    parent = os.environ.get("MATLOOM_PARENT_PID", "")
    exit_with_parent(int(parent) if parent.isdigit() else None)
    try:
        import bpy
    except ImportError:
        emit("error", kind="no_bpy", message="this Python has no bpy module")
        return 3
    version = tuple(bpy.app.version[:2])
    emit("start", blender=bpy.app.version_string, python=sys.version.split()[0])
    if version < MIN_VERSION:
        emit(
            "error",
            kind="version",
            message=f"Blender {bpy.app.version_string} is too old: MatLoom needs 4.2 or newer",
        )
        return 4
    try:
        with open(job_path(argv), encoding="utf-8") as handle:
            job = json.load(handle)
        if job.get("format") != "matloom-blender-job":
            raise ValueError("not a MatLoom Blender job")
        t0 = time.perf_counter()
        run(job)
        emit("done", seconds=round(time.perf_counter() - t0, 3))
        return 0
    except Exception as err:  # reported to MatLoom as one line; the traceback for debugging
        emit(
            "error",
            kind="exception",
            message=f"{type(err).__name__}: {err}",
            traceback=traceback.format_exc(limit=8),
        )
        return 1


if __name__ == "__main__":
    code = main(sys.argv)
    sys.stdout.flush()
    sys.stderr.flush()
    # inside `blender -b --python` Blender would go on and exit 0; os._exit keeps the status
    os._exit(code)
