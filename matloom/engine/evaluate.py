"""Evaluation: AST -> sampled fields -> composited :class:`MaterialMaps`.

Fields are numpy arrays broadcastable to (H, W): ``X()`` stays a (1, W) float32 axis and
constants stay scalars until an operation needs more, so separable work is never expanded.
Each Define is evaluated once per coordinate frame (a DAG, not a tree). Primitive kernels come
from a :class:`~matloom.engine.backends.Backend`.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field
from functools import lru_cache
from typing import Any

import numpy as np

from matloom.engine.backends import Backend, choose_backend
from matloom.engine.composite import RawLayer, composite
from matloom.engine.grid import sample_axes
from matloom.engine.kernels import mathops, shapes
from matloom.engine.limits import DEFAULT_LIMITS, Limits, check_request
from matloom.engine.maps import MaterialMaps, View
from matloom.lang import ast as A
from matloom.lang.api import parse
from matloom.lang.seeds import canonicalize_seeds, has_seedless_noise
from matloom.lang.static import static_number
from matloom.vocab import CONSTANTS, FUNCTIONS

Field = Any  # np.ndarray (broadcastable to (H, W)) or np.float64 scalar
Coords = tuple[Any, Any]


@dataclass
class EvalStats:
    """Counters gathered during one evaluation (reported by the CLI)."""

    zero_divisions: int = 0
    define_evaluations: int = 0
    notes: list[str] = field(default_factory=list)
    #: Texels of culled fBm fields (engine.cull): considered, and actually computed.
    noise_texels: int = 0
    noise_texels_computed: int = 0


class Evaluator:
    """Evaluates the expressions of one program on one sampling grid."""

    def __init__(self, program: A.Program, x: np.ndarray, y: np.ndarray, backend: Backend) -> None:
        self.program = program
        self.backend = backend
        self.base: Coords = (x, y)
        self.defines = {d.name: d.expr for d in program.defines}
        self.memo: dict[tuple[str, int], Field] = {}
        self.frames: list[Coords] = [self.base]  # keeps coordinate frames alive for the memo key
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
            return np.float64(-1.0) * self.eval(node.operand, c)
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
        for i, f in enumerate(self.frames):
            if f[0] is c[0] and f[1] is c[1]:
                return i
        self.frames.append(c)
        return len(self.frames) - 1

    def binop(self, op: str, a: Field, b: Field) -> Field:
        with np.errstate(all="ignore"):
            if op == "+":
                return a + b
            if op == "-":
                return a - b
            if op == "*":
                return a * b
            if op == "/":
                self.stats.zero_divisions += int(np.count_nonzero(np.asarray(b) == 0))
                return mathops.safe_div(a, b)
            if op == "**":
                return mathops.pow_(a, b)
        raise ValueError(f"unknown operator {op}")

    # ---------------------------------------------------------------- calls
    def num(self, call: A.Call, name: str) -> Any:
        """Static value of a numeric/enum/bool parameter (its default when not written)."""
        node = call.arg(name)
        p = FUNCTIONS[call.func].param(name)
        assert p is not None
        if node is None:
            return p.default
        if isinstance(node, A.Str | A.Lit):
            return node.value
        v = static_number(node)
        if v is None:
            raise ValueError(f"{call.func}: {name} is not a constant")
        return int(round(v)) if p.kind.value == "int" else float(v)

    def call(self, call: A.Call, c: Coords) -> Field:  # noqa: C901 - flat dispatch on the function
        f = call.func
        if f == "X":
            return c[0]
        if f == "Y":
            return c[1]
        if f == "Constant":
            return np.float64(self.num(call, "value"))
        if f in _UNARY:
            with np.errstate(all="ignore"):
                return _UNARY[f](self.eval(call.arg("expr"), c))  # type: ignore[arg-type]
        if f == "Log":
            return mathops.log(self.eval(call.arg("expr"), c), self.num(call, "base"))  # type: ignore[arg-type]
        if f in ("Min", "Max"):
            a = self.eval(call.arg("expr1"), c)  # type: ignore[arg-type]
            b = self.eval(call.arg("expr2"), c)  # type: ignore[arg-type]
            return np.minimum(a, b) if f == "Min" else np.maximum(a, b)
        if f in ("fBm", "Worley"):
            return self.noise(call, c)
        if f == "Bricks":
            return self.backend.bricks(c[0], c[1], **{p: self.num(call, p) for p in _BRICKS})
        if f == "Weave":
            fx, fy = self.freqs(call)
            kw = {p: self.num(call, p) for p in _WEAVE}
            return self.backend.weave(c[0], c[1], freq_x=fx, freq_y=fy, **kw)
        if f == "Threshold":
            v = np.asarray(self.eval(call.arg("expr"), c))  # type: ignore[arg-type]
            kw = {p: self.num(call, p) for p in _THRESHOLD}
            return self.backend.threshold(v, **kw)
        if f in ("Translate", "Scale", "Rotate"):
            return self.eval(call.arg("expr"), self.transform(call, c))  # type: ignore[arg-type]
        if f == "Fill":
            geom = self.shape(call.arg("shape"))  # type: ignore[arg-type]
            return self.backend.fill(
                geom, c[0], c[1], mode=self.num(call, "mode"), feather=self.num(call, "feather")
            )
        if f == "Stroke":
            geom = self.shape(call.arg("shape"))  # type: ignore[arg-type]
            return self.backend.stroke(
                geom, c[0], c[1], width=self.num(call, "width"), feather=self.num(call, "feather")
            )
        raise ValueError(f"{f}(...) cannot be evaluated as a field")

    def freqs(self, call: A.Call) -> tuple[float, float]:
        base = self.num(call, "base_freq")
        fx = self.num(call, "base_freq_x")
        fy = self.num(call, "base_freq_y")
        return (base if fx is None else fx), (base if fy is None else fy)

    def noise(self, call: A.Call, c: Coords) -> Field:
        if call.func == "fBm":
            return self.backend.fbm(c[0], c[1], **self.noise_args(call))
        return self.backend.worley(c[0], c[1], **self.noise_args(call))

    def noise_args(self, call: A.Call) -> dict[str, Any]:
        """The keyword arguments of the fBm/Worley kernel for ``call``."""
        fx, fy = self.freqs(call)
        seed = self.num(call, "seed")
        if seed is None:
            raise ValueError(f"{call.func} has no seed; canonicalise the program first")
        kw = dict(freq_x=fx, freq_y=fy, to_01=bool(self.num(call, "to_01")), seed=seed)
        return {**kw, **{name: self.num(call, name) for name in _NOISE[call.func]}}

    def transform(self, call: A.Call, c: Coords) -> Coords:
        x, y = c
        if call.func == "Translate":
            return x - self.num(call, "dx"), y - self.num(call, "dy")
        if call.func == "Scale":
            return x / self.num(call, "sx"), y / self.num(call, "sy")
        rad = math.radians(self.num(call, "degrees"))
        cs, sn = math.cos(rad), math.sin(rad)
        return cs * x + sn * y, -sn * x + cs * y

    def shape(self, node: A.Call) -> shapes.Shape:
        vals = {a.param: float(static_number(a.value) or 0.0) for a in node.args}
        if node.func == "Rect":
            return shapes.make_rect(
                vals["x"], vals["y"], vals["width"], vals["height"], vals.get("radius", 0.0)
            )
        if node.func == "Ellipse":
            return shapes.EllipseGeom(vals["cx"], vals["cy"], vals["rx"], vals["ry"])
        segs = []
        for s in node.extra:
            assert isinstance(s, A.Call)
            sv = [float(static_number(a.value) or 0.0) for a in s.args]
            segs.append(shapes.LineSeg(*sv) if s.func == "LineTo" else shapes.CubicSeg(*sv))
        return shapes.PathGeom(vals["start_x"], vals["start_y"], tuple(segs))


_UNARY = {
    "Abs": np.abs,
    "Sqrt": np.sqrt,
    "Floor": np.floor,
    "Ceil": np.ceil,
    "Sin": np.sin,
    "Cos": np.cos,
}
# Static keyword parameters passed straight to the kernels, read from the registry.
_BRICKS = FUNCTIONS["Bricks"].param_names
_WEAVE = tuple(p.name for p in FUNCTIONS["Weave"].params if not p.is_frequency)
_THRESHOLD = tuple(p.name for p in FUNCTIONS["Threshold"].params if p.name != "expr")
#: Kernel keywords of the noise functions besides frequencies, to_01 and seed (fBm: octaves,
#: lacunarity, gain; Worley: distance, combination).
_NOISE = {
    f: tuple(
        p.name
        for p in FUNCTIONS[f].params
        if not p.is_frequency and p.name not in ("to_01", "seed")
    )
    for f in ("fBm", "Worley")
}


def layer_fields(ev: Evaluator, layer: A.Layer) -> RawLayer:
    """Evaluate one layer's channels into a :class:`RawLayer` (defaults where not written)."""
    raw = RawLayer()
    if layer.alpha is not None:
        raw.alpha = ev.field(layer.alpha)
    for ch in layer.channels:
        vals = [ev.field(a) for a in ch.args]
        if ch.name in ("basecolor", "emissive"):
            setattr(raw, ch.name, tuple(vals))
        else:
            setattr(raw, ch.name, vals[0])
    return raw


