"""The fused numba evaluation path: bit-identical to the numpy path, several times faster.

For each band of rows the program's primitive fields are evaluated by a
:class:`~matloom.engine.lazy.LazyEvaluator` on the band's sample axes (every primitive is
point-wise, so a band evaluates to exactly the rows of the full evaluation). The deferred channel
arithmetic is compiled into a register program (:func:`compile_layers`) that the compositing
kernel runs per row. Normals and AO then run as numba kernels on the finished height.

Why it is exact: see :mod:`matloom.engine.kernels.composite_numba`; texels where the kernel's
sRGB decode cannot guarantee numpy's float32 result are recomposited with the numpy code
(:func:`_recomposite`). A program the kernel cannot take (too many leaves or registers, a
non-float leaf) is composited band-wise by the numpy path instead; the result is the same.

Memory: only one band of fields is alive at a time, so the peak stays near the size of the
output maps (about 88 bytes per texel) instead of growing with the number of fields.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from matloom.engine import composite as C
from matloom.engine import limits
from matloom.engine.backends import Backend
from matloom.engine.cull import resolve
from matloom.engine.interpret import EvalStats, layer_fields
from matloom.engine.kernels import composite_numba as K
from matloom.engine.kernels import register_numba as R
from matloom.engine.kernels import relief_numba
from matloom.engine.kernels.register_ops import ARITY, CONSTS, REGISTER_OPS, is_load, operands
from matloom.engine.kernels.threads import parallel_rows
from matloom.engine.lazy import (
    FUSABLE_DTYPES,
    OP_OF,
    Lazy,
    LazyEvaluator,
    gather,
    is_scalar,
    materialise,
)
from matloom.engine.maps import MaterialMaps, View
from matloom.engine.plans import Plan, PlanCache, leaf_array, signature
from matloom.lang import ast as A
from matloom.vocab.layout import LAYOUT, Group

#: Texels per band (the fields of one band are alive at a time): 384 rows at 1024 wide keeps
#: the traced peak at 1024x1024 near 90 MiB with few bands (Python work is per band). The
#: memory estimate (engine.limits) assumes this band size.
BAND_TEXELS = limits.BAND_TEXELS
#: Register cap of the kernel (each register is one float64 row per thread).
MAX_REGISTERS = 256
#: Fields of the kernel's 2-D output planes (alpha, the scalars, ior, height), in plane order.
_PLANES = LAYOUT.plane_fields
_LUTS: list[tuple[np.ndarray, np.ndarray]] = []


def decode_luts() -> tuple[np.ndarray, np.ndarray]:
    """The kernel's sRGB decode tables (exact, preview), built once per process."""
    if not _LUTS:
        _LUTS.append((K.decode_table(), K.fast_decode_table()))
    return _LUTS[0]


@dataclass
class FusedProgram:
    """A compiled register program plus the layer channel tables for the kernel."""

    loads: np.ndarray
    code: np.ndarray
    consts: np.ndarray
    n_regs: int
    leaves64: list[np.ndarray]
    leaves32: list[np.ndarray]
    chan_reg: np.ndarray
    chan_mode: np.ndarray


