"""A field parameter keeps its coordinate expression when printed: an inlined `sy=Y()` must
not print as its origin value 0 (found by the generated-program property test, seed 5332,
whose inlined program has `Scale(..., 1.414912302139225, Y())`)."""

from __future__ import annotations

import matloom
from matloom.lang.inline import inline_defines
from matloom.lang.parser import parse_source
from matloom.lang.printer import format_program
from matloom.lang.random_program import random_program


def test_an_inlined_coordinate_in_a_field_parameter_prints_as_written() -> None:
    inlined = inline_defines(matloom.parse(random_program(5332)))
    text = format_program(inlined)
    assert "1.414912302139225, Y())" in text
    reparsed, diags = parse_source(text)
    assert [x for x in diags if x.is_error] == [] and reparsed == inlined
