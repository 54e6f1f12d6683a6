"""``matloom dataset --filter``: conditions on a sample's metric values (``pbr.plausible>=0.8``,
``seam_ratio.max<=1.5``), parsed by hand (no ``eval``)."""

from __future__ import annotations

import math
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

_OPS = ("<=", ">=", "==", "!=", "<", ">")
_FORM = re.compile(
    r"^\s*([A-Za-z_][A-Za-z0-9_]*(?:\.[A-Za-z0-9_]+)*)\s*(<=|>=|==|!=|<|>)\s*(.+?)\s*$"
)


class FilterError(ValueError):
    """A filter that cannot be read; the message is one line."""


@dataclass(frozen=True)
class Condition:
    """``column OP value``: a sample is kept only when its value of ``column`` satisfies it."""

    column: str
    op: str
    value: float

    @property
    def text(self) -> str:
        return f"{self.column}{self.op}{self.value:g}"

    def holds(self, actual: float) -> bool:
        """Whether ``actual`` satisfies the condition (NaN never does)."""
        if isinstance(actual, float) and math.isnan(actual):
            return False
        return {
            "<=": actual <= self.value,
            ">=": actual >= self.value,
            "==": actual == self.value,
            "!=": actual != self.value,
            "<": actual < self.value,
            ">": actual > self.value,
        }[self.op]


def parse_condition(text: str) -> Condition:
    """One ``--filter`` text as a :class:`Condition`."""
    match = _FORM.match(text)
    if match is None:
        raise FilterError(
            f"--filter {text!r}: expected COLUMN OP NUMBER with OP one of "
            f"{' '.join(_OPS)}, e.g. 'pbr.plausible>=0.8'"
        )
    column, op, raw = match.groups()
    try:
        value = float(raw)
    except ValueError:
        raise FilterError(f"--filter {text!r}: {raw!r} is not a number") from None
    if math.isnan(value):
        raise FilterError(f"--filter {text!r}: compare with a number, not NaN")
    return Condition(column, op, value)


def parse_conditions(texts: Sequence[str]) -> tuple[Condition, ...]:
    return tuple(parse_condition(t) for t in texts)


def drop_reason(values: Mapping[str, object], conditions: Sequence[Condition]) -> str | None:
    """Why a sample with these column ``values`` is dropped (every failed condition, with the
    value it had), or None when it is kept. A missing or non-numeric value fails."""
    failed = []
    for cond in conditions:
        actual = values.get(cond.column)
        if isinstance(actual, bool):  # tileable==1
            actual = float(actual)
        if not isinstance(actual, int | float):
            failed.append(f"{cond.text} (no value)")
        elif not cond.holds(float(actual)):
            failed.append(f"{cond.text} (was {float(actual):g})")
    return "; ".join(failed) if failed else None