@dataclass
class _Compiler:
    """Turns channel values into registers: constants first, then leaves and operations."""

    shape: tuple[int, ...]
    consts: dict[tuple[float, str], int] = field(default_factory=dict)
    const_values: list[float] = field(default_factory=list)
    nodes: dict[int, int] = field(default_factory=dict)
    ops: list[tuple[int, ...]] = field(default_factory=list)
    leaves64: list[np.ndarray] = field(default_factory=list)
    leaves32: list[np.ndarray] = field(default_factory=list)
    keep: list[Any] = field(default_factory=list)
    #: ids of the channel values behind each leaf slot (for :mod:`matloom.engine.plans`)
    sources64: list[int] = field(default_factory=list)
    sources32: list[int] = field(default_factory=list)

    def const(self, value: Any) -> int:
        v = float(value)
        key = (v, np.float64(v).tobytes().hex())
        if key not in self.consts:
            self.consts[key] = -1 - len(self.const_values)
            self.const_values.append(v)
        return self.consts[key]

    def with_block(self, value: Lazy) -> tuple[int, ...]:
        """The op row of an opcode with a parameter block (e.g. Threshold): the op's ``block``
        rule gives the constants, stored consecutively; the rounding flag is the operand's."""
        op = OP_OF[value.op]
        source = value.args[0]
        base = len(self.const_values)
        self.const_values.extend(op.block(**dict(value.params)))  # type: ignore[misc]
        f32 = int(
            np.asarray(source).dtype == np.float32
            if not isinstance(source, Lazy)
            else source.dtype == np.float32
        )
        return (REGISTER_OPS[op.fast].code, 0, self.value(source), base, f32)  # type: ignore[index]

    def axpb(self, value: Any) -> tuple[int, ...] | None:
        """One ``x * c1 + c2`` row for ``x * c1 + c2``, ``c2 + x * c1`` or ``x * c1 - c2``
        (float64 nodes, non-NaN constants; IEEE + and * commute exactly and ``p - c`` is
        ``p + (-c)``), or None. The product node is still compiled if used elsewhere."""
        if not isinstance(value, Lazy) or value.op not in ("+", "-") or value.dtype != np.float64:
            return None
        left, right = value.args
        if value.op == "+" and _const(left) is not None:
            left, right = right, left
        c2 = _const(right)
        product = _scaled(left)
        if c2 is None or product is None:
            return None
        x, c1 = product
        base = len(self.const_values)
        self.const_values.extend([c1, -c2 if value.op == "-" else c2])
        return (R.OP_AXPB, 0, self.value(x), base, 0)

    def leaf(self, source: Any) -> int:
        array = np.asarray(source)
        if array.dtype not in FUSABLE_DTYPES or array.ndim > 3:
            raise UnsupportedProgram(f"leaf dtype {array.dtype} / ndim {array.ndim}")
        leaf = leaf_array(array, self.shape)
        pool, op, sources = (
            (self.leaves32, R.OP_LOAD32, self.sources32)
            if array.dtype == np.float32
            else (self.leaves64, R.OP_LOAD64, self.sources64)
        )
        pool.append(leaf)
        sources.append(id(source))
        self.ops.append((op, 0, len(pool) - 1, 0, 0))
        return len(self.ops) - 1

    def value(self, value: Any) -> int:
        """Register reference of a value (negative = constant, else index into ``ops``)."""
        if is_scalar(value):
            if np.asarray(value).dtype not in FUSABLE_DTYPES and not isinstance(value, float):
                raise UnsupportedProgram("non-float scalar")
            return self.const(value)
        key = id(value)
        if key not in self.nodes:
            self.keep.append(value)
            fused_row = self.axpb(value)
            if fused_row is not None:
                self.ops.append(fused_row)
                self.nodes[key] = len(self.ops) - 1
            elif isinstance(value, Lazy) and REGISTER_OPS[OP_OF[value.op].fast].consts:  # type: ignore[index]
                self.ops.append(self.with_block(value))
                self.nodes[key] = len(self.ops) - 1
            elif isinstance(value, Lazy):
                refs = [self.value(a) for a in value.args] + [0]
                code = REGISTER_OPS[OP_OF[value.op].fast].code  # type: ignore[index]
                f32 = int(value.dtype == np.float32)
                self.ops.append((code, 0, refs[0], refs[1], f32))
                self.nodes[key] = len(self.ops) - 1
            else:
                self.nodes[key] = self.leaf(value)
        return self.nodes[key]


def _const(value: Any) -> float | None:
    """A non-NaN float64 scalar operand as a float, else None."""
    if not is_scalar(value) or np.asarray(value).dtype != np.float64:
        return None
    v = float(value)
    return None if v != v else v


def _scaled(value: Any) -> tuple[Any, float] | None:
    """(x, c) for a float64 ``x * c`` or ``c * x`` node with a non-NaN constant c, else None."""
    if not isinstance(value, Lazy) or value.op != "*" or value.dtype != np.float64:
        return None
    a, b = value.args
    if _const(a) is not None and _const(b) is None:
        a, b = b, a
    c = _const(b)
    if c is None or _const(a) is not None:
        return None
    return a, c


class UnsupportedProgram(Exception):
    """The kernel cannot take this program; the numpy path composites it instead."""


