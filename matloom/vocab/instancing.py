"""Registry entries of ``Tile``: instancing of a motif over a grid of cells (language 2), and
``Choose``: a per-sample choice between fields, e.g. by a per-instance value (language 3).

They join :data:`matloom.vocab.functions.FUNCTIONS`; the engine's rule is
:func:`matloom.engine.rules.fields.tile` and the per-instance geometry lives in
:mod:`matloom.engine.kernels.tile`.
"""

from __future__ import annotations

from matloom.vocab.spec import FunctionSpec, Kind, ParamSpec, PrintStyle

P = ParamSpec


def instancing_specs() -> list[FunctionSpec]:
    """``Tile`` (``since=2``, its ``output`` ``since=3``) and ``Choose`` (``since=3``)."""
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
                P(
                    "output",
                    Kind.ENUM,
                    '"mask": the maximum of the instances\' motifs (the default); the other '
                    "outputs give, at each sample, a value of the instance whose motif is largest "
                    "there (the instance you see; among the kept instances whose motif is > 0, "
                    "0 where there is none): "
                    '"instance_value": a uniform random value in [0, 1) per instance, set by seed '
                    '(colour or vary each instance, or pick a motif with Choose); "row" / "column": '
                    "the integer row / column index of the instance's cell (row = Floor(y / "
                    "height) before jitter; in a tileable output both wrap to 0 .. count per View "
                    'period - 1); "angle": the instance\'s random rotation in degrees, '
                    'counter-clockwise, in [-rotate, rotate]; "u" / "v": the sample\'s x / y in '
                    "the instance's frame, where the motif is evaluated (origin at the instance "
                    "centre, rotated and scaled with it)",
                    "mask",
                    choices=("mask", "instance_value", "row", "column", "angle", "u", "v"),
                    since=3,
                ),
            ),
            print_style=PrintStyle.NONDEFAULT_KEYWORDS,
            since=2,
            instances=9,
        ),
        FunctionSpec(
            "Choose",
            "math",
            "one of two or more fields, picked per sample by index in [0, 1): with n options "
            "the option number Floor(index * n) (clamped to 0 .. n - 1; a, b, then the further "
            "options in order); NaN where index is NaN. Give it a per-cell random value to pick "
            'a motif, colour or height per cell: Worley(output="cell_value"), '
            'Bricks(output="cell_value"), Hash(...), or per Tile instance '
            'Tile(M, ..., output="instance_value") with the option Tiles on the same grid, '
            "jitter, rotate, scale, probability, offset and seed, M covering every option's "
            "motif (e.g. their Max), and instances that do not overlap (each sample then "
            "shows one instance, whose value picks the option)",
            "Choose(Hash(X() * 4, Y() * 4, seed=2), 0.2, 0.5, 0.9)",
            (
                P("index", Kind.EXPR, "the choice, in [0, 1)"),
                P("a", Kind.EXPR, "option 0"),
                P("b", Kind.EXPR, "option 1"),
            ),
            variadic=P("options", Kind.EXPR, "further options (option 2, 3, ...)"),
            since=3,
        ),
    ]
