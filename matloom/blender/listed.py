"""The files of an exported folder that Blender may read: those its manifest lists, unchanged.

A folder given to ``matloom blender`` may come from anyone, and a saved ``.blend`` packs every
image the material loads. So a map path in ``material.json`` is used only when it names a
regular file *inside* the folder, reached through real sub-folders (no ``..``, no absolute
path, no symlink on the way) and listed under ``files`` with the SHA-256 its content has now.
Anything else (``../secret/id_rsa``, ``/home/me/.ssh/id_rsa``, a symlinked map, a file put in
the folder after the export) is refused with one line before Blender starts.
"""

from __future__ import annotations

import hashlib
import os
import stat
from pathlib import Path, PurePosixPath
from typing import Any

MANIFEST = "material.json"
_HASH_CHUNK = 1 << 20


class UnlistedFileError(Exception):
    """A manifest names a file Blender may not read; the message is one line for the user."""


def listed_file(folder: Path, rel: str, manifest: dict[str, Any]) -> Path:
    """The path of ``rel`` inside ``folder``, checked as the module docstring says."""
    parts = PurePosixPath(rel).parts
    if not parts or PurePosixPath(rel).is_absolute() or ".." in parts or "\0" in rel:
        raise UnlistedFileError(
            f"{folder}: {MANIFEST} names {rel!r}, which is outside the folder; only files "
            "inside it are read"
        )
    current = folder
    for index, part in enumerate(parts):
        current = current / part
        try:
            mode = os.lstat(current).st_mode
        except OSError:
            raise UnlistedFileError(
                f"{folder}: {rel} is listed in {MANIFEST} but missing"
            ) from None
        last = index == len(parts) - 1
        if stat.S_ISLNK(mode):
            raise UnlistedFileError(
                f"{folder}: {rel} in {MANIFEST} is reached through a symlink; MatLoom reads only "
                "files inside the folder"
            )
        if not (stat.S_ISREG(mode) if last else stat.S_ISDIR(mode)):
            raise UnlistedFileError(f"{folder}: {rel} is listed in {MANIFEST} but missing")
    _check_digest(folder, rel, current, manifest)
    return current


def _check_digest(folder: Path, rel: str, path: Path, manifest: dict[str, Any]) -> None:
    files = manifest.get("files")
    expected = files.get(rel) if isinstance(files, dict) else None
    if not isinstance(expected, str):
        raise UnlistedFileError(
            f'{folder}: {rel} is not listed with its SHA-256 under "files" in {MANIFEST}; '
            "re-export the folder with `matloom render`"
        )
    try:
        actual = _sha256_nofollow(path)
    except OSError as err:
        raise UnlistedFileError(f"cannot read {path}: {err.strerror or err}") from None
    if actual != expected.lower():
        raise UnlistedFileError(
            f"{folder}: {rel} is not the file {MANIFEST} lists (its SHA-256 differs); "
            "re-export the folder with `matloom render`"
        )


def _sha256_nofollow(path: Path) -> str:
    """SHA-256 of the file at ``path``, opened without following a final symlink."""
    digest = hashlib.sha256()
    fd = os.open(path, os.O_RDONLY | os.O_NOFOLLOW)
    with os.fdopen(fd, "rb") as handle:
        while chunk := handle.read(_HASH_CHUNK):
            digest.update(chunk)
    return digest.hexdigest()