def _channel_refs(comp: _Compiler, layer: C.RawLayer) -> tuple[list[int], list[int]]:
    """(register refs, modes) of the kernel's channel slots (``K.N_CHANNELS``) of one layer.

    A constant channel is converted here (READY, or ZERO when it converts to 0); a constant
    colour x a varying strength is decoded here (DECODED); the rest is RAW."""
    refs, modes = [0] * K.N_CHANNELS, [K.RAW] * K.N_CHANNELS

    def ready(slot: int, converted: Any, mode: int = K.READY) -> None:
        refs[slot] = comp.const(converted)
        modes[slot] = K.ZERO if mode == K.READY and float(converted) == 0.0 else mode

    def raw(slot: int, value: Any) -> None:
        refs[slot] = comp.value(value)

    raw(K.CH_ALPHA, getattr(layer, C.COVERAGE))
    for channel in LAYOUT.maxed:
        raw(channel.slots[0], getattr(layer, channel.name))
    lit = LAYOUT.in_group(Group.COLOUR_STRENGTH)
    for channel in lit:
        raw(channel.slots[3], getattr(layer, channel.name)[3])
    for channel in LAYOUT.scalars:
        v, slot = getattr(layer, channel.name), channel.slots[0]
        ready(slot, C.convert_scalar(v, channel.clamp)) if is_scalar(v) else raw(slot, v)
    for k in range(3):
        for channel in LAYOUT.colours:
            values, slot = getattr(layer, channel.name), channel.slots[k]
            v = values[k]
            if not is_scalar(v):
                raw(slot, v)
            elif channel.group is Group.COLOUR:
                ready(slot, C.colour_to_linear(v))
            elif is_scalar(values[3]):
                ready(slot, C.emitted_radiance(np.asarray(v), np.asarray(values[3])))
            else:
                ready(slot, C.colour_to_linear64(np.asarray(v)), K.DECODED)
    return refs, modes


def compile_layers(layers: Sequence[C.RawLayer], shape: tuple[int, int]) -> FusedProgram:
    """Compile the layers' channel values for :func:`composite_numba.composite_rows`.

    Constants occupy the first registers (the compositing stage reads channel constants from
    registers); operations read constants directly. Other registers are reused once their value
    is dead, except those the channel tables read. Raises ``UnsupportedProgram`` past the kernel's
    fixed limits. A program of the same structure compiled before is reused with the new leaves
    (:mod:`matloom.engine.plans`).
    """
    key, leaves = signature(list(layers), shape)
    plan = _PLANS.get(key)
    if plan is not None:
        return plan.bind(leaves, shape)
    prog, comp = _compile(layers, shape)
    order = {id(v): k for k, v in enumerate(leaves)}
    if all(i in order for i in comp.sources64 + comp.sources32):
        empty = replace(prog, leaves64=[], leaves32=[])
        slots64 = tuple(order[i] for i in comp.sources64)
        _PLANS.put(key, Plan(empty, slots64, tuple(order[i] for i in comp.sources32)))
    return prog


_PLANS = PlanCache()


def _compile(layers: Sequence[C.RawLayer], shape: tuple[int, int]) -> tuple[FusedProgram, Any]:
    """:func:`compile_layers` without the plan cache; also returns the compiler state."""
    comp = _Compiler(shape)
    tables = [_channel_refs(comp, layer) for layer in layers]
    if len(comp.leaves64) > K.MAX_LEAVES64 or len(comp.leaves32) > K.MAX_LEAVES32:
        raise UnsupportedProgram("too many leaves")
    n_const = len(comp.const_values)
    pinned = {r for refs, _ in tables for r in refs if r >= 0}
    regs, code, n_regs = _allocate(comp.ops, pinned, n_const)
    if n_regs > MAX_REGISTERS:
        raise UnsupportedProgram("too many registers")

    def reg(ref: int) -> int:
        return -1 - ref if ref < 0 else regs[ref]

    chan_reg = np.array([[reg(r) for r in refs] for refs, _ in tables], dtype=np.int64)
    chan_mode = np.array([modes for _, modes in tables], dtype=np.int64)
    loading = ARITY[code[:, 0]] == 0
    loads = code[loading]
    code = code[~loading]
    prog = FusedProgram(
        loads,
        code,
        np.array(comp.const_values, np.float64),
        max(n_regs, 1),
        comp.leaves64,
        comp.leaves32,
        chan_reg,
        chan_mode,
    )
    return prog, comp


