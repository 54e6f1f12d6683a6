"""Seed sweep: render the original program and K seed variants as previews, score, keep the best.

Fast the way a graphics engineer would do it:

* the program is parsed once; variants are seed *assignments* applied during evaluation, so no
  variant is ever re-parsed (the variant text is produced only for the winners);
* every sub-expression that depends on no noise seed (Bricks, shapes, constants, transforms of
  coordinates) is evaluated once per sweep and reused by every candidate;
* seeded fBm fields are computed for a whole chunk of candidates at once with the backend's
  seed-batched kernel, which shares all seed-independent lattice work between seeds;
* candidates are split over ``jobs`` worker processes.
"""

from __future__ import annotations

import heapq
import math
import os
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from matloom.engine.backends import get_backend
from matloom.engine.composite import composite
from matloom.engine.evaluate import Coords, Evaluator, Field, layer_fields, prepare
from matloom.engine.grid import sample_axes
from matloom.engine.maps import View
from matloom.lang import ast as A
from matloom.lang.printer import format_program
from matloom.lang.seeds import apply_seed_map, seed_assignments, seed_literal_spans
from matloom.render.preview import shade

Progress = Callable[[int, int], None]
CHUNK = 32


@dataclass
class SweepCandidate:
    index: int  # 0 = the original program
    program: str
    score: float | None = None


@dataclass
class SweepResult:
    candidates: list[SweepCandidate]
    best_index: int
    best_program: str
    seconds: float
    rate: float  # candidates per second
    n_candidates: int = 0
    seed_free: bool = False
    top_images: list[tuple[int, np.ndarray]] = field(default_factory=list)
    message: str = ""


def seeded_nodes(program: A.Program) -> set[int]:
    """ids of the nodes whose value depends on a noise seed (through Defines too)."""
    dep_defs: set[str] = set()
    out: set[int] = set()

    def visit(node: A.Node) -> bool:
        kids = [visit(ch) for ch in A.children(node)]
        dep = any(kids)
        if isinstance(node, A.Call) and node.arg("seed") is not None:
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


class SweepEvaluator(Evaluator):
    """An :class:`Evaluator` reused across candidates: seed-free values persist, seeds are mapped."""

    def __init__(self, program: A.Program, x: np.ndarray, y: np.ndarray, backend_name: str) -> None:
        super().__init__(program, x, y, get_backend(backend_name))
        self.seeded = seeded_nodes(program)
        self.persistent: dict[tuple[int, int], Any] = {}
        self.batch: dict[tuple[int, int], np.ndarray] = {}
        self.chunk_maps: list[dict[int, int]] = [{}]
        self.slot = 0

    def begin_chunk(self, maps: list[dict[int, int]]) -> None:
        self.chunk_maps = maps
        self.batch.clear()

    def begin_candidate(self, slot: int) -> None:
        self.slot = slot
        self.memo.clear()

    def eval(self, node: A.Node, c: Coords) -> Field:
        if id(node) in self.seeded or isinstance(node, A.Num | A.Const):
            return super().eval(node, c)
        key = (id(node), self._frame_id(c))
        if key not in self.persistent:
            self.persistent[key] = super().eval(node, c)
        return self.persistent[key]

    def transform(self, call: A.Call, c: Coords) -> Coords:
        key = (id(call), -1 - self._frame_id(c))
        if key not in self.persistent:
            self.persistent[key] = super().transform(call, c)
        return self.persistent[key]

    def noise(self, call: A.Call, c: Coords) -> Field:
        seed = self.num(call, "seed")
        if call.func != "fBm":
            new = self.chunk_maps[self.slot].get(seed, seed)
            return self._noise_with_seed(call, c, new)
        key = (id(call), self._frame_id(c))
        if key not in self.batch:
            seeds = [m.get(seed, seed) for m in self.chunk_maps]
            fx, fy = self.freqs(call)
            self.batch[key] = self.backend.fbm_seed_batch(
                c[0], c[1], octaves=self.num(call, "octaves"),
                lacunarity=self.num(call, "lacunarity"), gain=self.num(call, "gain"),
                freq_x=fx, freq_y=fy, to_01=bool(self.num(call, "to_01")), seeds=seeds)
        return self.batch[key][self.slot]

    def _noise_with_seed(self, call: A.Call, c: Coords, seed: int) -> Field:
        fx, fy = self.freqs(call)
        return self.backend.worley(
            c[0], c[1], distance=self.num(call, "distance"),
            combination=self.num(call, "combination"), freq_x=fx, freq_y=fy,
            to_01=bool(self.num(call, "to_01")), seed=seed)


