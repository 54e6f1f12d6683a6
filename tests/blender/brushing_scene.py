"""Runs INSIDE Blender (bpy), like readback.py: ``python brushing_scene.py job.json`` (bpy module)
or ``blender -b --factory-startup --python brushing_scene.py -- job.json``.

Renders the highlight of a small point light over a 2 x 2 swatch seen straight down by an
orthographic camera (black world) and saves the render's luminance (rows from the top) as .npy.

The job (JSON, the last argument): ``mode`` "grooves" (a mesh of sine grooves along
``brush_deg``, ``cycles`` per 2 units, ``depth`` high, on a grid of ``cells``; isotropic
metal), "blend" (a flat plane with the material of ``material_blend``) or "gltf" (a flat plane
with the material Blender's glTF importer makes of ``gltf``); ``output`` (.npy), ``size``,
``samples``, ``roughness``."""

import json
import math
import sys

import bpy
import numpy as np

with open(sys.argv[-1], encoding="utf-8") as handle:
    job = json.load(handle)
bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene


def plane(name, cells, height):
    """A 2 x 2 grid centred on the origin, UV u along +x, v along +y, z = height(x, y)."""
    verts, faces = [], []
    for j in range(cells + 1):
        for i in range(cells + 1):
            x, y = -1 + 2 * i / cells, -1 + 2 * j / cells
            verts.append((x, y, height(x, y)))
    for j in range(cells):
        for i in range(cells):
            a = j * (cells + 1) + i
            faces.append((a, a + 1, a + cells + 2, a + cells + 1))
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata(verts, [], faces)
    layer = mesh.uv_layers.new(name="UVMap")
    for poly in mesh.polygons:
        for loop in poly.loop_indices:
            x, y, _ = verts[mesh.loops[loop].vertex_index]
            layer.data[loop].uv = ((x + 1) / 2, (y + 1) / 2)
    mesh.shade_smooth()
    obj = bpy.data.objects.new(name, mesh)
    scene.collection.objects.link(obj)
    return obj


def isotropic_metal():
    mat = bpy.data.materials.new("isotropic")
    if hasattr(mat, "use_nodes"):
        mat.use_nodes = True  # Blender < 5 (5.0 always uses nodes and deprecates this)
    bsdf = mat.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (0.8, 0.8, 0.8, 1.0)
    bsdf.inputs["Metallic"].default_value = 1.0
    bsdf.inputs["Roughness"].default_value = job["roughness"]
    return mat


mode = job["mode"]
if mode == "grooves":
    t = math.radians(job["brush_deg"])
    cycles, depth = job["cycles"], job["depth"]

    def grooves(x, y):
        return depth * math.sin(2 * math.pi * cycles / 2 * (-x * math.sin(t) + y * math.cos(t)))

    obj = plane("grooves", job["cells"], grooves)
    obj.data.materials.append(isotropic_metal())
elif mode == "blend":
    obj = plane("flat", 1, lambda x, y: 0.0)
    with bpy.data.libraries.load(job["material_blend"]) as (source, target):
        target.materials = list(source.materials)
    obj.data.materials.append(target.materials[0])
else:
    # the imported quad itself (its UVs and tangents as the importer made them): glTF's quad
    # faces +Z with +Y up, which the importer turns into Blender's -Y facing, +Z up; turn it
    # back to face the camera with its up along +Y, and scale its 1 m width to the swatch's 2
    bpy.ops.import_scene.gltf(filepath=job["gltf"])
    (obj,) = [o for o in scene.objects if o.type == "MESH"]
    obj.rotation_mode = "XYZ"  # the importer sets quaternions
    obj.rotation_euler = (-math.pi / 2, 0.0, 0.0)
    obj.scale = (2.0, 2.0, 2.0)

camera = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
camera.data.type = "ORTHO"
camera.data.ortho_scale = 2.0
camera.location = (0.0, 0.0, 5.0)
scene.collection.objects.link(camera)
scene.camera = camera
light = bpy.data.objects.new("light", bpy.data.lights.new("light", "POINT"))
light.data.energy = job.get("energy", 20.0)
light.data.shadow_soft_size = 0.01
light.location = (0.0, 0.0, 1.5)
scene.collection.objects.link(light)
world = bpy.data.worlds.new("black")
if hasattr(world, "use_nodes"):
    world.use_nodes = True
world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0
scene.world = world

scene.render.engine = "CYCLES"
scene.cycles.device = "CPU"
scene.cycles.samples = job["samples"]
scene.cycles.use_denoising = False
scene.render.resolution_x = scene.render.resolution_y = job["size"]
scene.render.resolution_percentage = 100
scene.view_settings.view_transform = "Standard"
scene.render.image_settings.file_format = "OPEN_EXR"
scene.render.image_settings.color_depth = "32"
exr = job["output"] + ".exr"
scene.render.filepath = exr
bpy.ops.render.render(write_still=True)
image = bpy.data.images.load(exr)
pixels = np.array(image.pixels[:], dtype=np.float32).reshape(job["size"], job["size"], -1)
# Blender's rows start at the bottom: flip to image rows (row 0 at the top)
np.save(job["output"], pixels[::-1, :, :3].mean(axis=-1))
