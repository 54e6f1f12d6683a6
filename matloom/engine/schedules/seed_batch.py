"""The seed-batched schedule: many seed variants of one program evaluated at once.

Seed variants are seed *assignments* applied during evaluation (no variant is re-parsed). A chunk
of candidates is evaluated with a leading seed axis: every seeded fBm / Worley is one
seed-batched kernel call per chunk, every other operation runs once per chunk on the batched
arrays (numpy broadcasting), and every sub-expression that depends on no seed is evaluated once
per sweep and reused by every chunk (:class:`SweepEvaluator`). The chunk's channel values are then
compiled for the fused compositing kernel (:func:`chunk_program`).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from matloom.engine.cull import resolve
from matloom.engine.interpret import layer_fields
from matloom.engine.lazy import LazyEvaluator, defer_fbm
from matloom.lang import ast as A
from matloom.lang.cost import field_params
from matloom.lang.seeds import uses_seed


def seeded_nodes(program: A.Program) -> set[int]:
    """ids of the nodes whose value depends on a noise seed (through Defines too)."""
    dep_defs: set[str] = set()
    out: set[int] = set()

    def visit(node: A.Node) -> bool:
        kids = [visit(ch) for ch in A.children(node)]
        dep = any(kids)
        if isinstance(node, A.Call) and node.arg("seed") is not None and uses_seed(node):
            dep = True
        if isinstance(node, A.Ref) and node.name in dep_defs:
            dep = True
        if dep:
            out.add(id(node))
        return dep

    for d in program.defines:
        if visit(d.expr):
            dep_defs.add(d.name)
    for _, e in A.program_expressions(program):
        visit(e)
    return out


class SweepEvaluator(LazyEvaluator):
    """Evaluates one chunk of candidates at once (leading seed axis on seeded values);
    seed-free values persist across chunks."""

    def __init__(
        self,
        program: A.Program,
        x: np.ndarray,
        y: np.ndarray,
        backend: Any,
        *,
        periods: tuple[float, float] | None = None,
    ) -> None:
        super().__init__(program, x, y, backend, periods=periods)
        self.seeded = seeded_nodes(program)
        self.persistent: dict[tuple[int, int], Any] = {}
        self.seed_maps: list[dict[int, int]] = [{}]

    def begin_chunk(self, seed_maps: list[dict[int, int]]) -> None:
        self.seed_maps = seed_maps
        self.memo.clear()
        self.materialised.clear()

    def eval(self, node: A.Node, c: Any) -> Any:
        if id(node) in self.seeded or isinstance(node, A.Num | A.Const):
            return super().eval(node, c)
        key = (id(node), self._frame_id(c))
        if key not in self.persistent:
            self.persistent[key] = super().eval(node, c)
        return self.persistent[key]

    def transform(self, call: A.Call, c: Any) -> Any:
        if any(id(call.arg(name)) in self.seeded for name in field_params(call)):
            raise _unsupported("a domain warp by a seeded field")
        key = (id(call), -1 - self._frame_id(c))
        if key not in self.persistent:
            self.persistent[key] = super().transform(call, c)
        return self.persistent[key]

    def seed_of(self, call: A.Call) -> int:
        """The one seed of ``call`` in this chunk (a primitive that cannot batch seeds, such as
        Tile's instances, makes the chunk unsupported when its seed varies)."""
        seed = super().seed_of(call)
        seeds = {m.get(seed, seed) for m in self.seed_maps}
        if len(seeds) > 1:
            raise _unsupported(f"{call.func} with a varying seed")
        return seeds.pop()

    def per_seed(self, call: A.Call, compute: Callable[[int], Any]) -> np.ndarray:
        """A seeded primitive without a seed-batch kernel (Bricks' cell values, see
        ``ops.fields``): ``compute(seed)`` for each of the chunk's seeds, float32 (S, ...) like
        the noise batches."""
        seed = self.num(call, "seed")
        seeds = [m.get(seed, seed) for m in self.seed_maps]
        first = np.asarray(compute(seeds[0]))
        out = np.empty((len(seeds), *first.shape), dtype=np.float32)
        out[0] = first
        for s, value in enumerate(seeds[1:], 1):
            out[s] = compute(value)
        return out

    def batch_seeds(self, call: A.Call) -> list[int]:
        """The chunk's seeds of ``call`` (one per candidate), for a primitive whose kernel takes
        them all at once (Hash, see ``ops.fields_math``; its operands may be batched too)."""
        seed = self.num(call, "seed")
        return [m.get(seed, seed) for m in self.seed_maps]

    def batch_args(self, call: A.Call, c: Any = None) -> dict[str, Any]:
        """The noise kernel's keywords with the chunk's seeds instead of the seed."""
        kw = self.noise_args(call, c)
        seed = kw.pop("seed")
        kw["seeds"] = [m.get(seed, seed) for m in self.seed_maps]
        return kw

    def worley(self, call: A.Call, c: Any) -> Any:
        return self.backend.worley_seed_batch(c[0], c[1], **self.batch_args(call, c))

    def fbm(self, call: A.Call, c: Any) -> Any:
        kw = self.batch_args(call, c)
        if self.backend.fbm_masked is None:  # its seed batch takes no mask
            return self.backend.fbm_seed_batch(c[0], c[1], **kw)

        batch = self.backend.fbm_seed_batch  # no reference to self (no cycle)

        def compute(mask: np.ndarray | None) -> np.ndarray:
            return batch(c[0], c[1], mask=mask, **kw)

        # the batch kernel skips a masked pixel at no cost: mask unless every pixel is needed
        return defer_fbm(compute, c[0], c[1], kw, seeds=len(kw["seeds"]), full_share=1.0)


def _unsupported(what: str) -> Exception:
    """The fused path's UnsupportedProgram: the sweep previews such variants one by one."""
    from matloom.engine.schedules import banded

    return banded.UnsupportedProgram(f"seed batches cannot take {what}")


def chunk_program(ev: SweepEvaluator, seed_maps: list[dict[int, int]], size: int) -> Any:
    """Evaluate one chunk of candidates and compile its layers for the compositing kernel: a
    :class:`~matloom.engine.schedules.banded.FusedProgram` (raises ``fused.UnsupportedProgram`` when the
    kernel cannot take the program). Imports the numba kernels on first use."""
    from matloom.engine.schedules import banded as fused

    ev.begin_chunk(seed_maps)
    with np.errstate(all="ignore"):
        layers = [layer_fields(ev, layer) for layer in ev.program.layers]
        resolve(layers, (size, size), ev.concrete)
        return fused.compile_layers(layers, (size, size))