def _render_shard(text: str, maps: list[dict[int, int]], indices: list[int], size: int,
                  backend: str, keep: int, scorer_name: str | None, prompt: str | None,
                  progress: Progress | None = None) -> tuple[list[tuple[int, float | None]], list]:
    """Render (and score) the candidates ``indices``; ``maps[i]`` is candidate i's seed map."""
    program = prepare(text)
    view = View(*program.view_tuple)
    x, y = sample_axes(view, size, size)
    ev = SweepEvaluator(program, x, y, backend)
    scorer = _get_scorer(scorer_name) if scorer_name else None
    results: list[tuple[int, float | None]] = []
    heap: list[tuple[float, int, np.ndarray]] = []
    done = 0
    for start in range(0, len(indices), CHUNK):
        chunk = indices[start : start + CHUNK]
        ev.begin_chunk([maps[i] for i in chunk])
        images = []
        for slot in range(len(chunk)):
            ev.begin_candidate(slot)
            with np.errstate(all="ignore"):
                raws = [layer_fields(ev, layer) for layer in program.layers]
                images.append(shade(composite(raws, size, size, view)))
        scores = scorer.score(images, prompt or "") if scorer else [None] * len(chunk)
        for i, img, s in zip(chunk, images, scores, strict=True):
            value = None if s is None else float(s)
            results.append((i, value))
            rank = -i if value is None else value
            item = (rank, -i, img)
            if len(heap) < keep:
                heapq.heappush(heap, item)
            elif item[:2] > heap[0][:2]:
                heapq.heapreplace(heap, item)
        done += len(chunk)
        if progress:
            progress(done, len(indices))
    top = [(-neg_i, img) for _, neg_i, img in sorted(heap, key=lambda t: t[:2], reverse=True)]
    return results, top


def _get_scorer(name: str) -> Any:
    from matloom.author.scorers.base import get_scorer

    return get_scorer(name)


def _worker(args: tuple) -> tuple[list[tuple[int, float | None]], list]:
    try:
        import numba

        numba.set_num_threads(1)
    except (ImportError, ValueError):
        pass
    return _render_shard(*args)


def run_sweep(
    program_text: str,
    *,
    variants: int,
    size: int = 256,
    scorer: Any = None,
    prompt: str | None = None,
    seed: int = 0,
    jobs: int = 0,
    keep: int = 8,
    backend: str = "auto",
    progress: Progress | None = None,
) -> SweepResult:
    """Render the original and ``variants`` seed variants; score them when a scorer is given.

    ``scorer`` is a registered scorer name (or an object with ``.name``); ``jobs`` = 0 uses all
    cores. The winner is the highest score (ties to the earliest); without a scorer it is the
    original. Same ``seed`` -> same variants and same winner.
    """
    t0 = time.perf_counter()
    text = format_program(prepare(program_text))
    spans = seed_literal_spans(text)
    maps = [{}] + seed_assignments(text, variants, seed)
    message = ""
    if len(maps) == 1:
        message = ("no field depends on a noise seed: the sweep has a single candidate"
                   if not spans else "no variants requested: only the original is rendered")
    scorer_name = getattr(scorer, "name", scorer)
    n = len(maps)
    jobs = jobs or (os.cpu_count() or 1)
    jobs = max(1, min(jobs, math.ceil(n / CHUNK)))
    if jobs == 1:
        results, top = _render_shard(text, maps, list(range(n)), size, backend, keep,
                                     scorer_name, prompt, progress)
    else:
        results, top = _parallel(text, maps, n, size, backend, keep, scorer_name, prompt, jobs,
                                 progress)
    results.sort()
    scored = [s for _, s in results if s is not None]
    best = 0
    if scored:
        best = max(range(n), key=lambda i: (results[i][1], -i))
    cands = [SweepCandidate(i, "", s) for i, s in results]
    best_program = apply_seed_map(text, maps[best], spans)
    cands[best].program = best_program
    cands[0].program = text
    secs = time.perf_counter() - t0
    return SweepResult(cands, best, best_program, secs, n / secs if secs else 0.0, n,
                       seed_free=not spans, top_images=top, message=message)


def _parallel(text: str, maps: list[dict[int, int]], n: int, size: int, backend: str, keep: int,
              scorer_name: str | None, prompt: str | None, jobs: int,
              progress: Progress | None) -> tuple[list, list]:
    import multiprocessing as mp
    from concurrent.futures import ProcessPoolExecutor, as_completed

    shards = [list(range(k, n, jobs)) for k in range(jobs)]
    ctx = mp.get_context("forkserver")
    ctx.set_forkserver_preload(["matloom.render.sweep"])
    results: list = []
    tops: list = []
    done = 0
    with ProcessPoolExecutor(max_workers=jobs, mp_context=ctx) as pool:
        futs = [pool.submit(_worker, (text, maps, s, size, backend, keep, scorer_name, prompt))
                for s in shards]
        for fut in as_completed(futs):
            r, t = fut.result()
            results.extend(r)
            tops.extend(t)
            done += len(r)
            if progress:
                progress(done, n)
    score_of = dict(results)
    tops.sort(key=lambda it: ((score_of[it[0]] if score_of[it[0]] is not None else -it[0]), -it[0]),
              reverse=True)
    return results, tops[:keep]


def variant_program(text: str, index: int, variants: int, seed: int = 0) -> str:
    """Text of candidate ``index`` of a sweep (0 = original) without rendering anything."""
    maps: Sequence[dict[int, int]] = [{}] + seed_assignments(text, variants, seed)
    return apply_seed_map(text, maps[index])
