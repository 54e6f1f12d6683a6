"""Atomic file and directory writes, so an interrupted export never looks complete.

* :func:`atomic_write_bytes` / :func:`atomic_write_with` write to a temporary sibling file and
  ``os.replace`` it onto the target, so readers see either the old file or the whole new one.
* Whole output folders are staged and installed by :mod:`matloom.io.outdir`, which never
  replaces a folder as a whole (that would delete files MatLoom did not write).

Temporary names start with a dot and contain ``.tmp-`` so they are easy to recognise and clean
up; they are created with the process umask (not the 0600/0700 of ``tempfile``), so the
installed files and folder get ordinary permissions.
"""

from __future__ import annotations

import os
import shutil
import uuid
from collections.abc import Callable
from pathlib import Path


def _sibling_name(path: Path, kind: str) -> Path:
    """A fresh hidden sibling path of ``path`` (``.<name>.<kind>-<random>``)."""
    return path.with_name(f".{path.name}.{kind}-{uuid.uuid4().hex[:12]}")


def _remove_quietly(path: Path) -> None:
    """Remove a file or directory tree if it exists, ignoring errors (cleanup only)."""
    if path.is_dir() and not path.is_symlink():
        shutil.rmtree(path, ignore_errors=True)
    else:
        try:
            path.unlink()
        except FileNotFoundError:
            pass


def atomic_write_with(path: str | os.PathLike[str], write: Callable[[Path], None]) -> Path:
    """Call ``write(temp_path)`` for a temporary sibling, then move it onto ``path``.

    For writers that insist on a file name (e.g. the OpenEXR library). The temporary file is
    removed if ``write`` raises.
    """
    target = Path(path)
    temp = _sibling_name(target, "tmp")
    try:
        write(temp)
        os.replace(temp, target)
    except BaseException:
        _remove_quietly(temp)
        raise
    return target


def atomic_write_bytes(path: str | os.PathLike[str], data: bytes) -> Path:
    """Write ``data`` to ``path`` atomically (temp file in the same folder + ``os.replace``)."""

    def write(temp: Path) -> None:
        descriptor = os.open(temp, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o666)
        with os.fdopen(descriptor, "wb") as handle:
            handle.write(data)
            handle.flush()
            os.fsync(handle.fileno())

    return atomic_write_with(path, write)


def rewrite_file(path: str | os.PathLike[str], data: bytes) -> Path:
    """Replace the contents of an existing file atomically, keeping what makes it the same file.

    A symlink stays a symlink (its target is rewritten); the target's permission bits and,
    where allowed, owner and group are kept.
    """
    import stat as stat_module

    target = Path(os.path.realpath(path))
    before = target.stat()

    def write(temp: Path) -> None:
        descriptor = os.open(temp, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600)
        with os.fdopen(descriptor, "wb") as handle:
            handle.write(data)
            handle.flush()
            os.fchmod(handle.fileno(), stat_module.S_IMODE(before.st_mode))
            try:
                os.fchown(handle.fileno(), before.st_uid, before.st_gid)
            except PermissionError:
                pass
            os.fsync(handle.fileno())

    return atomic_write_with(target, write)
