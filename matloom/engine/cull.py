"""Coverage culling: compute a noise field only where some layer can see it.

In the fused path (:mod:`matloom.engine.schedules.banded`) the fBm fields of a band are *deferred*
(:class:`DeferredField`) while the layers' channels are evaluated. :func:`resolve` then looks at
how each deferred field is used:

* in an **alpha** channel (or anywhere its value is needed in full, e.g. under ``Sin``): computed
  everywhere;
* in a **height** channel of layer l: needed where that layer's clamped alpha is > 0 (the height
  rule ignores layers that do not cover a texel);
* in any **other channel** of layer l: needed where that layer's visible coverage
  ``V_l = alpha_l * prod(1 - alpha_above)`` is not 0, because compositing adds ``V_l * value``.

Elsewhere the field holds a placeholder (0, inside every fBm range). That is exact only if the
channel value built from the placeholder is a finite number, since ``0 * x`` is 0 for finite x
but NaN for inf/NaN. :func:`channel_bounds` proves this with interval arithmetic over the channel
expression (the deferred fields' ranges, the other leaves' finite min/max, the constants); a use
it cannot prove safe makes the field computed everywhere. So the maps are bit-identical to the
unculled evaluation (tests/engine/test_cull.py compares every fixture program and random ones).

For the paper's tile program the grout noise is only computed in the mortar lines and the glaze
noises only on the tiles: about a third of the noise work at any size. The masks are themselves
work (every alpha above the field's layer materialised with numpy): when they would take more
than :data:`MASK_OPS_PER_OCTAVE` passes per octave they could save, the fields are computed in
full instead.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from typing import Any

import numpy as np

from matloom.engine.lazy import OP_OF, DeferredField, Lazy, shape_of
from matloom.ops import Bounds

#: Channel bounds beyond this magnitude count as unsafe (float32 rounding overflows at 3.4e38).
BOUND_LIMIT = 1e37
#: Build the coverage masks only when their alphas need at most this many element-wise numpy
#: passes per octave of the fields they would cull (``benchmarks/library_entries.py``, both ways
#: alternating on the 169 library entries above 4: 12 saved the most; a persian rug whose masks
#: take 354 passes for 10 octaves went from 0.95 to 0.21 s at 512). Either way the maps are the
#: same: culling only skips work.
MASK_OPS_PER_OCTAVE = 12
#: Compute a field everywhere when it is needed on more than this share of the band (the dense
#: kernels beat the masked ones above it); a field can set its own (``DeferredField.full_share``).
FULL_SHARE = 0.85


@dataclass
class CullStats:
    """Texels of deferred fields computed vs deferred (for reports and tests)."""

    deferred_texels: int = 0
    computed_texels: int = 0


def nodes(value: Any, seen: set[int] | None = None) -> Iterator[Any]:
    """Every node of a channel value (Lazy nodes and their operands), once, depth first."""
    seen = set() if seen is None else seen
    if id(value) in seen:
        return
    seen.add(id(value))
    yield value
    if isinstance(value, Lazy):
        for arg in value.args:
            yield from nodes(arg, seen)


def leaves(value: Any, seen: set[int] | None = None) -> Iterator[Any]:
    """Every non-Lazy operand (arrays, scalars, deferred fields) of a channel value, once."""
    return (v for v in nodes(value, seen) if not isinstance(v, Lazy))


def _array_bounds(array: np.ndarray) -> Bounds:
    if array.size == 0:
        return (0.0, 0.0)
    lo, hi = float(np.min(array)), float(np.max(array))  # NaN in -> NaN out
    if not (math.isfinite(lo) and math.isfinite(hi)):
        return None
    return (lo, hi)


def channel_bounds(value: Any, memo: dict[int, Bounds]) -> Bounds:
    """Interval of a channel value over all texels, treating deferred fields as their range.

    None when the value may be NaN or beyond ``BOUND_LIMIT`` anywhere (then culling a field
    used by it is not proven exact). ``memo`` caches shared sub-expressions and leaves.
    """
    key = id(value)
    if key in memo:
        return memo[key]
    result: Bounds
    if isinstance(value, DeferredField):
        result = (value.lo, value.hi) if value.finite_coords else None
    elif isinstance(value, Lazy):  # the op's bounds rule (ops)
        args = [channel_bounds(a, memo) for a in value.args]
        if any(a is None for a in args):
            result = None
        else:
            result = OP_OF[value.op].bounds(*args, **dict(value.params))
    else:
        result = _array_bounds(np.asarray(value, dtype=np.float64))
    if result is not None and not (abs(result[0]) <= BOUND_LIMIT and abs(result[1]) <= BOUND_LIMIT):
        result = None
    memo[key] = result
    return result


def _mask_ops(layers: list[Any]) -> int:
    """Element-wise operations the numpy masks of ``layers`` materialise (their alphas' Lazy
    nodes, each shared node once)."""
    seen: set[int] = set()
    return sum(isinstance(v, Lazy) for layer in layers for v in nodes(layer.alpha, seen))


def _deferred_in(value: Any) -> list[DeferredField]:
    return [v for v in leaves(value) if isinstance(v, DeferredField) and v.array is None]


def _visibility_masks(
    layers: list[Any],
    shape: tuple[int, ...],
    concrete: Callable[[Any], Any],
    want_weight: set[int],
    want_alpha: set[int],
) -> tuple[dict[int, np.ndarray], dict[int, np.ndarray]]:
    """Boolean masks ``V_l != 0`` (layers in ``want_weight``) and ``a_l > 0`` (``want_alpha``)
    with a_l and V_l in float32 as the compositing kernel has them: a = clip(float32(alpha),
    0, 1), V = a * running, running *= 1 - a, top layer first. Only the running product and
    one layer's values are alive at a time (bands are large; memory is part of the budget)."""
    visible: dict[int, np.ndarray] = {}
    covers: dict[int, np.ndarray] = {}
    running: Any = np.float32(1)
    lowest = min(want_weight | want_alpha)
    for index in range(len(layers) - 1, lowest - 1, -1):
        raw = np.asarray(concrete(layers[index].alpha), dtype=np.float64)
        a = np.clip(raw.astype(np.float32), np.float32(0), np.float32(1))
        if index in want_weight:
            visible[index] = np.broadcast_to((a * running) != 0, shape)  # NaN counts as visible
        if index in want_alpha:
            covers[index] = np.broadcast_to(a > 0, shape)
        if index > lowest:
            running = running * (np.float32(1) - a)
    return visible, covers


