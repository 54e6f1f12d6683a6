"""Static evaluation cost: coordinate frames and the expression nodes an evaluation visits.

The evaluator memoises each Define per *coordinate frame*: the composed affine map from the
sampling grid to the coordinates an expression is evaluated at (``Translate``, ``Scale`` and
``Rotate`` each compose one more map). A frame is identified by the six coefficients of that map
(composed in float64 from the very numbers the evaluator applies, rounded to 40 significant bits:
:func:`frame_key`), so equal frames reached by different paths compare equal:
``Translate(Translate(d, 1, 0), 2, 0)`` and ``Translate(Translate(d, 2, 0), 1, 0)`` are one
frame, and so are two rotations applied in either order. :class:`FrameTable` numbers the distinct frames for the evaluator and for
:func:`expanded_cost`, which counts, without evaluating anything, the expression nodes the
evaluator will visit: each Define once per distinct frame it is used in, and each call weighted by
its op's *work* (``Op.work``, :mod:`matloom.ops.work`: a bound, from the call's static
parameters, of every loop its kernels run, in units of one element-wise operation). That count
times the texel count bounds the work of an evaluation (see ``docs/limits.md``).
"""

from __future__ import annotations

import math
import struct
from dataclasses import dataclass
from typing import Any

from matloom.lang import ast as A
from matloom.lang.constants import resolve_static
from matloom.lang.macros import expand_program
from matloom.lang.static import COORDINATES, is_static, param_value, static_number
from matloom.ops import OPS
from matloom.ops.transform import Transform
from matloom.vocab import FUNCTIONS, Kind
from matloom.vocab.spec import Returns

MAX_EXPANDED_NODES = 200_000
"""Most expression-node evaluations one program may need (E071), whatever the image size."""

#: The coordinate transforms (ops with transform rules: Translate, Scale, Rotate).
TRANSFORMS = tuple(name for name, op in OPS.items() if op.transform is not None)

#: x' = a x + b y + c, y' = d x + e y + f (the sampling grid's x, y): (a, b, c, d, e, f).
Affine = tuple[float, float, float, float, float, float]
IDENTITY: Affine = (1.0, 0.0, 0.0, 0.0, 1.0, 0.0)
#: Significant bits of the frame coefficients that frames must share to be equal.
KEY_BITS = 40


def transform_values(call: A.Call) -> tuple[float, float]:
    """The two numbers a transform applies (its op's ``transform.values``,
    :mod:`matloom.ops.transform`): (dx, dy) of Translate, (sx, sy) of Scale, (cos, sin) of
    Rotate's angle. The evaluator maps (x, y) to (x - dx, y - dy), (x / sx, y / sy) and
    (cos x + sin y, -sin x + cos y)."""
    return _rule(call.func).values(lambda name: param_value(call, name))


def field_params(call: A.Call) -> tuple[str, ...]:
    """The parameters of ``call`` that accept fields and are written as fields (noise,
    patterns, Define references, ...): a transform with any is a domain warp, evaluated per
    sample, whose frame equals no other. X()/Y() alone keep their language-1 meaning (evaluated
    once at the origin, warning W004), so every language-1 program means what it meant."""
    spec = FUNCTIONS.get(call.func)
    if spec is None:
        return ()
    return tuple(
        p.name
        for p in spec.params
        if p.field and (node := call.arg(p.name)) is not None and static_number(node) is None
    )


def _rule(func: str) -> Transform:
    rule = OPS[func].transform
    if rule is None:
        raise ValueError(f"{func}(...) is not a coordinate transform")
    return rule


def compose(frame: Affine, func: str, values: tuple[float, float]) -> Affine | None:
    """The frame reached by applying transform ``func`` with ``values`` in ``frame`` (float64
    arithmetic); None when it is not finite (or a scale is 0): such a frame equals no other."""
    if not _rule(func).affine:
        return None  # Quantize: its frames equal no other (but repeat calls share them)
    try:
        t0, t1, t2, t3, t4, t5 = _rule(func).matrix(float(values[0]), float(values[1]))
    except (ValueError, OverflowError, ZeroDivisionError, TypeError):
        return None
    a, b, c, d, e, f = frame
    out = (
        t0 * a + t1 * d,
        t0 * b + t1 * e,
        t0 * c + t1 * f + t2,
        t3 * a + t4 * d,
        t3 * b + t4 * e,
        t3 * c + t4 * f + t5,
    )
    return out if all(map(math.isfinite, out)) else None


