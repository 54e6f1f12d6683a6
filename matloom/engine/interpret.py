"""The interpreter: AST -> field values, every function dispatched through the op table.

Fields are numpy arrays broadcastable to (H, W): ``X()`` stays a (1, W) float32 axis and
constants stay scalars until an operation needs more, so separable work is never expanded.
Each Define is evaluated once per distinct coordinate frame (a DAG, not a tree; equal frames
reached by different paths share it, see :mod:`matloom.lang.cost`). Primitive kernels come from
a :class:`~matloom.engine.backends.Backend`.

:class:`Evaluator` is the interpreter over dense values; a schedule changes the kind of value by
overriding its hooks (:meth:`Evaluator.apply` for element-wise ops, :meth:`Evaluator.fbm` /
:meth:`Evaluator.worley` for noise, :meth:`Evaluator.eval` for memoisation): lazy expressions
(:mod:`matloom.engine.lazy`), seed batches (:mod:`matloom.engine.schedules.seed_batch`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cache
from typing import Any

import numpy as np

from matloom.engine.backends import Backend
from matloom.engine.composite import RawLayer
from matloom.engine.kernels import shapes
from matloom.engine.kernels.mathops import count_zero
from matloom.lang import ast as A
from matloom.lang.cost import FrameTable, field_params, transform_values
from matloom.lang.static import param_value
from matloom.ops import OPS, Kind, Op, operator_ops
from matloom.ops.transform import Transform
from matloom.vocab import CONSTANTS, FUNCTIONS
from matloom.vocab.spec import Kind as ParamKind

Field = Any  # np.ndarray (broadcastable to (H, W)) or np.float64 scalar
Coords = tuple[Any, Any]
#: The binary operators' ops ("+" -> Add, ...).
OPERATORS: dict[str, Op] = operator_ops()


class Frame(tuple):
    """Coordinates (x, y) that know their frame number ``fid`` (see :meth:`Evaluator.transform`)."""

    fid: int

    def __new__(cls, x: Any, y: Any, fid: int) -> Frame:
        self = super().__new__(cls, (x, y))
        self.fid = fid
        return self


@dataclass
class EvalStats:
    """Counters gathered during one evaluation (reported by the CLI)."""

    zero_divisions: int = 0
    define_evaluations: int = 0
    notes: list[str] = field(default_factory=list)
    #: Texels of culled fBm fields (engine.cull): considered, and actually computed.
    noise_texels: int = 0
    noise_texels_computed: int = 0


@cache
def operand_names(func: str) -> tuple[str, ...]:
    """The expression parameters of ``func`` (an element-wise op's operands), registry order."""
    return tuple(p.name for p in FUNCTIONS[func].params if p.kind is ParamKind.EXPR)


@cache
def static_names(func: str, frequency: bool = True) -> tuple[str, ...]:
    """The static parameters of ``func`` (``frequency=False``: without frequencies)."""
    return tuple(
        p.name
        for p in FUNCTIONS[func].params
        if p.kind not in (ParamKind.EXPR, ParamKind.SHAPE, ParamKind.SEGMENT)
        and (frequency or not p.is_frequency)
    )


@cache
def _noise_names(func: str) -> tuple[str, ...]:
    """Kernel keywords of a noise function besides frequencies, to_01 and seed."""
    return tuple(n for n in static_names(func, False) if n not in ("to_01", "seed"))


class Evaluator:
    """Evaluates the expressions of one program on one sampling grid (dense values)."""

    def __init__(
        self,
        program: A.Program,
        x: np.ndarray,
        y: np.ndarray,
        backend: Backend,
        *,
        periods: tuple[float, float] | None = None,
    ) -> None:
        self.program = program
        #: (W, H) of a tileable View (every noise repeats with them), else None
        self.periods = periods
        self.backend = backend
        self.base: Coords = Frame(x, y, 0)
        self.defines = {d.name: d.expr for d in program.defines}
        self.memo: dict[tuple[str, int], Field] = {}
        #: the distinct coordinate frames (equal composed transforms share one number)
        self.frame_table = FrameTable()
        #: frames of coordinates passed in by a caller: (ids of x, y) -> (frame, coordinates)
        self._foreign: dict[tuple[int, int], tuple[int, Coords]] = {}
        #: frames made by a non-affine transform (Quantize) and the transforms inside it:
        #: their periods come from the period rules (:meth:`_nonaffine_periods`)
        self.nonaffine: set[int] = set()
        self.stats = EvalStats()

    # ---------------------------------------------------------------- public
    def field(self, node: A.Node, coords: Coords | None = None) -> Field:
        return self.eval(node, coords or self.base)

    # ---------------------------------------------------------------- dispatch
    def eval(self, node: A.Node, c: Coords) -> Field:
        if isinstance(node, A.Num):
            return np.float64(node.value)
        if isinstance(node, A.Const):
            return np.float64(CONSTANTS[node.name])
        if isinstance(node, A.Ref):
            return self.ref(node.name, c)
        if isinstance(node, A.Neg):
            return self.binop("*", np.float64(-1.0), self.eval(node.operand, c))
        if isinstance(node, A.BinOp):
            return self.binop(node.op, self.eval(node.left, c), self.eval(node.right, c))
        if isinstance(node, A.Call):
            return self.call(node, c)
        raise TypeError(f"cannot evaluate {type(node).__name__} as a field")

    def ref(self, name: str, c: Coords) -> Field:
        key = (name, self._frame_id(c))
        if key not in self.memo:
            self.stats.define_evaluations += 1
            self.memo[key] = self.eval(self.defines[name], c)
        return self.memo[key]

    def _frame_id(self, c: Coords) -> int:
        """Number of the coordinate frame of ``c`` (the memo key of Define values)."""
        fid = getattr(c, "fid", None)
        if fid is not None:
            return fid
        entry = self._foreign.get((id(c[0]), id(c[1])))
        if entry is None:  # the entry keeps ``c`` alive so that the ids stay unique
            entry = (self.frame_table.unique(), c)
            self._foreign[(id(c[0]), id(c[1]))] = entry
        return entry[0]

    def binop(self, op: str, a: Field, b: Field) -> Field:
        if op not in OPERATORS:
            raise ValueError(f"unknown operator {op}")
        return self.operate(OPERATORS[op], [a, b], {})

    def call(self, call: A.Call, c: Coords) -> Field:
        op = OPS.get(call.func)
        if op is None or op.kind is Kind.GEOMETRY:
            raise ValueError(f"{call.func}(...) cannot be evaluated as a field")
        if op.kind is Kind.FIELD:
            return op.numpy(self, call, c)
        args = [self.eval(call.arg(name), c) for name in operand_names(call.func)]  # type: ignore[arg-type]
        params = self.params(call)
        out = self.operate(op, args, params)
        for extra in call.extra:  # Min(a, b, c, ...): the binary op folded left
            out = self.operate(op, [out, self.eval(extra, c)], params)
        return out

    def operate(self, op: Op, args: list[Field], params: dict[str, Any]) -> Field:
        """An element-wise op: counts zero divisors, then :meth:`apply`."""
        if op.divisor is not None:
            self.count_divisor(args[op.divisor])
        return self.apply(op, args, params)

    def count_divisor(self, b: Field) -> None:
        self.stats.zero_divisions += count_zero(b)

    def apply(self, op: Op, args: list[Field], params: dict[str, Any]) -> Field:
        """The value of an element-wise op (dense: its numpy implementation)."""
        with np.errstate(all="ignore"):
            return op.numpy(*args, **params)

    # ---------------------------------------------------------------- parameters
    def num(self, call: A.Call, name: str) -> Any:
        """Static value of a numeric/enum/bool parameter (its default when not written)."""
        return param_value(call, name)

    def params(self, call: A.Call, frequency: bool = True) -> dict[str, Any]:
        """Every static parameter of ``call`` (``frequency=False``: without frequencies)."""
        return {p: self.num(call, p) for p in static_names(call.func, frequency)}

    def freqs(self, call: A.Call) -> tuple[float, float]:
        base = self.num(call, "base_freq")
        fx = self.num(call, "base_freq_x")
        fy = self.num(call, "base_freq_y")
        return (base if fx is None else fx), (base if fy is None else fy)

    # ---------------------------------------------------------------- primitives
    def fbm(self, call: A.Call, c: Coords) -> Field:
        return self.backend.fbm(c[0], c[1], **self.noise_args(call, c))

    def worley(self, call: A.Call, c: Coords) -> Field:
        return self.backend.worley(c[0], c[1], **self.noise_args(call, c))

    def noise_args(self, call: A.Call, c: Coords | None = None) -> dict[str, Any]:
        """The keyword arguments of the fBm/Worley kernel for ``call`` (in coordinates ``c``:
        with ``period`` where the output is tileable, see :meth:`periods_of`)."""
        fx, fy = self.freqs(call)
        seed = self.num(call, "seed")
        if seed is None:
            raise ValueError(f"{call.func} has no seed; canonicalise the program first")
        kw = dict(freq_x=fx, freq_y=fy, to_01=bool(self.num(call, "to_01")), seed=seed)
        period = None if c is None else self.periods_of(c, call.func)
        if period is not None:
            kw["period"] = period
        return {**kw, **{name: self.num(call, name) for name in _noise_names(call.func)}}

    def periods_of(self, c: Coords, func: str = "") -> tuple[float, float] | None:
        """The View's periods (W, H) in the frame of ``c``, for a tileable output whose frame
        is an axis-aligned affine map of the grid (Translate, Scale): (|a| W, |e| H). None
        when the output is not tileable, and (with a note) for a rotated frame, a domain
        warp whose period rule does not keep the periods (``Period.warp_keeps``: Translate's
        adds periodic offsets) or a frame whose periods are not finite and positive, where a
        noise cannot repeat with the View; Tile's instance frames need no period (their
        instances repeat). ``func`` only names the field in the notes."""
        if self.periods is None:
            return None
        fid = self._frame_id(c)
        affine = self.frame_table.affine(fid)
        warped = self.frame_table.warped
        if warped.get(fid) is not None:
            return warped[fid]
        if affine is None or not _axis_aligned(affine):
            if affine is not None or fid in warped:
                note = f"tileable: {func or 'a field'} in a rotated or warped frame cannot repeat"
                if note not in self.stats.notes:
                    self.stats.notes.append(note)
            return None
        width, height = self.periods
        periods = abs(affine[0]) * width, abs(affine[4]) * height
        if not all(math.isfinite(p) and p > 0 for p in periods):
            # a Scale by a subnormal (or huge) factor: periods past the float range
            what = func or "a field"
            note = f"tileable: {what} in a frame scaled past the float range cannot repeat"
            if note not in self.stats.notes:
                self.stats.notes.append(note)
            return None
        return periods

    def transform(self, call: A.Call, c: Coords) -> Coords:
        """Coordinates of ``call``'s operand. Their frame is the composed transform, so a Define
        used in equal frames reached by different paths is evaluated once (the first path's
        value is shared; see :mod:`matloom.lang.cost`). A transform with field parameters is a
        domain warp (:meth:`warp`)."""
        warped = field_params(call)
        if warped:
            return self.warp(call, c, warped)
        a, b = transform_values(call)
        rule = _transform(call.func)
        new = rule.coords(c[0], c[1], a, b)
        parent = self._frame_id(c)
        fid = self.frame_table.child(parent, call.func, (a, b))
        if not rule.affine or parent in self.nonaffine:
            self.nonaffine.add(fid)
            if self.periods is not None and fid not in self.frame_table.warped:
                self._nonaffine_periods(call, c, fid)
        return Frame(*new, fid)

    def _nonaffine_periods(self, call: A.Call, c: Coords, fid: int) -> None:
        """The periods of the frame ``fid`` that a non-affine transform (Quantize), or a
        transform inside one, made from ``c``: its period rule's (``Op.period.frame``), kept with the warps' frames so that
        :meth:`periods_of` finds them; none when ``c`` has none or the rule breaks them."""
        parent = self.periods_of(c, call.func)
        rule = OPS[call.func].period.frame
        if parent is None or rule is None:
            return
        inner = rule(call.func, lambda name: param_value(call, name), parent)
        if not isinstance(inner, str):
            self.frame_table.warped[fid] = inner

    def warp(self, call: A.Call, c: Coords, warped: tuple[str, ...]) -> Coords:
        """A domain warp: the field parameters evaluated at the samples' coordinates ``c``,
        then the transform applied per sample in the coordinates' dtype (a constant given as a
        field gives the very coordinates of the constant transform); a frame of its own."""
        dtype = np.result_type(c[0], c[1])
        values: list[Any] = []
        for p in FUNCTIONS[call.func].params:
            if not p.field:
                continue
            if p.name in warped:
                values.append(np.asarray(self.concrete(self.eval(call.arg(p.name), c))))
            else:
                values.append(param_value(call, p.name))
        rule = _transform(call.func)
        a, b = rule.warp(values)
        a, b = (np.asarray(v).astype(dtype) if np.ndim(v) else v for v in (a, b))
        with np.errstate(all="ignore"):
            new = rule.coords(c[0], c[1], a, b)
        frame = self.new_frame(*new)
        # a warp whose period rule keeps the periods (Translate's periodic offsets): its frame
        # has the periods of ``c``
        keeps = OPS[call.func].period.warp_keeps
        kept = self.periods_of(c, call.func) if keeps else None
        self.frame_table.warped[frame.fid] = kept  # type: ignore[attr-defined]
        return frame

    def new_frame(self, x: Any, y: Any) -> Coords:
        """Coordinates that no transform of the grid made (a frame equal to no other)."""
        return Frame(x, y, self.frame_table.unique())

    def motif_support(self, node: A.Node) -> Any:
        """The box outside which ``node`` is exactly 0, or None (engine.rules.support)."""
        from matloom.engine.rules.support import support

        return support(self, node, OPS, OPERATORS)

    def concrete(self, value: Any) -> Any:
        """The array of a value (dense values already are; see LazyEvaluator)."""
        return value

    def instance_value(self, node: A.Node, frame: Coords) -> Any:
        """The array of ``node`` in a frame of its own (a Tile instance), without keeping the
        frame's Define values or intermediate arrays once it is computed: the 9 instances of a
        Tile then hold one instance's arrays at a time."""
        memo = set(self.memo)
        try:
            return self.concrete(self.eval(node, frame))
        finally:
            for key in [k for k in self.memo if k not in memo]:
                del self.memo[key]

    def per_seed(self, call: A.Call, compute: Any) -> Any:
        """``compute(seed)`` with ``call``'s seed (a seed batch stacks it over its seeds)."""
        return compute(self.num(call, "seed"))

    def seed_of(self, call: A.Call) -> int:
        """The seed ``call`` runs with (a seed batch may vary it)."""
        seed = self.num(call, "seed")
        if seed is None:
            raise ValueError(f"{call.func} has no seed; canonicalise the program first")
        return int(seed)

    def shape(self, node: A.Call) -> shapes.Shape:
        """The geometry of a shape (or path segment) node."""
        return OPS[node.func].numpy(self, node)  # type: ignore[no-any-return]


def _axis_aligned(affine: tuple[float, ...]) -> bool:
    """The frame maps axes to axes (a rotation by a multiple of 180 degrees included: its
    sine is ~1e-16, not 0)."""
    a, b, _, d, e, _ = affine
    return abs(b) <= 1e-12 * abs(a) and abs(d) <= 1e-12 * abs(e)


def _transform(func: str) -> Transform:
    """The transform rules of ``func`` (``Op.transform``)."""
    rule = OPS[func].transform
    if rule is None:
        raise ValueError(f"{func}(...) is not a coordinate transform")
    return rule


def layer_fields(ev: Evaluator, layer: A.Layer) -> RawLayer:
    """Evaluate one layer's channels into a :class:`RawLayer` (defaults where not written)."""
    raw = RawLayer()
    if layer.alpha is not None:
        raw.alpha = ev.field(layer.alpha)
    for ch in layer.channels:
        raw.set(ch.name, [ev.field(a) for a in ch.args])
    return raw
