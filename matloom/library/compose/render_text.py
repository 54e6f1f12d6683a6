"""The composed program's text around its Defines: the surface Defines and the layers, and the
front matter that labels its parameters (the keys of a library entry, docs/library.md)."""

from __future__ import annotations

import json

from matloom.library.compose.layouts import LayoutParts
from matloom.library.compose.palette import Palette
from matloom.library.compose.plan import Plan
from matloom.library.compose.spec import CompositionSpec
from matloom.library.compose.structure import Structure
from matloom.library.compose.writer import Writer, num

#: tile body height (m) and bevel width (units) of layouts with joints
TILE_M = 0.003
#: depth of the joints of a soft base (fabric, leather, paper: seams and printed lines), m
SEAM_M = 0.0005
BEVEL = 0.03
#: plate thickness under perforations (m) and a motif's raise on hard bases (m)
PLATE_M = 0.002
MOTIF_RAISE_M = 0.0003


def layers(
    w: Writer, p: Plan, palette: Palette, parts: LayoutParts, st: Structure, motif: str | None,
    scalars: dict[str, str],
) -> str:  # fmt: skip
    """Write the surface Defines (a scalar it adds goes into ``scalars``) and return the
    ``Material(...)`` text."""
    b, layout = p.base, p.layout
    holes = layout is not None and layout.holes
    w.section("surface")
    shade = "1"
    if parts.pick:
        scalars[w.define("variation", 0.12, "tile-to-tile variation")] = "other"
        shade = w.define("shade", f"1 + (({parts.pick} - 0.5) * variation)",
                         "each tile a little different")  # fmt: skip
    terms = [st.bump]
    if parts.edge:
        depth, what = (SEAM_M, "seams") if b.flat_motif else (TILE_M, "tile body")
        terms.append(w.define("body", f"Sqrt(Clamp(({parts.edge} / {num(BEVEL)}))) * "
                              f"{num(w.units(depth))}", f"{what}, rounded at the edges"))  # fmt: skip
    if holes:
        terms.append(w.define("plate", w.units(PLATE_M), "thickness around the holes"))
    if parts.height:
        terms.append(parts.height)
    surface = w.define("surface", f"({' + '.join(terms)}) * relief", "height")
    cover = parts.cells
    if holes and motif is not None:
        cover = w.define("solid", f"1 - {motif}", "0 in the holes")

    rough = "rough" if st.rough is None else f"Clamp((rough + {st.rough}))"
    tail = [f".roughness({rough})"]
    if "metal" in w.names:
        tail.append(".metallic(metal)" if st.metal is None else f".metallic((metal * {st.metal}))")
    if "gloss" in w.names:
        tail.append(".coat(gloss)")
    if "clarity" in w.names:
        tail.append(".transmission(clarity)")
        if b.ior != 1.5:
            tail.append(f".ior({num(b.ior)})")
    if b.sheen:
        tail.append(f".sheen({num(b.sheen)})")
    if b.subsurface:
        tail.append(f".subsurface({num(b.subsurface)})")
    if b.anisotropy:
        tail.append(f".anisotropy({num(b.anisotropy)})")
        if b.directional and parts.upright:
            tail.append(f".anisotropy_angle(({parts.upright} * 90))")
    tail.append(f".height({surface})")

    out: list[str] = []
    if cover is not None and "grout" in palette.slots:
        what = "the void under the holes" if holes else "joints and gaps"
        out.append(_layer("1", "grout", [".roughness(0.9)", ".height(0)"], what))
    ratio = palette.ratio("base")
    out.append(_layer(cover or "1", _mix("base", "secondary", st.tone, shade), tail, b.noun))
    if layout is not None and layout.two_colour and parts.alt is not None:
        alt = layout.alt_slot
        shaded = ", ".join(
            _shaded(f"Mix({alt}_{c}, ({alt}_{c} * {num(ratio[k], 3)}), {st.tone})", shade)
            for k, c in enumerate("rgb")
        )
        out.append(_layer(_times(parts.alt, cover), shaded, tail, f"the {alt} colour"))
    if st.accent is not None and "accent" in palette.slots:
        out.append(_layer(_times(st.accent, cover), "accent", tail, "accents"))
    if motif is not None and "motif" in palette.slots:
        raise_ = "" if b.flat_motif else f" + {num(w.units(MOTIF_RAISE_M))}"
        mtail = [f".roughness({rough})"]
        if "gloss" in w.names:
            mtail.append(".coat(gloss)")
        mtail.append(f".height(({surface}{raise_}))")
        out.append(_layer(_times(motif, cover), "motif", mtail, "the motif"))
    return "Material(\n" + ",\n".join(out) + "\n)"


