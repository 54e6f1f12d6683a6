"""The dense schedule: every field of the whole image as numpy arrays, then the numpy compositing."""

from __future__ import annotations

import numpy as np

from matloom.engine.backends import Backend
from matloom.engine.composite import composite
from matloom.engine.interpret import EvalStats, Evaluator, layer_fields
from matloom.engine.maps import MaterialMaps, View
from matloom.lang import ast as A


def evaluate_dense(
    program: A.Program,
    x: np.ndarray,
    y: np.ndarray,
    view: View,
    backend: Backend,
    *,
    ao_radius_units: float | None = None,
    stats: EvalStats | None = None,
) -> MaterialMaps:
    """Evaluate ``program`` on the sample axes ``x`` (1, W), ``y`` (H, 1) and composite it."""
    height, width = y.shape[0], x.shape[1]
    ev = Evaluator(program, x, y, backend, periods=view.periods)
    raws = [layer_fields(ev, layer) for layer in program.layers]
    maps = composite(raws, width, height, view, ao_radius_units=ao_radius_units)
    maps.n_layers = len(program.layers)
    if stats is not None:
        stats.zero_divisions = ev.stats.zero_divisions
        stats.define_evaluations = ev.stats.define_evaluations
    return maps
