"""Private temporary folders of ``matloom blender`` that a killed run does not leak for ever.

Each folder (``$TMPDIR/matloom-blender-*``) holds a marker file that its process keeps locked
(``flock``) for as long as it uses the folder; the kernel drops the lock when the process ends,
however it ends (SIGKILL included). The first temporary folder a process makes removes the
folders of earlier runs whose marker is no longer locked. A folder is removed only when it is
a real folder (not a symlink) owned by this user, with the marker as a regular file whose lock
this process could take: anything else under that name (another user's, a folder without the
marker, one still in use) is left alone. ``shutil.rmtree`` does not follow symlinks inside.
"""

from __future__ import annotations

import errno
import fcntl
import os
import shutil
import stat
import tempfile
import threading
from pathlib import Path

PREFIX = "matloom-blender-"
#: The marker file in every folder; locked while the folder is in use.
MARKER = ".matloom-blender-temp"

_cleaned = False
_clean_lock = threading.Lock()


class TempDir:
    """A fresh temporary folder, marked and locked as this process's until :meth:`remove`."""

    def __init__(self, kind: str = "") -> None:
        clean_stale_once()
        self.path = Path(tempfile.mkdtemp(prefix=PREFIX + kind))
        try:
            self._fd: int | None = _create_locked_marker(self.path)
        except BaseException:
            shutil.rmtree(self.path, ignore_errors=True)
            raise

    def remove(self) -> None:
        """Delete the folder (still holding its lock, so no cleaner races us), then unlock."""
        if self._fd is None:
            return
        shutil.rmtree(self.path, ignore_errors=True)
        os.close(self._fd)
        self._fd = None

    def __enter__(self) -> Path:
        return self.path

    def __exit__(self, *exc: object) -> None:
        self.remove()


def _create_locked_marker(folder: Path) -> int:
    """Create the marker already locked: it is written under a temporary name, locked, then
    renamed, so a cleaner never sees an unlocked marker of a live folder."""
    pending = folder / f"{MARKER}.new"
    fd = os.open(pending, os.O_RDWR | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW, 0o600)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX)
        os.write(fd, f"matloom blender temporary folder of process {os.getpid()}\n".encode())
        os.rename(pending, folder / MARKER)
    except BaseException:
        os.close(fd)
        raise
    return fd


def clean_stale_once() -> None:
    """:func:`clean_stale` the first time a process asks (later calls return at once)."""
    global _cleaned
    with _clean_lock:
        if _cleaned:
            return
        _cleaned = True
    clean_stale()


def clean_stale(root: Path | None = None) -> list[Path]:
    """Remove the temporary folders of earlier runs that ended without removing them (killed);
    return those removed. Errors only skip a folder (cleanup never stops a run)."""
    root = Path(tempfile.gettempdir() if root is None else root)
    removed: list[Path] = []
    try:
        entries = list(os.scandir(root))
    except OSError:
        return removed
    for entry in entries:
        if entry.name.startswith(PREFIX) and _remove_if_stale(Path(entry.path)):
            removed.append(Path(entry.path))
    return removed


def _remove_if_stale(folder: Path) -> bool:
    try:
        info = os.lstat(folder)
        if not stat.S_ISDIR(info.st_mode) or info.st_uid != os.getuid():
            return False  # a symlink, a file, or another user's folder: never ours to remove
        fd = os.open(folder / MARKER, os.O_RDWR | os.O_NOFOLLOW | os.O_NONBLOCK)
    except OSError:
        return False  # no marker (or a symlinked one): not a folder this module made
    try:
        if not stat.S_ISREG(os.fstat(fd).st_mode):
            return False
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError as err:
            if err.errno in (errno.EWOULDBLOCK, errno.EAGAIN):
                return False  # its process is alive and still using it
            raise
        shutil.rmtree(folder)  # refuses a symlink; never follows one inside
        return True
    except OSError:
        return False
    finally:
        os.close(fd)
