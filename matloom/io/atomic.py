"""Atomic file and directory writes, so an interrupted export never looks complete.

* :func:`atomic_write_bytes` / :func:`atomic_write_with` write to a temporary sibling file and
  ``os.replace`` it onto the target, so readers see either the old file or the whole new one.
* :func:`atomic_directory` yields a temporary sibling directory; only when the ``with`` body
  finishes without an exception is it renamed onto the final path. On an exception the
  temporary directory is removed and any previous final directory is left untouched.

Temporary names start with a dot and contain ``.tmp-`` so they are easy to recognise and clean
up; they are created with the process umask (not the 0600/0700 of ``tempfile``), so the
installed files and folder get ordinary permissions.
"""

from __future__ import annotations

import os
import shutil
import uuid
from collections.abc import Callable, Iterator
from contextlib import contextmanager
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


def _install_directory(temp: Path, final: Path) -> None:
    """Rename ``temp`` onto ``final``, replacing an existing directory there.

    An existing ``final`` is first renamed to a hidden backup, then ``temp`` takes its place,
    then the backup is deleted; if the second rename fails the backup is put back. (POSIX has
    no portable atomic directory swap, so ``final`` is briefly absent, never half-written.)
    """
    if final.is_symlink() or (final.exists() and not final.is_dir()):
        raise FileExistsError(f"{final} exists and is not a directory; refusing to replace it")
    if not final.exists():
        os.rename(temp, final)
        return
    backup = _sibling_name(final, "old")
    os.rename(final, backup)
    try:
        os.rename(temp, final)
    except BaseException:
        os.rename(backup, final)
        raise
    shutil.rmtree(backup, ignore_errors=True)


@contextmanager
def atomic_directory(final_dir: str | os.PathLike[str]) -> Iterator[Path]:
    """Yield a temporary sibling directory that becomes ``final_dir`` only on success.

    Parent folders are created. If ``final_dir`` already exists as a directory it is replaced
    as a whole after the body succeeds. If the body (or the install) raises, the temporary
    directory is deleted and a previous ``final_dir`` is left exactly as it was.
    """
    final = Path(final_dir).absolute()
    final.parent.mkdir(parents=True, exist_ok=True)
    temp = _sibling_name(final, "tmp")
    os.mkdir(temp, 0o777)
    try:
        yield temp
        _install_directory(temp, final)
    except BaseException:
        _remove_quietly(temp)
        raise
