"""``edit``: the one entry point, offline rules or a model (:mod:`matloom.author.edit`)."""

from __future__ import annotations

from typing import TYPE_CHECKING

from matloom.author.edit.core import EditResult, edit_offline
from matloom.author.edit.model import edit_with_model
from matloom.lang import ast as A
from matloom.lang.printer import format_program
from matloom.runtime.locality import LOCALITY_SIZE

if TYPE_CHECKING:
    from matloom.author.llm.base import ChatModel
    from matloom.engine.session import Session


def edit(
    program: A.Program | str,
    request: str,
    model: ChatModel | None = None,
    *,
    repair_turns: int = 2,
    size: int = LOCALITY_SIZE,
    session: Session | None = None,
) -> EditResult:
    """Edit ``program`` (text or AST) by ``request``: with ``model`` (a chat model of
    :mod:`matloom.author.llm`) through the model, else by the offline rules."""
    text = program if isinstance(program, str) else format_program(program, comments=True)
    if model is None:
        return edit_offline(text, request, size=size, session=session)
    return edit_with_model(
        text, request, model, repair_turns=repair_turns, size=size, session=session
    )
