"""High-level render entry points used by the CLI and the authoring pipeline."""

from __future__ import annotations

from typing import Any, Literal

import numpy as np

from matloom.engine.evaluate import evaluate, prepare
from matloom.engine.limits import Usage
from matloom.lang import ast as A
from matloom.render.preview import Light, shade, tile_image

#: Preview layouts: the reference's ``flat`` swatch, the ``lit`` studio swatch
#: (:mod:`matloom.render.lit`), or ``both`` side by side (flat left, lit right).
Layout = Literal["flat", "lit", "both"]
LAYOUTS: tuple[str, ...] = ("flat", "lit", "both")


def preview(
    program_or_text: A.Program | str,
    size: int = 256,
    *,
    width: int | None = None,
    height: int | None = None,
    light: Light | None = None,
    tile: int = 1,
    backend: str = "auto",
    layout: Layout = "flat",
    **eval_kwargs: Any,
) -> np.ndarray:
    """Shaded head-on swatch (uint8 RGB, H x W x 3) of a program, optionally tiled n x n.

    ``layout``: ``flat`` (the reference's fixed-light preview, the default), ``lit``
    (:func:`~matloom.render.lit.shade_lit`, whose key light ``light`` replaces) or ``both``
    (H x 2W: flat left, lit right). The size, the tiled size and the memory of evaluation,
    shading and tiling are checked before any work (:class:`~matloom.engine.limits.LimitError`).
    """
    if layout not in LAYOUTS:
        raise ValueError(f"unknown preview layout {layout!r}; have {', '.join(LAYOUTS)}")
    w = size if width is None else width
    h = size if height is None else height
    usage = Usage(preview_tile=max(tile, 1))
    maps = evaluate(program_or_text, w, h, backend=backend, usage=usage, **eval_kwargs)
    images = []
    if layout != "lit":
        img = shade(maps, light=light)
        images.append(tile_image(img, tile) if tile > 1 else img)
    if layout != "flat":
        from matloom.render.lit import shade_lit

        images.append(shade_lit(maps, key_light=light, tile=max(tile, 1)))
    return images[0] if len(images) == 1 else np.concatenate(images, axis=1)


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


def visible_stats_text(
    program_or_text: A.Program | str, size: int = 512, backend: str = "auto"
) -> str:
    """The visible-statistics block (:mod:`matloom.render.visible_stats`) of a program
    evaluated at ``size`` x ``size``, the resolution of the preview the critic sees."""
    from matloom.render.visible_stats import visible_stats_text as maps_text

    return maps_text(evaluate(program_or_text, size, size, backend=backend))


__all__ = [
    "LAYOUTS",
    "Layout",
    "Light",
    "preview",
    "prepare",
    "stats",
    "stats_text",
    "visible_stats_text",
]
