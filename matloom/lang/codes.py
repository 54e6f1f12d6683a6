"""Every diagnostic code: its name, severity, one-line meaning and usual fix.

Emitters name a code by its constant (``Code.UNKNOWN_NAME``), never by its text; the reporter
takes the severity from here. ``docs/diagnostics.md`` is generated from this table
(``python -m matloom.lang.codes_doc > docs/diagnostics.md``) and a test keeps both in sync and
checks that every code is emitted somewhere. Codes are stable: a code is never reused for
another meaning. ``E0xx`` are errors (the program is rejected), ``W0xx`` warnings.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass

from matloom.lang.diagnostics import Diagnostic, Severity, Span

_E, _W = Severity.ERROR, Severity.WARNING


@dataclass(frozen=True)
class CodeInfo:
    """One row of the table."""

    code: str
    severity: Severity
    meaning: str
    hint: str


class Code(enum.Enum):
    """The diagnostic codes (member name: what the code is called in the code)."""

    # ------------------------------------------------------------------ lexer
    BAD_CHARACTER = CodeInfo(
        "E001",
        _E,
        "a character that starts no token (such as ';', '[' or a Markdown fence)",
        "remove it: statements need no separator and only parentheses group",
    )
    UNTERMINATED_STRING = CodeInfo(
        "E002",
        _E,
        "a string literal without its closing quote on the same line",
        'close the string with the quote it opened with, as in "radial"',
    )
    BAD_NUMBER = CodeInfo(
        "E003",
        _E,
        "a numeric literal that is malformed, longer than 400 characters or past the float range",
        "write a finite number such as 0.5 or 1e-3",
    )
    # ------------------------------------------------------------------ syntax
    EXPECTED_TOKEN = CodeInfo(
        "E010",
        _E,
        "a required '(', ')', ',' or name is missing",
        "the caret marks where it is expected; the hint names the construct left open",
    )
    EXPECTED_EXPRESSION = CodeInfo(
        "E011",
        _E,
        "an expression is missing (an empty argument, a sign after a sign, the end of input)",
        "write a number, a name, a call or a parenthesised expression",
    )
    UNEXPECTED_INPUT = CodeInfo(
        "E012",
        _E,
        "a token that starts no statement at the top level, or input after Material(...)",
        "a program is View(...), Define(...) lines and one Material(...), in that order",
    )
    TRAILING_COMMA = CodeInfo(
        "E013",
        _E,
        "a comma after the last argument or layer",
        "remove the comma or add the missing item",
    )
    VIEW_NOT_FIRST = CodeInfo(
        "E020",
        _E,
        "View(...) after a Define or Material, or a second View",
        "move the one View line to the top of the program",
    )
    MISSING_MATERIAL = CodeInfo(
        "E022",
        _E,
        "the program has no Material(...)",
        "end the program with Material(Layer(...), ...)",
    )
    AFTER_MATERIAL = CodeInfo(
        "E023",
        _E,
        "a Define or a second Material after Material(...)",
        "move Defines above Material(...); a program has exactly one Material",
    )
    EMPTY_MATERIAL = CodeInfo(
        "E024",
        _E,
        "Material() has no layers",
        "add a base layer such as Layer(1).basecolor(128, 128, 128)",
    )
    MISPLACED_LAYER = CodeInfo(
        "E025",
        _E,
        "a Layer outside Material(...), or something other than Layer(...) inside it",
        "put every Layer(...) inside the one Material(...)",
    )
    UNKNOWN_CHANNEL = CodeInfo(
        "E026",
        _E,
        "a layer method that names no channel",
        "use a channel of docs/language.md, such as .basecolor(r, g, b)",
    )
    ARGUMENT_COUNT = CodeInfo(
        "E027",
        _E,
        "View, Define or a channel method with the wrong number of arguments, or a View "
        "keyword given twice",
        "View(x1, y1, x2, y2), Define(name, expression), .roughness(value)",
    )
    LAYER_ARGUMENTS = CodeInfo(
        "E028",
        _E,
        "Layer(...) with more than one argument (its alpha)",
        "set channels with methods: Layer(1).basecolor(r, g, b)",
    )
    # ------------------------------------------------------------------ calls and names
    UNKNOWN_FUNCTION = CodeInfo(
        "E030",
        _E,
        "a call of a name that is no function of the vocabulary",
        "check the spelling against docs/language.md",
    )
    UNKNOWN_PARAMETER = CodeInfo(
        "E031",
        _E,
        "a keyword argument that names no parameter of the function (or any keyword in a "
        "channel method)",
        "use the parameter names of the function's signature",
    )
    TOO_MANY_ARGUMENTS = CodeInfo(
        "E032",
        _E,
        "more positional arguments than the function has parameters",
        "remove the extra arguments or name them with keywords",
    )
    DUPLICATE_ARGUMENT = CodeInfo(
        "E033",
        _E,
        "a parameter given twice (twice by keyword, or by keyword and by position)",
        "give each parameter at most once",
    )
    MISSING_ARGUMENT = CodeInfo(
        "E034",
        _E,
        "a required parameter is not given",
        "add the missing arguments of the function's signature",
    )
    FUNCTION_NOT_CALLED = CodeInfo(
        "E035",
        _E,
        "a function's name used as a value, without its call",
        "call it: X(), fBm(...)",
    )
    UNKNOWN_NAME = CodeInfo(
        "E036",
        _E,
        "a name that is no Define, constant or literal",
        "Define it above, or use pi, e, True, False or None",
    )
    DUPLICATE_DEFINE = CodeInfo(
        "E038",
        _E,
        "two Defines with the same name",
        "rename one of the Defines",
    )
    # ------------------------------------------------------------------ kinds and values
    SHAPE_OUTSIDE_FILL = CodeInfo(
        "E040",
        _E,
        "a shape (Rect, Ellipse, Path) outside Fill(...) or Stroke(...), or bound by a Define",
        "write the shape inline: Fill(Rect(...))",
    )
    SEGMENT_OUTSIDE_PATH = CodeInfo(
        "E041",
        _E,
        "a path segment (LineTo, CubicTo) outside Path(...)",
        "write segments as the extra arguments of Path(x, y, ...)",
    )
    NOT_A_FIELD = CodeInfo(
        "E042",
        _E,
        "a string, bool or None where a number or field expression is expected",
        "write a number or an expression",
    )
    EXPECTED_SHAPE = CodeInfo(
        "E043",
        _E,
        "a shape parameter given something other than an inline shape",
        "write Rect(...), Ellipse(...) or Path(...) inline; shapes cannot be Define'd",
    )
    BAD_SEGMENTS = CodeInfo(
        "E044",
        _E,
        "Path(...) with a segment that is not LineTo/CubicTo, or with too few segments",
        "Path(x, y, LineTo(x, y), CubicTo(c1x, c1y, c2x, c2y, x, y), ...)",
    )
    NOT_A_NUMBER = CodeInfo(
        "E045",
        _E,
        "a numeric parameter given a string, a bool or a field expression",
        "write a constant (constant arithmetic and Defines of constants are fine); only "
        "marked parameters take fields",
    )
    OUT_OF_RANGE = CodeInfo(
        "E050",
        _E,
        "a number that is not finite or outside its parameter's range",
        "use a value within the range the signature gives",
    )
    BAD_CHOICE = CodeInfo(
        "E051",
        _E,
        "an enum parameter given a value that is not one of its choices",
        'write one of the choices as a quoted string, such as output="mortar"',
    )
    NOT_AN_INTEGER = CodeInfo(
        "E052",
        _E,
        "an integer parameter given a fractional number",
        "write a whole number",
    )
    NOT_A_BOOL = CodeInfo(
        "E053",
        _E,
        "a bool parameter given something other than True, False, 0 or 1",
        "write True or False",
    )
    ZERO_NOT_ALLOWED = CodeInfo(
        "E054",
        _E,
        "0 for a parameter that must not be zero",
        "use a non-zero value",
    )
    BASE_FREQ_AXES = CodeInfo(
        "E055",
        _E,
        "base_freq=None without both base_freq_x and base_freq_y",
        "give base_freq, or both base_freq_x and base_freq_y",
    )
    # ------------------------------------------------------------------ program
    DEFINE_ORDER = CodeInfo(
        "E060",
        _E,
        "a Define used before its definition, or by itself",
        "Defines form an acyclic graph: move the Define above its first use",
    )
    DEFINE_ARGUMENTS = CodeInfo(
        "E062",
        _E,
        "a parameterised Define used without its arguments or with the wrong number of them, "
        "or a plain Define called with arguments",
        "call Define(name(a, b), ...) as name(x, y), and use a Define without parameters by "
        "its bare name",
    )
    DEFINE_PARAMETER = CodeInfo(
        "E063",
        _E,
        "a bad parameter name in Define(name(a, b), ...): repeated, or the name of a "
        "function, constant, keyword or earlier Define",
        "give each parameter its own new name, e.g. Define(stripe(width, phase), ...)",
    )
    BAD_VIEW = CodeInfo(
        "E061",
        _E,
        "View corners that are not finite numbers, equal, or past the float32 sample grid, "
        "or a bad tileable or unit_m",
        "View(x1, y1, x2, y2, tileable=True, unit_m=0.5) with x1 < x2 and y1 < y2",
    )
    SIZE_LIMIT = CodeInfo(
        "E070",
        _E,
        "a size limit exceeded: characters, tokens, nesting depth, nodes, inlined size or "
        "octaves (docs/limits.md)",
        "move sub-expressions into Defines, or use a smaller program",
    )
    WORK_LIMIT = CodeInfo(
        "E071",
        _E,
        "the program needs more than 200,000 expression-node evaluations (docs/limits.md)",
        "use fewer octaves, repeats or nested Tiles; the message names the costliest call",
    )
    # ------------------------------------------------------------------ warnings
    UNUSED_DEFINE = CodeInfo(
        "W001",
        _W,
        "a Define that no layer uses",
        "remove it or reference it in a layer",
    )
    HIDDEN_LAYER = CodeInfo(
        "W002",
        _W,
        "a layer that is never visible (alpha 0, or under an opaque layer)",
        "lower the upper layer's alpha, reorder or remove the layer",
    )
    NO_SEED = CodeInfo(
        "W003",
        _W,
        "a noise call without seed=; one is drawn when the program is canonicalised",
        "write seed=N so the program is reproducible as written",
    )
    COORDINATES_IN_NUMBER = CodeInfo(
        "W004",
        _W,
        "X()/Y() in a numeric parameter, evaluated once at (0, 0)",
        "to vary it per sample, Define the expression and pass the Define's name",
    )
    SHADOWED_DEFINE = CodeInfo(
        "W005",
        _W,
        "a Define named like a built-in, which can never be referenced",
        "choose another name",
    )
    CHANNEL_SET_TWICE = CodeInfo(
        "W006",
        _W,
        "a layer sets the same channel twice; the last one wins",
        "remove one of the two methods",
    )
    REVERSED_VIEW = CodeInfo(
        "W007",
        _W,
        "a View with x1 > x2 or y1 > y2, so the image is mirrored",
        "(x1, y1) is the bottom-left corner, (x2, y2) the top-right",
    )
    NO_EFFECT = CodeInfo(
        "W008",
        _W,
        "a parameter that has no effect without another one (fmt drops it)",
        "give the parameter it needs, or remove it",
    )
    DOES_NOT_TILE = CodeInfo(
        "W009",
        _W,
        "tileable: a noise, pattern, Hash or shape that cannot repeat with the View",
        "follow the hint's nearest tiling values; see docs/tileable.md",
    )
    COORDINATE_SEAM = CodeInfo(
        "W010",
        _W,
        "tileable: X()/Y() used non-periodically, so the output has a seam",
        "wrap it in Fract/Mod/Sin/Cos with whole cycles per View",
    )

    @property
    def code(self) -> str:
        """The code's text, as diagnostics carry it (``"E036"``)."""
        return self.value.code

    @property
    def severity(self) -> Severity:
        return self.value.severity

    def diagnostic(
        self,
        message: str,
        span: Span,
        expected: str | None = None,
        hint: str | None = None,
        excerpt: str = "",
    ) -> Diagnostic:
        """A diagnostic of this code (and its severity)."""
        return Diagnostic(self.code, message, span, self.severity, expected, hint, excerpt)


#: Every code by its text.
CODES: dict[str, Code] = {c.code: c for c in Code}