def _times(a: str, b: str | None) -> str:
    return a if b is None else f"({a} * {b})"


def _mix(a: str, b: str, t: str, shade: str) -> str:
    return ", ".join(_shaded(f"Mix({a}_{c}, {b}_{c}, {t})", shade) for c in "rgb")


def _shaded(colour: str, shade: str) -> str:
    return colour if shade == "1" else f"({colour} * {shade})"


def _layer(alpha: str, colour: str, channels: list[str], comment: str) -> str:
    if "," not in colour:
        colour = f"{colour}_r, {colour}_g, {colour}_b"
    lines = [f"  # {comment}", f"  Layer({alpha})", f"    .basecolor({colour})"]
    lines += [f"    {c}" for c in channels]
    return "\n".join(lines)


def front_matter(
    p: Plan, palette: Palette, scalars: dict[str, str], spec: CompositionSpec, tileable: bool,
    description: str,
) -> list[str]:  # fmt: skip
    """The ``# ---`` block: what ``matloom params`` labels parameters by, and what
    ``matloom library add`` keeps."""
    tags = [*p.base.words[:3]]
    for extra in (p.layout.name if p.layout else None, p.motif.name if p.motif else None,
                  p.named.name if p.named else None, "composed"):  # fmt: skip
        if extra and extra not in tags:
            tags.append(extra)
    rows = [
        f"description = {json.dumps(description)}",
        f'category = "{p.base.category}"',
        f"tags = {json.dumps(tags)}",
        f"size_m = {num(p.side * p.unit_m, 6)}",
        f"tileable = {'true' if tileable else 'false'}",
        f"colours = {json.dumps(list(palette.slots))}",
    ]
    if p.layout is not None or p.motif is not None:
        unit = p.layout.unit if p.layout is not None else "motif"
        rows += [f"feature_m = {num(p.cell_m, 6)}", f"units = {json.dumps([unit])}"]
    rows.append(f"note = {json.dumps(_note(p, spec))}")
    roles = {s.name: s.role for s in palette.slots.values() if s.role != "base"}
    if roles:
        rows.append("[roles]")
        rows += [f'{k} = "{v}"' for k, v in roles.items()]
    rows.append("[scalars]")
    rows += [f'{k} = "{v}"' for k, v in scalars.items()]
    return ["# ---", *(f"# {r}" for r in rows), "# ---"]


def _note(p: Plan, spec: CompositionSpec) -> str:
    parts = [f"base {p.base.name}"]
    if p.named is not None:
        parts.append(f"named material {p.named.name}")
    if p.layout is not None:
        parts.append(f"layout {p.layout.name}")
    if p.motif is not None:
        parts.append(f"motif {p.motif.name}")
    return "composed from parts (" + ", ".join(parts) + f"), seed {spec.seed}"


def header(p: Plan) -> list[str]:
    """The comment lines before the View."""
    line = f"# Composed from parts: {p.base.noun}"
    if p.named is not None:
        line += f" as {p.named.name}"
    if p.layout is not None:
        line += f", {p.layout.noun}"
    if p.motif is not None:
        line += f", {p.motif.noun}"
    size = p.side * p.unit_m
    return [line, f"# The View covers {num(size, 3)} m and repeats seamlessly."]
