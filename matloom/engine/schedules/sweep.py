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
  preview mode (:func:`~matloom.engine.schedules.banded.composite_preview`) and a fused
  normals + AO + shading kernel (:class:`~matloom.engine.kernels.preview_numba.ShadeInputs`);
  candidates are shaded on ``jobs`` threads (the kernels release the GIL), with no worker
  processes to start.

The sweep is an engine schedule: what it needs from the layers above comes in as data. The
caller gives the :class:`Shading` (the preview's light and half vectors, and the exact shading
of evaluated maps: ``matloom.render.preview.ShadeParams``) and a :class:`Scorer` object (a
registered name is resolved by the caller, e.g. ``matloom.author.scorers.lookup.get_scorer``).

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
from typing import TYPE_CHECKING, Any, Protocol

import numpy as np

from matloom.engine.evaluate import evaluate, prepare
from matloom.engine.limits import Usage, check_size, fit_seed_batch
from matloom.engine.maps import MaterialMaps
from matloom.engine.schedules.seed_batch import SweepEvaluator, chunk_program, seeded_nodes
from matloom.lang import ast as A
from matloom.lang.deps import seed_dependent_outputs
from matloom.lang.printer import format_program
from matloom.lang.seeds import apply_seed_map, seed_assignments, seed_literal_spans
from matloom.ops import OPS

if TYPE_CHECKING:  # numba modules: imported when a KernelRenderer is made
    from matloom.engine.kernels.preview_numba import ShadeInputs
    from matloom.engine.schedules.banded import FusedProgram

Progress = Callable[[int, int], None]
#: Upper bound of candidates per chunk (larger chunks amortise the noise lattice work).
MAX_CHUNK = 128
#: Bytes the seed-batched fields of one chunk may take (sets the chunk size).
CHUNK_BUDGET_BYTES = 128 << 20
#: Backends :func:`run_sweep` takes.
BACKENDS = ("auto", "numba", "numpy")


class Scorer(Protocol):
    """Batched text-image scoring (``matloom.author.scorers``' scorers satisfy it)."""

    def score(self, images: Sequence[np.ndarray], text: str) -> Sequence[float | None] | np.ndarray:
        """One score per (H, W, 3) uint8 image for ``text`` (higher = better; None = none)."""
        ...


class Shading(Protocol):
    """How the previews are shaded (``matloom.render.preview.ShadeParams`` satisfies it)."""

    @property
    def direction(self) -> np.ndarray:
        """Unit light vector L, float64."""
        ...

    @property
    def half(self) -> np.ndarray:
        """Unit half vector H = normalize(L + V), V = (0, 0, 1), float64."""
        ...

    def shade(self, maps: MaterialMaps) -> np.ndarray:
        """The exact uint8 (H, W, 3) preview of evaluated maps, with this light."""
        ...


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


def exact_preview(text: str, size: int, shading: Shading, backend: str) -> np.ndarray:
    """The exact engine's preview of a program text (``matloom.preview``'s evaluation and
    shading): the sweep's path for what its kernels cannot take."""
    return shading.shade(evaluate(text, size, size, backend=backend, usage=Usage(preview_tile=1)))


@dataclass
class ShadingBuffers:
    """One shading thread's reused buffers (zeroed once, see ``banded.composite_preview``)."""

    planes: np.ndarray  # (N_PLANES, n, n) float32: every plane, colours too
    flags: np.ndarray  # (n, n) uint8
    mean: np.ndarray  # (n, n) float32 scratch of the AO box filter


@dataclass
class KernelRenderer:
    """The numba path: everything fixed for a sweep (program, grid, the kernels' constant
    inputs) and the shading threads' buffers."""

    program: A.Program
    size: int
    shading: Shading
    evaluator: SweepEvaluator = field(init=False)
    shade_inputs: ShadeInputs = field(init=False)
    local: threading.local = field(default_factory=threading.local)

    def __post_init__(self) -> None:
        # numba is imported here (ImportError without it); get_backend is looked up at call
        # time (benchmarks/sweep.py wraps it to time the seed-batched noise)
        from matloom.engine import backends
        from matloom.engine.grid import sample_axes
        from matloom.engine.kernels.preview_numba import ShadeInputs
        from matloom.engine.maps import View
        from matloom.engine.schedules import banded

        view = View(*self.program.view_tuple, tileable=self.program.tileable)
        x, y = sample_axes(view, self.size, self.size)
        numba = backends.get_backend("numba")
        self.evaluator = SweepEvaluator(self.program, x, y, numba, periods=view.periods)
        dx, dy = view.texel_size(self.size, self.size)
        self.shade_inputs = ShadeInputs.build(dx, dy, self.shading.direction, self.shading.half)
        banded.decode_luts()  # built once here, before the shading threads use them

    def prepare_chunk(self, seed_maps: list[dict[int, int]]) -> FusedProgram | None:
        """The compiled chunk program, or None when the fused kernel cannot take the program
        (``banded.UnsupportedProgram``; its variants are then previewed one by one with the
        exact engine). Runs on the preparation thread, one chunk ahead of the shading."""
        from matloom.engine.schedules.banded import UnsupportedProgram

        try:
            return chunk_program(self.evaluator, seed_maps, self.size)
        except UnsupportedProgram:
            return None

    def render_prepared(
        self, prog: FusedProgram | None, seed_maps: list[dict[int, int]], pool: ThreadPoolExecutor
    ) -> list[np.ndarray]:
        """Previews of one prepared chunk of candidates, shaded on ``pool``."""
        if prog is None:
            text = format_program(self.program)
            return [
                exact_preview(apply_seed_map(text, m), self.size, self.shading, "numba")
                for m in seed_maps
            ]
        return list(pool.map(lambda cand: self.render(prog, cand), range(len(seed_maps))))

    def buffers(self) -> ShadingBuffers:
        """This thread's buffers (allocated, zeroed, on its first candidate)."""
        from matloom.engine.kernels.composite_numba import N_PLANES

        buffers = getattr(self.local, "buffers", None)
        if buffers is None:
            n = self.size
            buffers = ShadingBuffers(
                planes=np.zeros((N_PLANES, n, n), np.float32),
                flags=np.zeros((n, n), np.uint8),
                mean=np.empty((n, n), np.float32),
            )
            self.local.buffers = buffers
        return buffers

    def render(self, prog: FusedProgram, cand: int) -> np.ndarray:
        """Preview of candidate ``cand`` of the chunk program ``prog`` (runs on any thread)."""
        from matloom.engine.schedules.banded import composite_preview

        buffers = self.buffers()
        composite_preview(prog, buffers.planes, buffers.flags, cand)
        image = np.empty((self.size, self.size, 3), np.uint8)
        self.shade_inputs.shade(buffers.planes, buffers.mean, image)
        return image


