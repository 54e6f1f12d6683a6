"""Dependency analysis: which numeric literals and seeds each output channel depends on.

Implements the paper's formal dependency statement: channel k's map is a function of the
parameters in D_k only (with fixed sampling coordinates, settings and engine version). Coverage
expressions enter every blended channel, and height feeds normal and AO.
"""

from __future__ import annotations

from dataclasses import dataclass

from matloom.lang import ast as A
from matloom.lang.constants import resolve_static
from matloom.lang.seeds import uses_seed
from matloom.vocab.layout import LAYOUT

#: The coverage channel: its expressions enter every blended and max-blended output.
COVERAGE = LAYOUT.coverage.name
#: Coverage-weighted ("over") channels, in registry order.
BLENDED = LAYOUT.blended
#: Max-blended channels (height): coverage decides which layers count.
MAXED = tuple(c.name for c in LAYOUT.maxed)
#: Maps computed from a composited channel (normal and AO from height) -> that channel.
DERIVED = {d.name: d.source for d in LAYOUT.derived}
#: Every output map name: alpha, the blended channels, height, normal, ao.
OUTPUTS = LAYOUT.outputs


@dataclass(frozen=True)
class ParamRef:
    """One numeric coordinate of a program: a literal (or seed) at a source position."""

    line: int
    col: int
    value: int | float
    is_seed: bool
    where: str  # e.g. "Define tileMask", "layer 1 .roughness"

    @property
    def key(self) -> str:
        return f"{self.line}:{self.col}"


def _expr_params(
    node: A.Node, where: str, defines: dict[str, frozenset[ParamRef]], seen: set[str]
) -> set[ParamRef]:
    out: set[ParamRef] = set()
    seed_nums: set[int] = set()
    unused: set[int] = set()  # seeds of calls that ignore them (Bricks without cell values)
    for n in A.walk(node):
        if isinstance(n, A.Call):
            s = n.arg("seed")
            if isinstance(s, A.Num):
                (seed_nums if uses_seed(n) else unused).add(id(s))
    for n in A.walk(node):
        if isinstance(n, A.Num) and id(n) not in unused:
            out.add(ParamRef(n.span.line, n.span.col, n.value, id(n) in seed_nums, where))
        elif isinstance(n, A.Ref) and n.name in defines:
            out |= defines[n.name]
            seen.add(n.name)
    return out


def define_params(program: A.Program) -> dict[str, frozenset[ParamRef]]:
    """Transitive parameter set of every Define (Defines may use earlier Defines)."""
    out: dict[str, frozenset[ParamRef]] = {}
    for d in program.defines:
        out[d.name] = frozenset(_expr_params(d.expr, f"Define {d.name}", out, set()))
    return out


def channel_dependencies(program: A.Program) -> dict[str, frozenset[ParamRef]]:
    """Output map name -> the parameters it transitively depends on (a named static value,
    ``Bricks(mortar=grout)``, through the Define's literals; a named seed counts as a seed)."""
    program = resolve_static(program)
    defs = define_params(program)
    per: dict[str, set[ParamRef]] = {name: set() for name in OUTPUTS}
    for i, layer in enumerate(program.layers):
        if layer.alpha is not None:
            per[COVERAGE] |= _expr_params(layer.alpha, f"layer {i} alpha", defs, set())
        for ch in layer.channels:
            for a in ch.args:
                per[ch.name] |= _expr_params(a, f"layer {i} .{ch.name}", defs, set())
    coverage = per[COVERAGE]
    for name in (*BLENDED, *MAXED):
        per[name] |= coverage
    for name, source in DERIVED.items():
        per[name] = set(per[source])
    return {k: frozenset(v) for k, v in per.items()}


def seed_dependent_outputs(program: A.Program) -> set[str]:
    """Outputs whose maps change when any noise seed changes."""
    return {k for k, ps in channel_dependencies(program).items() if any(p.is_seed for p in ps)}
