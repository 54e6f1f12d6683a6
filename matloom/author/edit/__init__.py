"""Edit a material by words: offline rules or a model, checked, with a computed locality report
(see :mod:`matloom.author.edit.core`)."""

from matloom.author.edit.api import edit
from matloom.author.edit.core import (
    Change,
    EditError,
    EditReport,
    EditResult,
    apply_edit,
    edit_offline,
)
from matloom.author.edit.rules import EditRefused, Plan, plan_edit

__all__ = [
    "Change",
    "EditError",
    "EditRefused",
    "EditReport",
    "EditResult",
    "Plan",
    "apply_edit",
    "edit",
    "edit_offline",
    "plan_edit",
]
