"""The paper's random program generator (reference-engine.md §9), built from the registry.

Every function, parameter, range, enum and channel comes from :mod:`matloom.vocab`: the generator
never lists the vocabulary itself, so a function added to the registry is generated automatically.
Functions are classified by what the registry says about them:

* **terminals**: field functions without expression parameters (X, Y, Constant, noise, patterns,
  Fill/Stroke), plus a reference to an earlier ``Define`` when one exists;
* **producers**: field functions with expression parameters (math, transforms, Threshold);
  operator functions (``PrintStyle.OPERATOR``) are built as infix :class:`~matloom.lang.ast.BinOp`;
* **shapes** and **segments**: functions returning ``Returns.SHAPE`` / ``Returns.SEGMENT``, used
  for ``Kind.SHAPE`` parameters and variadic Path segments.

Parameter values are drawn from each :class:`~matloom.vocab.ParamSpec`'s constraints (enum
choices, open/closed bounds, non-zero), with the §9 config ranges for unbounded reals, positive
reals and non-negative reals. Optional parameters whose default is "off" (0, False, None: feather,
corner radius, ``to_01``, Threshold sides) are written with probability ``optional_prob``; other
optional values are always drawn, as the reference does. Noise seeds are always written.

One ``random.Random(seed)`` drives everything, so a seed always gives the same program. Output is
canonical text that checks without errors (the work limit E071 included: a draw over it is
redrawn from a derived seed); the warnings W001 (unused Define) and W002 (hidden or
invisible layer) are avoided by construction, so generated programs are warning-free in practice.
"""

from __future__ import annotations

import math
import random
from dataclasses import dataclass

from matloom.lang import ast as A
from matloom.lang.codes import Code
from matloom.lang.cost import MAX_EXPANDED_NODES, expanded_cost
from matloom.lang.printer import format_program
from matloom.lang.static import static_number, uses_coordinates
from matloom.vocab import CHANNELS, FUNCTIONS, FunctionSpec, Kind, ParamSpec, PrintStyle, Returns
from matloom.vocab.spec import LANGUAGE_VERSION

SEED_RANGE = 2**31
"""Noise seeds are drawn from [0, 2**31), as in the reference."""

_ALPHA_ATTEMPTS = 50
"""Redraws of a layer alpha that came out constant (which would hide or blank layers)."""

_VALUE_ATTEMPTS = 100
"""Redraws of a parameter value that violates its constraint (e.g. an exact 0 for non-zero)."""

_ALWAYS_DRAWN_FAMILIES = ("coord", "transform")
"""Families whose optional values are always drawn: their defaults make the call a no-op."""


@dataclass(frozen=True)
class RandomConfig:
    """Generator settings; the defaults are the reference's ``matloom-generate`` defaults (§9)."""

    min_layers: int = 1
    max_layers: int = 3
    min_defs: int = 0
    max_defs: int = 2
    max_depth: int = 6
    leaf_bias: float = 0.5
    opaque_base: bool = True
    random_view: bool = True
    real_lo: float = -10.0
    real_hi: float = 10.0
    pos_real_min: float = 1e-3
    pos_real_max: float = 10.0
    non_neg_real_max: float = 10.0
    max_octaves: int = 8
    max_path_segments: int = 4
    #: Probability of writing an optional parameter whose default switches a feature off.
    optional_prob: float = 0.5
    #: Probability of writing each chained channel (the reference writes all of them).
    channel_prob: float = 1.0
    #: Build colour components as ``(expr * 255)``, as the reference generator does.
    colour_times_255: bool = True
    #: Extra value ranges, keyed ``"Function.param"`` or ``"param"`` (e.g. rotation in degrees).
    param_ranges: tuple[tuple[str, float, float], ...] = (("Rotate.degrees", 0.0, 360.0),)
    #: Language version whose vocabulary is drawn from (functions, parameters and channels with
    #: ``since`` <= it); 1 reproduces the reference generator's programs seed for seed.
    language: int = LANGUAGE_VERSION
    #: Language 2: probability of a field expression for a parameter that accepts one.
    field_param_prob: float = 0.25

    def __post_init__(self) -> None:
        checks = (
            (1 <= self.min_layers <= self.max_layers, "need 1 <= min_layers <= max_layers"),
            (0 <= self.min_defs <= self.max_defs, "need 0 <= min_defs <= max_defs"),
            (self.max_depth >= 0, "max_depth must be >= 0"),
            (0.0 <= self.leaf_bias <= 1.0, "leaf_bias must be in [0, 1]"),
            (self.real_lo < self.real_hi, "need real_lo < real_hi"),
            (0 < self.pos_real_min < self.pos_real_max, "need 0 < pos_real_min < pos_real_max"),
            (self.non_neg_real_max > 0, "non_neg_real_max must be > 0"),
            (self.max_octaves >= 1, "max_octaves must be >= 1"),
            (self.max_path_segments >= 1, "max_path_segments must be >= 1"),
        )
        for ok, message in checks:
            if not ok:
                raise ValueError(f"RandomConfig: {message}")

    def range_for(self, func: str, param: str) -> tuple[float, float] | None:
        """The configured value range of ``func``'s ``param``, or ``None`` for the default rule."""
        ranges = {"octaves": (1.0, float(self.max_octaves))}
        ranges.update({key: (lo, hi) for key, lo, hi in self.param_ranges})
        return ranges.get(f"{func}.{param}") or ranges.get(param)


