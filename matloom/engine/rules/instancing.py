"""Field rules of language 3's per-instance values: Tile's outputs other than the mask, and
``Choose`` (referenced by the op table).

Both are computed with numpy from values the backend computed (the motif in each instance's
frame, the instance frames of the backend's tile kernel, the operands of Choose), so every
backend gives the same bits whenever its kernels do.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from matloom.lang import ast as A


def tile_output(ev: Any, call: A.Call, c: Any, params: Any, output: str) -> Any:
    """Tile's ``output`` other than "mask": at each sample, the value of the instance whose
    motif is largest there (the first of :data:`~matloom.engine.kernels.tile.NEIGHBOURS` on
    a tie), among the kept instances whose motif is > 0; 0 where there is none. "u"/"v": the
    sample's coordinates in that instance's frame (where the motif was evaluated); the others
    from :func:`~matloom.engine.kernels.tile.attribute`."""
    from matloom.engine.kernels.tile import NEIGHBOURS, attribute

    motif = call.arg("expr")
    box = ev.motif_support(motif)
    shape = np.broadcast_shapes(np.shape(c[0]), np.shape(c[1]))
    best = np.zeros(shape).reshape(-1)
    out = np.zeros(shape).reshape(-1)
    xs = ys = None
    for dr, dc in NEIGHBOURS:
        lx, ly, inside = ev.backend.tile(c[0], c[1], params, dr, dc, box)
        idx = np.flatnonzero(np.broadcast_to(inside, shape))
        if idx.size == 0:
            continue
        px = np.broadcast_to(lx, shape).reshape(-1)[idx]
        py = np.broadcast_to(ly, shape).reshape(-1)[idx]
        del lx, ly
        points = ev.new_frame(px[None, :], py[None, :])
        value = np.broadcast_to(ev.instance_value(motif, points), (1, idx.size))[0]
        with np.errstate(invalid="ignore"):
            wins = value > best[idx]
        if not wins.any():
            continue
        at = idx[wins]
        best[at] = value[wins]
        if output == "u":
            out[at] = px[wins]
        elif output == "v":
            out[at] = py[wins]
        else:
            if xs is None:
                xs = np.broadcast_to(np.asarray(c[0], np.float64), shape).reshape(-1)
                ys = np.broadcast_to(np.asarray(c[1], np.float64), shape).reshape(-1)
            out[at] = attribute(xs[at], ys[at], params, dr, dc, output)  # type: ignore[index]
    return out.reshape(shape)


def choose(ev: Any, call: A.Call, c: Any) -> Any:
    """``Choose(index, a, b, ...)``: option ``k = clamp(floor(index * n), 0, n - 1)`` of the
    ``n`` options at each sample (float64; NaN where index is NaN)."""
    from matloom.engine.rules.fields_math import _concrete

    nodes = [call.arg("a"), call.arg("b"), *call.extra]
    index = np.asarray(_concrete(ev, ev.eval(call.arg("index"), c)), dtype=np.float64)
    options = [np.asarray(_concrete(ev, ev.eval(n, c))) for n in nodes]  # type: ignore[arg-type]
    return pick(index, options)


def pick(index: Any, options: list[Any]) -> np.ndarray:
    """The selection of :func:`choose` on arrays (or numbers)."""
    n = len(options)
    index = np.asarray(index, dtype=np.float64)
    shape = np.broadcast_shapes(index.shape, *(np.shape(o) for o in options))
    with np.errstate(invalid="ignore", over="ignore"):
        k = np.clip(np.floor(index * n), 0, n - 1)
    out = np.full(shape, np.nan)
    for j, option in enumerate(options):
        np.copyto(out, np.asarray(option, dtype=np.float64), where=np.broadcast_to(k == j, shape))
    return out


def choose_static(values: list[Any], strict: bool) -> float | None:
    """Choose of written constants (index first, then the options)."""
    if len(values) < 3 or any(not isinstance(v, int | float) for v in values):
        return None
    return float(pick(float(values[0]), [float(v) for v in values[1:]]))
