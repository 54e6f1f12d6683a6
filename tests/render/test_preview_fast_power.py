"""The flat preview's numpy shading takes numpy's fast sRGB power and re-shades texels near a
quantisation boundary with the portable one: its images equal the all-portable shading."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from matloom.engine.colour import linear_to_srgb
from matloom.engine.evaluate import evaluate
from matloom.render import preview as P

EXAMPLES = sorted((Path(__file__).parents[2] / "matloom" / "examples").glob("*.mat"))


def _portable(m: dict[str, np.ndarray]) -> np.ndarray:
    params = P.ShadeParams.of()
    with np.errstate(all="ignore"):
        levels = np.floor(
            P._scaled_levels(P._shade_values(m, params.direction, params.half, linear_to_srgb))
        )
        levels[np.isnan(levels)] = 0.0
    return levels.astype(np.uint8)


def _inputs(path: Path, size: int = 96) -> dict[str, np.ndarray]:
    return P._kernel_inputs(evaluate(path.read_text(), size, size, backend="numpy"))


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.stem)
def test_numpy_shading_equals_the_portable_shading(path: Path) -> None:
    m = _inputs(path)
    params = P.ShadeParams.of()
    assert np.array_equal(P._shade_numpy(m, params.direction, params.half), _portable(m))


def test_texels_near_a_level_are_shaded_again_with_the_portable_power(monkeypatch) -> None:
    """A deliberately wrong fast encode (0.3 of a level too bright) changes the image unless
    the near-boundary texels are shaded again; with a margin covering every texel, they all
    are, and the image is the portable one."""
    m = _inputs(EXAMPLES[0])
    params = P.ShadeParams.of()
    monkeypatch.setattr(P, "fast_linear_to_srgb", lambda v: linear_to_srgb(v) + 0.3 / 255)
    monkeypatch.setattr(P, "_LEVEL_MARGIN", 0.0)
    assert not np.array_equal(P._shade_numpy(m, params.direction, params.half), _portable(m))
    monkeypatch.setattr(P, "_LEVEL_MARGIN", 0.5)
    assert np.array_equal(P._shade_numpy(m, params.direction, params.half), _portable(m))
