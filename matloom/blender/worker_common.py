"""Helpers shared by MatLoom's Blender worker modules; runs INSIDE Blender, never imported by
``matloom`` itself (``worker.py`` puts this folder on ``sys.path``).

Standard library only: events as JSON lines, temporary names, settings that some Blender
versions lack, colour conversions, and a guard that ends the worker when MatLoom is gone.
"""

from __future__ import annotations

import json
import os
import sys
import threading
import time
import uuid
from typing import Any

PREFIX = "MATLOOM-JSON "
#: linear Rec.709 -> linear Rec.2020 (greys unchanged); used when that is the working space
_709_TO_2020 = (
    (0.627404, 0.329283, 0.043313),
    (0.069097, 0.919540, 0.011362),
    (0.016391, 0.088013, 0.895595),
)
state: dict[str, Any] = {"working_space": "Linear Rec.709"}


def emit(event: str, **data: Any) -> None:
    sys.stdout.write(PREFIX + json.dumps({"event": event, **data}) + "\n")
    sys.stdout.flush()


def temp_name(path: str) -> str:
    """A hidden sibling name (``.<name>.tmp-<12 hex>``, the pattern MatLoom cleans up)."""
    head, tail = os.path.split(path)
    return os.path.join(head, f".{tail}.tmp-{uuid.uuid4().hex[:12]}")


def try_set(obj: Any, attr: str, value: Any) -> bool:
    """Set a setting that some Blender versions lack; report it instead of failing."""
    try:
        setattr(obj, attr, value)
        return True
    except (AttributeError, TypeError, ValueError) as err:
        emit("warning", message=f"cannot set {attr}={value!r}: {err}")
        return False


def try_use_nodes(datablock: Any) -> None:
    """Node trees are always on from Blender 5.0 (``use_nodes`` is deprecated there)."""
    if tuple(__import__("bpy").app.version[:2]) < (5, 0):
        datablock.use_nodes = True


def srgb8(colour: list[int]) -> tuple[float, float, float]:
    def one(c: float) -> float:
        v = c / 255.0
        return v / 12.92 if v <= 0.04045 else ((v + 0.055) / 1.055) ** 2.4

    return working(tuple(one(c) for c in colour[:3]))


def working(rgb: Any) -> tuple[float, float, float]:
    """A linear Rec.709 colour in the file's working space."""
    r, g, b = (float(c) for c in list(rgb)[:3])
    if state["working_space"] != "Linear Rec.2020":
        return (r, g, b)
    return tuple(m[0] * r + m[1] * g + m[2] * b for m in _709_TO_2020)  # type: ignore[return-value]


def exit_with_parent(parent_pid: int | None, interval: float = 0.5) -> None:
    """End this process when MatLoom (``parent_pid``) is gone, even if it was killed outright:
    an orphaned Blender would otherwise render on for nothing. Linux asks the kernel
    (``PR_SET_PDEATHSIG``); elsewhere a daemon thread watches the parent id."""
    if not parent_pid:
        return
    if sys.platform.startswith("linux"):
        try:
            import ctypes
            import signal

            libc = ctypes.CDLL(None, use_errno=True)
            libc.prctl(1, int(signal.SIGKILL), 0, 0, 0)  # PR_SET_PDEATHSIG
        except (OSError, AttributeError):
            pass
    if os.getppid() != parent_pid:
        os._exit(5)  # the parent died before we could ask

    def watch() -> None:
        while True:
            time.sleep(interval)
            if os.getppid() != parent_pid:
                os._exit(5)

    threading.Thread(target=watch, name="matloom-parent-watch", daemon=True).start()