def frame_key(affine: Affine) -> tuple[int, ...]:
    """The coefficients rounded to :data:`KEY_BITS` significant bits (their IEEE bit patterns
    with the low mantissa bits rounded off; -0.0 counts as 0.0).

    Frames reached by different paths differ by float64 rounding (~1e-16 relative), which this
    absorbs (a rare pair that straddles a rounding step just stays two frames). Coefficients
    closer than 2**-40 relative give coordinates equal to far below float32 resolution."""
    bits = _WORDS.unpack(_DOUBLES.pack(*(v + 0.0 for v in affine)))
    return tuple((b + _HALF) >> _DROP for b in bits)


_DOUBLES, _WORDS = struct.Struct("<6d"), struct.Struct("<6Q")
_DROP = 52 - KEY_BITS
_HALF = 1 << (_DROP - 1)


class FrameTable:
    """The distinct coordinate frames met so far, numbered in order of first use (0 = the grid).

    A frame keeps the coefficients of the first path that reached it."""

    def __init__(self) -> None:
        self._affine: list[Affine | None] = [IDENTITY]
        self._ids: dict[tuple[int, ...], int] = {frame_key(IDENTITY): 0}
        self._children: dict[tuple[int, str, float, float], int] = {}
        #: frames made by domain warps -> their tileable periods (the evaluator's; None: the
        #: warp cannot keep them)
        self.warped: dict[int, tuple[float, float] | None] = {}

    def __len__(self) -> int:
        return len(self._affine)

    def child(self, parent: int, func: str, values: tuple[float, float]) -> int:
        """The frame of transform ``func`` (with ``values``) applied in frame ``parent``."""
        key = (parent, func, *values)
        fid = self._children.get(key)  # NaN never equals itself: such frames stay unshared
        if fid is None:
            base = self._affine[parent]
            affine = None if base is None else compose(base, func, values)
            fid = self._add(affine)
            self._children[key] = fid
        return fid

    def unique(self) -> int:
        """A new frame equal to no other (coordinates that no transform of the grid made)."""
        return self._add(None)

    def _add(self, affine: Affine | None) -> int:
        key = None if affine is None else frame_key(affine)
        if key is not None and key in self._ids:
            return self._ids[key]
        self._affine.append(affine)
        if key is not None:
            self._ids[key] = len(self._affine) - 1
        return len(self._affine) - 1

    def affine(self, fid: int) -> Affine | None:
        """The frame's map from the grid's (x, y), or None (coordinates no transform made)."""
        return self._affine[fid]

    def is_rotated(self, fid: int) -> bool:
        """True when the frame mixes x and y (its coordinates are full grids, not axes)."""
        affine = self._affine[fid]
        return affine is None or affine[1] != 0 or affine[3] != 0


@dataclass(frozen=True)
class Cost:
    """What :func:`expanded_cost` found (counts stop growing once ``over``)."""

    #: expression nodes the evaluator visits (more than the cap when ``over``)
    nodes: int
    #: visits of nodes that may allocate a field-sized array (not literals, constant math,
    #: X()/Y(), Define references or transforms)
    arrays: int
    #: the part of ``arrays`` of the ``batched`` nodes
    batched_arrays: int
    #: distinct (Define, frame) pairs: the Define values the evaluator keeps
    define_evaluations: int
    #: distinct coordinate frames, and those of them that are rotated (full-grid coordinates)
    frames: int
    rotated_frames: int
    #: most field values alive at once along the evaluation stack (an upper bound)
    pending: int
    #: non-constant layer channel values (each may be a field of its own), and layers
    channel_fields: int
    layers: int
    over: bool
    #: (name, frames) of the Define evaluated in the most distinct frames, if any
    busiest_define: tuple[str, int] | None = None


