"""Registry entries of the pattern functions: ``Bricks``, ``Weave`` and ``Threshold`` (with the
frequency parameters they share with the noises). They join
:data:`matloom.vocab.functions.FUNCTIONS`.
"""

from __future__ import annotations

from matloom.vocab.spec import FunctionSpec, Kind, ParamSpec, PrintStyle

P = ParamSpec
_FREQ_SEARCH = (0.1, 50.0)


def freq_param(name: str, doc: str, default: float | None, positive: bool) -> ParamSpec:
    """A frequency parameter (noises and Weave)."""
    return P(
        name,
        Kind.FLOAT,
        doc,
        default=default,
        nullable=True,
        lo=0.0 if positive else None,
        lo_open=positive,
        nonzero=not positive,
        is_frequency=True,
        search=_FREQ_SEARCH,
        search_log=True,
    )


def _output_seed(output: str, since: int) -> ParamSpec:
    """The ``seed`` of a pattern whose one ``output`` is random (Bricks' cell_value, Weave's
    thread_value); the other outputs ignore it."""
    return P(
        "seed",
        Kind.INT,
        f'random seed of output="{output}" (integer >= 0; made explicit by '
        "canonicalisation when omitted); the other outputs ignore it and get none",
        default=None,
        nullable=True,
        lo=0,
        is_seed=True,
        since=since,
        used_when=("output", (output,)),
    )


