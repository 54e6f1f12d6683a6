"""Every base x layout x motif combination the composer offers (the plain base and the motif-less
program included) composes into a program that checks clean, tiles with its View and keeps its
named parameters. About 19,000 programs: marked ``grid``, outside the default suite, run by
``make test-grid`` (``.ci/run`` runs it after ``make test``). The default suite covers every
base x layout and layout x motif pair (``test_compose_grid.py``)."""

from __future__ import annotations

import pytest

from matloom.library.compose.build import compose
from matloom.library.compose.spec import CompositionSpec, MotifSpec
from matloom.library.compose.tables import BASES, LAYOUTS, MOTIFS

pytestmark = pytest.mark.grid

MOTIF_CHOICES: list[str | None] = [None, *MOTIFS]


@pytest.mark.parametrize("layout", [None, *LAYOUTS])
@pytest.mark.parametrize("base", list(BASES))
def test_every_base_layout_motif_combination(base: str, layout: str | None) -> None:
    bad = []
    for k, motif in enumerate(MOTIF_CHOICES):
        spec = CompositionSpec(
            base=base, layout=layout, motif=None if motif is None else MotifSpec(motif), seed=k
        )
        try:
            r = compose(spec)  # parses and checks: any diagnostic raises
        except ValueError as err:
            bad.append(f"{motif}: {err}")
            continue
        names = {d.name for d in r.program.defines}
        if not (r.tileable and r.program.view is not None and r.program.view.tileable):
            bad.append(f"{motif}: does not tile ({r.dropped})")
        elif not {"base_r", "rough", "relief"} <= names:
            bad.append(f"{motif}: named parameters missing")
    assert not bad, f"{base} / {layout}: " + "; ".join(bad[:5])
