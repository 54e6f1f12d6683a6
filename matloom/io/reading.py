"""Reading a file the user's folder names, without following a symlink out of it.

Manifests and run records are read from folders an attacker may have prepared: the file itself
may be a symlink to another user file, a device, or huge. :func:`read_regular_bytes` opens it
with ``O_NOFOLLOW`` and reads it only when it is a regular file below a size cap.
"""

from __future__ import annotations

import json
import os
import stat
from pathlib import Path
from typing import Any


class UnsafeReadError(OSError):
    """The path is a symlink, not a regular file, or larger than allowed."""


def read_regular_bytes(path: str | os.PathLike[str], max_bytes: int) -> bytes:
    """The bytes of ``path`` when it is a regular file (not a symlink) of at most ``max_bytes``.

    Raises :class:`UnsafeReadError` (an ``OSError``) otherwise, or the ``OSError`` of the read.
    """
    try:
        fd = os.open(Path(path), os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK)
    except OSError as err:
        if os.path.islink(path):
            raise UnsafeReadError(f"{path} is a symlink; MatLoom does not follow it") from err
        raise
    with os.fdopen(fd, "rb") as handle:
        info = os.fstat(handle.fileno())
        if not stat.S_ISREG(info.st_mode):
            raise UnsafeReadError(f"{path} is not a regular file")
        if info.st_size > max_bytes:
            raise UnsafeReadError(f"{path} is larger than {max_bytes:,} bytes")
        data = handle.read(max_bytes + 1)
    if len(data) > max_bytes:  # grew while being read
        raise UnsafeReadError(f"{path} is larger than {max_bytes:,} bytes")
    return data


def read_json_file(path: str | os.PathLike[str], max_bytes: int) -> Any:
    """``path`` parsed as JSON under the rules of :func:`read_regular_bytes`.

    Raises ``OSError`` or ``ValueError`` (bad UTF-8 or JSON).
    """
    return json.loads(read_regular_bytes(path, max_bytes).decode("utf-8"))