def pattern_specs() -> list[FunctionSpec]:
    feather = P(
        "feather", Kind.FLOAT, "edge softening width (0 = hard edge)", 0.0, lo=0, search=(0.0, 0.2)
    )
    bricks = FunctionSpec(
        "Bricks",
        "pattern",
        "brick/tile pattern: a mask (1 on bricks, 0 in mortar), a random value per brick, the "
        "position inside the brick or the distance to its border (see output); rows start at "
        "the origin",
        "Bricks(brick_width=0.5, brick_height=0.25, mortar=0.02)",
        (
            P(
                "brick_width",
                Kind.FLOAT,
                "brick size along x",
                1.0,
                lo=0,
                lo_open=True,
                search=(0.05, 5),
            ),
            P(
                "brick_height",
                Kind.FLOAT,
                "brick size along y",
                0.5,
                lo=0,
                lo_open=True,
                search=(0.05, 5),
            ),
            P(
                "offset",
                Kind.FLOAT,
                "shift of each successive course, as a fraction of the brick length: with "
                'axis="row" the course one brick_height higher (row index + 1) is shifted by '
                "+offset * brick_width along +x (to the right; row 0 starts at x = 0), with "
                'axis="column" the column one brick_width further right (column index + 1) is '
                "shifted by +offset * brick_height along +y (up); 0 = stacked",
                0.5,
                search=(0.0, 1.0),
            ),
            P("mortar", Kind.FLOAT, "gap width between bricks", 0.05, lo=0, search=(0.0, 1.0)),
            P(
                "axis",
                Kind.ENUM,
                "courses run along rows or columns",
                "row",
                choices=("row", "column"),
            ),
            feather,
            P(
                "output",
                Kind.ENUM,
                '"mask": 1 on bricks, 0 in mortar (feather softens the edge; the other outputs '
                'ignore feather); "cell_value": a uniform random value in [0, 1) per brick, '
                'constant over the brick and the half mortar around it, set by seed; "u" / '
                '"v": the position inside the brick\'s cell (brick_width x brick_height: the '
                "brick and half the mortar on each side) along x / y, from 0 at its left / "
                'bottom side to 1 at its right / top side; "edge": the distance, in coordinate '
                "units, from the sample to the brick's border (the nearest of its four sides), "
                '0 in the mortar; "row" / "column" (language 3): the brick\'s integer row / '
                'column index (row = Floor(y / brick_height) with axis="row", column = '
                'Floor(x / brick_width) with axis="column"; the other index counts bricks along '
                "the shifted course), constant over the brick and the half mortar around it; "
                "in a tileable output both wrap to 0 .. (count per View period - 1)",
                "mask",
                choices=("mask", "cell_value", "u", "v", "edge", "row", "column"),
                since=2,
                choice_since=(("row", 3), ("column", 3)),
            ),
            _output_seed("cell_value", since=2),
        ),
        print_style=PrintStyle.NONDEFAULT_KEYWORDS,
    )
    weave = FunctionSpec(
        "Weave",
        "pattern",
        "woven threads: a mask (1 on whichever thread is on top, 0 in the gaps), the warp or "
        "weft part of it, the position along / across the thread on top or a random value per "
        "thread (see output); warp and weft may have different widths",
        "Weave(over=2, under=1, base_freq=16, warp_width=0.8, feather=0.1)",
        (
            P("over", Kind.INT, "cells the warp passes over", 1, lo=1, search=(1, 4)),
            P("under", Kind.INT, "cells the warp passes under", 1, lo=1, search=(1, 4)),
            P("shift", Kind.INT, "step of the draft per row (twill diagonal)", 1, search=(0, 3)),
            freq_param("base_freq", "thread cells per coordinate unit", 8.0, True),
            freq_param("base_freq_x", "per-axis cell frequency along x", None, True),
            freq_param("base_freq_y", "per-axis cell frequency along y", None, True),
            P(
                "warp_width",
                Kind.FLOAT,
                "thread width as a fraction of the cell",
                0.5,
                lo=0,
                lo_open=True,
                hi=1,
                search=(0.05, 1.0),
            ),
            feather,
            P(
                "output",
                Kind.ENUM,
                '"mask": 1 on whichever thread is on top, 0 in the gaps; "warp" / "weft": the '
                "mask where the warp (vertical) / weft (horizontal) thread is on top, 0 elsewhere "
                '(warp + weft = mask); "along": the position along the visible float of the '
                "thread on top (its run of consecutive cells), from 0 at its start (bottom end "
                "of a warp float, left end of a weft float) to 1 at its end; a float that never "
                "ends (a warp column always on top, e.g. shift=0) restarts in every cell; "
                '"across": the position across the thread on top, from 0 at its left (warp) / '
                "bottom (weft) edge to 1 at its other edge, 0 or 1 in the gaps beside it; "
                '"thread_value" (language 3): a uniform random value in [0, 1) per thread, set '
                "by seed: the warp thread of each column and the weft thread of each row has its "
                "own, constant along the thread; the value is the thread on top's, over the "
                "whole cell (the gaps beside it included: multiply by the mask to leave them "
                "out); in a tileable output the threads repeat with the View. along, across "
                "and thread_value ignore feather",
                "mask",
                choices=("mask", "warp", "weft", "along", "across", "thread_value"),
                since=2,
                choice_since=(("thread_value", 3),),
            ),
            P(
                "weft_width",
                Kind.FLOAT,
                "weft (horizontal) thread width as a fraction of the cell; None: warp_width",
                None,
                nullable=True,
                lo=0,
                lo_open=True,
                hi=1,
                search=(0.05, 1.0),
                since=3,
            ),
            _output_seed("thread_value", since=3),
        ),
        print_style=PrintStyle.NONDEFAULT_KEYWORDS,
    )
    threshold = FunctionSpec(
        "Threshold",
        "mask",
        "clamp or binarise a field: values >= above_at become above_to, values <= below_at become "
        "below_to; values in between pass through unchanged, except inside the transition ramps "
        "(with transition_width w > 0: in [above_at - w, above_at] the value blends smoothly "
        "into above_to, in [below_at, below_at + w] from below_to). So below_at=0.4, "
        "below_to=0, above_at=0.6, above_to=1 keeps the input itself between 0.4 and 0.6 (a "
        "jump at each cutoff), not a 0-to-1 ramp: use Smoothstep(0.4, 0.6, f) for a soft mask. "
        "Binarise with below_at = above_at = t: below_to at and under t, above_to above",
        "Threshold(fBm(to_01=True, seed=1), below_at=0.5, below_to=0, above_at=0.5, above_to=1)",
        (
            P("expr", Kind.EXPR, "input field"),
            P("below_at", Kind.FLOAT, "lower cutoff", None, nullable=True, search=(0.0, 1.0)),
            P(
                "below_to",
                Kind.FLOAT,
                "value below the lower cutoff (default: below_at; no effect without below_at)",
                None,
                nullable=True,
                search=(0.0, 1.0),
                needs="below_at",
            ),
            P("above_at", Kind.FLOAT, "upper cutoff", None, nullable=True, search=(0.0, 1.0)),
            P(
                "above_to",
                Kind.FLOAT,
                "value above the upper cutoff (default: above_at; no effect without above_at)",
                None,
                nullable=True,
                search=(0.0, 1.0),
                needs="above_at",
            ),
            P(
                "transition_width",
                Kind.FLOAT,
                "width of the smooth ramp inside the band",
                0.0,
                lo=0,
                search=(0.0, 1.0),
            ),
        ),
        print_style=PrintStyle.THRESHOLD,
    )
    return [bricks, weave, threshold]