@lru_cache(maxsize=64)
def _parse_cached(text: str) -> A.Program:
    """``parse`` memoised on the text (the AST is immutable, so sharing it is safe)."""
    return parse(text)


def prepare(program_or_text: A.Program | str, program_seed: int = 0) -> A.Program:
    """Parse (if text) and make omitted seeds explicit so evaluation is deterministic."""
    if isinstance(program_or_text, str):
        return _prepare_text(program_or_text, program_seed)
    return _with_seeds(program_or_text, program_seed)


@lru_cache(maxsize=64)
def _prepare_text(text: str, program_seed: int) -> A.Program:
    """:func:`prepare` of a text, memoised (the AST is immutable, so sharing it is safe)."""
    return _with_seeds(_parse_cached(text), program_seed)


def _with_seeds(program: A.Program, program_seed: int) -> A.Program:
    if has_seedless_noise(program):
        return canonicalize_seeds(program, program_seed)
    return program


def evaluate(
    program_or_text: A.Program | str,
    width: int = 512,
    height: int = 512,
    *,
    backend: str | Backend = "auto",
    view: View | tuple[float, float, float, float] | None = None,
    ao_radius_units: float | None = None,
    program_seed: int = 0,
    limits: Limits = DEFAULT_LIMITS,
    stats: EvalStats | None = None,
) -> MaterialMaps:
    """Evaluate a program into composited float32 maps at ``width`` x ``height``.

    ``view`` overrides the program's View; ``ao_radius_units`` makes AO resolution-independent
    (default: the reference's 8 texels). Omitted seeds are derived from ``program_seed``.
    """
    program = prepare(program_or_text, program_seed)
    check_request(width, height, len(program.defines), len(program.layers), limits)
    if not program.layers:
        raise ValueError("material has no layers: add at least one Layer(...) to Material(...)")
    v = view if isinstance(view, View) else View(*(view or program.view_tuple))
    be = backend if isinstance(backend, Backend) else choose_backend(backend, width * height)
    x, y = sample_axes(v, width, height)
    if be.fused:  # same maps as below, bit for bit (see matloom.engine.fused)
        from matloom.engine.fused import evaluate_fused

        with warnings.catch_warnings(), np.errstate(all="ignore"):
            warnings.simplefilter("ignore", RuntimeWarning)
            return evaluate_fused(
                program, x, y, v, be, ao_radius_units=ao_radius_units, stats=stats
            )
    ev = Evaluator(program, x, y, be)
    with warnings.catch_warnings(), np.errstate(all="ignore"):
        warnings.simplefilter("ignore", RuntimeWarning)
        raws = [layer_fields(ev, layer) for layer in program.layers]
        maps = composite(raws, width, height, v, ao_radius_units=ao_radius_units)
    maps.n_layers = len(program.layers)
    if stats is not None:
        stats.zero_divisions = ev.stats.zero_divisions
        stats.define_evaluations = ev.stats.define_evaluations
    return maps
