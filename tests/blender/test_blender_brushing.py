"""Brushed metal in Blender stretches its highlight the way real grooves do.

``anisotropy_angle`` is the brushing direction. Blender renders (Cycles) the highlight of a
small point light straight above: (1) on a mesh of real sine grooves running along the
brushing direction, with an isotropic metal; (2) on a flat plane with the material that
``matloom blender --save-material-only`` saved; (3) on a flat plane with the material Blender's
glTF importer makes of the ``gltf`` preset. The elongation axis of each highlight (the principal
axis of its second moments) must agree with the grooves' (across the lines), for a constant
angle and for an angle map. The scene script is brushing_scene.py; skipped without Blender or
bpy.
"""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from matloom.blender.runner import Blender

pytestmark = pytest.mark.blender

ROOT = Path(__file__).resolve().parents[2]
SCENE = Path(__file__).with_name("brushing_scene.py")
#: Render size and samples; groove cycles over the 2-unit swatch, their depth, the mesh grid.
SIZE, SAMPLES = 96, 16
GROOVES = {"cycles": 40, "depth": 0.002, "cells": 400}
ROUGHNESS = 0.2
PROGRAM = """Material(
  Layer(1)
    .basecolor(230, 230, 230)
    .metallic(1)
    .roughness({roughness})
    .anisotropy(0.9)
    .anisotropy_angle({brush})
)
"""


def _matloom(blender: Blender, *args: str) -> None:
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    env["MATLOOM_BLENDER_PYTHON" if blender.kind == "bpy" else "MATLOOM_BLENDER"] = blender.path
    res = subprocess.run(
        [sys.executable, "-m", "matloom", *args],
        capture_output=True,
        text=True,
        env=env,
        timeout=600,
    )
    assert res.returncode == 0, res.stderr


def _highlight(blender: Blender, folder: Path, name: str, **job: object) -> np.ndarray:
    """Luminance of the scene ``job`` describes (see brushing_scene.py), rows from the top."""
    output = folder / f"{name}.npy"
    job_file = folder / f"{name}.json"
    job_file.write_text(
        json.dumps(
            {"size": SIZE, "samples": SAMPLES, "roughness": ROUGHNESS, "output": str(output), **job}
        )  # fmt: skip
    )
    if blender.kind == "bpy":
        cmd = [blender.path, str(SCENE), str(job_file)]
    else:
        cmd = [blender.path, "-b", "--factory-startup", "--python", str(SCENE), "--"]
        cmd.append(str(job_file))
    res = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
    assert res.returncode == 0 and output.is_file(), res.stdout[-2000:] + res.stderr[-2000:]
    return np.clip(np.load(output).astype(np.float64), 0.0, None)


def elongation(weights: np.ndarray) -> tuple[float, float]:
    """(axis in degrees counter-clockwise from +x in [0, 180), major / minor std) of the
    weighted second moments; image rows grow downward, the swatch's +y is up."""
    rows, cols = np.mgrid[0 : weights.shape[0], 0 : weights.shape[1]]
    x, y = cols + 0.5, -(rows + 0.5)
    total = weights.sum()
    assert total > 0, "the highlight is black"
    cx, cy = (weights * x).sum() / total, (weights * y).sum() / total
    cxx = (weights * (x - cx) ** 2).sum() / total
    cyy = (weights * (y - cy) ** 2).sum() / total
    cxy = (weights * (x - cx) * (y - cy)).sum() / total
    axis = math.degrees(0.5 * math.atan2(2 * cxy, cxx - cyy)) % 180.0
    half_trace, root = (cxx + cyy) / 2, math.sqrt(((cxx - cyy) / 2) ** 2 + cxy**2)
    return axis, math.sqrt((half_trace + root) / (half_trace - root))


def axial_gap(a: float, b: float) -> float:
    gap = abs(a - b) % 180.0
    return min(gap, 180.0 - gap)


def _consumers(blender: Blender, folder: Path, brush: int) -> dict[str, dict[str, str]]:
    """The scene jobs of the consumers: the saved material of a constant angle and of an angle
    map (a texture: Blender's node path), and the glTF import of the angle map (Blender's glTF
    importer wires a UV tangent only for an anisotropy texture; with a constant rotation it
    leaves Blender's default tangent, whatever the file says)."""
    jobs = {}
    for kind, angle in (("constant", f"{brush}"), ("map", f"{brush} + X() * 0.001")):
        program = folder / f"{kind}.mat"
        program.write_text(PROGRAM.format(roughness=ROUGHNESS, brush=angle))
        saved = folder / f"saved_{kind}"
        _matloom(blender, "blender", str(program), "-o", str(saved), "--size", "32",
                 "--samples", "1", "--displacement", "off", "--save-material-only")  # fmt: skip
        jobs[f"saved .blend, {kind}"] = {
            "mode": "blend",
            "material_blend": str(saved / "material.blend"),
        }
    exported = folder / "exported"
    _matloom(blender, "render", str(folder / "map.mat"), "-o", str(exported), "--size", "16",
             "--preset", "gltf", "--name", "brushed")  # fmt: skip
    jobs["glTF import, map"] = {"mode": "gltf", "gltf": str(exported / "gltf" / "brushed.gltf")}
    return jobs


@pytest.mark.parametrize("brush", [0, 30, 90])
def test_anisotropy_stretches_the_highlight_like_real_grooves(
    blender: Blender, tmp_path: Path, brush: int
) -> None:
    real_axis, real_ratio = elongation(
        _highlight(blender, tmp_path, "grooves", mode="grooves", brush_deg=brush, **GROOVES)
    )
    assert real_ratio > 1.5 and axial_gap(real_axis, brush + 90) < 15, (real_axis, real_ratio)
    for k, (name, job) in enumerate(_consumers(blender, tmp_path, brush).items()):
        axis, ratio = elongation(_highlight(blender, tmp_path, f"consumer{k}", **job))
        assert ratio > 1.5, (name, ratio)
        assert axial_gap(axis, real_axis) < 15, (name, axis, real_axis)
