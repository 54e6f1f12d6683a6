"""Blender Cycles renders of MatLoom materials, with Blender as a separate process.

``layouts`` holds the paper's flat and staged layouts as data, ``job`` turns a program or an
exported folder into a JSON job (``packed`` finds an ORM / mask map a preset wrote), ``runner``
finds Blender and runs ``worker.py`` (with ``worker_material.py`` and ``worker_common.py``, the
only modules that import ``bpy``, and only inside Blender), ``images`` checks what Blender wrote
and ``render`` installs it. Nothing here imports ``bpy``.

The Python API: :func:`render_layouts` renders an exported maps folder into
``out_dir/<layout>.png``; every failure is a :class:`BlenderError` with a one-line message.
"""

from matloom.blender.render import render_layouts
from matloom.blender.runner import BlenderError

__all__ = ["BlenderError", "render_layouts"]