def _field_children(node: A.Node) -> tuple[A.Node, ...]:
    """The sub-expressions the evaluator evaluates as fields (not static parameters; field
    parameters written as non-constant expressions are fields)."""
    if not isinstance(node, A.Call):
        return A.children(node)
    spec = FUNCTIONS.get(node.func)
    if spec is None:
        return A.children(node)
    fields = {p.name for p in spec.params if p.kind is Kind.EXPR} | set(field_params(node))
    extra = node.extra if spec.nary else ()  # Min(a, b, c, ...): one more op per operand
    return tuple(a.value for a in node.args if a.param in fields) + extra


def op_work(call: A.Call) -> int:
    """Node evaluations one evaluation of ``call`` counts by itself: its op's ``work``
    (:mod:`matloom.ops.work`: a number, or a rule over the call's static parameters
    that bounds every loop its kernels run), at least 1."""
    op = OPS.get(call.func)
    work = 1 if op is None else op.work
    try:
        if callable(work):
            work = work(lambda name: param_value(call, name))
        return max(1, math.ceil(work))
    except (ValueError, TypeError, ArithmeticError, AssertionError, KeyError):
        return 1  # parameters the checker rejects (not constants, out of range)


def call_work(call: A.Call) -> int:
    """:func:`op_work` of ``call``, with a Fill/Stroke's shape and its path segments (each
    segment's edges are drawn on every sample)."""
    work = op_work(call)
    if call.extra and _nary(call):  # Min(a, b, c, ...): one binary op per further operand
        work += op_work(call) * len(call.extra)
    shape = call.arg("shape") if call.func in _SHAPED else None
    if isinstance(shape, A.Call):
        work += op_work(shape)
        work += sum(op_work(s) for s in shape.extra if isinstance(s, A.Call))
    return work


def _transform_values(node: A.Call) -> tuple[float, float] | None:
    try:
        return transform_values(node)
    except (ValueError, TypeError, OverflowError, AssertionError, KeyError):
        return None


#: What the walk needs of a node: ("ref", name), ("transform", func, values or None, body,
#: warp parameters, instances, extra nodes) or ("field", extra nodes, field children, arrays
#: it may allocate); extra nodes: the node's work beyond 1 (:func:`call_work`).
_Info = tuple[Any, ...]
#: The functions that draw a shape (Fill, Stroke): a parameter of kind SHAPE.
_SHAPED = tuple(n for n, s in FUNCTIONS.items() if any(p.kind is Kind.SHAPE for p in s.params))
#: Functions whose value is a scalar when their field operands are (as numpy gives it).
_SCALAR_MATH = frozenset(
    ("Constant", "Abs", "Sqrt", "Floor", "Ceil", "Sin", "Cos", "Log", "Min", "Max")
)


def _constant(node: A.Node, cache: dict[int, bool]) -> bool:
    """True when the evaluator's value of ``node`` is a scalar (literals and math on them)."""
    hit = cache.get(id(node))
    if hit is None:
        if isinstance(node, A.Num | A.Const):
            hit = True
        elif isinstance(node, A.Call) and node.func not in _SCALAR_MATH:
            hit = False
        elif isinstance(node, A.Neg | A.BinOp | A.Call):
            hit = all(_constant(k, cache) for k in _field_children(node))
        else:
            hit = False
        cache[id(node)] = hit
    return hit