def _allocate(
    ops: list[tuple[int, ...]], pinned: set[int], n_const: int
) -> tuple[list[int], np.ndarray, int]:
    """Linear-scan register allocation in execution order (all leaf loads first, then the
    arithmetic): (register of each op, code rows in execution order, register count)."""
    order = [k for k, o in enumerate(ops) if is_load(o[0])] + [
        k for k, o in enumerate(ops) if not is_load(o[0])
    ]
    position = {k: p for p, k in enumerate(order)}

    last_use = {k: len(ops) if k in pinned else position[k] for k in range(len(ops))}
    for k in order:
        for ref in operands(ops[k][0], ops[k][2], ops[k][3]):
            if ref >= 0:
                last_use[ref] = max(last_use[ref], position[k])
    free: list[int] = []
    regs = [0] * len(ops)
    rows = []
    n_regs = n_const
    for k in order:
        op, _, a, b, f32 = ops[k]
        refs = operands(op, a, b)
        for ref in refs:
            if ref >= 0 and last_use[ref] == position[k] and regs[ref] not in free:
                free.append(regs[ref])
        dst = free.pop() if free else n_regs
        n_regs = max(n_regs, dst + 1)
        regs[k] = dst
        if not refs:
            rows.append((op, dst, a, 0, 0, 0))
            continue
        if CONSTS[op]:  # b is the index of its constant block
            rows.append((op, dst, regs[a] if a >= 0 else -1 - a, b, f32, int(a < 0)))
            continue
        mask = sum(bit for bit, ref in zip((1, 2), refs) if ref < 0)
        fields = [(-1 - ref) if ref < 0 else regs[ref] for ref in refs] + [0]
        rows.append((op, dst, fields[0], fields[1], f32, mask))
    code = np.array(rows, dtype=np.int64).reshape(-1, 6)
    return regs, code, n_regs


_DUMMY64 = np.zeros((1, 1, 1), np.float64)
_DUMMY32 = np.zeros((1, 1, 1), np.float32)


def leaf_tuples(prog: FusedProgram) -> tuple[tuple[np.ndarray, ...], tuple[np.ndarray, ...]]:
    """The leaves padded to the kernel's fixed slot counts."""
    l64 = tuple(prog.leaves64) + (_DUMMY64,) * (K.MAX_LEAVES64 - len(prog.leaves64))
    l32 = tuple(prog.leaves32) + (_DUMMY32,) * (K.MAX_LEAVES32 - len(prog.leaves32))
    return l64, l32


def allocate_maps(width: int, height: int) -> dict[str, np.ndarray]:
    """Zeroed output maps like :func:`composite.allocate_maps`, except that the 2-D maps
    (alpha, the scalars, ior, height) are views of one (K.N_MAP_PLANES, H, W) buffer, the
    kernel's ``planes`` argument (see :func:`planes_of`), and that the height is not pre-set to
    the -inf accumulator start: the kernel writes every height row (the numpy fallback sets its
    band)."""
    buffer = np.zeros((len(_PLANES), height, width), np.float32)
    maps = {name: buffer[p] for p, name in enumerate(_PLANES)}
    for channel in LAYOUT.colours:
        maps[channel.field] = np.zeros((height, width, 3), np.float32)
    return maps


def planes_of(maps: dict[str, np.ndarray]) -> np.ndarray:
    """The (K.N_MAP_PLANES, H, W) buffer behind the plane maps of :func:`allocate_maps`."""
    base = maps[_PLANES[0]].base
    assert base is not None and base.shape[0] == len(_PLANES)
    return base


def colours_of(maps: dict[str, np.ndarray]) -> tuple[np.ndarray, ...]:
    """The kernel's interleaved colour outputs (basecolor, emissive) in ``maps``."""
    return tuple(maps[channel.field] for channel in LAYOUT.colours)


