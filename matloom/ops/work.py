"""Work rules: how much one evaluation of an op costs, in the cost model's unit.

The unit is one *node evaluation*: an element-wise operation such as ``+`` on every texel
(:mod:`matloom.lang.cost` counts them, ``docs/limits.md`` bounds them). An op's ``Op.work`` is a
number or a rule ``work(param) -> number`` over the call's static parameters (``param(name)``
gives a parameter's value as the evaluator uses it), and it bounds every loop the op's kernels
run: fBm's octaves, Weave's search along a float, a path's flattened edges, Tile's instances.
The numbers are measured (``tests/engine/test_cost_coverage.py`` checks every registry function
over a sweep of its parameters against them): the time per texel of the slower backend, relative
to an element-wise op, rounded up, so that no accepted program does far more work than it counts.

Pure Python: the checker reads these rules without importing numpy or a kernel.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

Param = Callable[[str], Any]

#: Transcendental element-wise functions (Sin, Cos, Log, Pow, Exp, Atan2): portable polynomial
#: evaluations, the same on every CPU, not one machine instruction (Pow measured highest).
TRANSCENDENTAL = 64
#: Hash: a 64-bit integer mix per texel; Threshold and Smoothstep: a few comparisons and ramps.
HASH = 16
THRESHOLD = 8
SMOOTHSTEP = 4
#: fBm: per octave (one 2-D OpenSimplex evaluation per texel) and the fixed part.
FBM_OCTAVE = 4
FBM_BASE = 4
#: Worley: the 5 x 5 neighbouring feature points per texel (distances and cell values) and the
#: border distance, which searches further.
WORLEY = 128
WORLEY_EDGE = 320
#: Worley(smoothness > 0): the 25 distances twice and a portable exp per feature point.
WORLEY_SMOOTH = 640
#: Bricks and Weave's closed-form outputs, and Weave(output="along")'s fixed part (the
#: distinct draft places present).
BRICKS = 8
WEAVE = 8
WEAVE_ALONG = 24
#: Weave(output="along"): one step of the search along a warp float, per distinct draft place
#: (two searches, a handful of array operations each).
WEAVE_ALONG_STEP = 12
#: Fill/Stroke of a Rect or Ellipse (a distance field and a coverage ramp), and each straight
#: edge of a Path (its distance and winding on every texel).
SHAPE = 4
PATH_EDGE = 6
#: Straight edges a CubicTo is flattened into (``matloom.engine.kernels.shapes.CUBIC_STEPS``).
CUBIC_EDGES = 16
#: Tile: per instance (9 per texel), the cell hash, jitter, rotation, scale and the maximum.
TILE_INSTANCE = 24
#: Choose: the index, a comparison and a copy per option (counted again per further option).
CHOOSE = 8


def fbm(param: Param) -> float:
    """One OpenSimplex evaluation per octave."""
    return FBM_BASE + FBM_OCTAVE * int(param("octaves"))


def worley(param: Param) -> float:
    if param("output") == "edge":
        return WORLEY_EDGE
    return WORLEY_SMOOTH if float(param("smoothness") or 0.0) > 0 else WORLEY


def weave(param: Param) -> float:
    """The closed forms, plus for ``output="along"`` the step-by-step search of
    :mod:`matloom.engine.kernels.patterns_weave`: up to ``period - 1`` steps per distinct draft
    place, ``period`` being the rows after which a warp's draft place repeats."""
    if param("output") != "along":
        return WEAVE
    return WEAVE_ALONG + WEAVE_ALONG_STEP * weave_search_steps(
        int(param("over")), int(param("under")), int(param("shift"))
    )


def weave_search_steps(over: int, under: int, shift: int) -> int:
    """Steps of the warp-float search (``patterns_weave._run``): none when a row up moves the
    draft place by +-1 (closed forms), else ``period - 1``."""
    repeat = over + under
    step = shift % repeat
    if step in (1, repeat - 1):
        return 0
    return repeat // math.gcd(step, repeat) - 1


def tile_work(instances: int) -> int:
    """Tile's own work: the instance geometry of each of its ``instances`` frames (the motif
    is counted once per instance by the cost walk)."""
    return instances * TILE_INSTANCE


#: What to write instead, for the ops whose work grows with a parameter (E071's hint).
HINTS: dict[str, str] = {
    "fBm": "use fewer octaves",
    "Weave": 'keep over + under small, or use shift=1 or -1 for output="along" '
    "(its float search takes a step per row of the draft's period)",
    "Fill": "draw fewer path segments (each CubicTo counts as 16 edges)",
    "Stroke": "draw fewer path segments (each CubicTo counts as 16 edges)",
    "Tile": "avoid nesting Tiles (each evaluates its motif 9 times)",
}
