"""Field and geometry rules of the ops that are not element-wise (referenced by the op table).

A field rule is ``rule(interpreter, call, coords)``: it asks the interpreter (any schedule's
:class:`~matloom.engine.interpret.Evaluator`) for operands, static parameters and the backend's
kernels, so that one rule serves the dense, banded and seed-batched schedules.
"""

from __future__ import annotations

from collections.abc import Callable
from functools import partial
from typing import Any

import numpy as np

from matloom.engine.kernels import shapes
from matloom.engine.kernels import threshold as _threshold
from matloom.lang import ast as A
from matloom.lang.seeds import uses_seed
from matloom.lang.static import static_number


def x(ev: Any, call: A.Call, c: Any) -> Any:
    return c[0]


def y(ev: Any, call: A.Call, c: Any) -> Any:
    return c[1]


def constant(ev: Any, call: A.Call, c: Any) -> Any:
    return np.float64(ev.num(call, "value"))


def fbm(ev: Any, call: A.Call, c: Any) -> Any:
    return ev.fbm(call, c)


def worley(ev: Any, call: A.Call, c: Any) -> Any:
    return ev.worley(call, c)


def bricks(ev: Any, call: A.Call, c: Any) -> Any:
    """Bricks; its seed only where the output uses one (``ParamSpec.used_when``). Cell values
    and the row / column indices wrap in a tileable output."""
    from matloom.engine.kernels import patterns

    params = ev.params(call)
    seeded = uses_seed(call)
    if not seeded and params["output"] not in patterns.BRICK_INDEX_OUTPUTS:
        return ev.backend.bricks(c[0], c[1], **{**params, "seed": None})
    kernel = ev.backend.bricks
    period = ev.periods_of(c, call.func)
    wrap = None if period is None else brick_wrap(params, period)
    if wrap is not None:  # tileable cells: the numpy kernel wraps them (both backends)
        kernel = partial(patterns.bricks, wrap=wrap)
    if not seeded:
        return kernel(c[0], c[1], **{**params, "seed": None})
    return per_seed(ev, call, lambda seed: kernel(c[0], c[1], **{**params, "seed": seed}))


def brick_wrap(params: dict[str, Any], period: tuple[float, float]) -> tuple[int, int, int] | None:
    """Bricks' :func:`~matloom.ops.periodic.course_wrap` in a frame of periods ``period``:
    courses are rows (axis "row") or columns."""
    from matloom.ops.periodic import course_wrap

    bw, bh, offset = (float(params[k]) for k in ("brick_width", "brick_height", "offset"))
    if params["axis"] == "row":
        return course_wrap(period[0], period[1], bw, bh, offset)
    return course_wrap(period[1], period[0], bh, bw, offset)


def per_seed(ev: Any, call: A.Call, compute: Callable[[int], Any]) -> Any:
    """``compute(seed)`` for ``call``'s seed (``Evaluator.per_seed``; the sweep's schedule
    stacks it over its seeds instead)."""
    return ev.per_seed(call, compute)


def weave(ev: Any, call: A.Call, c: Any) -> Any:
    """Weave; its seed only for output="thread_value", whose thread indices wrap in a tileable
    output (columns and rows per View period, where they are whole numbers)."""
    fx, fy = ev.freqs(call)
    params = {"freq_x": fx, "freq_y": fy, **ev.params(call, frequency=False)}
    if not uses_seed(call):
        return ev.backend.weave(c[0], c[1], **{**params, "seed": None})
    period = ev.periods_of(c, call.func)
    if period is not None:
        params["wrap"] = weave_wrap(fx, fy, period)
    return per_seed(ev, call, lambda seed: ev.backend.weave(c[0], c[1], **{**params, "seed": seed}))


def weave_wrap(fx: float, fy: float, period: tuple[float, float]) -> tuple[int, int]:
    """Thread columns and rows per period (0 for an axis where they are not a whole number
    that :func:`~matloom.ops.periodic.wraps`)."""
    from matloom.ops.period import whole
    from matloom.ops.periodic import wraps

    out = []
    for n in (fx * period[0], fy * period[1]):
        k = whole(n)
        out.append(int(k) if k is not None and wraps(n) and k > 0 else 0)
    return out[0], out[1]


def fill(ev: Any, call: A.Call, c: Any) -> Any:
    geom = ev.shape(call.arg("shape"))
    mode, feather = ev.num(call, "mode"), ev.num(call, "feather")
    return wrapped_shape(
        ev, call, c, lambda x, y: ev.backend.fill(geom, x, y, mode=mode, feather=feather)
    )


def stroke(ev: Any, call: A.Call, c: Any) -> Any:
    geom = ev.shape(call.arg("shape"))
    width, feather = ev.num(call, "width"), ev.num(call, "feather")
    return wrapped_shape(
        ev, call, c, lambda x, y: ev.backend.stroke(geom, x, y, width=width, feather=feather)
    )


def wrapped_shape(ev: Any, call: A.Call, c: Any, coverage: Callable[[Any, Any], Any]) -> Any:
    """``coverage(x, y)`` of a Fill/Stroke; in a tileable output (an axis-aligned frame with
    the View's periods, :meth:`~matloom.engine.interpret.Evaluator.periods_of`) the maximum
    over the shape's images one period apart that reach the samples, so that a shape crossing
    the View's edge comes back on the opposite side. Every other image is exactly 0 there
    (outside the coverage's support box), so the value does not depend on which samples are
    evaluated together (bands, Tile instances). Inside a Tile motif the instances repeat."""
    period = ev.periods_of(c, call.func)
    if period is None:
        return coverage(c[0], c[1])
    from matloom.ops.periodic import image_shifts

    box, extent = ev.motif_support(call), _extent(c)
    shifts = None if box is None or extent is None else image_shifts(box, period, extent)
    if shifts is None:
        note = f"tileable: a {call.func} many Views wide is not wrapped"
        if box is not None and extent is not None and note not in ev.stats.notes:
            ev.stats.notes.append(note)
        return coverage(c[0], c[1])
    out = coverage(c[0], c[1])
    for sx, sy in shifts[1:]:
        with np.errstate(invalid="ignore"):
            out = np.maximum(out, coverage(c[0] - sx, c[1] - sy))
    return out


