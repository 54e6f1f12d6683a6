"""The generator system prompt, rendered from the vocabulary registry (reference-engine.md §8.2).

Only prose that is not vocabulary is written here: the role, the rules, the five pitfalls, the
playbook and the output format. Every function signature, parameter, constraint, channel range
and default is rendered from :mod:`matloom.vocab`, so the prompt can never drift from the parser.
The few-shot programs live in ``examples/*.mat`` (canonical text, tested to check and render):
the paper's six descriptions, and the ``v3`` set (``v3_*.mat``) of the ``recommended`` settings.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache
from importlib import resources

from matloom.vocab import CHANNELS, CONSTANTS, FUNCTIONS, FunctionSpec, ParamSpec
from matloom.vocab.spec import format_default

ROLE = (
    "You are an expert technical artist. You write **layered-material DSL** programs: a compact, "
    "declarative language that compiles deterministically into physically based material maps. "
    "Given a natural-language description of a material, output a program that reproduces it."
)


@dataclass(frozen=True)
class FewShotExample:
    """One example of the prompt: a description and the file holding its program."""

    description: str
    file_name: str

    def program(self) -> str:
        """The canonical program text of the example."""
        path = resources.files("matloom.author.prompts").joinpath("examples", self.file_name)
        return path.read_text(encoding="utf-8").strip()


#: The paper's six example descriptions, with our own programs (1 to 4 layers).
FEW_SHOT_EXAMPLES: tuple[FewShotExample, ...] = (
    FewShotExample("Polished green marble", "1_green_marble.mat"),
    FewShotExample(
        "Frosted glass panel in a brushed steel frame", "2_frosted_glass_steel_frame.mat"
    ),
    FewShotExample("Weathered red brick wall with pale mortar", "3_weathered_brick.mat"),
    FewShotExample("Chipped blue paint over rusted steel", "4_chipped_paint_rust.mat"),
    FewShotExample("Beach sand with pebbles", "5_beach_sand_pebbles.mat"),
    FewShotExample(
        "Glow-in-the-dark stars with a crescent moon and a comet", "6_glow_stars_moon_comet.mat"
    ),
)

#: The ``v3`` examples (``examples = "v3"``, the ``recommended`` settings): written for this
#: prompt in its language 2 and 3 idioms (Defines of named values used as parameters,
#: ``Bricks(mortar=grout)``, per-cell values with Choose, Tile instance outputs, a
#: parameterised Define, n-ary Min, Weave thread values, smooth Worley), on subjects far from
#: the benchmark prompts (``tests/author/test_examples_v3.py`` compares their words with the
#: development prompts and bans the tricks the prompt forbids).
FEW_SHOT_EXAMPLES_V3: tuple[FewShotExample, ...] = (
    FewShotExample(
        "Hand-hammered pewter sheet covered in rounded dents", "v3_1_hammered_pewter.mat"
    ),
    FewShotExample(
        "Glass mosaic of tiny square chips in three shades of teal with grey grout",
        "v3_2_teal_glass_mosaic.mat",
    ),
    FewShotExample(
        "Deep green velvet upholstery quilted in a diamond pattern", "v3_3_quilted_velvet.mat"
    ),
    FewShotExample(
        "Woven rattan cane: wide vertical strands crossed by thin horizontal ones",
        "v3_4_rattan_cane.mat",
    ),
    FewShotExample(
        "Terracotta roof covered in overlapping fish-scale shingles", "v3_5_fish_scale_roof.mat"
    ),
    FewShotExample("Riveted steel panels painted navy blue", "v3_6_riveted_panels.mat"),
)

#: The example sets by name (``AuthorConfig.examples``).
EXAMPLE_SETS: dict[str, tuple[FewShotExample, ...]] = {
    "paper": FEW_SHOT_EXAMPLES,
    "v3": FEW_SHOT_EXAMPLES_V3,
}


# ----------------------------------------------------------------------------- registry text


def _param_line(p: ParamSpec) -> str:
    default = "required" if p.required else f"default {format_default(p.default)}"
    constraint = p.constraint_text()
    extra = f"; {constraint}" if constraint else ""
    field = (
        "; may be a field (noise, pattern, Define name), evaluated per sample" if p.field else ""
    )
    return f"  - `{p.name}` ({default}{extra}{field}): {p.doc}"


def function_entry(spec: FunctionSpec, *, with_params: bool = True) -> str:
    """Markdown entry of one function: signature, meaning, parameters, example."""
    lines = [f"- `{spec.signature()}`: {spec.doc}."]
    if with_params:
        lines += [_param_line(p) for p in spec.params if p.doc and p.kind.value != "expr"]
        if spec.variadic is not None:
            lines.append(f"  - `{spec.variadic.name}...`: {spec.variadic.doc}")
    lines.append(f"  Example: `{spec.example}`")
    return "\n".join(lines)


def _family(*families: str, with_params: bool = True) -> str:
    specs = [s for s in FUNCTIONS.values() if s.family in families]
    return "\n".join(function_entry(s, with_params=with_params) for s in specs)


def channel_skeleton() -> str:
    """The annotated Layer skeleton: every channel method with its range and default."""
    lines = []
    for ch in CHANNELS.values():
        args = ", ".join(ch.arg_names)
        defaults = ", ".join(format_default(d) for d in ch.defaults)
        lines.append(f"- `.{ch.name}({args})`: {ch.doc}; range {ch.units}; default ({defaults})")
    return "\n".join(lines)


def _clamp_note() -> str:
    clamped = [
        c.name for c in CHANNELS.values() if c.clamp_lo is not None and c.clamp_hi is not None
    ]
    unclamped = [c.name for c in CHANNELS.values() if c.clamp_lo is None and c.clamp_hi is None]
    lower_only = [
        c.name for c in CHANNELS.values() if c.clamp_lo is not None and c.clamp_hi is None
    ]
    return (
        f"Values are clamped automatically to their ranges ({', '.join(clamped)}); "
        f"{', '.join(lower_only)} only from below; {', '.join(unclamped)} is never clamped "
        "(negative heights carve below the substrate)."
    )


# ----------------------------------------------------------------------------- sections


def structure_section() -> str:
    return "\n".join(
        [
            "# Program structure",
            "A program is, in this order: an optional `View(x1, y1, x2, y2)`, zero or more "
            "`Define(name, expression)`, then exactly one `Material(...)` holding one or more "
            "layers, bottom layer first. Nothing may follow the closing parenthesis of Material.",
            "Each layer is `Layer(alpha)` followed by chained channel methods:",
            channel_skeleton(),
            "Every argument is an expression evaluated at each sample point: a number, `X()`/"
            "`Y()`, a Define name, or nested functions; each RGB component is its own expression. "
            "Methods are optional (omitted ones take their defaults), may come in any order, and "
            "are chained with a dot directly before the name. Comments (`#`, `//`) are not "
            "allowed anywhere.",
            _clamp_note(),
            "Compositing: layers stack with the over operator using their alpha (coverage), for "
            "every channel except height; an upper layer with alpha 1 hides what is below.",
        ]
    )


def coordinates_section() -> str:
    return "\n".join(
        [
            "# Coordinates & View",
            "The material is a field on the infinite plane: x grows to the right, y grows "
            "upwards. Positions, sizes, frequencies and heights share one unit.",
            "`View(x1, y1, x2, y2)` is the window rendered into the square output, (x1, y1) "
            "bottom-left and (x2, y2) top-right; without it the window is (0, 0, 1, 1). Its four "
            "arguments are plain numbers.",
            "Choose the window to fit the pattern: e.g. 0..6 to show a few rows of 1-unit bricks, "
            "0..1 for a single tile or motif. A non-square window is stretched into the square "
            "output.",
        ]
    )


def define_section() -> str:
    return "\n".join(
        [
            "# Define",
            "- Reference a Define by its bare name (`tone`), never as a call; only a "
            "parameterised Define is called: `Define(stripe(w, c), Smoothstep(0, w, X()) * c)` "
            "then `stripe(0.2, 0.5)` (each use is its body with the arguments filled in). Use one "
            "instead of near-duplicate Defines that differ only in a few numbers.",
            "- A Define may use only earlier Defines.",
            "- Shapes cannot be Defined; Define the `Fill(...)`/`Stroke(...)` field instead, and "
            "repeat a shape inline to stroke it at several widths.",
            "- Reuse one Define for a layer's mask, colour and height so that pattern, colour and "
            "relief stay aligned.",
        ]
    )


def expressions_section() -> str:
    constants = ", ".join(f"`{name}`" for name in CONSTANTS)
    ops = [s for s in FUNCTIONS.values() if s.operator]
    op_lines = "\n".join(f"- `{s.operator}`, or `{s.signature()}`: {s.doc}." for s in ops)
    threshold = function_entry(FUNCTIONS["Threshold"])
    return "\n\n".join(
        [
            "# Expressions",
            "## Coordinates & constants\n" + _family("coord") + f"\n- Constants: {constants}.",
            "## Operators\n" + op_lines + "\n"
            "Usual precedence; `**` binds tightest and is right-associative; unary minus is "
            "allowed (`2 * -x`). Prefer operators to the functional forms.",
            "## Math\n"
            + "\n".join(
                function_entry(s)
                for s in FUNCTIONS.values()
                if s.family == "math" and not s.operator
            ),
            "## Threshold\n" + threshold + "\n"
            "Idioms: clamp a field to [0, 1] with "
            "`Threshold(f, below_at=0, below_to=0, above_at=1, above_to=1)`; binarise at 0.5 with "
            "`Threshold(f, below_at=0.5, below_to=0, above_at=0.5, above_to=1)`.",
            "## Noise\n" + _family("noise") + "\n"
            "Use `to_01=True` whenever noise drives a colour, a weight or a mask. A noise without "
            "`seed=` gets a fixed random seed when the program is accepted.",
            "## Patterns\n" + _family("pattern"),
            "## Shapes\n" + _family("shape", "segment"),
            "## Transforms\n" + _family("transform"),
            "## Combining masks\n"
            "For masks in [0, 1]: union `Max(a, b)`, intersection `Min(a, b)`, invert `1 - a`, "
            "subtract `a * (1 - b)`.",
        ]
    )


PITFALLS = """# Five things that surprise generators (read before emitting)
1. Multi-tone patterns belong in an upper layer's alpha mask over a substrate, not in height: \
colour comes only from basecolor, and a pattern encoded in height alone barely shows.
2. The composite height is the maximum over all covered layers (any alpha > 0), whatever their \
order: a low upper layer does not dent a high substrate, and colour and relief can disagree.
3. Only height variation is visible: a constant height creates no slope (a linear one only tilts \
the normal). Drive height with a pattern, and think in absolute differences between layers.
4. Shapes (`Rect`, `Ellipse`, `Path`) exist only inline inside `Fill`/`Stroke`; transform the \
`Fill`/`Stroke` result, not the shape.
5. Match frequencies and sizes to the View scale (a base_freq of 2 shows 2 features per unit), \
and keep values in range: colours 0..255, other channels mostly 0..1."""

PLAYBOOK = """# Organic texture playbook
- Multi-octave layering: a low-frequency `fBm` Define for broad form (few octaves) plus a \
high-frequency one for fine grain, each reused wherever its scale is needed.
- Anisotropic striation: `fBm`/`Worley` with `base_freq_x` different from `base_freq_y` elongates \
features along an axis, e.g. `fBm(octaves=4, base_freq_x=18, base_freq_y=2, to_01=True)` over a \
2x2 View gives bark-like vertical fibres (brushed metal, wood grain).
- Domain warping: transform parameters take fields, so `Translate(f, warp * 0.3, 0)` bends any \
field (noise, bricks, shapes) along a noise; `Rotate(f, swirl * 40)` swirls it. Warp grain along \
a board or vein along a leaf by warping the pattern, and drive height from the same warped field.
- Micro-gloss grain: add a high-frequency, low-amplitude `fBm` to roughness only, for skin, bark \
or stone microstructure.
- Substrate-matrix-first: a continuous substrate in a bottom `Layer(1)`, then discrete features \
as upper layers whose thresholded masks (thresholded `Worley` for islands, thresholded `fBm` \
for blobs) let the substrate show through."""

IDIOMS = """# Cells, instances and angles (use these instead of sine-hash tricks)
- Per-cell variation: `Bricks(..., output="cell_value", seed=N)` gives one random value per \
brick or board, `Worley(..., output="cell_value")` one per stone or plate, `Hash(X() * k, Y() * k, \
seed=N)` one per cell of a k-per-unit grid; use it for tone, height or a per-cell offset \
(`Translate(grain, cell * 7, 0)` shifts grain per board). `Worley(output="edge")` is the true \
distance to the cell border, for cracks and grout of constant width.
- Instancing: `Tile(motif, w, h, jitter=..., rotate=..., scale_min=..., probability=..., \
seed=N)` scatters copies of a motif drawn around (0, 0) (flowers, studs, rivets, glyphs) instead \
of writing each placement by hand.
- Angles and repeats: `Atan2(Y() - cy, X() - cx)` gives the polar angle for rosettes and radial \
brushing; `Mod`/`Fract` repeat a coordinate (herringbone, stripes) without sine tricks.
"""

EXAMPLES_PREAMBLE = (
    "# Examples\n"
    "These show the vocabulary, not templates to copy. Take each description literally: do not "
    "add weathering, dirt or layers that were not asked for."
)

#: The answer format every generator turn asks for (request, repairs, revisions).
ANSWER_FORMAT = (
    "Think as much as you need, then give the complete program in a <material>...</material> "
    "block; when a reply holds several, the last one is used."
)

OUTPUT_FORMAT = """# Output format
Think first about structure, scale, colours and relief, then give the complete program in a \
<material>...</material> block; when a reply holds several, the last one is used. The program \
must parse. Prefer few, well-chosen layers."""


def examples_section(examples: str = "paper") -> str:
    """The examples section with the example set ``examples`` (:data:`EXAMPLE_SETS`)."""
    entries = [
        f"Description: {ex.description}\n<material>\n{ex.program()}\n</material>"
        for ex in EXAMPLE_SETS[examples]
    ]
    return "\n\n".join([EXAMPLES_PREAMBLE, *entries])


def dsl_reference() -> str:
    """Sections 2-6 of the system prompt (also given to a critic that reads code)."""
    return "\n\n".join(
        [
            structure_section(),
            coordinates_section(),
            define_section(),
            expressions_section(),
            PITFALLS,
        ]
    )


@cache
def system_prompt(
    *,
    playbook: bool = True,
    few_shot: bool = True,
    render_size: int = 512,
    views: tuple[str, ...] = ("flat",),
    examples: str = "paper",
) -> str:
    """The full generator system prompt (the API and the CLI both default to everything on).

    ``render_size`` is the size the critic's previews are rendered at and ``views`` their
    layouts (:mod:`matloom.author.prompts.previews`); ``examples`` names the few-shot set
    (:data:`EXAMPLE_SETS`: the paper's, or ``v3``).
    """
    from matloom.author.prompts.previews import previews_section

    parts = [ROLE, dsl_reference(), previews_section(render_size, views)]
    if playbook:
        parts += [PLAYBOOK, IDIOMS]
    if few_shot:
        parts.append(examples_section(examples))
    parts.append(OUTPUT_FORMAT)
    return "\n\n".join(parts) + "\n"
