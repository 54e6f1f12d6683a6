"""Render the language reference (docs/language.md) from the registry."""

from __future__ import annotations

from matloom.vocab import CHANNELS, FUNCTIONS
from matloom.vocab.docs_lang3 import language3_examples
from matloom.vocab.spec import Kind, format_default

_FAMILIES = (
    ("coord", "Coordinates and constants"),
    ("math", "Math"),
    ("noise", "Noise"),
    ("pattern", "Patterns"),
    ("mask", "Masks"),
    ("transform", "Transforms"),
    ("shape", "Shapes, Fill and Stroke"),
    ("segment", "Path segments"),
)


def _param_line(p) -> str:  # noqa: ANN001
    kind = p.kind.value
    if p.choices:
        kind = "enum"
    default = "required" if p.required else f"default `{format_default(p.default)}`"
    cons = p.constraint_text()
    extra = f"; {cons}" if cons else ""
    seed = " (noise seed)" if p.is_seed else ""
    field = " (accepts a field: evaluated at each sample)" if p.field else ""
    since = f" (language {p.since})" if p.since > 1 else ""
    return f"  - `{p.name}` ({kind}, {default}{extra}){seed}{field}{since}: {p.doc}"


def render_language_reference() -> str:
    """Markdown reference of every channel and function, straight from the registry."""
    out = [
        "# MatLoom language reference",
        "",
        "_Generated from the vocabulary registry (`matloom/vocab`) by "
        "`python -m matloom.vocab.docs > docs/language.md`; a test keeps it in sync._",
        "",
        "A program is an optional `View(x1, y1, x2, y2)`, then `Define(name, expr)` lines, then "
        "one `Material(Layer(...), ...)` with layers listed bottom first. A parameterised Define "
        "(language 3), `Define(stripe(w, c), Smoothstep(0, w, X()) * c)`, is used as a call, "
        "`stripe(0.2, 0.5)` or `stripe(w=0.2, c=0.5)`: each use is its body with the arguments "
        "filled in (checked, costed and evaluated expanded; `fmt` keeps it, `fmt --inline` and "
        "the reference-compatible export write the expansion). `#` starts a comment "
        "that runs to the end of the line. `matloom fmt` keeps comments: on their own lines before "
        "a `View`, `Define`, `Material`, `Layer` or channel call, or after the code of the line "
        "where one of these ends; any other comment (inside an expression) moves before the "
        "enclosing statement, layer or channel call. Canonical text for the reference engine "
        "(`matloom.format`, exports, seed variants) leaves comments out.",
        "",
        "`View(x1, y1, x2, y2, tileable=True)` (or `--tileable` on render, preview, sweep and "
        "generate, or `matloom.evaluate(..., tileable=True)`) makes every map repeat seamlessly "
        "with the View's width and height; the keyword is printed only when true. Every fBm, "
        "Worley, Hash and Tile repeats with the View: fBm samples each octave through a map "
        "that puts a whole number of its lattice periods in the View (a stretch of at most "
        "about half a lattice cell per View), Worley's frequencies and Tile's cell size and row "
        "offset are snapped to whole cells, and Hash (and the cell values of Worley and Bricks) "
        "wrap their cells; the normal and AO see across the edges. Under Translate and Scale "
        "(and Translate warps) the periods follow the transform. What cannot repeat is a "
        "warning: W009 for a noise or pattern under Rotate (other than by a multiple of 180 "
        "degrees) or another domain warp, for a Bricks or Weave whose cells do not divide the "
        "View (naming the nearest tiling value) and for a Hash with fractional cells per View; "
        "W010 for X()/Y() used other than in Fract, Mod, Sin, Cos, Floor or Hash with a whole "
        "number of cycles per View. Output without tileable is unchanged. See docs/tileable.md.",
        "",
        "## Layer channels",
        "",
        "| method | arguments | default | range / units | meaning |",
        "|---|---|---|---|---|",
    ]
    for c in CHANNELS.values():
        args = ", ".join(c.arg_names)
        default = ", ".join(format_default(v) for v in c.defaults)
        since = f" (language {c.since})" if c.since > 1 else ""
        out.append(f"| `.{c.name}` | {args} | {default} | {c.units} | {c.doc}{since} |")
    out += [
        "",
        "Language 2 added functions, parameters and a channel (marked below); every language-1 "
        "program means what it meant. `matloom random --language 1` draws from language 1 "
        "only.",
        "",
        "Numeric parameters are constants (constant arithmetic and `pi`, `e` allowed; `X()`/`Y()` "
        "there are evaluated once at the origin, with warning W004) except the parameters marked "
        "as accepting a field: those take any field (noise, patterns, Define references), "
        "evaluated at each sample (domain warping). An expression of `X()`/`Y()` and constants "
        "only keeps its language-1 meaning there too; to warp by the coordinates themselves, "
        "Define the expression and pass the Define's name: `Define(swirl, X() * 20)` then "
        "`Rotate(f, swirl)`.",
        "",
        "A numeric parameter also takes a named value: a Define of a constant (`Define(grout, "
        "0.02)` then `Bricks(mortar=grout)`), constant arithmetic of such Defines "
        "(`base_freq=(scale * 8)`) and chains of them. The checker reads the value (a range "
        "error names the Define), the maps are bit for bit those of the program with the "
        "number written in, `matloom fmt` keeps the names, and `matloom fmt --inline` and "
        "seed variants write plain numbers. A Define that is a field (noise, a pattern, "
        "`X()`, `Y()`) is still error E045 there. One edit then changes every use:",
        "",
        "```python",
        "import numpy as np",
        "import matloom",
        "",
        'named = """Define(grout, 0.03)',
        "Define(scale, 2)",
        "Material(Layer().basecolor(Bricks(mortar=grout), 0.5, 0.5)",
        '  .height((Bricks(mortar=grout) * 0.02) + fBm(base_freq=(scale * 8), seed=1) * 0.001))"""',
        'literal = named.replace("mortar=grout", "mortar=0.03").replace("(scale * 8)", "16")',
        'assert "mortar=grout" in matloom.format(named)  # the canonical text keeps the names',
        "a, b = matloom.evaluate(named, 64, 64), matloom.evaluate(literal, 64, 64)",
        "assert np.array_equal(a.height, b.height) and np.array_equal(a.alpha, b.alpha)",
        "```",
        "",
        "Operators: `+ - * / **` (`**` is right-associative; unary minus binds looser "
        "than `**`, so `-2 ** 2 = -4`). Constants: `pi`, `e`.",
        "",
        *language3_examples(),
    ]
    for family, title in _FAMILIES:
        specs = [f for f in FUNCTIONS.values() if f.family == family]
        if not specs:
            continue
        out += [f"## {title}", ""]
        for f in specs:
            out.append(f"### `{f.signature()}`")
            out.append("")
            since = f" (Language {f.since}.)" if f.since > 1 else ""
            out.append(f.doc + "." + since)
            out.append("")
            for p in f.params:
                if p.kind is Kind.EXPR and p.name == "expr":
                    out.append(f"  - `{p.name}` (field): {p.doc}")
                else:
                    out.append(_param_line(p))
            if f.variadic is not None:
                least = f"at least {f.min_variadic}" if f.min_variadic else "optional"
                out.append(f"  - `{f.variadic.name}...` ({least}): {f.variadic.doc}")
            out += ["", f"Example: `{f.example}`", ""]
    return "\n".join(out).rstrip() + "\n"


if __name__ == "__main__":
    print(render_language_reference(), end="")
