"""Documented resource limits (docs/limits.md), checked before any evaluation work.

Every entry point that evaluates or renders a program (``matloom.evaluate``, ``matloom.preview``,
``matloom.render.api.stats``, seed sweeps, the gallery and ``generate``'s renders) goes through
:func:`check_request`: image size, the evaluation work (expression nodes with Defines expanded
per coordinate frame, times texels) and the memory estimate, each with a one-line
:class:`LimitError` that names the limit and how to change it.
"""

from __future__ import annotations

import math
import os
from collections import OrderedDict
from dataclasses import dataclass, replace

from matloom.lang import ast as A
from matloom.lang.checker import MAX_NODES, MAX_OCTAVES
from matloom.lang.codes import Code
from matloom.lang.cost import MAX_EXPANDED_NODES, Cost, costliest_call, expanded_cost, over_limit

MEMORY_ENV = "MATLOOM_MAX_MEMORY_MB"
DEFAULT_MEMORY_MB = 8192


class LimitError(ValueError):
    """A request exceeds a documented resource limit (or a limit setting is invalid)."""


def memory_budget_mb(environ: dict[str, str] | None = None) -> float:
    """The memory budget in MiB: $MATLOOM_MAX_MEMORY_MB (a positive number), else 8192."""
    raw = (os.environ if environ is None else environ).get(MEMORY_ENV)
    if raw is None or raw.strip() == "":
        return float(DEFAULT_MEMORY_MB)
    try:
        value = float(raw)
    except ValueError:
        value = math.nan
    if not (math.isfinite(value) and value > 0):
        raise LimitError(f"{MEMORY_ENV} must be a positive number of MiB (e.g. 8192), got {raw!r}")
    return value


@dataclass(frozen=True)
class Limits:
    """Resource limits. ``max_memory_mb=None`` reads $MATLOOM_MAX_MEMORY_MB at each check."""

    max_resolution: int = 8192
    max_octaves: int = MAX_OCTAVES
    max_nodes: int = MAX_NODES
    #: expression-node evaluations of one program, whatever the size (E071 in the checker)
    max_expanded_nodes: int = MAX_EXPANDED_NODES
    #: expression-node evaluations (each call weighted by its op's work) times texels of one
    #: evaluation: 65,536 per texel at 8192x8192, enough for every library entry (the largest
    #: counts 64,637); about 20 minutes on two cores with the compiled kernels (docs/limits.md)
    max_node_texels: int = 1 << 42
    max_memory_mb: float | None = None

    def memory_mb(self) -> float:
        return memory_budget_mb() if self.max_memory_mb is None else float(self.max_memory_mb)


DEFAULT_LIMITS = Limits()


@dataclass(frozen=True)
class Usage:
    """What a request makes besides the evaluation (for the memory estimate)."""

    #: a shaded preview tiled n x n (0: no preview); the output is n times the size each way
    preview_tile: int = 0
    #: seed sweep: candidates evaluated at once (leading seed axis), shading threads, and the
    #: ids of the nodes that have a value per candidate (the seed-dependent ones)
    seed_batch: int = 0
    threads: int = 1
    batched: frozenset[int] = frozenset()


EVALUATE = Usage()


@dataclass(frozen=True)
class Estimate:
    """The outcome of :func:`check_request`."""

    memory_mb: float
    cost: Cost


#: Texels per band of the fused path (engine.fused evaluates one band of fields at a time).
BAND_TEXELS = 3 << 17
#: Bytes per texel of the finished maps (20 float32 components) plus the fused path's per-row
#: scratch, the normal/AO passes and numpy compositing's band temporaries (measured, see
#: docs/limits.md).
MAP_BYTES = 4 * 22
#: Field-sized arrays a primitive kernel or the compositing may hold besides the counted ones,
#: and the fused path's band compositing by numpy when the kernel cannot take a program (its
#: temporaries; plus one float32 pair per layer).
KERNEL_FIELDS = 8
COMPOSITE_FIELDS = 24
#: Bytes per texel of the preview shading (numba kernels' float64 scratch and the image; the
#: numpy shading's whole-array temporaries, used with the numpy path), per output texel of the
#: tiled image and its PNG encoding, and per texel and thread of a sweep's shading buffers
#: (16 float32 planes, flags, a float32 mean, an image). Measured, with some margin.
SHADE_BYTES = 64
SHADE_BYTES_NUMPY = 448
OUTPUT_BYTES = 12
SWEEP_THREAD_BYTES = 4 * 16 + 4 + 1 + 3