def _extent(c: Any) -> tuple[float, float, float, float] | None:
    """(x0, y0, x1, y1): the finite range of the sample coordinates, None when there is none."""
    ranges = []
    for v in (c[0], c[1]):
        a = np.asarray(v)
        finite = a[np.isfinite(a)]
        if finite.size == 0:
            return None
        ranges.append((float(finite.min()), float(finite.max())))
    return ranges[0][0], ranges[1][0], ranges[0][1], ranges[1][1]


def tile(ev: Any, call: A.Call, c: Any) -> Any:
    """Tile: the maximum over the 9 neighbouring instances of the motif evaluated in each
    instance's frame, dropped instances giving 0 (see :mod:`matloom.engine.kernels.tile`).

    Where the motif's support is known (:mod:`matloom.engine.rules.support`: it is exactly 0
    outside a box), each instance evaluates the motif only at the samples whose local
    coordinates fall in the box, and every other instance contributes its exact 0: the same
    values as evaluating all 9 everywhere, for about the cost of the motif's own area."""
    from matloom.engine.kernels.tile import NEIGHBOURS, TileParams

    params = TileParams.of({**ev.params(call), "seed": ev.seed_of(call)})
    period = ev.periods_of(c, call.func)
    if period is not None:
        params = params.tiled(period)
    output = ev.num(call, "output")
    if output != "mask":  # language 3: a value of the instance on top
        from matloom.engine.rules.instancing import tile_output

        return tile_output(ev, call, c, params, output)
    motif = call.arg("expr")
    box = ev.motif_support(motif)
    shape = np.broadcast_shapes(np.shape(c[0]), np.shape(c[1]))
    if box is None:
        out = None
        for dr, dc in NEIGHBOURS:
            lx, ly, keep = ev.backend.tile(c[0], c[1], params, dr, dc)
            value = ev.instance_value(motif, ev.new_frame(lx, ly))
            del lx, ly
            with np.errstate(invalid="ignore"):
                value = np.where(keep, value, 0.0)
                out = value if out is None else np.maximum(out, value)
        return out
    best = np.full(shape, -np.inf)
    flat = best.reshape(-1)
    missed = np.zeros(shape, dtype=np.bool_)  # some instance contributes its exact 0
    for dr, dc in NEIGHBOURS:
        lx, ly, inside = ev.backend.tile(c[0], c[1], params, dr, dc, box)
        missed |= ~inside
        idx = np.flatnonzero(inside)
        if idx.size == 0:
            continue
        points = ev.new_frame(lx.reshape(-1)[idx][None, :], ly.reshape(-1)[idx][None, :])
        value = np.broadcast_to(ev.instance_value(motif, points), (1, idx.size))[0]
        flat[idx] = np.maximum(flat[idx], value)
    with np.errstate(invalid="ignore"):
        return np.where(missed, np.maximum(best, 0.0), best)


def transformed(ev: Any, call: A.Call, c: Any) -> Any:
    """The operand evaluated in the transformed coordinates (see ``Evaluator.transform``)."""
    return ev.eval(call.arg("expr"), ev.transform(call, c))


def turned(values: list[Any]) -> tuple[Any, Any]:
    """A rotation warp's (cos, sin) from its angle's values in degrees (arrays or floats):
    numpy's radians, then the portable cos and sin (the same bits on every CPU)."""
    from matloom.engine.kernels import mathops

    rad = np.radians(values[0])
    return mathops.cos(rad), mathops.sin(rad)


def threshold(value: Any, **params: Any) -> np.ndarray:
    """Threshold's numpy implementation (grid-path rules of ``kernels.threshold``)."""
    return _threshold.threshold(np.asarray(value), **params)


def check_threshold(**params: Any) -> None:
    """Raise the kernel's error for invalid parameters (before Threshold is deferred)."""
    if float(params["transition_width"]) < 0:
        _threshold.threshold(np.zeros(1), **params)


# ------------------------------------------------------------------ geometry
def _values(node: A.Call) -> dict[str, float]:
    return {a.param: float(static_number(a.value) or 0.0) for a in node.args}


def _positional(node: A.Call) -> list[float]:
    return [float(static_number(a.value) or 0.0) for a in node.args]


def rect(ev: Any, node: A.Call) -> shapes.Shape:
    v = _values(node)
    return shapes.make_rect(v["x"], v["y"], v["width"], v["height"], v.get("radius", 0.0))


def ellipse(ev: Any, node: A.Call) -> shapes.Shape:
    v = _values(node)
    return shapes.EllipseGeom(v["cx"], v["cy"], v["rx"], v["ry"])


def path(ev: Any, node: A.Call) -> shapes.Shape:
    v = _values(node)
    segments = tuple(ev.shape(s) for s in node.extra)
    return shapes.PathGeom(v["start_x"], v["start_y"], segments)


def line_to(ev: Any, node: A.Call) -> Any:
    return shapes.LineSeg(*_positional(node))


def cubic_to(ev: Any, node: A.Call) -> Any:
    return shapes.CubicSeg(*_positional(node))