def kernel_args(
    prog: FusedProgram,
    planes: np.ndarray,
    colours: tuple[np.ndarray, ...],
    flags: np.ndarray,
    *,
    cand: int = 0,
    row0: int = 0,
    margin: float | None = None,
    zeroed: bool = True,
) -> K.CompositeArgs:
    """The one :class:`~composite_numba.CompositeArgs` builder: ``prog``'s tables and leaves
    padded to the kernel's slot counts, the decode tables, and the outputs. ``margin`` defaults
    to ``K.DECODE_MARGIN`` (exact mode); < 0 is the preview mode. ``zeroed``: the outputs were
    zero-filled (channels no layer writes are then not written)."""
    l64, l32 = leaf_tuples(prog)
    return K.CompositeArgs(
        loads=prog.loads,
        code=prog.code,
        consts=prog.consts,
        n_regs=prog.n_regs,
        leaves64=l64,
        leaves32=l32,
        cand=cand,
        chan_reg=prog.chan_reg,
        chan_mode=prog.chan_mode,
        luts=decode_luts(),
        margin=K.DECODE_MARGIN if margin is None else margin,
        planes=planes,
        colours=colours,
        row0=row0,
        flags=flags,
        zeroed=zeroed,
    )


def run_kernel(
    prog: FusedProgram, maps: dict[str, np.ndarray], row0: int, flags: np.ndarray, cand: int = 0
) -> None:
    """Composite the band of rows ``row0``.. (``flags.shape[0]`` rows; candidate ``cand`` of
    batched leaves) into ``maps`` (from :func:`allocate_maps`, which zero-fills), rows split
    over threads."""
    args = kernel_args(prog, planes_of(maps), colours_of(maps), flags, cand=cand, row0=row0)
    parallel_rows(flags.shape[0], flags.shape[1], lambda a, b: K.composite_rows(args, a, b))


#: The kernel's ``margin`` for the preview mode (the linear decode table, no exactness flags).
PREVIEW_MARGIN = -1.0
#: The interleaved colour outputs of the planar preview mode: never written (see below).
_NO_COLOURS = (np.zeros((1, 1, 3), np.float32),) * len(K.COLOUR_OUTPUT_PLANES)


def composite_preview(prog: FusedProgram, planes: np.ndarray, flags: np.ndarray, cand: int) -> None:
    """Composite candidate ``cand`` of ``prog`` in the preview mode into ``planes``, a planar
    (K.N_PLANES, H, W) float32 buffer (the colours too, as planes), on the calling thread (the
    sweep composites several candidates at once on threads). ``planes`` and ``flags`` (H, W)
    uint8 may be reused between calls without zeroing them again: a channel no layer writes is
    never anything but 0 (where a NaN coverage makes the kernel write it, the coverage is NaN
    too and 0 is written), so the zeros of their first allocation stay."""
    args = kernel_args(prog, planes, _NO_COLOURS, flags, cand=cand, margin=PREVIEW_MARGIN)
    K.composite_rows(args, 0, planes.shape[1])


def _map_layer(fn: Any, *layers: C.RawLayer) -> C.RawLayer:
    """A RawLayer whose every channel value is ``fn(values of that channel in layers)``."""
    return C.map_channels(fn, *layers)


@dataclass
class _Flagged:
    """Texels the kernel flagged (output rows and columns) and the layers' values there."""

    rows: np.ndarray
    cols: np.ndarray
    layers: list[C.RawLayer]


def _flagged(layers: Sequence[C.RawLayer], flags: np.ndarray, row0: int) -> _Flagged | None:
    """The flagged texels of a band (``flags`` rows are band rows from output row ``row0``)
    with every channel value gathered there, or None (the common case)."""
    words = flags.view(np.uint64) if flags.shape[1] % 8 == 0 else flags  # 8 flags per test
    if not words.any():
        return None
    hit = np.flatnonzero(words.any(axis=1))  # flags are rare: search only the rows with any
    sub_rows, cols = np.nonzero(flags[hit])
    rows = hit[sub_rows]
    cache: dict[int, Any] = {}

    def pick(value: Any) -> Any:
        return gather(value, rows, cols, flags.shape, cache)  # (1, k) array, or the scalar

    return _Flagged(rows + row0, cols, [_map_layer(pick, ly) for ly in layers])


def _join(*values: Any) -> Any:
    """One band-independent scalar as it is (numpy promotes scalars and arrays differently),
    else the bands' (1, k) values side by side."""
    if np.ndim(values[0]) == 0:
        return values[0]
    return np.concatenate(values, axis=1)


