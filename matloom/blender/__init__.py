"""Blender Cycles renders of MatLoom materials, with Blender as a separate process.

``layouts`` holds the paper's flat and staged layouts as data, ``job`` turns a program or an
exported folder into a JSON job, ``runner`` finds Blender and runs ``worker.py`` (the only
module that imports ``bpy``, and only inside Blender). Nothing here imports ``bpy``.
"""
