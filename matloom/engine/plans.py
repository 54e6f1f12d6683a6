"""Reuse of compiled register programs across evaluations of the same program.

:func:`matloom.engine.schedules.banded.compile_layers` turns the channel values of a band (trees of
:class:`~matloom.engine.lazy.Lazy` operations over leaf arrays and constants) into a register
program. Evaluating the same program again at the same size gives trees of the same *structure*
with new leaf arrays (other seeds, other views). :func:`signature` describes that structure --
operations, dtypes, shapes, the exact constants, which nodes are shared -- and lists the leaves in
a fixed order, so a program compiled once is rebound to new leaves instead of compiled again
(about 1 ms of Python per band, most of a 256x256 evaluation's overhead).
"""

from __future__ import annotations

from collections import OrderedDict
from collections.abc import Hashable
from dataclasses import dataclass
from typing import Any

import numpy as np

from matloom.engine.lazy import Lazy, is_scalar

#: Compiled programs kept (least recently used dropped first).
MAX_PLANS = 32


def _layer_values(layer: Any) -> list[Any]:
    """Every channel value of a layer in a fixed order."""
    return [layer.alpha, layer.height, *layer.blended_values()]


def signature(layers: list[Any], shape: tuple[int, ...]) -> tuple[Hashable, list[Any]]:
    """(structural key, leaves in visiting order) of the layers' channel values."""
    leaves: list[Any] = []
    seen: dict[int, int] = {}
    keep: list[Any] = []  # keeps visited objects alive so that their ids stay unique

    def token(value: Any) -> Hashable:
        if is_scalar(value):
            array = np.asarray(value)
            return ("s", array.dtype.str, array.tobytes(), type(value).__name__)
        key = id(value)
        if key in seen:
            return ("ref", seen[key])
        seen[key] = len(seen)
        keep.append(value)
        if isinstance(value, Lazy):
            children = tuple(token(a) for a in value.args)
            return ("L", value.op, value.dtype.str, value.shape, children, value.params)
        array = np.asarray(value)  # a deferred field is resolved by now
        leaves.append(value)
        return ("A", array.dtype.str, array.shape)

    key = (tuple(shape), tuple(tuple(token(v) for v in _layer_values(ly)) for ly in layers))
    keep.clear()
    token = None  # type: ignore[assignment]  # break the closure's self-reference (no cycle)
    return key, leaves


def leaf_array(value: Any, shape: tuple[int, ...]) -> np.ndarray:
    """A leaf as the kernel reads it: contiguous (S|1, H|1, W|1)."""
    array = np.asarray(value)
    np.broadcast_shapes(array.shape, shape)
    return np.ascontiguousarray(array.reshape((1,) * (3 - array.ndim) + array.shape))


@dataclass(frozen=True)
class Plan:
    """A compiled program minus its leaves: which visited leaf goes to which leaf slot."""

    program: Any  # FusedProgram with its leaf lists emptied
    slots64: tuple[int, ...]
    slots32: tuple[int, ...]

    def bind(self, leaves: list[Any], shape: tuple[int, ...]) -> Any:
        from dataclasses import replace

        return replace(
            self.program,
            leaves64=[leaf_array(leaves[i], shape) for i in self.slots64],
            leaves32=[leaf_array(leaves[i], shape) for i in self.slots32],
        )


class PlanCache:
    """Least-recently-used store of :class:`Plan` by structural key."""

    def __init__(self, size: int = MAX_PLANS) -> None:
        self.size = size
        self.plans: OrderedDict[Hashable, Plan] = OrderedDict()

    def get(self, key: Hashable) -> Plan | None:
        plan = self.plans.get(key)
        if plan is not None:
            self.plans.move_to_end(key)
        return plan

    def put(self, key: Hashable, plan: Plan) -> None:
        self.plans[key] = plan
        self.plans.move_to_end(key)
        while len(self.plans) > self.size:
            self.plans.popitem(last=False)