def _recomposite(maps: dict[str, np.ndarray], found: list[_Flagged]) -> None:
    """Redo the flagged texels of all bands at once with the numpy reference compositing."""
    if not found:
        return
    rows = np.concatenate([f.rows for f in found])
    cols = np.concatenate([f.cols for f in found])
    layers = [_map_layer(_join, *band_layers) for band_layers in zip(*(f.layers for f in found))]
    fixed = C.allocate_maps(rows.size, 1)
    C.composite_band(layers, fixed, slice(0, 1))
    for name, array in fixed.items():
        maps[name][rows, cols] = array[0]


def _band_slices(height: int, width: int) -> list[slice]:
    """Row bands of about BAND_TEXELS texels, each at least 2 rows unless height is 1."""
    rows = max(2, BAND_TEXELS // max(width, 1))
    starts = list(range(0, height, rows))
    if len(starts) > 1 and height - starts[-1] < 2:
        starts.pop()
    return [
        slice(s, starts[k + 1] if k + 1 < len(starts) else height) for k, s in enumerate(starts)
    ]


def composite_program(
    program: A.Program,
    x: np.ndarray,
    y: np.ndarray,
    backend: Backend,
    stats: EvalStats,
    cull: bool = True,
    periods: tuple[float, float] | None = None,
) -> dict[str, np.ndarray]:
    """Evaluate and composite every band; returns the blended maps (no normal/AO yet).
    ``cull``: compute fBm fields only where a layer can see them (:mod:`matloom.engine.cull`)."""
    height, width = y.shape[0], x.shape[1]
    maps = allocate_maps(width, height)
    flagged: list[_Flagged] = []
    for index, rows in enumerate(_band_slices(height, width)):
        ev = LazyEvaluator(program, x, y[rows], backend, periods=periods)
        ev.count_row_invariant_zero_divisions = index == 0
        ev.defer_noise = cull
        shape = (rows.stop - rows.start, width)
        with np.errstate(all="ignore"):
            layers = [layer_fields(ev, layer) for layer in program.layers]
            culled = resolve(layers, shape, materialise)  # no cache: alphas freed after
        stats.noise_texels += culled.deferred_texels
        stats.noise_texels_computed += culled.computed_texels
        try:
            prog = compile_layers(layers, shape)
        except UnsupportedProgram:
            layers = [_map_layer(ev.concrete, layer) for layer in layers]
            band = {name: array[rows] for name, array in maps.items()}
            for channel in LAYOUT.maxed:  # the numpy compositing's max accumulator
                band[channel.field][...] = -np.inf
            with np.errstate(all="ignore"):
                C.composite_band(layers, band, slice(0, shape[0]))
        else:
            flags = np.zeros(shape, np.uint8)
            run_kernel(prog, maps, rows.start, flags)
            with np.errstate(all="ignore"):
                found = _flagged(layers, flags, rows.start)
            if found is not None:
                flagged.append(found)
        stats.zero_divisions += ev.stats.zero_divisions
        if index == 0:
            stats.define_evaluations = ev.stats.define_evaluations
    with np.errstate(all="ignore"):
        _recomposite(maps, flagged)
    return maps


def evaluate_fused(
    program: A.Program,
    x: np.ndarray,
    y: np.ndarray,
    view: View,
    backend: Backend,
    *,
    ao_radius_units: float | None = None,
    stats: EvalStats | None = None,
    cull: bool = True,
) -> MaterialMaps:
    """Fused evaluation of ``program`` on the sample axes ``x`` (1, W) and ``y`` (H, 1);
    ``cull=False`` computes every fBm field everywhere (same maps, for comparison)."""
    height, width = y.shape[0], x.shape[1]
    stats = stats if stats is not None else EvalStats()
    radius_x, radius_y = C.ao_radii(view, width, height, None, ao_radius_units)
    maps = composite_program(program, x, y, backend, stats, cull, periods=view.periods)
    from matloom.engine.tiling import relief_maps

    maps["normal"], maps["ao"] = relief_maps(
        maps["height"],
        view,
        (radius_x, radius_y),
        relief_numba.normals,
        relief_numba.ambient_occlusion,
    )
    return MaterialMaps(**maps, view=view, n_layers=len(program.layers))
