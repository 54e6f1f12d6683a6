"""High-level render entry points used by the CLI and the authoring pipeline."""

from __future__ import annotations

from typing import Any

import numpy as np

from matloom.engine.evaluate import evaluate, prepare
from matloom.engine.limits import Usage
from matloom.lang import ast as A
from matloom.render.preview import Light, shade, tile_image


def preview(
    program_or_text: A.Program | str,
    size: int = 256,
    *,
    width: int | None = None,
    height: int | None = None,
    light: Light | None = None,
    tile: int = 1,
    backend: str = "auto",
    **eval_kwargs: Any,
) -> np.ndarray:
    """Shaded head-on swatch (uint8 RGB, H x W x 3) of a program, optionally tiled n x n.

    The size, the tiled size and the memory of evaluation, shading and tiling are checked
    before any work (:class:`~matloom.engine.limits.LimitError`)."""
    w = size if width is None else width
    h = size if height is None else height
    usage = Usage(preview_tile=max(tile, 1))
    maps = evaluate(program_or_text, w, h, backend=backend, usage=usage, **eval_kwargs)
    img = shade(maps, light=light)
    return tile_image(img, tile) if tile > 1 else img


def stats(
    program_or_text: A.Program | str, grid: int = 128, backend: str = "auto"
) -> dict[str, float]:
    """The 28 material statistics, computed on a ``grid`` x ``grid`` evaluation like the reference."""
    from matloom.render.stats import material_stats

    return material_stats(evaluate(program_or_text, grid, grid, backend=backend))


def stats_text(program_or_text: A.Program | str, grid: int = 128, backend: str = "auto") -> str:
    """The statistics block ready to paste into a critic prompt."""
    from matloom.render.stats import format_stats

    return format_stats(stats(program_or_text, grid, backend))


__all__ = ["Light", "preview", "prepare", "stats", "stats_text"]
