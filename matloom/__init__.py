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


def params(program_or_text: Any) -> list[Any]:
    """The exposed parameters of a program (or its text): a list of
    :class:`~matloom.lang.params.Param` (address, value, kind, range, unit, label, affects)."""
    from matloom.lang.params import list_params

    return list_params(program_or_text)


def set_params(program_or_text: Any, values: dict[str, Any]) -> tuple[str, list[str]]:
    """Set parameters by address (see :func:`params`): the new program text and the warnings
    (values clamped into range). Raises ValueError for an unknown address or a wrong value."""
    from matloom.lang.layout import keep_layout
    from matloom.lang.params import set_params as _set_params

    text, warnings = _set_params(program_or_text, values)
    if isinstance(program_or_text, str):  # the untouched lines as they were written
        text = keep_layout(program_or_text, text)
    return text, warnings


def edit(program_or_text: Any, request: str, model: Any = None, **kwargs: Any) -> Any:
    """Edit a program by words ("wider grout", "blue glaze"): offline rules, or ``model`` (a
    chat model of :mod:`matloom.author.llm`). Returns an ``EditResult``: ``.program`` (the new
    text) and ``.report`` (the edit, the changed parameters and the computed locality).
    Raises ``EditRefused`` (a ValueError listing the parameters) for a request it cannot map."""
    from matloom.author.edit import edit as _edit

    return _edit(program_or_text, request, model, **kwargs)


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
    "edit",
    "evaluate",
    "format",
    "params",
    "parse",
    "preview",
    "set_params",
]