@dataclass
class ExactRenderer:
    """Without the numba path (numba missing, or ``backend="numpy"``): every variant is
    previewed by the exact engine on ``backend``."""

    program: A.Program
    size: int
    shading: Shading
    backend: str

    def prepare_chunk(self, seed_maps: list[dict[int, int]]) -> None:
        del seed_maps

    def render_prepared(
        self, prog: None, seed_maps: list[dict[int, int]], pool: Any
    ) -> list[np.ndarray]:
        del prog, pool
        text = format_program(self.program)
        return [
            exact_preview(apply_seed_map(text, m), self.size, self.shading, self.backend)
            for m in seed_maps
        ]


def make_renderer(
    program: A.Program, size: int, shading: Shading, backend: str
) -> KernelRenderer | ExactRenderer:
    """The renderer for ``backend``: ``numba`` the kernels (ImportError without numba),
    ``numpy`` the exact numpy engine, ``auto`` the kernels when numba imports, else the exact
    engine's own ``auto``."""
    if backend != "numpy":
        try:
            return KernelRenderer(program, size, shading)
        except ImportError:
            if backend == "numba":
                raise
    return ExactRenderer(program, size, shading, backend)


def chunk_size(program: A.Program, size: int) -> int:
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
    shading threads' buffers); returns the chunk size, made smaller than :func:`chunk_size`
    when the memory estimate of that chunk exceeds the budget. Raises ``LimitError``."""
    check_size(size, size)
    chunk = min(chunk_size(program, size), max(candidates, 1))
    batched = frozenset(seeded_nodes(program))
    # a thread pool starts threads (each with its buffers) only for tasks that wait: at most
    # one per candidate of a chunk
    usage = Usage(seed_batch=chunk, threads=min(jobs, chunk), batched=batched)
    return fit_seed_batch(program, size, size, usage)


@dataclass(frozen=True)
class SweepPlan:
    """One sweep's fixed settings (``maps[i]`` is candidate i's seed map; 0 = the original)."""

    text: str
    maps: list[dict[int, int]]
    size: int
    jobs: int
    keep: int
    shading: Shading
    backend: str


def _render_all(
    plan: SweepPlan, scorer: Scorer | None, prompt: str | None, progress: Progress | None
) -> tuple[list[tuple[int, float | None]], list[tuple[int, np.ndarray]]]:
    """Render (and score) every candidate; the scores by index and the ``keep`` best images."""
    maps = plan.maps
    program = prepare(plan.text)
    chunk = check_sweep(program, plan.size, plan.jobs, len(maps))
    renderer = make_renderer(program, plan.size, plan.shading, plan.backend)
    results: list[tuple[int, float | None]] = []
    heap: list[tuple[float, int, np.ndarray]] = []
    chunks = [list(range(s, min(s + chunk, len(maps)))) for s in range(0, len(maps), chunk)]
    with (
        ThreadPoolExecutor(max_workers=plan.jobs, thread_name_prefix="matloom-sweep") as pool,
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
                if len(heap) < plan.keep:
                    heapq.heappush(heap, item)
                elif item[:2] > heap[0][:2]:
                    heapq.heapreplace(heap, item)
            if progress:
                progress(len(results), len(maps))
    top = [(-neg_i, img) for _, neg_i, img in sorted(heap, key=lambda t: t[:2], reverse=True)]
    return results, top


def run_sweep(
    program_text: str,
    *,
    variants: int,
    shading: Shading,
    size: int = 256,
    scorer: Scorer | None = None,
    prompt: str | None = None,
    seed: int = 0,
    jobs: int = 0,
    keep: int = 8,
    backend: str = "auto",
    progress: Progress | None = None,
) -> SweepResult:
    """Render the original and ``variants`` seed variants; score them when a scorer is given.

    ``shading``: the previews' light (``matloom.render.preview.ShadeParams.of()`` for the
    reference's); ``scorer``: an object with ``.score(images, text)`` (see :class:`Scorer`);
    ``jobs`` = 0 shades on all cores (threads). ``backend``: ``auto`` (the numba kernels when
    numba is installed, else the exact engine's ``auto``), ``numba`` (the kernels; ImportError
    without numba) or ``numpy`` (every variant previewed by the exact numpy engine, as
    ``matloom.preview(variant, size, backend="numpy")``, slower). The winner is the highest
    score (ties to the earliest); without a scorer it is the original. The same ``seed`` gives
    the same variants and the same winner.
    """
    if backend not in BACKENDS:
        raise ValueError(f"unknown sweep backend {backend!r}; have {', '.join(BACKENDS)}")
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
    plan = SweepPlan(text, maps, size, jobs, keep, shading, backend)
    results, top = _render_all(plan, scorer, prompt, progress)
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