def band_texels(width: int, height: int) -> int:
    """Texels of the largest band of rows the fused path evaluates at once."""
    rows = max(2, BAND_TEXELS // max(width, 1))
    return min(height, rows + 1) * width


def live_fields(cost: Cost, *, fused: bool) -> int:
    """Field-sized arrays one evaluation may hold at once (an upper bound).

    Fused path: every array-valued node visit of a band (its channel arithmetic stays symbolic,
    so the layers keep their leaves until the band is composited; the numpy fallback
    materialises each deferred node once, and its compositing holds two float32 planes per
    layer and some temporaries). Numpy path: the Define values per frame, the layers'
    non-constant channels, the operands held along the evaluation stack. Both: rotated frames'
    coordinates and kernel scratch."""
    if fused:
        held = cost.arrays + cost.layers + COMPOSITE_FIELDS
    else:
        held = cost.define_evaluations + cost.channel_fields + cost.pending
    return held + cost.rotated_frames + KERNEL_FIELDS


def estimate_memory_mb(
    width: int, height: int, cost: Cost, *, fused: bool = True, usage: Usage = EVALUATE
) -> float:
    """Upper bound of the working set of one request, in MiB: the maps, plus the live fields
    (:func:`live_fields`, float64) over a band of rows (fused path) or the whole image (numpy
    path), plus the preview buffers; or for a sweep, :func:`sweep_bytes`."""
    texels = width * height
    if usage.seed_batch:
        return sweep_bytes(texels, cost, usage) / 2**20
    field_texels = band_texels(width, height) if fused else texels
    total = texels * MAP_BYTES + field_texels * 8 * live_fields(cost, fused=fused)
    if usage.preview_tile:
        shading = SHADE_BYTES if fused else SHADE_BYTES_NUMPY
        total += texels * shading + texels * usage.preview_tile**2 * OUTPUT_BYTES
    return total / 2**20


def sweep_bytes(texels: int, cost: Cost, usage: Usage) -> int:
    """A seed sweep evaluates a chunk of ``usage.seed_batch`` candidates on the whole image at
    once: the arrays of seed-dependent nodes (``usage.batched``) have one plane per candidate,
    the others one; each shading thread has its own planes, each candidate an image."""
    batched = cost.batched_arrays
    planes = cost.arrays - batched + usage.seed_batch * batched
    fields = planes + cost.layers + cost.rotated_frames + KERNEL_FIELDS
    images = usage.seed_batch + 8  # a chunk's previews and the kept best ones
    return texels * (8 * fields + usage.threads * SWEEP_THREAD_BYTES + 3 * images)


_COSTS: OrderedDict[tuple[int, ...], tuple[A.Program, Cost]] = OrderedDict()


def request_cost(program: A.Program, width: int, height: int, usage: Usage, limits: Limits) -> Cost:
    """The cost of evaluating ``program`` at ``width`` x ``height`` for ``usage``, counted up
    to the node cap the limits allow at that size (:func:`program_cost`, remembered)."""
    cap = min(limits.max_expanded_nodes, limits.max_node_texels // (width * height))
    return program_cost(program, cap, usage.batched)


def program_cost(program: A.Program, cap: int, batched: frozenset[int] = frozenset()) -> Cost:
    """:func:`~matloom.lang.cost.expanded_cost`, remembered for the last few programs."""
    key = (id(program), cap, len(batched), hash(batched))
    hit = _COSTS.get(key)
    if hit is not None and hit[0] is program:
        _COSTS.move_to_end(key)
        return hit[1]
    cost = expanded_cost(program, cap, batched)
    _COSTS[key] = (program, cost)  # the entry keeps the program alive, so its id stays unique
    if len(_COSTS) > 32:
        _COSTS.popitem(last=False)
    return cost


def check_size(width: int, height: int, tile: int = 1, limits: Limits = DEFAULT_LIMITS) -> None:
    """The size limits alone (positive integers, at most ``max_resolution`` each way, tiled
    output included)."""
    for name, v in (("width", width), ("height", height)):
        if isinstance(v, bool) or not isinstance(v, int) or v < 1:
            raise LimitError(f"{name} must be a positive integer, got {v!r}")
        if v > limits.max_resolution:
            raise LimitError(
                f"{name} {v} exceeds the maximum resolution {limits.max_resolution} "
                "(see docs/limits.md)"
            )
        if tile > 1 and v * tile > limits.max_resolution:
            raise LimitError(
                f"a {tile}x{tile} tiled preview of {name} {v} is {v * tile} pixels, more than "
                f"the maximum resolution {limits.max_resolution} (see docs/limits.md)"
            )


def _check_work(program: A.Program, width: int, height: int, cost: Cost, limits: Limits) -> None:
    if not cost.over:
        return
    if cost.nodes > limits.max_expanded_nodes:
        message, hint, _ = over_limit(program, cost, limits.max_expanded_nodes)
        raise LimitError(f"{message} ({Code.WORK_LIMIT.code}; {hint})")
    heavy = costliest_call(program)
    costliest = (
        f"; the costliest call is {heavy.call.func} in {heavy.owner} ({heavy.work:,} each)"
        if heavy is not None and heavy.work > 1
        else ""
    )
    raise LimitError(
        f"evaluating {width}x{height} needs more than {cost.nodes - 1:,} expression-node "
        f"evaluations x {width * height:,} texels, more than the limit of "
        f"{limits.max_node_texels:,} node-texels{costliest}; lower the size (see docs/limits.md)"
    )


def check_request(
    program: A.Program,
    width: int,
    height: int,
    *,
    fused: bool = True,
    usage: Usage = EVALUATE,
    limits: Limits = DEFAULT_LIMITS,
) -> Estimate:
    """Raise :class:`LimitError` if evaluating ``program`` at ``width`` x ``height`` (on the
    fused path or not, for ``usage``) exceeds a limit; else return the estimate."""
    check_size(width, height, max(usage.preview_tile, 1), limits)
    budget = limits.memory_mb()
    cost = request_cost(program, width, height, usage, limits)
    _check_work(program, width, height, cost, limits)
    mb = estimate_memory_mb(width, height, cost, fused=fused, usage=usage)
    if mb > budget:
        raise LimitError(
            f"{_what(width, height, usage)} needs about {mb:,.0f} MiB, more than the budget of "
            f"{budget:,.0f} MiB; lower the size or raise {MEMORY_ENV} (see docs/limits.md)"
        )
    return Estimate(mb, cost)


def fit_seed_batch(
    program: A.Program,
    width: int,
    height: int,
    usage: Usage,
    limits: Limits = DEFAULT_LIMITS,
) -> int:
    """The largest seed batch up to ``usage.seed_batch`` whose sweep fits the memory budget
    (a sweep evaluates its candidates in smaller chunks rather than fail). Raises
    :class:`LimitError` when even one candidate at a time exceeds a limit."""
    one = check_request(
        program, width, height, fused=False, usage=replace(usage, seed_batch=1), limits=limits
    )
    texels = width * height
    step = sweep_bytes(texels, one.cost, replace(usage, seed_batch=2)) - sweep_bytes(
        texels, one.cost, replace(usage, seed_batch=1)
    )
    room = limits.memory_mb() * 2**20 - one.memory_mb * 2**20
    fit = usage.seed_batch if step <= 0 else 1 + int(room // step)
    return max(1, min(usage.seed_batch, fit))


def _what(width: int, height: int, usage: Usage) -> str:
    if usage.seed_batch:
        return f"sweeping at {width}x{height}"
    if usage.preview_tile > 1:
        return f"a {usage.preview_tile}x{usage.preview_tile} tiled preview of {width}x{height}"
    if usage.preview_tile:
        return f"previewing {width}x{height}"
    return f"evaluating {width}x{height}"
