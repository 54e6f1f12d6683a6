"""Read a saved .blend back with bpy and print what the tests check, as one JSON line.

Run like the worker: ``python readback.py file.blend`` (bpy module) or
``blender -b --factory-startup --python readback.py -- file.blend``.
"""

import json
import os
import sys

import bpy

args = sys.argv[sys.argv.index("--") + 1 :] if "--" in sys.argv else sys.argv[1:]
bpy.ops.wm.open_mainfile(filepath=args[0])
out = {"materials": {}, "scenes": {}, "images": {}}
for mat in bpy.data.materials:
    if mat.node_tree is None:
        continue
    out["materials"][mat.name] = {
        "links": sorted(
            [lk.from_node.name, lk.from_socket.name, lk.to_node.name, lk.to_socket.name]
            for lk in mat.node_tree.links
        ),
        "frames": sorted(n.name for n in mat.node_tree.nodes if n.type == "FRAME"),
        "displacement_method": getattr(mat, "displacement_method", None),
        "inputs": {
            name: mat.node_tree.nodes["Principled BSDF"].inputs[name].default_value
            for name in ("IOR",)
        }
        if "Principled BSDF" in mat.node_tree.nodes
        else {},
        "asset": mat.asset_data is not None,
    }
for image in bpy.data.images:
    if image.source != "FILE":
        continue  # the Render Result
    out["images"][image.name] = {
        "colour_space": image.colorspace_settings.name,
        "packed": image.packed_file is not None,
    }
for scene in bpy.data.scenes:
    lights = {
        o.name: {
            "location": list(o.location),
            "energy": o.data.energy,
            "size": o.data.size,
            "shape": o.data.shape,
        }
        for o in scene.objects
        if o.type == "LIGHT"
    }
    cam = scene.camera
    out["scenes"][scene.name] = {
        "samples": scene.cycles.samples,
        "camera": {"location": list(cam.location), "lens": cam.data.lens} if cam else None,
        "lights": lights,
        "objects": sorted(o.name for o in scene.objects),
        "view_transform": scene.view_settings.view_transform,
        "film_transparent": scene.render.film_transparent,
    }
sys.stdout.write("READBACK " + json.dumps(out) + "\n")
sys.stdout.flush()
os._exit(0)
