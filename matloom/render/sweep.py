"""Seed sweep: render the original program and K seed variants as previews, score, keep the best.

Made fast the way a graphics engineer would:

* the program is parsed once; variants are seed *assignments* applied during evaluation, so no
  variant is ever re-parsed (the variant text is produced only for the winners);
* every sub-expression that depends on no noise seed (Bricks, shapes, constants, transforms of
  coordinates) is evaluated once per sweep and reused by every candidate
  (:class:`~matloom.engine.schedules.seed_batch.SweepEvaluator`);
* the candidates are evaluated in chunks with a leading seed axis: each seeded fBm / Worley is
  one seed-batched kernel call per chunk, and every other operation runs once per chunk on the
  batched arrays (numpy broadcasting), so the Python work is per chunk, not per candidate;
* per candidate only two compiled kernels run: the fused arithmetic + compositing kernel in its
  preview mode and a fused normals + AO + shading kernel; candidates are shaded on ``jobs``
  threads (the kernels release the GIL), with no worker processes to start.

Previews may differ from :func:`matloom.preview` by one 8-bit level at a few texels (float32
seed-batched noise, table-based sRGB conversions, float32 shading); the sweep ranks candidates,
the winner's maps are then rendered by the exact engine.
"""

from __future__ import annotations

import heapq
import os
import threading
import time
from collections.abc import Callable, Sequence
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from matloom.engine.ops import OPS
from matloom.engine.schedules.seed_batch import seeded_nodes
from matloom.lang import ast as A
from matloom.lang.printer import format_program
from matloom.lang.seeds import apply_seed_map, seed_assignments, seed_literal_spans

Progress = Callable[[int, int], None]
#: Upper bound of candidates per chunk (larger chunks amortise the noise lattice work).
MAX_CHUNK = 128
#: Bytes the seed-batched fields of one chunk may take (sets the chunk size).
CHUNK_BUDGET_BYTES = 128 << 20


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


@dataclass
class _Renderer:
    """Everything fixed for a sweep: program, grid, kernels' constant inputs, thread buffers."""

    program: A.Program
    size: int
    jobs: int
    evaluator: Any = None
    shade_args: tuple[Any, ...] = ()
    local: threading.local = field(default_factory=threading.local)

    def __post_init__(self) -> None:
        from matloom.engine.backends import get_backend
        from matloom.engine.grid import sample_axes
        from matloom.engine.kernels import preview_numba, relief_numba
        from matloom.engine.maps import View
        from matloom.engine.schedules import banded as fused
        from matloom.engine.schedules.seed_batch import SweepEvaluator
        from matloom.render.preview import _light_and_half_vectors

        view = View(*self.program.view_tuple, tileable=self.program.tileable)
        x, y = sample_axes(view, self.size, self.size)
        numba = get_backend("numba")
        self.evaluator = SweepEvaluator(self.program, x, y, numba, periods=view.periods)
        dx, dy = view.texel_size(self.size, self.size)
        wx, div_x = relief_numba._tap_weights(8.0) or (np.ones(17, np.float32), np.float32(17))
        light, half = _light_and_half_vectors(None)
        spacing = np.array([dx, 2.0 * dx, dy, 2.0 * dy], dtype=np.float32)
        self.shade_args = (
            spacing,
            wx,
            div_x,
            wx,
            div_x,
            np.float32(8.0 * dx),
            light.astype(np.float32),
            half.astype(np.float32),
            preview_numba.encode_coefficients(),
        )
        fused.decode_luts()  # built once here, before the shading threads use them

    def chunk_program(self, seed_maps: list[dict[int, int]]) -> Any:
        """Evaluate one chunk and compile its layers for the compositing kernel."""
        from matloom.engine.schedules.seed_batch import chunk_program

        return chunk_program(self.evaluator, seed_maps, self.size)

    def prepare_chunk(self, seed_maps: list[dict[int, int]]) -> Any:
        """The compiled chunk program, or None when the fused kernel cannot take the program
        (see :class:`fused.UnsupportedProgram`; its variants are then previewed one by one with
        the exact engine). Runs on the preparation thread, one chunk ahead of the shading."""
        from matloom.engine.schedules import banded as fused

        try:
            return self.chunk_program(seed_maps)
        except fused.UnsupportedProgram:
            return None

    def render_prepared(
        self, prog: Any, seed_maps: list[dict[int, int]], pool: ThreadPoolExecutor
    ) -> list[np.ndarray]:
        """Previews of one prepared chunk of candidates, shaded on ``pool``."""
        if prog is None:
            return [self.exact_preview(m) for m in seed_maps]
        return list(pool.map(lambda cand: self.render(prog, cand), range(len(seed_maps))))

    def exact_preview(self, seed_map: dict[int, int]) -> np.ndarray:
        """The exact engine's preview of one variant (fallback path)."""
        from matloom.lang.printer import format_program as fmt
        from matloom.render.api import preview

        text = apply_seed_map(fmt(self.program), seed_map)
        return preview(text, self.size, backend="numba")

    def render(self, prog: Any, cand: int) -> np.ndarray:
        """Preview of candidate ``cand`` of the chunk program ``prog`` (runs on any thread)."""
        from matloom.engine.kernels import composite_numba, preview_numba
        from matloom.engine.schedules import banded as fused

        buffers = getattr(self.local, "buffers", None)
        if buffers is None:
            n = self.size
            buffers = (
                np.zeros((composite_numba.N_PLANES, n, n), np.float32),  # every plane, colours too
                np.zeros((n, n), np.uint8),
                np.empty((n, n), np.float32),
                np.zeros((1, 1, 3), np.float32),
            )
            self.local.buffers = buffers
        planes, flags, mean, dummy = buffers
        colours = (dummy,) * len(composite_numba.COLOUR_OUTPUT_PLANES)  # planar: not written
        # Reused buffers (zeroed=True): a channel no layer writes is never anything but 0 (where
        # a NaN coverage makes the kernel write it, the coverage is NaN too and 0 is written),
        # so the zeros of the first allocation need not be written again.
        args = fused.kernel_args(prog, planes, colours, flags, cand=cand, margin=-1.0)
        composite_numba.composite_rows(args, 0, self.size)
        image = np.empty((self.size, self.size, 3), np.uint8)
        preview_numba.relief_shade(planes, *self.shade_args, mean, image)
        return image