def resolve(layers: list[Any], shape: tuple[int, ...], concrete: Callable[[Any], Any]) -> CullStats:
    """Compute every deferred field of the band's ``layers`` where it is needed (see the module
    docstring). ``concrete`` materialises a Lazy value with numpy (for the alpha channels)."""
    stats = CullStats()
    gated: dict[int, list[int]] = {}  # field id -> layers whose coverage gates it
    height_of: dict[int, list[int]] = {}  # field id -> layers whose alpha gates it
    fields: dict[int, DeferredField] = {}
    memo: dict[int, Bounds] = {}
    for index, layer in enumerate(layers):
        for f in _deferred_in(layer.alpha):
            f.full()
        for value in layer.blended_values():
            found = _deferred_in(value)
            if found and channel_bounds(value, memo) is None:
                for f in found:
                    f.full()  # not provably exact when culled
                continue
            for f in found:
                fields[id(f)] = f
                gated.setdefault(id(f), []).append(index)
        for f in _deferred_in(layer.height):
            fields[id(f)] = f
            height_of.setdefault(id(f), []).append(index)
    pending = [f for f in fields.values() if f.array is None]
    if any(len(shape_of(layer.alpha)) > len(shape) for layer in layers):
        pending = []  # coverage differs per seed (sweeps): not worth a mask per candidate
    if pending:
        lowest = min(i for f in pending for i in gated.get(id(f), []) + height_of.get(id(f), []))
        if _mask_ops(layers[lowest:]) > MASK_OPS_PER_OCTAVE * sum(f.octaves for f in pending):
            pending = []  # the masks would cost more than culling can save: computed in full
    if pending:
        visible, covers = _visibility_masks(
            layers,
            shape,
            concrete,
            {i for f in pending for i in gated.get(id(f), [])},
            {i for f in pending for i in height_of.get(id(f), [])},
        )
        for f in pending:
            if f.array is not None:
                continue
            need = np.zeros(shape, np.bool_)
            for index in gated.get(id(f), []):
                need |= visible[index]
            for index in height_of.get(id(f), []):
                need |= covers[index]
            share = float(np.count_nonzero(need)) / max(need.size, 1)
            dense = share > (FULL_SHARE if f.full_share is None else f.full_share)
            f.array = f.compute(None if dense else need)
            stats.deferred_texels += need.size
            stats.computed_texels += need.size if dense else int(share * need.size)
    for f in fields.values():
        f.full()
    return stats
