"""The composition plan: a spec's names resolved against the tables (unknown ones dropped,
with the reason), the named material's finish filled in, and the sizes: the View's side and
origin, metres per unit and the motif lattice."""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

from matloom.library.compose.bases import BASES, BaseSpec
from matloom.library.compose.layouts import LAYOUTS, Lattice, LayoutSpec
from matloom.library.compose.motifs import MOTIFS, MotifShape
from matloom.library.compose.named import NamedMaterial, named_material
from matloom.library.compose.spec import CompositionSpec, Finish
from matloom.library.compose.writer import num

#: the base used when the spec names none the composer knows
FALLBACK_BASE = "plaster"
#: a layout's View widens (by whole repeats of it) to show at least this much of the
#: material, at most ``MAX_REPEATS`` times: four 2 cm tesserae would fill a preview
MIN_VIEW_M = 0.3
MAX_REPEATS = 4
#: View side (units) of a plain base, and of a base with motifs but no layout
PLAIN_SIDE = 1.0
MOTIF_SIDE = 4.0


@dataclass(frozen=True)
class Plan:
    """What will be built: the resolved parts, the sizes and the notes so far."""

    base: BaseSpec
    layout: LayoutSpec | None
    motif: MotifShape | None
    named: NamedMaterial | None
    finish: Finish
    side: float
    unit_m: float
    cell_m: float
    origin: tuple[float, float]
    lattice: Lattice
    shown: tuple[str, ...]
    dropped: tuple[str, ...]


def plan(spec: CompositionSpec) -> Plan:
    """Resolve the spec's names (unknown ones are dropped, with the reason) and the sizes."""
    shown: list[str] = []
    dropped: list[str] = []
    named = named_material(spec.named) if spec.named else None
    if spec.named and named is None:
        dropped.append(f"named material {spec.named!r}: not in the table of named materials")
    base_name = spec.base if spec.base in BASES else (named.base if named else FALLBACK_BASE)
    if spec.base not in BASES:
        dropped.append(f"base {spec.base!r}: unknown; used {base_name}")
    base = BASES[base_name]
    shown.append(f"base: {base.noun} ({base.name})")
    if named is not None:
        shown.append(f"named material: {named.name} ({named.description})")
    layout = None
    layout_name = spec.layout or (named.layout if named else None)
    if layout_name is not None:
        layout = LAYOUTS.get(layout_name)
        if layout is None:
            dropped.append(f"layout {layout_name!r}: unknown layout")
        else:
            shown.append(f"layout: {layout.name} ({layout.noun})")
            if layout.name == "checks" and base.flat_motif:
                layout = replace(layout, joints=False)  # printed checks: no joints
    motif = None
    name = spec.motif.shape if spec.motif else (named.motif if named else None)
    if name is None and layout is not None:
        name = layout.default_motif
    if name is not None:
        motif = MOTIFS.get(name)
        if motif is None:
            dropped.append(f"motif {name!r}: unknown motif")
        else:
            how = "as the holes" if layout is not None and layout.holes else "one per cell"
            if layout is not None and layout.name == "scatter":
                how = "scattered"
            shown.append(f"motif: {motif.name} ({how})")
    cell_m = spec.size_m or (named.size_m if named else None)
    if layout is not None:
        cell_m = cell_m or layout.cell_m or base.cell_m
        side, origin, lattice = layout.side, layout.origin, layout.lattice
        unit_m = cell_m / layout.cell_w
        # small cells (mosaic tesserae, fine perforations): whole repeats of the layout's own
        # View until it shows MIN_VIEW_M of the material, at most MAX_REPEATS of them
        repeats = min(MAX_REPEATS, max(1, math.ceil(MIN_VIEW_M / (side * unit_m))))
        side *= repeats
        shown.append(f"size: {num(cell_m, 3)} m per {layout.unit}")
    elif motif is not None:
        cell_m = cell_m or base.cell_m
        side, origin, lattice, unit_m = MOTIF_SIDE, (0.25, 0.25), Lattice(), cell_m
        shown.append(f"size: {num(cell_m, 3)} m per motif")
    else:
        cell_m = cell_m or base.plain_m
        side, origin, lattice, unit_m = PLAIN_SIDE, (0.0, 0.0), Lattice(), cell_m / PLAIN_SIDE
        shown.append(f"size: {num(cell_m, 3)} m across")
    finish = _finish(spec.finish, named)
    return Plan(base, layout, motif, named, finish, side, float(num(unit_m, 6)), cell_m, origin,
                lattice, tuple(shown), tuple(dropped))  # fmt: skip


def _finish(asked: Finish, named: NamedMaterial | None) -> Finish:
    """The request's finish, its gaps filled from the named material."""
    if named is None:
        return asked
    return Finish(
        roughness=asked.roughness if asked.roughness is not None else named.finish.roughness,
        metallic=asked.metallic if asked.metallic is not None else named.finish.metallic,
        translucency=(
            asked.translucency if asked.translucency is not None else named.finish.translucency
        ),
        words=asked.words,
    )
