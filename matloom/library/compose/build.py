"""The composer: :func:`compose` builds a tileable program with named parameters from a
:class:`~matloom.library.compose.spec.CompositionSpec`.

The program reads like a library entry: a front matter (so ``matloom params`` labels its
parameters and ``matloom library add`` takes it as it is), a header comment, the colour slots
and finish scalars as named Defines, the layout's Defines, the base's structure, the motif, and
a few layers bottom first: the ground (grout, gaps or the void under holes), the base, the
layout's second colour, the base's accents and the motif. The text is parsed and checked by the
language (an error is a bug: it raises), and its tileability is measured
(:func:`~matloom.lang.tileable.tileable_warnings`), never assumed.
"""

from __future__ import annotations

from dataclasses import replace

from matloom.lang.api import analyse
from matloom.lang.diagnostics import ProgramError
from matloom.lang.printer import format_program
from matloom.lang.tileable import tileable_warnings
from matloom.library.compose.bases import BaseSpec
from matloom.library.compose.layouts import LayoutParts, build_layout
from matloom.library.compose.motifs import place_motif
from matloom.library.compose.palette import Palette, resolve
from matloom.library.compose.plan import Plan, plan
from matloom.library.compose.render_text import front_matter, header, layers
from matloom.library.compose.spec import ComposedProgram, CompositionSpec
from matloom.library.compose.structure import Ctx, Structure
from matloom.library.compose.structures import STRUCTURES
from matloom.library.compose.writer import Axes, Writer, num


def compose(spec: CompositionSpec) -> ComposedProgram:
    """The program for ``spec``: checked, tileable (measured), with named parameters."""
    p = plan(spec)
    colours = spec.colours
    if p.named is not None:
        own = {r for r, _ in colours}
        colours = colours + tuple(
            (r, c) for r, c in p.named.colours if r not in own and r != "accent"
        )
        if p.named.colour("accent") and "accent" not in own and p.base.accent_share > 0:
            colours = colours + (("accent", p.named.colour("accent")),)  # type: ignore[operator]
    motif_colour = spec.motif.colour if spec.motif else None
    palette = resolve(colours, motif_colour, p.base, p.layout, p.motif is not None, p.named)
    w = Writer(p.unit_m, p.side, 100 + 1000 * spec.seed)
    scalars = _write_head(w, p, palette, spec)
    parts = LayoutParts()
    if p.layout is not None:
        mark = len(w.lines)
        w.section(f"layout: {p.layout.noun}")
        parts = build_layout(w, p.layout)
        if len(w.lines) == mark + 1:  # nothing of its own (scatter, perforations)
            w.lines.pop()
    w.section(f"structure: {p.base.noun}")
    structure = _structure(w, p.base, parts)
    motif = None
    if p.motif is not None:
        w.section(f"motif: {p.motif.noun}")
        scatter = p.layout is not None and p.layout.name == "scatter"
        motif = place_motif(w, p.motif, p.lattice, scatter)
    body = layers(w, p, palette, parts, structure, motif, scalars)
    x0, y0 = p.origin
    corners = ", ".join(num(v, 12) for v in (x0, y0, x0 + p.side, y0 + p.side))
    view = f"View({corners}, tileable=True, unit_m={num(p.unit_m, 6)})"
    source = "\n".join([*header(p), view, *w.lines, body]) + "\n"
    program, diags = analyse(source)
    if program is None or diags:
        raise ProgramError(diags, source)  # a composer bug: every combination is tested
    warnings = tileable_warnings(program)
    dropped = list(p.dropped) + list(palette.dropped)
    if warnings:
        dropped.append("tiling: " + warnings[0].message)
        program = replace(program, view=replace(program.view, tileable=False))
    description = _description(p)
    head = front_matter(p, palette, scalars, spec, not warnings, description)
    return ComposedProgram(
        program=program,
        text="\n".join(head) + "\n" + format_program(program, comments=True),
        tileable=not warnings,
        unit_m=p.unit_m,
        shown=(*p.shown, *palette.shown, *_finish_notes(spec)),
        dropped=tuple(dropped),
        labels=tuple(_labels(palette, scalars)),
        category=p.base.category,
        description=description,
    )