DEFAULT_CONFIG = RandomConfig()


def random_program(
    seed: int,
    *,
    layers: int | None = None,
    defines: int | None = None,
    config: RandomConfig = DEFAULT_CONFIG,
) -> str:
    """Canonical text of a random, always-valid program (the reference generator's behaviour).

    ``layers`` / ``defines`` fix the counts (otherwise drawn from the config ranges).
    """
    return format_program(random_program_ast(seed, layers=layers, defines=defines, config=config))


def random_program_ast(
    seed: int,
    *,
    layers: int | None = None,
    defines: int | None = None,
    config: RandomConfig = DEFAULT_CONFIG,
) -> A.Program:
    """The generated program as an AST (before canonical printing normalises it)."""
    if layers is not None and layers < 1:
        raise ValueError(f"a program needs at least one layer, got layers={layers}")
    if defines is not None and defines < 0:
        raise ValueError(f"defines must be >= 0, got {defines}")
    program = _Generator(random.Random(seed), config).program(layers, defines)
    # "always valid" includes the work limit (E071): a draw over it (about 1 in 1,000 with the
    # default config: many frames of costly calls) is replaced by a draw of a derived seed
    for attempt in range(1, _MAX_REDRAWS + 1):
        if not expanded_cost(program, MAX_EXPANDED_NODES).over:
            return program
        rng = random.Random(f"{seed}/{attempt}")
        program = _Generator(rng, config).program(layers, defines)
    raise ValueError(
        f"seed {seed}: every draw of this config exceeds the work limit ({Code.WORK_LIMIT.code})"
    )


#: Draws tried for one seed before giving up (a config whose programs are all too costly).
_MAX_REDRAWS = 100


def _number(value: float) -> A.Node:
    """A literal as the parser builds it: negative numbers are ``Neg(Num)``."""
    return A.Neg(A.Num(-value)) if value < 0 else A.Num(value)


def _takes_fields(spec: FunctionSpec) -> bool:
    return any(p.kind is Kind.EXPR for p in spec.params)


def _has_off_default(p: ParamSpec) -> bool:
    """True for optional parameters whose default leaves a feature off (0, False, None)."""
    return not p.required and (p.default is None or p.default is False or p.default == 0)


