"""Sampling grid: float32 pixel-centre axes over the View, exactly as the reference builds them."""

from __future__ import annotations

import numpy as np

from matloom.engine.maps import View


def sample_axes(view: View, width: int, height: int) -> tuple[np.ndarray, np.ndarray]:
    """(x of shape (1, W), y of shape (H, 1)), float32; row 0 is the top (largest Y).

    Column j: X = x1 + (j + 0.5)(x2 - x1)/W; row i: Y = y2 + (i + 0.5)(y1 - y2)/H, computed in
    float32 (arange, + 0.5, times span/length, plus start) like the reference.
    """
    xs = np.arange(width, dtype=np.float32)
    xs += np.float32(0.5)
    xs *= np.float32((view.x2 - view.x1) / width)
    xs += np.float32(view.x1)
    ys = np.arange(height, dtype=np.float32)
    ys += np.float32(0.5)
    ys *= np.float32((view.y1 - view.y2) / height)
    ys += np.float32(view.y2)
    return xs.reshape(1, width), ys.reshape(height, 1)