def _write_head(w: Writer, p: Plan, palette: Palette, spec: CompositionSpec) -> dict[str, str]:
    """Colour slots and finish scalars; returns scalar Define -> front matter kind."""
    w.section("colours")
    for slot in palette.slots.values():
        slot.write(w)
    w.section("finish")
    b, f = p.base, p.finish
    scalars: dict[str, str] = {}
    rough = f.roughness if f.roughness is not None else b.roughness
    scalars[w.define("rough", rough, "0 mirror .. 1 matte")] = "roughness"
    metal = f.metallic if f.metallic is not None else b.metallic
    if metal > 0:
        scalars[w.define("metal", metal, "metalness")] = "metallic"
    coat = b.coat
    if f.roughness is not None:
        coat = 0.0 if rough >= 0.6 else (max(coat, 0.5) if rough <= 0.15 else coat)
    if coat > 0:
        scalars[w.define("gloss", coat, "clear coat")] = "gloss"
    clarity = f.translucency if f.translucency is not None else b.transmission
    if clarity > 0:
        scalars[w.define("clarity", clarity, "see-through transmission")] = "other"
    scalars[w.define("relief", 1, "height multiplier")] = "relief"
    if p.layout is not None and p.layout.joints:
        scalars["grout_width"] = "gap"
    if p.layout is not None and p.layout.name == "stripes":
        scalars["stripe_share"] = "other"
    if p.motif is not None:
        size = spec.motif.scale if spec.motif is not None else 0.6
        size = min(0.95, max(0.2, size))
        scalars[w.define("motif_size", size, "motif size, share of its cell")] = "other"
    return scalars


def _structure(w: Writer, base: BaseSpec, parts: LayoutParts) -> Structure:
    """The base's structure; a directional one under upright planks is written for both
    directions and mixed by ``upright``."""
    build = STRUCTURES[base.structure]
    phase = parts.pick or "0"
    if not (base.directional and parts.upright):
        return build(Ctx(w, base, Axes(), "", phase))
    flat = build(Ctx(w, base, Axes(), "_flat", phase))
    up = build(Ctx(w, base, Axes(vertical=True), "_up", phase))

    def both(a: str | None, b: str | None, name: str) -> str | None:
        if a is None or b is None:
            return None
        return w.define(name, f"Mix({a}, {b}, {parts.upright})")

    return Structure(
        tone=both(flat.tone, up.tone, "tone") or "0",
        bump=both(flat.bump, up.bump, "bump") or "0",
        accent=both(flat.accent, up.accent, "accent_mask"),
        rough=both(flat.rough, up.rough, "rough_var"),
        metal=both(flat.metal, up.metal, "metal_var"),
    )


def _finish_notes(spec: CompositionSpec) -> list[str]:
    f = spec.finish
    out = []
    words = " ".join(f.words)
    if f.roughness is not None:
        out.append(f"finish: roughness {num(f.roughness, 2)}" + (f" ({words})" if words else ""))
    if f.metallic is not None:
        out.append(f"finish: metalness {num(f.metallic, 2)}")
    if f.translucency is not None:
        out.append(f"finish: translucency {num(f.translucency, 2)} (transmission)")
    return out


def _labels(palette: Palette, scalars: dict[str, str]) -> list[tuple[str, str]]:
    from matloom.lang.params import words
    from matloom.library.labels import SCALAR_LABELS

    out = []
    for slot in palette.slots.values():
        name = "grout" if slot.role == "grout" else words(slot.name)
        out.append((f"define:{slot.name}", f"{name} colour"))
    for name, kind in scalars.items():
        out.append((f"define:{name}", SCALAR_LABELS.get(kind) or words(name)))
    return out


def _description(p: Plan) -> str:
    what = p.named.name if p.named is not None else p.base.noun
    text = what if p.layout is None else f"{what} {p.layout.noun}"
    if p.motif is not None and not (p.layout is not None and p.layout.holes):
        text += f" with {p.motif.noun}"
    elif p.motif is not None:
        text += f" ({p.motif.noun})"
    return f"Composed: {text}"


__all__ = ["compose", "plan"]
