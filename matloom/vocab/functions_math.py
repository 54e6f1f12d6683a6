"""Registry entries of the math functions added in language 2 (angles, wrap-around maths,
interpolation, per-cell random values). They join :data:`matloom.vocab.functions.FUNCTIONS`."""

from __future__ import annotations

from matloom.vocab.spec import FunctionSpec


def math_v2_specs() -> list[FunctionSpec]:
    """The language-2 math functions (each with ``since=2``)."""
    return []
