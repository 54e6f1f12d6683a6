"""MatLoom: text to editable layered material programs that evaluate to PBR texture maps.

Quick API::

    import matloom
    prog = matloom.parse(text)          # raises matloom.ProgramError with diagnostics
    text = matloom.format(prog)         # canonical text
    diags = matloom.check(text)         # list[Diagnostic] (errors and warnings)
    maps = matloom.evaluate(text, width=512, height=512)   # MaterialMaps (float32)
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from matloom._version import __version__
from matloom.lang.api import analyse, check, format, parse
from matloom.lang.diagnostics import Diagnostic, ProgramError, Severity

if TYPE_CHECKING:
    from matloom.engine.maps import MaterialMaps


def evaluate(
    program_or_text: Any, width: int = 512, height: int = 512, **kwargs: Any
) -> MaterialMaps:
    """Evaluate a program (or its text) into :class:`~matloom.engine.maps.MaterialMaps`."""
    from matloom.engine.evaluate import evaluate as _evaluate

    return _evaluate(program_or_text, width=width, height=height, **kwargs)


def preview(program_or_text: Any, size: int = 256, **kwargs: Any) -> Any:
    """Head-on shaded preview (uint8 RGB array) of a program, as the critic and scorer see it."""
    from matloom.render.api import preview as _preview

    return _preview(program_or_text, size=size, **kwargs)


__all__ = [
    "Diagnostic",
    "ProgramError",
    "Severity",
    "__version__",
    "analyse",
    "check",
    "evaluate",
    "format",
    "parse",
    "preview",
]
