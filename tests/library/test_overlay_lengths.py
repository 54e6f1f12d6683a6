"""Overlays drawn with shapes (the scratches: one ``Tile`` of thin ellipses at random angles)
keep their size relative to the host like noise overlays do: their lengths scale with the Views,
so their count per tileable repeat stays whole; and the scratches run in every direction (the
earlier overlay drew two axis-aligned noise bands that read as a grid)."""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from matloom.engine.evaluate import evaluate
from matloom.lang import ast as A
from matloom.lang.tileable import tileable_warnings
from matloom.library import load_library
from matloom.library.overlay import compose

LIB = load_library()


def _tile_widths(program: A.Program) -> list[float]:
    return [
        float(a.value.value)  # type: ignore[union-attr]
        for _, e in A.program_expressions(program)
        for n in A.walk(e)
        if isinstance(n, A.Call) and n.func == "Tile"
        for a in n.args
        if a.param == "width"
    ]


def _host(width: float) -> A.Program:
    host = LIB.ast("cobblestone")
    assert host.view is not None
    v = host.view
    return replace(host, view=replace(v, x2=v.x1 + width, y2=v.y1 + width))


def test_shape_lengths_scale_with_the_views() -> None:
    overlay = LIB.overlays["scratched"]
    (own,) = _tile_widths(overlay.ast)
    ov_width = overlay.ast.view.x2 - overlay.ast.view.x1  # type: ignore[union-attr]
    for width in (1.0, 4.0):
        (w,) = _tile_widths(compose(_host(width), overlay, main_colour="base"))
        assert w == own * width / ov_width  # the same number of cells per View


def test_scratches_tile_and_run_in_every_direction() -> None:
    host = LIB.ast("cobblestone")
    program = compose(host, LIB.overlays["scratched"], main_colour="base", cover=0.8)
    assert program.tileable and tileable_warnings(program) == []
    top = program.layers[-1]
    probe = replace(program, layers=(A.Layer(None, (A.ChannelSet("roughness", (top.alpha,)),)),))
    m = np.asarray(evaluate(probe, 256, 256).roughness, np.float64)
    gy, gx = np.gradient(m)
    mag = np.hypot(gx, gy)
    strong = mag > 0.5 * mag.max()
    angles = np.degrees(np.arctan2(gy[strong], gx[strong])) % 90.0
    near_axis = np.mean((angles < 10) | (angles > 80))
    assert strong.sum() > 100
    assert near_axis < 0.5  # random angles: about 22 %; axis-aligned bands: nearly all
