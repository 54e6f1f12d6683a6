"""Registry entry of ``Quantize``: a field sampled at cell centres (language 3).

It joins :data:`matloom.vocab.functions.FUNCTIONS`. Quantize is a coordinate transform (its op
entry is :mod:`matloom.ops.table_quantize`): its operand is evaluated at the centre of the
width x height cell that holds each sample, so it composes with every field, noise and pattern
included, and with the other transforms.
"""

from __future__ import annotations

from matloom.vocab.spec import FunctionSpec, Kind, ParamSpec

P = ParamSpec


def quantize_specs() -> list[FunctionSpec]:
    """``Quantize`` (``since=3``)."""
    positive = dict(lo=0.0, lo_open=True)
    return [
        FunctionSpec(
            "Quantize",
            "transform",
            "the field sampled at cell centres: a grid of width x height cells aligned to the "
            "origin (cell edges at whole multiples of width and height), each sample taking the "
            "value of `expr` at its cell's centre ((Floor(x / width) + 0.5) * width, likewise "
            "for y); stepped, pixelated or mosaic patterns. In a tileable View it repeats when "
            "the View's width and height hold whole numbers of cells",
            "Quantize(fBm(base_freq=3, seed=4), 0.125, 0.125)",
            (
                P("expr", Kind.EXPR, "field to sample (noise included)"),
                P("width", Kind.FLOAT, "cell width", search=(0.01, 1.0), **positive),
                P("height", Kind.FLOAT, "cell height", search=(0.01, 1.0), **positive),
            ),
            since=3,
        ),
    ]
