"""The language-3 examples of the language reference (per-instance, per-brick and per-thread
values, smooth Worley), rendered by :mod:`matloom.vocab.docs`; ``tests/docs`` runs them."""

from __future__ import annotations

_EXAMPLES = """import numpy as np
import matloom

def height(expr: str) -> np.ndarray:
    return matloom.evaluate(f"Material(Layer(1).height({expr}))", 64, 64).height

# Bricks(output="row" / "column"): integer indices, e.g. alternating brick colours
brick = 'Bricks(brick_width=0.25, brick_height=0.125, output="{}")'
checks = height(f"Mod({brick.format('row')} + {brick.format('column')}, 2)")
assert set(np.unique(checks).tolist()) == {0.0, 1.0}

# Weave: a weft thinner than the warp, and a random shade per thread
weave = "Weave(base_freq=8, warp_width=0.8, weft_width=0.4{})"
shade = height(weave.format(', output="thread_value", seed=3') + " * " + weave.format(""))
assert shade.min() >= 0 and shade.max() < 1 and np.unique(shade).size > 8

# Tile(output=...) and Choose: a disc or a square per instance, picked by the instance's
# random value (same grid and seed for every Tile; a motif covering both picks)
disc, square = "Fill(Ellipse(0, 0, 0.1, 0.1))", "Fill(Rect(-0.08, -0.08, 0.16, 0.16))"
grid = "0.25, 0.25, jitter=0.1, seed=4"
pick = f'Tile(Max({disc}, {square}), {grid}, output="instance_value")'
mixed = height(f"Choose({pick}, Tile({disc}, {grid}), Tile({square}, {grid}))")
assert set(np.unique(mixed).tolist()) == {0.0, 1.0}
angle = height('Tile(Fill(Rect(-0.1, -0.02, 0.2, 0.04)), 0.25, 0.25, rotate=60, seed=1, '
               'output="angle")')
assert np.abs(angle).max() <= 60

# Worley(smoothness=s): rounded cells, never above the exact F1
sharp = height("Worley(base_freq=4, seed=2)")
soft = height("Worley(base_freq=4, seed=2, smoothness=0.15)")
assert (soft <= sharp).all() and (soft < sharp).any()
"""


def language3_examples() -> list[str]:
    """Markdown lines: the examples as a python block that the docs tests execute."""
    return [
        "Language 3 adds per-instance, per-brick and per-thread values and rounded Worley "
        "cells (marked below). Examples (executed by the docs tests):",
        "",
        "```python",
        *_EXAMPLES.rstrip("\n").split("\n"),
        "```",
        "",
    ]
