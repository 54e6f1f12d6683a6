"""Typed specifications of the language vocabulary: functions, parameters and layer channels.

Everything that needs to know the vocabulary (parser, checker, printer, evaluator, docs, LLM
prompt text, parameter-search ranges) reads these specs; nothing writes the vocabulary twice.
"""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass, field
from typing import Any


class Kind(enum.Enum):
    """What a parameter accepts."""

    EXPR = "expr"  # a spatial field expression
    FLOAT = "float"  # a static real number (an expression is evaluated once at (0, 0))
    INT = "int"  # a static integer
    BOOL = "bool"
    ENUM = "enum"  # one of a fixed set of strings
    SHAPE = "shape"  # an inline Rect/Ellipse/Path
    SEGMENT = "segment"  # LineTo/CubicTo, only inside Path


class Blend(enum.Enum):
    """How the layers' values of a channel combine into the material's map."""

    COVERAGE = "coverage"  # the layer's coverage: the weight of every OVER channel
    OVER = "over"  # coverage-weighted "over" rule: sum(V_i * c_i) / A
    MAX = "max"  # max over the covering layers (height)


class ValueKind(enum.Enum):
    """What a channel's arguments hold (derived from its argument list)."""

    SCALAR = "scalar"  # one value
    COLOUR = "colour"  # sRGB r, g, b on 0..255
    COLOUR_STRENGTH = "colour+strength"  # sRGB r, g, b on 0..255 and a strength >= 0


class Returns(enum.Enum):
    """What a call produces."""

    FIELD = "field"
    SHAPE = "shape"
    SEGMENT = "segment"


class PrintStyle(enum.Enum):
    """How the canonical printer writes a call (reference-engine.md §5.1)."""

    OPERATOR = "operator"  # Add/Sub/Mul/Div/Pow -> infix
    POSITIONAL = "positional"  # every parameter positionally (transforms, shapes, math)
    WRITTEN_KEYWORDS = "written_keywords"  # fBm/Worley: keywords the author wrote, seed always
    NONDEFAULT_KEYWORDS = "nondefault_keywords"  # Bricks/Weave: keywords whose value != default
    THRESHOLD = "threshold"
    SHAPE_OP = "shape_op"  # Fill/Stroke: required positionally, options as non-default keywords
    CONSTANT = "constant"  # Constant(v) -> v


REQUIRED: Any = object()
"""Sentinel default of a parameter that must be given."""


@dataclass(frozen=True)
class ParamSpec:
    """One parameter of a function."""

    name: str
    kind: Kind
    doc: str
    default: Any = REQUIRED
    #: Inclusive/exclusive numeric bounds; ``None`` means unbounded on that side.
    lo: float | None = None
    lo_open: bool = False
    hi: float | None = None
    hi_open: bool = False
    nonzero: bool = False
    nullable: bool = False  # ``None`` is an accepted value
    choices: tuple[str, ...] = ()
    is_seed: bool = False
    is_frequency: bool = False
    #: Range used by parameter search, and whether to search it on a log scale.
    search: tuple[float, float] | None = None
    search_log: bool = False
    #: Language version that introduced the parameter (``matloom random --language 1`` leaves
    #: out everything newer, reproducing the reference generator's programs).
    since: int = 1
    #: Accepts a field expression (language 2): noise, patterns, Define references, ... are
    #: evaluated at each sample, like an operand. A constant is used as the number it is, and so
    #: is an expression of X()/Y() and constants only (evaluated once at the origin, warning
    #: W004: its language-1 meaning); pass it through a Define to vary it per sample.
    field: bool = False
    #: A parameter without which this one has no effect (the checker warns, W008; the printer
    #: drops it, as the reference's serialiser does).
    needs: str | None = None
    #: A seed used only for some values of another parameter, as (parameter, values): e.g.
    #: Bricks' ``("output", ("cell_value",))``. For other values the seed has no effect, and
    #: canonicalisation draws none (``matloom.lang.seeds.uses_seed``). None: always used.
    used_when: tuple[str, tuple[str, ...]] | None = None
    #: The parameter's cycle: the change of its value after which the function gives the same
    #: result again (Sin's and Cos' 2 pi, Fract's 1, Hash's unit cells, Rotate's 360 degrees), or
    #: the name of the parameter whose value it is (Mod's ``x`` repeats every ``m``); None: not
    #: periodic. The op table's period rules read it (:mod:`matloom.ops.period`): an argument
    #: with a cycle repeats with the View where it advances by whole cycles per View period.
    cycle: float | str | None = None
    #: Enum choices added by a later language than the parameter's own ``since`` (choice ->
    #: version, e.g. Bricks' ``output="row"`` in language 3): ``matloom random --language N``
    #: draws only :meth:`choices_in` N.
    choice_since: tuple[tuple[str, int], ...] = ()

    @property
    def required(self) -> bool:
        return self.default is REQUIRED

    def choices_in(self, language: int) -> tuple[str, ...]:
        """The choices of language ``language`` (see ``choice_since``)."""
        later = dict(self.choice_since)
        return tuple(c for c in self.choices if later.get(c, self.since) <= language)

    def constraint_text(self) -> str:
        """Human-readable constraint, e.g. ``> 0``, ``in [0, 1]``, ``one of "row", "column"``."""
        if self.choices:
            return "one of " + ", ".join(f'"{c}"' for c in self.choices)
        parts: list[str] = []
        if self.lo is not None and self.hi is not None:
            lb = "(" if self.lo_open else "["
            rb = ")" if self.hi_open else "]"
            parts.append(f"in {lb}{_num(self.lo)}, {_num(self.hi)}{rb}")
        elif self.lo is not None:
            parts.append(f"{'>' if self.lo_open else '>='} {_num(self.lo)}")
        elif self.hi is not None:
            parts.append(f"{'<' if self.hi_open else '<='} {_num(self.hi)}")
        if self.nonzero:
            parts.append("non-zero")
        return ", ".join(parts)

    def check_value(self, value: float) -> str | None:
        """Return a violation message for a static numeric value, or ``None`` if it is valid."""
        if self.nonzero and value == 0:
            return f"{self.name} must be non-zero, got {_num(value)}"
        if self.lo is not None and (value < self.lo or (self.lo_open and value == self.lo)):
            return f"{self.name} must be {self.constraint_text()}, got {_num(value)}"
        if self.hi is not None and (value > self.hi or (self.hi_open and value == self.hi)):
            return f"{self.name} must be {self.constraint_text()}, got {_num(value)}"
        return None