@dataclass
class _ExactRenderer:
    """Fallback without numba: every variant is previewed by the (numpy) engine."""

    program: A.Program
    size: int

    def prepare_chunk(self, seed_maps: list[dict[int, int]]) -> None:
        del seed_maps

    def render_prepared(
        self, prog: None, seed_maps: list[dict[int, int]], pool: Any
    ) -> list[np.ndarray]:
        del prog, pool
        from matloom.render.api import preview

        text = format_program(self.program)
        return [preview(apply_seed_map(text, m), self.size) for m in seed_maps]


def _chunk_size(program: A.Program, size: int) -> int:
    """Candidates per chunk: as many as the seed-batched fields fit in the budget (float32
    noise per seeded call, plus about four float64 arrays for each seeded primitive that runs
    in numpy on the batch, e.g. Threshold and its temporaries)."""
    seeded = seeded_nodes(program)
    noise = fields = 0
    for _, expr in A.program_expressions(program):
        for node in A.walk(expr):
            if isinstance(node, A.Call) and id(node) in seeded:
                noise += node.arg("seed") is not None
                fields += OPS[node.func].materialised
    per_candidate = max(1, 4 * noise + 32 * fields) * size * size
    return int(max(8, min(MAX_CHUNK, CHUNK_BUDGET_BYTES // per_candidate)))


def check_sweep(program: A.Program, size: int, jobs: int, candidates: int) -> int:
    """Check the sweep against the engine's limits before any work (size, evaluation work,
    memory: a chunk of seed-batched candidates evaluated at once on the whole image, plus the
    shading threads' buffers); returns the chunk size, made smaller than :func:`_chunk_size`
    when the memory estimate of that chunk exceeds the budget. Raises ``LimitError``."""
    from matloom.engine.limits import Usage, check_size, fit_seed_batch

    check_size(size, size)
    chunk = min(_chunk_size(program, size), max(candidates, 1))
    batched = frozenset(seeded_nodes(program))
    # a thread pool starts threads (each with its buffers) only for tasks that wait: at most
    # one per candidate of a chunk
    usage = Usage(seed_batch=chunk, threads=min(jobs, chunk), batched=batched)
    return fit_seed_batch(program, size, size, usage)


def _render_all(
    text: str,
    maps: list[dict[int, int]],
    size: int,
    jobs: int,
    keep: int,
    scorer: Any,
    prompt: str | None,
    progress: Progress | None,
) -> tuple[list[tuple[int, float | None]], list]:
    """Render (and score) every candidate; ``maps[i]`` is candidate i's seed map."""
    from matloom.engine.evaluate import prepare

    program = prepare(text)
    chunk = check_sweep(program, size, jobs, len(maps))
    try:
        renderer: Any = _Renderer(program, size, jobs)
    except ImportError:  # no numba: exact numpy previews, one variant at a time
        renderer = _ExactRenderer(program, size)
    results: list[tuple[int, float | None]] = []
    heap: list[tuple[float, int, np.ndarray]] = []
    chunks = [list(range(s, min(s + chunk, len(maps)))) for s in range(0, len(maps), chunk)]
    with (
        ThreadPoolExecutor(max_workers=jobs, thread_name_prefix="matloom-sweep") as pool,
        ThreadPoolExecutor(max_workers=1, thread_name_prefix="matloom-sweep-prep") as prep,
    ):
        # chunk k + 1 is evaluated (noise, compile) while chunk k is shaded
        ahead = prep.submit(renderer.prepare_chunk, [maps[i] for i in chunks[0]])
        for k, indices in enumerate(chunks):
            prepared = ahead.result()
            if k + 1 < len(chunks):
                ahead = prep.submit(renderer.prepare_chunk, [maps[i] for i in chunks[k + 1]])
            images = renderer.render_prepared(prepared, [maps[i] for i in indices], pool)
            scores = scorer.score(images, prompt or "") if scorer else [None] * len(indices)
            for i, img, s in zip(indices, images, scores, strict=True):
                value = None if s is None else float(s)
                results.append((i, value))
                item = (-i if value is None else value, -i, img)
                if len(heap) < keep:
                    heapq.heappush(heap, item)
                elif item[:2] > heap[0][:2]:
                    heapq.heapreplace(heap, item)
            if progress:
                progress(len(results), len(maps))
    top = [(-neg_i, img) for _, neg_i, img in sorted(heap, key=lambda t: t[:2], reverse=True)]
    return results, top


def _resolve_scorer(scorer: Any) -> Any:
    """A scorer object from a registered name (or the object itself, or None)."""
    if scorer is None or hasattr(scorer, "score"):
        return scorer
    from matloom.author.scorers.base import get_scorer

    return get_scorer(str(scorer))


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

    ``scorer`` is a registered scorer name or an object with ``.name`` and
    ``.score(images, text)``; ``jobs`` = 0 shades on all cores (threads). The winner is the
    highest score (ties to the earliest); without a scorer it is the original. The same ``seed``
    gives the same variants and the same winner. ``backend`` is accepted for compatibility;
    the sweep always uses the numba kernels.
    """
    del backend
    from matloom.engine.evaluate import prepare
    from matloom.lang.deps import seed_dependent_outputs

    t0 = time.perf_counter()
    program = prepare(program_text)
    text = format_program(program)
    spans = seed_literal_spans(text)
    # seeds that feed no output (e.g. an unused Define) would only give identical candidates
    seed_free = not spans or not seed_dependent_outputs(program)
    maps: list[dict[int, int]] = [{}]
    if not seed_free:
        maps += seed_assignments(text, variants, seed)
    message = ""
    if len(maps) == 1:
        message = (
            "no field depends on a noise seed: the sweep has a single candidate"
            if seed_free
            else "no variants requested: only the original is rendered"
        )
    jobs = max(1, jobs or (os.cpu_count() or 1))
    results, top = _render_all(
        text, maps, size, jobs, keep, _resolve_scorer(scorer), prompt, progress
    )
    results.sort()
    n = len(maps)
    best = 0
    if any(s is not None for _, s in results):
        best = max(range(n), key=lambda i: (results[i][1], -i))
    cands = [SweepCandidate(i, "", s) for i, s in results]
    best_program = apply_seed_map(text, maps[best], spans)
    cands[best].program = best_program
    cands[0].program = text
    secs = time.perf_counter() - t0
    return SweepResult(
        cands,
        best,
        best_program,
        secs,
        n / secs if secs else 0.0,
        n,
        seed_free=seed_free,
        top_images=top,
        message=message,
    )


def variant_program(text: str, index: int, variants: int, seed: int = 0) -> str:
    """Text of candidate ``index`` of a sweep (0 = original) without rendering anything."""
    maps: Sequence[dict[int, int]] = [{}] + seed_assignments(text, variants, seed)
    return apply_seed_map(text, maps[index])