class _Generator:
    """Draws one program; every random choice goes through ``self.rng`` in a fixed order."""

    def __init__(self, rng: random.Random, config: RandomConfig) -> None:
        self.rng = rng
        self.cfg = config
        vocabulary = [s for s in FUNCTIONS.values() if s.since <= config.language]
        fields = [s for s in vocabulary if s.returns is Returns.FIELD]
        self.terminals = [s for s in fields if not _takes_fields(s)]
        self.producers = [s for s in fields if _takes_fields(s)]
        self.shapes = [s for s in vocabulary if s.returns is Returns.SHAPE]
        self.segments = [s for s in vocabulary if s.returns is Returns.SEGMENT]
        self.refs: list[str] = []

    # ------------------------------------------------------------------ program
    def program(self, n_layers: int | None, n_defines: int | None) -> A.Program:
        cfg, rng = self.cfg, self.rng
        if n_layers is None:
            n_layers = rng.randint(cfg.min_layers, cfg.max_layers)
        view = self.view()
        if n_defines is None:
            n_defines = rng.randint(cfg.min_defs, cfg.max_defs)
        defs = []
        for k in range(1, n_defines + 1):
            defs.append(A.Define(f"def{k}", self.expr(cfg.max_depth)))
            self.refs.append(f"def{k}")
        layers = [self.layer(i) for i in range(n_layers)]
        layers = self._use_every_define(defs, layers)
        return A.Program(view, tuple(defs), tuple(layers))

    def view(self) -> A.ViewDecl:
        cfg, rng = self.cfg, self.rng
        if not cfg.random_view:
            return A.ViewDecl(0.0, 0.0, 1.0, 1.0)
        x1, y1 = rng.uniform(cfg.real_lo, cfg.real_hi), rng.uniform(cfg.real_lo, cfg.real_hi)
        w = rng.uniform(cfg.pos_real_min, cfg.pos_real_max)
        h = rng.uniform(cfg.pos_real_min, cfg.pos_real_max)
        return A.ViewDecl(x1, y1, x1 + w, y1 + h)

    def layer(self, index: int) -> A.Layer:
        if index == 0 and self.cfg.opaque_base:
            alpha: A.Node = A.Num(1)
        else:
            alpha = self.alpha()
        channels = []
        for name, ch in CHANNELS.items():
            if name == "alpha" or ch.since > self.cfg.language:  # alpha: the Layer(...) argument
                continue
            if self.cfg.channel_prob < 1.0 and self.rng.random() >= self.cfg.channel_prob:
                continue
            args = [self.expr(self.cfg.max_depth) for _ in range(ch.arity)]
            if self.cfg.colour_times_255:
                args = [
                    A.BinOp("*", a, A.Num(255)) if k in ch.colour_args else a
                    for k, a in enumerate(args)
                ]
            channels.append(A.ChannelSet(name, tuple(args)))
        return A.Layer(alpha, tuple(channels))

    def alpha(self) -> A.Node:
        """A coverage expression that is not a constant (a constant hides or blanks layers)."""
        node = self.expr(self.cfg.max_depth)
        for _ in range(_ALPHA_ATTEMPTS):
            if uses_coordinates(node) or static_number(node) is None:
                break
            node = self.expr(self.cfg.max_depth)
        return node

    def _use_every_define(self, defs: list[A.Define], layers: list[A.Layer]) -> list[A.Layer]:
        """Add each unused Define to a random channel (``expr + name``), latest Define first."""
        for d in reversed(defs):
            if d.name in _used_defines(defs, layers):
                continue
            candidates = [
                (i, c) for i, layer in enumerate(layers) for c in range(len(layer.channels))
            ]
            if not candidates:  # no channels at all: use it as coverage of the top layer
                top = layers[-1]
                alpha = (
                    A.Ref(d.name) if top.alpha is None else A.BinOp("*", top.alpha, A.Ref(d.name))
                )
                layers[-1] = A.Layer(alpha, top.channels)
                continue
            i, c = self.rng.choice(candidates)
            ch = layers[i].channels[c]
            k = self.rng.randrange(len(ch.args))
            args = list(ch.args)
            args[k] = A.BinOp("+", args[k], A.Ref(d.name))
            chans = list(layers[i].channels)
            chans[c] = A.ChannelSet(ch.name, tuple(args))
            layers[i] = A.Layer(layers[i].alpha, tuple(chans))
        return layers

    # ------------------------------------------------------------------ expressions
    def expr(self, depth: int) -> A.Node:
        """A field expression: a terminal at depth 0 or with probability ``leaf_bias``."""
        if depth <= 0 or self.rng.random() < self.cfg.leaf_bias:
            return self.terminal()
        return self.call(self.rng.choice(self.producers), depth)

    def terminal(self) -> A.Node:
        k = self.rng.randrange(len(self.terminals) + (1 if self.refs else 0))
        if k == len(self.terminals):
            return A.Ref(self.rng.choice(self.refs))
        return self.call(self.terminals[k], 0)

    def call(self, spec: FunctionSpec, depth: int) -> A.Node:
        """A call of ``spec`` with arguments drawn from its parameter specs, in parameter order."""
        freq = self._frequencies(spec)
        args: list[A.Arg] = []
        for p in spec.params:
            if p.since > self.cfg.language:
                continue
            node = freq.get(p.name) if p.is_frequency else self.argument(spec, p, depth)
            if node is not None:
                args.append(A.Arg(p.name, node))
        if spec.print_style is PrintStyle.OPERATOR and spec.operator is not None:
            return A.BinOp(spec.operator, args[0].value, args[1].value)
        extra: tuple[A.Node, ...] = ()
        if spec.variadic is not None and spec.variadic.kind is Kind.SEGMENT:
            lo = max(1, spec.min_variadic)
            n = self.rng.randint(lo, max(lo, self.cfg.max_path_segments))
            extra = tuple(self.call(self.rng.choice(self.segments), 0) for _ in range(n))
        return A.Call(spec.name, tuple(args), extra)

    def argument(self, spec: FunctionSpec, p: ParamSpec, depth: int) -> A.Node | None:
        """A value for one parameter, or ``None`` to leave an optional parameter unwritten."""
        if p.kind is Kind.EXPR:
            return self.expr(depth - 1)
        if p.kind is Kind.SHAPE:
            return self.call(self.rng.choice(self.shapes), 0)
        if p.is_seed:
            return A.Num(self.rng.randrange(SEED_RANGE))
        if p.field and self.cfg.language >= 2 and self.rng.random() < self.cfg.field_param_prob:
            field = self.expr(depth - 1)
            if static_number(field) is None:  # else it is a constant: a valid number instead
                return field
        optional = _has_off_default(p) and spec.family not in _ALWAYS_DRAWN_FAMILIES
        if optional and self.rng.random() >= self.cfg.optional_prob:
            return None
        return self.value(spec, p)

    def _frequencies(self, spec: FunctionSpec) -> dict[str, A.Node]:
        """The shared frequency, or (half of the time) the per-axis pair instead."""
        freq = [p for p in spec.params if p.is_frequency]
        if not freq:
            return {}
        shared = [p for p in freq if p.default is not None]
        axes = [p for p in freq if p.default is None]
        chosen = axes if axes and (not shared or self.rng.random() < 0.5) else shared
        return {p.name: self.value(spec, p) for p in chosen}

    # ------------------------------------------------------------------ static values
    def value(self, spec: FunctionSpec, p: ParamSpec) -> A.Node:
        """A literal satisfying ``p``'s kind and constraints."""
        if p.kind is Kind.ENUM:
            return A.Str(self.rng.choice(p.choices_in(self.cfg.language)))
        if p.kind is Kind.BOOL:
            return A.Lit(self.rng.random() < 0.5)
        draw = self._int if p.kind is Kind.INT else self._float
        lo, hi = self._range(spec, p)
        for _ in range(_VALUE_ATTEMPTS):
            v = draw(lo, hi)
            if p.check_value(v) is None:
                return _number(v)
        return _number(p.default if isinstance(p.default, int | float) else lo)

    def _int(self, lo: float, hi: float) -> int:
        a, b = math.ceil(lo), math.floor(hi)
        return self.rng.randint(a, max(a, b))

    def _float(self, lo: float, hi: float) -> float:
        return self.rng.uniform(lo, hi)

    def _range(self, spec: FunctionSpec, p: ParamSpec) -> tuple[float, float]:
        """Sampling range: a config override, else the search range of a bounded parameter,
        else the §9 ranges for positive, non-negative and unbounded reals."""
        cfg = self.cfg
        override = cfg.range_for(spec.name, p.name)
        if override is not None:
            return override
        if p.kind is Kind.INT and p.search is not None:
            return (max(p.search[0], p.lo if p.lo is not None else -math.inf), p.search[1])
        if p.lo is not None and p.hi is not None:
            return p.search if p.search is not None else (p.lo, p.hi)
        if p.lo is not None:
            if p.lo_open:
                return (p.lo + cfg.pos_real_min, p.lo + cfg.pos_real_max)
            return (p.lo, p.lo + cfg.non_neg_real_max)
        if p.hi is not None:
            return (p.hi - cfg.non_neg_real_max, p.hi)
        return (cfg.real_lo, cfg.real_hi)


def _used_defines(defs: list[A.Define], layers: list[A.Layer]) -> set[str]:
    """Names of the Defines reachable from the layers (directly or through other Defines)."""
    by_name = {d.name: d.expr for d in defs}
    program = A.Program(None, tuple(defs), tuple(layers))
    stack = [e for owner, e in A.program_expressions(program) if owner[0] == "layer"]
    used: set[str] = set()
    while stack:
        for n in A.walk(stack.pop()):
            if isinstance(n, A.Ref) and n.name not in used and n.name in by_name:
                used.add(n.name)
                stack.append(by_name[n.name])
    return used


__all__ = ["DEFAULT_CONFIG", "SEED_RANGE", "RandomConfig", "random_program", "random_program_ast"]
