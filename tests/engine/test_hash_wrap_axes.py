"""Tileable Hash whose operand follows the other axis (``Hash(x=Floor(Y() * 8))``) or both
(``Hash(x=col + row)``): the cells wrap, so the output repeats exactly with the View."""

from __future__ import annotations

import numpy as np
import pytest

import matloom

BODY = (
    "Define(row, Floor((Y() * 8)))\n"
    "Define(col, Floor((X() * 8)))\n"
    "Define(v, Hash(x=row, seed=11))\n"
    "Define(w, Hash(x=(col + row), seed=12))\n"
    "Material(Layer(1).basecolor((v * 255), (w * 255), 100))\n"
)


@pytest.mark.parametrize("backend", ["numpy", "auto"])
@pytest.mark.parametrize("shift", [(2.0, 0.0), (0.0, 2.0), (2.0, 2.0)])
def test_swapped_and_mixed_axis_hash_repeats_with_the_view(
    backend: str, shift: tuple[float, float]
) -> None:
    """Moving the tileable View by one period (its own size) changes nothing."""
    dx, dy = shift
    base = matloom.evaluate(
        "View(0.03, 0.03, 2.03, 2.03, tileable=True)\n" + BODY, 64, 64, backend=backend
    )
    moved = matloom.evaluate(
        f"View({0.03 + dx}, {0.03 + dy}, {2.03 + dx}, {2.03 + dy}, tileable=True)\n" + BODY,
        64,
        64,
        backend=backend,
    )
    assert np.array_equal(base.basecolor_linear, moved.basecolor_linear)


def test_non_tileable_output_is_unchanged_by_the_wrap() -> None:
    plain = matloom.evaluate("View(0, 0, 2, 2)\n" + BODY, 32, 32, backend="numpy")
    rows = plain.basecolor_linear[:, :, 0]
    # without wrapping, the 16 rows of cells over the View height take more than 8 values
    assert len(np.unique(rows)) > 8
