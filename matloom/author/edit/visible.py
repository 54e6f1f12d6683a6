"""Whether an edit shows: the share of texels of the intended maps that moved by a visible
amount (not the locality tolerance of half an 8-bit level, but a step a viewer of a lit preview
would notice). The offline edits escalate a step whose change does not show
(:func:`matloom.author.edit.core.edit_offline`)."""

from __future__ import annotations

from collections.abc import Iterable
from typing import TYPE_CHECKING

import numpy as np

from matloom.lang.deps import OUTPUTS

if TYPE_CHECKING:
    from matloom.engine.maps import MaterialMaps

#: A texel changed visibly when a component moved by more than this: colours in 8-bit sRGB
#: levels, height as a share of its range, the rest in their own units.
THRESHOLDS: dict[str, float] = {
    "basecolor": 8 / 255,
    "emissive": 8 / 255,
    "height": 0.1,
    "normal": 0.06,
    "ao": 0.06,
    "ior": 0.05,
    "anisotropy_angle": 10.0,
}
DEFAULT_THRESHOLD = 0.08
#: The normal map's threshold is at most this share of its spread (2.5 to 97.5 percentile of
#: a component), never under ``NORMAL_FLOOR``.
NORMAL_SHARE = 0.25
NORMAL_FLOOR = 0.01
#: Grid side the visible change is measured on, whatever the locality grid (a preview is 192
#: to 256 pixels: what shows at 128 shows there).
VISIBLE_SIZE = 128


def _array(maps: MaterialMaps, name: str) -> np.ndarray:
    if hasattr(maps, f"{name}_linear"):
        lin = np.clip(np.asarray(getattr(maps, f"{name}_linear"), np.float64), 0.0, 1.0)
        return np.where(lin <= 0.0031308, 12.92 * lin, 1.055 * lin ** (1 / 2.4) - 0.055)
    return np.asarray(getattr(maps, name), np.float64)


def visible_changes(
    before: MaterialMaps, after: MaterialMaps, names: Iterable[str] = OUTPUTS
) -> dict[str, float]:
    """Map -> the fraction of its texels that changed visibly."""
    out: dict[str, float] = {}
    for name in names:
        a, b = _array(before, name), _array(after, name)
        if a.shape != b.shape:
            out[name] = 1.0
            continue
        limit = THRESHOLDS.get(name, DEFAULT_THRESHOLD)
        if name == "height":
            finite = a[np.isfinite(a)]
            limit *= max(float(np.ptp(finite)) if finite.size else 0.0, 1e-9)
        elif name == "normal" and a.ndim == 3:
            # a subtle texture (a fine stipple) tilts its normals little: a change of a
            # quarter of its spread shows in a lit preview, whatever the absolute step
            finite = np.where(np.isfinite(a), a, 0.0).reshape(-1, a.shape[2])
            spread = float(np.max(np.percentile(finite, 97.5, 0) - np.percentile(finite, 2.5, 0)))
            limit = min(limit, max(NORMAL_SHARE * spread, NORMAL_FLOOR))
        diff = np.abs(a - b)
        diff = np.where(np.isnan(a) & np.isnan(b), 0.0, diff)
        diff = np.where(np.isfinite(diff), diff, np.inf)
        if diff.ndim == 3:
            diff = diff.max(axis=2)
        out[name] = float(np.count_nonzero(diff > limit)) / max(1, diff.size)
    return out


#: A pixel of the lit preview changed visibly when a channel moved by more than this many
#: 8-bit levels; it moved at all above ``LIT_MOVED`` levels.
LIT_VISIBLE = 8
LIT_MOVED = 1


def lit_changes(before: MaterialMaps, after: MaterialMaps) -> tuple[float, float]:
    """(visible, moved): the fractions of the lit preview's pixels that changed visibly, and
    at all. A relief edit is judged here: a height map may double its range and its normals
    move on half the texels while the lit preview a viewer looks at hardly changes (measured:
    a wood grain's relief x2 moved 49 % of the normals but 1 % of the lit pixels by more than
    8 levels)."""
    from matloom.render.lit import shade_lit

    a = shade_lit(before).astype(np.int16)
    b = shade_lit(after).astype(np.int16)
    if a.shape != b.shape:
        return 1.0, 1.0
    diff = np.abs(a - b).max(axis=2)
    return float(np.mean(diff > LIT_VISIBLE)), float(np.mean(diff > LIT_MOVED))
