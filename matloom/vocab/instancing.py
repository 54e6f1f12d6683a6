"""Registry entry of ``Tile``: instancing of a motif over a grid of cells (language 2).

They join :data:`matloom.vocab.functions.FUNCTIONS`; the engine's rule is
:func:`matloom.engine.rules.fields.tile` and the per-instance geometry lives in
:mod:`matloom.engine.kernels.tile`.
"""

from __future__ import annotations

from matloom.vocab.spec import FunctionSpec, Kind, ParamSpec, PrintStyle

P = ParamSpec


def instancing_specs() -> list[FunctionSpec]:
    """``Tile`` (``since=2``)."""
    positive = dict(lo=0.0, lo_open=True)
    return [
        FunctionSpec(
            "Tile",
            "transform",
            "scatter copies of a motif, one per cell of a width x height grid (rows shifted "
            "by offset * width, as in Bricks). In each cell the motif is evaluated in "
            "cell-local coordinates whose origin is the cell centre (plus a random shift of "
            "up to jitter * cell size per axis, a random rotation within +-rotate degrees and "
            "a uniform random scale in [scale_min, scale_max]); a cell is kept with "
            "probability `probability` (dropped cells give 0). Each sample takes the maximum "
            "over its own cell's instance and the 8 neighbouring cells' instances, so motifs "
            "up to a cell in size are never cut at cell borders. With the defaults the result "
            "is the motif repeated, centred in every cell",
            "Tile(Fill(Ellipse(0, 0, 0.3, 0.3), feather=0.02), 1, 1, jitter=0.2, seed=7)",
            (
                P("expr", Kind.EXPR, "the motif, drawn around (0, 0)"),
                P("width", Kind.FLOAT, "cell width", search=(0.05, 2.0), **positive),
                P("height", Kind.FLOAT, "cell height", search=(0.05, 2.0), **positive),
                P(
                    "jitter",
                    Kind.FLOAT,
                    "largest random shift of an instance, as a fraction of the cell size",
                    0.0,
                    lo=0,
                    hi=1,
                    search=(0.0, 0.5),
                ),
                P(
                    "rotate",
                    Kind.FLOAT,
                    "largest random rotation of an instance, in degrees (either way)",
                    0.0,
                    lo=0,
                    hi=180,
                    search=(0.0, 180.0),
                ),
                P(
                    "scale_min",
                    Kind.FLOAT,
                    "smallest instance scale",
                    1.0,
                    search=(0.3, 1.0),
                    **positive,
                ),
                P(
                    "scale_max",
                    Kind.FLOAT,
                    "largest instance scale",
                    1.0,
                    search=(1.0, 2.0),
                    **positive,
                ),
                P(
                    "probability",
                    Kind.FLOAT,
                    "chance that a cell holds an instance",
                    1.0,
                    lo=0,
                    hi=1,
                    search=(0.3, 1.0),
                ),
                P(
                    "offset",
                    Kind.FLOAT,
                    "row shift, as a fraction of the width",
                    0.0,
                    search=(0.0, 1.0),
                ),
                P(
                    "seed",
                    Kind.INT,
                    "seed of the per-instance randomness (integer >= 0); omitted seeds are made "
                    "explicit by canonicalisation",
                    default=None,
                    nullable=True,
                    lo=0,
                    is_seed=True,
                ),
            ),
            print_style=PrintStyle.NONDEFAULT_KEYWORDS,
            since=2,
            instances=9,
        )
    ]