def _info(node: A.Node, constants: dict[int, bool]) -> _Info:
    if isinstance(node, A.Ref):
        return ("ref", node.name)
    if isinstance(node, A.Call) and node.func in TRANSFORMS:
        warp = field_params(node)
        values = None if warp else _transform_values(node)
        params = tuple(node.arg(name) for name in warp)
        return ("transform", node.func, values, node.arg("expr"), params, 1, op_work(node) - 1)
    spec = FUNCTIONS.get(node.func) if isinstance(node, A.Call) else None
    if spec is not None and spec.instances:  # instancing (Tile): one frame per instance
        extra = op_work(node) - 1
        return ("transform", node.func, None, node.arg("expr"), (), spec.instances, extra)
    extra = call_work(node) - 1 if isinstance(node, A.Call) else 0
    axis = isinstance(node, A.Call) and node.func in COORDINATES
    if axis or _constant(node, constants):
        return ("field", extra, _field_children(node), 0)
    return ("field", extra, _field_children(node), _arrays(node))


def _arrays(node: A.Node) -> int:
    """Field-sized arrays one evaluation of ``node`` allocates (the op table's ``arrays``)."""
    op = OPS.get(node.func) if isinstance(node, A.Call) else None
    arrays = op.arrays if op is not None else 1
    if isinstance(node, A.Call) and node.extra and _nary(node):
        arrays *= 1 + len(node.extra)  # Min(a, b, c, ...): one array per binary op
    return arrays


def _nary(call: A.Call) -> bool:
    """``call`` takes extra field operands (``FunctionSpec.nary``: Min, Max)."""
    spec = FUNCTIONS.get(call.func)
    return spec is not None and spec.nary


def _roots(program: A.Program) -> list[A.Node]:
    roots: list[A.Node] = []
    for layer in program.layers:
        if layer.alpha is not None:
            roots.append(layer.alpha)
        roots.extend(a for ch in layer.channels for a in ch.args)
    return roots


class _Walk:
    """The evaluator's traversal without the arrays (see :func:`expanded_cost`)."""

    def __init__(self, program: A.Program) -> None:
        self.defines = {d.name: d.expr for d in program.defines}
        self.table = FrameTable()
        self.seen: set[tuple[str, int]] = set()
        self.rotated: set[int] = set()
        self.infos: dict[int, _Info] = {}
        self.constants: dict[int, bool] = {}
        self.nodes = self.arrays = self.pending = self.batched_arrays = 0
        #: ids of the nodes whose arrays are counted in ``batched_arrays`` too
        self.batched: frozenset[int] = frozenset()

    def run(self, roots: list[A.Node], cap: int) -> None:
        stack: list[tuple[A.Node, int, int]] = [(r, 0, 0) for r in reversed(roots)]
        infos = self.infos
        while stack and self.nodes <= cap:
            node, frame, held = stack.pop()
            self.nodes += 1
            info = infos.get(id(node))
            if info is None:
                info = infos[id(node)] = _info(node, self.constants)
            if info[0] == "ref":
                key = (info[1], frame)
                if key not in self.seen and info[1] in self.defines:
                    self.seen.add(key)
                    stack.append((self.defines[info[1]], frame, held))
            elif info[0] == "transform":
                self.nodes += info[6]
                for _ in range(info[5]):  # Tile: one frame per instance
                    child = self.child_frame(info[1], info[2], frame)
                    turned = child != frame and self.table.is_rotated(child)
                    if turned:
                        self.rotated.add(child)
                    if info[3] is not None:
                        stack.append((info[3], child, held + turned))
                if info[4]:  # a warp's field parameters, in the parent frame (evaluated first)
                    self.arrays += len(info[4])
                    stack.extend((k, frame, held) for k in reversed(info[4]))
            else:
                self.nodes += info[1]
                self.arrays += info[3]
                if info[3] and id(node) in self.batched:
                    self.batched_arrays += 1
                kids = info[2]
                self.pending = max(self.pending, held + len(kids) + 1)
                stack.extend((kids[i], frame, held + i) for i in range(len(kids) - 1, -1, -1))

    def child_frame(self, func: str, values: tuple[float, float] | None, frame: int) -> int:
        if values is None:
            return self.table.unique()
        return self.table.child(frame, func, values)