@dataclass(frozen=True)
class FunctionSpec:
    """One callable of the language."""

    name: str
    family: str  # coord, math, noise, pattern, shape, segment, transform, mask
    doc: str
    example: str
    params: tuple[ParamSpec, ...] = ()
    returns: Returns = Returns.FIELD
    print_style: PrintStyle = PrintStyle.POSITIONAL
    operator: str | None = None  # infix operator for PrintStyle.OPERATOR
    #: Extra trailing positional arguments (Path segments).
    variadic: ParamSpec | None = None
    min_variadic: int = 0
    #: Language version that introduced the function (see ``ParamSpec.since``).
    since: int = 1
    #: Instancing: the frames its ``expr`` is evaluated in per sample (Tile: its cell and the 8
    #: neighbours); 0 for every other function. The cost walk counts the operand this often.
    instances: int = 0

    def param(self, name: str) -> ParamSpec | None:
        for p in self.params:
            if p.name == name:
                return p
        return None

    @property
    def param_names(self) -> tuple[str, ...]:
        return tuple(p.name for p in self.params)

    @property
    def nary(self) -> bool:
        """Takes more field operands than its parameters (language 3: ``Min(a, b, c, ...)``),
        held in ``Call.extra`` and folded left by the engine (``Min(Min(a, b), c)``)."""
        return self.variadic is not None and self.variadic.kind is Kind.EXPR

    @property
    def is_noise(self) -> bool:
        return any(p.is_seed for p in self.params)

    def signature(self) -> str:
        """Signature text for docs and prompts, e.g. ``Bricks(brick_width=1, ...)``."""
        parts = []
        for p in self.params:
            if p.required:
                parts.append(p.name)
            else:
                parts.append(f"{p.name}={format_default(p.default)}")
        if self.variadic is not None:
            parts.append(f"{self.variadic.name}...")
        return f"{self.name}({', '.join(parts)})"


@dataclass(frozen=True)
class ChannelSpec:
    """One layer method (channel) and how its values are clamped and defaulted."""

    name: str
    arg_names: tuple[str, ...]
    defaults: tuple[float, ...]
    units: str
    doc: str
    example: str
    clamp_lo: float | None = 0.0
    clamp_hi: float | None = 1.0
    search: tuple[float, float] | None = None
    #: Arguments on the 0..255 sRGB scale (colour channels).
    colour_args: tuple[int, ...] = field(default_factory=tuple)
    #: How the layers' values combine (see :mod:`matloom.vocab.layout`).
    blend: Blend = Blend.OVER
    #: Meaning of the exported map, written into ``material.json`` (default: ``doc``).
    map_doc: str = ""
    #: Language version that introduced the channel (see ``ParamSpec.since``).
    since: int = 1

    @property
    def arity(self) -> int:
        return len(self.arg_names)

    @property
    def kind(self) -> ValueKind:
        """Scalar (one argument), colour (r, g, b) or colour+strength (r, g, b, strength)."""
        colour = self.colour_args == (0, 1, 2)
        if self.arity == 1 and not self.colour_args:
            return ValueKind.SCALAR
        if colour and self.arity == 3:
            return ValueKind.COLOUR
        if colour and self.arity == 4:
            return ValueKind.COLOUR_STRENGTH
        raise ValueError(f"channel {self.name!r}: no value kind for arguments {self.arg_names}")


def _num(v: float) -> str:
    if isinstance(v, float) and v.is_integer():
        return str(int(v))
    return repr(v)


def format_default(v: Any) -> str:
    """Text of a default value as it would be written in a program."""
    if v is None:
        return "None"
    if isinstance(v, bool):
        return "True" if v else "False"
    if isinstance(v, str):
        return f'"{v}"'
    if v == math.e:
        return "e"
    return _num(v)


#: The current language version (``FunctionSpec.since`` and friends are at most this).
LANGUAGE_VERSION = 3
