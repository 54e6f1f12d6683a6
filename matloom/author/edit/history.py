"""The history of an edited program: every version, so edits chain and ``--undo`` works.

A program written by ``matloom edit`` has a history file beside it, ``NAME.history.json``
(for ``tiles.edited.mat``: ``tiles.edited.mat.history.json``), holding every version in order:
the program the first edit started from (``request`` null, ``source`` its file), then one entry
per edit (its request, mode and changed parameters). The file is *managed* while its text is
the history's last version; a program changed by hand since is appended as a version of its
own before the next edit, so nothing is lost. :meth:`History.undo` drops the last version and
returns the one before it.
"""

from __future__ import annotations

import json
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from matloom.io.atomic import atomic_write_bytes

SUFFIX = ".history.json"
FORMAT = 1


def history_path(program: Path) -> Path:
    """The history file of the program file ``program``."""
    return program.with_name(program.name + SUFFIX)


class HistoryError(ValueError):
    """A history that cannot be read or used (one line)."""


@dataclass
class History:
    """The versions of one program file (oldest first)."""

    path: Path
    versions: list[dict[str, Any]] = field(default_factory=list)

    @classmethod
    def load(cls, program: Path) -> History:
        """The history of ``program`` (empty when it has none)."""
        path = history_path(program)
        if not path.exists():
            return cls(path)
        try:
            data = json.loads(path.read_text(encoding="utf-8"))
        except (OSError, UnicodeDecodeError, json.JSONDecodeError) as err:
            raise HistoryError(f"cannot read the history {path}: {err}") from None
        versions = data.get("versions") if isinstance(data, dict) else None
        if not isinstance(versions, list) or not all(
            isinstance(v, dict) and isinstance(v.get("program"), str) for v in versions
        ):
            raise HistoryError(f"{path} is not a matloom edit history")
        return cls(path, versions)

    @property
    def current(self) -> str | None:
        """The last version's program text (None for an empty history)."""
        return self.versions[-1]["program"] if self.versions else None

    def manages(self, text: str) -> bool:
        """Whether ``text`` is the history's last version (the file is ours, unchanged)."""
        return self.current is not None and self.current == text

    def add(self, program: str, request: str | None = None, **info: Any) -> None:
        """Append a version (``request`` None: a starting point or a hand edit)."""
        entry: dict[str, Any] = {
            "version": len(self.versions),
            "time": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()),
            "request": request,
            **info,
            "program": program,
        }
        self.versions.append(entry)

    def undo(self) -> str:
        """Drop the last version; return the one before it."""
        if len(self.versions) < 2:
            raise HistoryError(f"nothing to undo: {self.path} has no earlier version")
        self.versions.pop()
        return self.versions[-1]["program"]

    def save(self) -> None:
        data = {"format": FORMAT, "versions": self.versions}
        atomic_write_bytes(self.path, (json.dumps(data, indent=2) + "\n").encode("utf-8"))

    def summary(self) -> list[dict[str, Any]]:
        """The versions without their programs (for listings)."""
        return [{k: v for k, v in e.items() if k != "program"} for e in self.versions]