def expanded_cost(
    program: A.Program, cap: int = MAX_EXPANDED_NODES, batched: frozenset[int] = frozenset()
) -> Cost:
    """Count, without evaluating, the nodes an evaluation of ``program`` visits (stops past
    ``cap``). It walks the layer expressions in evaluation order, entering a Define's body the
    first time the Define is referenced in each distinct frame, as the evaluator's memo does.
    ``batched``: ids of nodes (e.g. the seed-dependent ones of a sweep) whose array visits are
    also counted apart. Named static values are read as the evaluator reads them
    (:func:`~matloom.lang.constants.resolve_static`)."""
    program = resolve_static(expand_program(program))
    roots = _roots(program)
    walk = _Walk(program)
    walk.batched = batched
    walk.run(roots, cap)
    return Cost(
        nodes=walk.nodes,
        arrays=walk.arrays,
        batched_arrays=walk.batched_arrays,
        define_evaluations=len(walk.seen),
        frames=len(walk.table),
        rotated_frames=len(walk.rotated),
        pending=walk.pending,
        channel_fields=sum(1 for r in roots if not is_static(r)),
        layers=len(program.layers),
        over=walk.nodes > cap,
        busiest_define=_busiest(walk.seen),
    )


def _busiest(seen: set[tuple[str, int]]) -> tuple[str, int] | None:
    """(name, frames) of the Define evaluated in the most frames."""
    counts: dict[str, int] = {}
    for name, _ in seen:
        counts[name] = counts.get(name, 0) + 1
    return max(counts.items(), key=lambda kv: kv[1], default=None)


@dataclass(frozen=True)
class Costliest:
    """The call of a program that counts the most node evaluations by itself."""

    call: A.Call
    work: int
    #: where it is written: "Define 'name'" or "layer N"
    owner: str


def costliest_call(program: A.Program) -> Costliest | None:
    """The field call with the largest :func:`call_work` (the first such in evaluation order),
    or None when the program has no call."""
    best: Costliest | None = None
    for owner, expr in A.program_expressions(resolve_static(program)):
        for node in A.walk(expr):
            spec = FUNCTIONS.get(node.func) if isinstance(node, A.Call) else None
            if spec is None or spec.returns is not Returns.FIELD:
                continue
            work = call_work(node)  # type: ignore[arg-type]
            if best is None or work > best.work:
                where = f"Define '{owner[1]}'" if owner[0] == "define" else f"layer {owner[1]}"
                best = Costliest(node, work, where)  # type: ignore[arg-type]
    return best


#: A single call counting at least 1/_DOMINANT_SHARE of the limit is named as the cause.
_DOMINANT_SHARE = 10


def over_limit(program: A.Program, cost: Cost, limit: int) -> tuple[str, str, A.Call | None]:
    """(message, hint, call to point at) for a program counting more than ``limit`` node
    evaluations: the call whose own work is a large share of it (a loop its parameters make
    long), else the Define evaluated in the most coordinate frames."""
    from matloom.lang.printer import format_expr
    from matloom.ops.work import HINTS

    heavy = costliest_call(program)
    if heavy is not None and heavy.work * _DOMINANT_SHARE >= limit:
        text = format_expr(heavy.call)
        text = text if len(text) <= 80 else text[:77] + "..."
        message = (
            f"{heavy.call.func} in {heavy.owner} counts {heavy.work:,} node evaluations per "
            f"sample by itself ({text}), and the program more than {limit:,} expression-node "
            "evaluations, the limit"
        )
        hint = HINTS.get(heavy.call.func, "lower the parameters that set its work")
        return message, hint + " (see docs/limits.md)", heavy.call
    busiest = cost.busiest_define
    where = f"; Define '{busiest[0]}' in {busiest[1]:,} frames" if busiest else ""
    message = (
        f"program needs more than {limit:,} expression-node evaluations, the limit: each Define "
        "is evaluated once in every distinct coordinate frame (Translate/Scale/Rotate) it is "
        f"used in ({cost.define_evaluations:,} Define evaluations in {cost.frames:,} frames "
        f"counted before stopping{where})"
    )
    hint = (
        "transforms of Defines that combine transformed Defines multiply the work; transform a "
        "Define once and reuse it"
    )
    return message, hint, None
