"""Op entry of ``Quantize`` (see :mod:`matloom.vocab.quantize`); :data:`matloom.ops.table.OPS`
includes it.

Quantize is a coordinate transform (``Op.transform``, :mod:`matloom.ops.transform`) whose map is
not affine: ``(x, y) -> ((floor(x / w) + 0.5) w, (floor(y / h) + 0.5) h)``. Its frame
(:class:`matloom.lang.cost.FrameTable`) therefore equals no frame of an affine transform, but
two Quantize calls with the same cells in the same frame share one frame (the evaluator's Define
memo and the cost model agree). The coordinates are computed in float64 (IEEE division, floor,
addition and multiplication: the same bits on every machine and backend) and given back in the
coordinates' dtype.

Tileable output (period rule): the operand's frame keeps the View's periods when they hold a
whole number of cells along each axis, since then ``q(x + P) = q(x) + P`` (cells are aligned to
the origin, so a View starting off a cell edge is fine: only the period counts); otherwise the
cells do not repeat with the View and the checker warns (W009/W010) about what inside needs the
periods. No support rule (a motif's box grows by half a cell; not analysed).
"""

from __future__ import annotations

from typing import Any

import matloom.ops.period as P
import matloom.ops.transform as T
from matloom.ops.op import NUMPY, Kind, Op, Ref, not_constant, unbounded

_FIELDS = "matloom.engine.rules.fields:"


def _centres(x: Any, y: Any, w: Any, h: Any) -> tuple[Any, Any]:
    """Cell centres of the samples (x, y) for cells of w x h (float64, back in x's dtype)."""
    import numpy as np

    out = []
    for v, size in ((x, w), (y, h)):
        v = np.asarray(v)
        size64 = np.float64(size)
        with np.errstate(all="ignore"):
            q = (np.floor(v.astype(np.float64) / size64) + 0.5) * size64
        out.append(q.astype(np.result_type(v.dtype, np.float32)) if v.dtype.kind == "f" else q)
    return out[0], out[1]


def _no_matrix(u: float, v: float) -> T.Affine:
    raise ValueError("Quantize is not an affine map")


def _back(u: float, v: float, a: float, b: float) -> tuple[float, float]:
    return u, v  # unused: Quantize has no support rule


def _quantized(width: str, height: str) -> P.FrameRule:
    """The operand keeps the periods when each holds a whole number of cells."""

    def rule(name: str, param: P.Param, periods: P.Periods) -> P.Frame:
        cells = (periods[0] / float(param(width)), periods[1] / float(param(height)))
        if all(P.whole(n) for n in cells):
            return periods
        return f"{name} cells that do not divide the View ({cells[0]:.4g} x {cells[1]:.4g})"

    return rule


QUANTIZE_ENTRIES: tuple[Op, ...] = (
    Op(
        "Quantize",
        Kind.FIELD,
        Ref(_FIELDS + "transformed"),
        not_constant,
        unbounded,
        NUMPY,
        transform=T.Transform(
            values=T.params("width", "height"),
            coords=_centres,
            matrix=_no_matrix,
            warp=T.pair,
            back=_back,
            affine=False,
        ),
        period=P.transform(_quantized("width", "height")),
    ),
)
