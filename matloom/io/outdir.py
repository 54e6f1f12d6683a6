"""Output folders that MatLoom writes into without ever losing a file it did not write.

Every command that writes a folder (``render``, ``generate``, ``sweep``, ``seeds``, ``gallery``,
``demo``) goes through :class:`OutputFolder`:

* **Ownership.** A hidden index, ``.matloom-files.json``, lists every file MatLoom wrote in the
  folder with its size, modification time and SHA-256. A file counts as MatLoom's only while
  it is listed *and* unchanged; anything else (a user's ``notes.txt``, the source program, a
  map the artist edited by hand, a symlink) is foreign. Foreign files are never deleted or
  overwritten: a write that would replace one fails with :class:`OutputError` before anything
  changes. A path outside the folder or below a symlinked sub-folder is never MatLoom's,
  whatever an index or an old manifest says: it is never read, adopted, written or deleted
  (deletes walk the folders with ``O_NOFOLLOW``), and the index and lock file are never
  followed through a symlink.
* **Staging.** A :meth:`OutputFolder.batch` is written into a hidden staging folder inside the
  output folder (same file system, so every install is a rename) and installed only when the
  whole batch was written. Install order makes an interrupted install look incomplete: the
  index is first rewritten as a journal (old and new hashes both accepted), the batch's
  *completion marker* (``material.json`` for a render) is removed first and installed last,
  and MatLoom's own files of the previous batch that the new one does not contain are removed.
* **Locking.** The folder is locked (``flock`` on ``.matloom.lock``) for as long as it is open,
  so a second writer fails at once with a clear message instead of mixing outputs. The lock
  file is removed on close.
* **Cleanup.** Staging folders and temporary files left by killed runs are removed when the
  folder is next opened (they are recognisable by name and, for staging folders, by a marker
  file inside).
"""

from __future__ import annotations

import errno
import hashlib
import json
import os
import re
import shutil
import uuid
from collections.abc import Callable, Iterable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from matloom.io.atomic import atomic_write_bytes
from matloom.io.reading import read_json_file

#: The ownership index (and install journal) kept in every output folder.
INDEX_NAME = ".matloom-files.json"
#: The lock file held while a MatLoom process writes the folder.
LOCK_NAME = ".matloom.lock"
#: Prefix of staging folders; each holds a :data:`STAGING_MARKER` file.
STAGING_PREFIX = ".matloom-staging-"
STAGING_MARKER = ".matloom-staging"
INDEX_FORMAT = ("matloom-files", 1)
#: Temporary names written by :mod:`matloom.io.atomic` (``.<name>.tmp-<12 hex>``).
_TEMP_FILE = re.compile(r"^\.(?P<name>.+)\.(?:tmp|old)-[0-9a-f]{12}$")
#: Files an older MatLoom (no index) wrote, recognised by their manifest or run record.
_LEGACY_RENDER = ("material.json", "material.mat", "preview.png", "height16.png")
_LEGACY_RUN = ("record.json", "material.mat", "preview.png")
_HASH_CHUNK = 1 << 20


class OutputError(Exception):
    """An output folder cannot be written safely; the message is one line for the user."""


@dataclass
class _Entry:
    sha256: str
    size: int
    mtime_ns: int
    group: str | None
    pending: str | None = None

    def as_json(self) -> dict[str, Any]:
        data: dict[str, Any] = {
            "sha256": self.sha256,
            "size": self.size,
            "mtime_ns": self.mtime_ns,
            "group": self.group,
        }
        if self.pending:
            data["pending"] = self.pending
        return data


def file_sha256(path: Path) -> str:
    digest = hashlib.sha256()
    with open(path, "rb") as handle:
        while chunk := handle.read(_HASH_CHUNK):
            digest.update(chunk)
    return digest.hexdigest()


def describe_os_error(err: OSError, path: Path | str) -> str:
    """A one-line description of ``err`` for the user (no traceback)."""
    reason = err.strerror or str(err)
    if err.errno == errno.ENOSPC:
        reason = "no space left on device"
    elif err.errno in (errno.EACCES, errno.EPERM, errno.EROFS):
        reason = "permission denied" if err.errno != errno.EROFS else "read-only file system"
    where = err.filename or path
    return f"cannot write {where}: {reason}"


class OutputFolder:
    """A locked output folder; use as a context manager (see the module docstring)."""

    def __init__(self, path: str | os.PathLike[str]) -> None:
        self.path = Path(path).absolute()
        self._lock_fd: int | None = None
        self._index: dict[str, _Entry] = {}

    # ---------------------------------------------------------------- open / close

    def __enter__(self) -> OutputFolder:
        self.open()
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def open(self) -> None:
        if self.path.exists() and not self.path.is_dir():
            raise OutputError(f"{self.path} exists and is not a folder; choose a folder for -o")
        try:
            self.path.mkdir(parents=True, exist_ok=True)
            self._lock()
        except OSError as err:
            raise OutputError(describe_os_error(err, self.path)) from None
        try:
            self._index = self._read_index()
            if not self._index:
                self._adopt_legacy()
            self._clean_stale()
        except BaseException:
            self.close()
            raise

    def close(self) -> None:
        if self._lock_fd is None:
            return
        try:
            os.unlink(self.path / LOCK_NAME)
        except OSError:
            pass
        os.close(self._lock_fd)
        self._lock_fd = None

    def _lock(self) -> None:
        import fcntl

        lock_path = self.path / LOCK_NAME
        while True:
            # O_NOFOLLOW: a symlinked lock file must not create or open a file elsewhere
            try:
                fd = os.open(lock_path, os.O_RDWR | os.O_CREAT | os.O_NOFOLLOW, 0o666)
            except OSError as err:
                if err.errno != errno.ELOOP:
                    raise
                raise OutputError(
                    f"{lock_path} is a symlink; MatLoom never follows one out of its output "
                    "folder: remove it or choose another -o"
                ) from None
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except BlockingIOError:
                os.close(fd)
                raise OutputError(
                    f"{self.path} is being written by another MatLoom process; "
                    "wait for it to finish or choose another -o"
                ) from None
            # The previous holder may have unlinked the lock file between our open and flock:
            # only a lock on the file that is still at the path counts.
            try:
                same = os.fstat(fd).st_ino == os.stat(lock_path).st_ino
            except FileNotFoundError:
                same = False
            if same:
                self._lock_fd = fd
                return
            os.close(fd)

    # ---------------------------------------------------------------- ownership

    def _read_index(self) -> dict[str, _Entry]:
        data = _read_json(self.path / INDEX_NAME)  # never a symlink: nothing read from elsewhere
        if data is None:
            return {}
        try:
            files = data["files"] if data.get("format") == INDEX_FORMAT[0] else {}
            return {
                str(rel): _Entry(
                    str(e["sha256"]),
                    int(e["size"]),
                    int(e["mtime_ns"]),
                    e.get("group"),
                    e.get("pending"),
                )
                for rel, e in files.items()
                if self._contained(str(rel))
            }
        except (ValueError, KeyError, TypeError, AttributeError):
            return {}  # an unreadable index owns nothing: every file is treated as foreign

    def _adopt_legacy(self) -> None:
        """Index the files an older MatLoom wrote here (before the index existed)."""
        for rel, group in sorted(self._legacy_owned().items()):
            target = self.path / rel
            if self._contained(rel) and target.is_file() and not target.is_symlink():
                self._record(rel, group)
        if self._index:
            self._save_index()

    def _legacy_owned(self) -> dict[str, str | None]:
        """Files an older MatLoom wrote here, with their group, recognised by their manifest."""
        owned: dict[str, str | None] = {}
        record = self._read_json_inside("record.json")
        if isinstance(record, dict) and "prompt" in record and "programs" in record:
            owned.update(dict.fromkeys(_LEGACY_RUN))
            renders = self.path / "renders"
            if self._contained("renders/x") and renders.is_dir():
                owned.update(dict.fromkeys(f"renders/{p.name}" for p in renders.glob("p*.png")))
        for prefix, group in (("", "render"), ("maps/", "maps")):
            manifest = self._read_json_inside(prefix + "material.json")
            if not (isinstance(manifest, dict) and manifest.get("format") == "matloom-material"):
                continue
            names = set(_LEGACY_RENDER) if group == "render" else {"material.json", "height16.png"}
            for entry in manifest.get("maps") or []:
                if isinstance(entry, dict) and isinstance(entry.get("file"), str):
                    names.add(entry["file"])
            owned.update({prefix + n: group for n in names if prefix + n not in owned})
        return owned

    def _blocking_parent(self, rel: str) -> str | None:
        """The outermost parent folder of ``rel`` that is a symlink or not a folder, if any."""
        blocking = None
        parent = (self.path / rel).parent
        while parent != self.path:  # ends at the outermost one, the one to name to the user
            if parent.is_symlink() or (parent.exists() and not parent.is_dir()):
                blocking = str(parent.relative_to(self.path))
            parent = parent.parent
        return blocking

    def _contained(self, rel: str) -> bool:
        """True when ``rel`` names a path inside the folder reached through real folders only.

        A parent that is a symlink could lead anywhere (the user's documents): such a path is
        never read, adopted, written or deleted.
        """
        return _is_safe_relative(rel) and self._blocking_parent(rel) is None

    def _read_json_inside(self, rel: str) -> Any:
        """``rel`` parsed as JSON, or None when unreadable or not inside the folder."""
        return _read_json(self.path / rel) if self._contained(rel) else None

    def owns(self, rel: str) -> bool:
        """True when ``rel`` is absent or is a regular file MatLoom wrote and nobody changed.

        A path outside the folder or below a symlinked parent is never MatLoom's.
        """
        if not self._contained(rel):
            return False
        target = self.path / rel
        if not os.path.lexists(target):
            return True
        if target.is_symlink() or not target.is_file():
            return False
        entry = self._index.get(rel)
        if entry is None:
            return False
        stat = target.stat()
        if stat.st_size == entry.size and stat.st_mtime_ns == entry.mtime_ns:
            return True
        digest = file_sha256(target)
        return digest in (entry.sha256, entry.pending)

    def check_writable(self, names: Iterable[str]) -> None:
        """Raise :class:`OutputError` if writing ``names`` would replace a foreign file."""
        foreign: list[str] = []
        for rel in sorted(names):
            blocking = self._blocking_parent(rel) if _is_safe_relative(rel) else rel
            if blocking is not None:
                if blocking not in foreign:
                    foreign.append(blocking)
            elif not self.owns(rel):
                foreign.append(rel)
        if foreign:
            shown = ", ".join(foreign[:3]) + (
                f" and {len(foreign) - 3} more" if len(foreign) > 3 else ""
            )
            raise OutputError(
                f"{self.path} already holds {shown}, not written by MatLoom (or changed since); "
                "MatLoom never overwrites such files: move them or choose another -o"
            )

    def _record(self, rel: str, group: str | None, digest: str | None = None) -> None:
        stat = (self.path / rel).stat()
        sha = digest or file_sha256(self.path / rel)
        self._index[rel] = _Entry(sha, stat.st_size, stat.st_mtime_ns, group)

    def _save_index(self) -> None:
        data = {
            "format": INDEX_FORMAT[0],
            "format_version": INDEX_FORMAT[1],
            "note": "files MatLoom wrote in this folder; others are never overwritten or deleted",
            "files": {rel: e.as_json() for rel, e in sorted(self._index.items())},
        }
        atomic_write_bytes(self.path / INDEX_NAME, (json.dumps(data, indent=1) + "\n").encode())

    # ---------------------------------------------------------------- cleanup

    def _clean_stale(self) -> None:
        """Remove staging folders and temporary files that killed runs left behind."""
        for child in self.path.iterdir():
            name = child.name
            if name.startswith(STAGING_PREFIX) and child.is_dir() and not child.is_symlink():
                if (child / STAGING_MARKER).is_file():
                    shutil.rmtree(child, ignore_errors=True)
                continue
            match = _TEMP_FILE.match(name)
            if match and child.is_file() and not child.is_symlink():
                # a file MatLoom wrote, or its own index (killed while saving it)
                if match["name"] in self._index or match["name"] == INDEX_NAME:
                    child.unlink(missing_ok=True)
        # the sibling staging folders (".<name>.tmp-…") of MatLoom before 0.4: only this
        # folder's own (".out.x.tmp-…" belongs to a folder "out.x", not to "out")
        for sibling in self.path.parent.glob(f".{self.path.name}.*-*"):
            match = _TEMP_FILE.match(sibling.name)
            if match is None or match["name"] != self.path.name:
                continue
            if sibling.is_dir() and not sibling.is_symlink():
                if _looks_like_old_staging(sibling):
                    shutil.rmtree(sibling, ignore_errors=True)

    def remove_owned(self) -> list[str]:
        """Delete every file MatLoom wrote here that nobody changed since; return their names.

        Foreign and changed files stay. Used to start a run afresh in a folder of a previous run.
        """
        removed = []
        for rel in sorted(self._index):
            target = self.path / rel
            if os.path.lexists(target) and self.owns(rel) and self._unlink_inside(rel):
                _remove_empty_parents(target, self.path)
                removed.append(rel)
            if not os.path.lexists(target):
                self._index.pop(rel)
        self._save_index()
        return removed

    # ---------------------------------------------------------------- writing

    def write_bytes(self, rel: str, data: bytes, *, group: str | None = None) -> Path:
        """Write one file now (atomically), refusing to replace a foreign file."""
        _require_safe(rel)
        self.check_writable([rel])
        target = self.path / rel
        try:
            target.parent.mkdir(parents=True, exist_ok=True)
            atomic_write_bytes(target, data)
            self._record(rel, group, hashlib.sha256(data).hexdigest())
            self._save_index()
        except OSError as err:
            raise OutputError(describe_os_error(err, target)) from None
        return target

    @contextmanager
    def batch(self, group: str, *, marker: str | None = None) -> Iterator[Path]:
        """Yield a staging folder; on success its files are installed as group ``group``.

        Files of ``group`` from a previous batch that this batch does not write are removed
        (they are MatLoom's own); ``marker`` (relative name) is removed first and installed
        last, so a folder without it is one whose install did not finish.
        """
        staging = self.path / f"{STAGING_PREFIX}{os.getpid()}-{uuid.uuid4().hex[:8]}"
        try:
            staging.mkdir()
            (staging / STAGING_MARKER).write_bytes(b"")
        except OSError as err:
            raise OutputError(describe_os_error(err, self.path)) from None
        try:
            yield staging
            self._install(staging, group, marker)
        except OSError as err:
            raise OutputError(describe_os_error(err, self.path)) from None
        finally:
            shutil.rmtree(staging, ignore_errors=True)

    def _install(self, staging: Path, group: str, marker: str | None) -> None:
        staged = sorted(
            p.relative_to(staging).as_posix()
            for p in staging.rglob("*")
            if p.is_file() and p.name != STAGING_MARKER
        )
        self.check_writable(staged)
        digests = {rel: file_sha256(staging / rel) for rel in staged}
        old = {rel for rel, e in self._index.items() if e.group == group}
        # 1. journal: every name that may appear during the install is owned whatever happens
        for rel, digest in digests.items():
            entry = self._index.get(rel)
            if entry is not None:
                entry.pending = digest
            else:
                self._index[rel] = _Entry(digest, -1, -1, group, digest)
        self._save_index()
        # 2. the completion marker goes first ...
        if marker is not None and os.path.lexists(self.path / marker) and self.owns(marker):
            self._unlink_inside(marker)
        for rel in staged:
            if rel != marker:
                self._move(staging, rel)
        for rel in sorted(old - set(staged)):
            if os.path.lexists(self.path / rel) and self.owns(rel) and self._unlink_inside(rel):
                _remove_empty_parents(self.path / rel, self.path)
            self._index.pop(rel, None)
        # 3. ... and comes back last
        if marker is not None and marker in digests:
            self._move(staging, marker)
        for rel, digest in digests.items():
            self._record(rel, group, digest)
        self._save_index()

    def _unlink_inside(self, rel: str) -> bool:
        """Delete the file ``rel``, reaching it through real folders only; False if refused.

        The walk opens each parent with ``O_NOFOLLOW`` relative to the one before, so a parent
        swapped for a symlink after :meth:`owns` looked cannot redirect the delete elsewhere.
        """
        parts = Path(rel).parts
        fd = os.open(self.path, os.O_RDONLY | os.O_DIRECTORY)
        try:
            for part in parts[:-1]:
                inner = os.open(part, os.O_RDONLY | os.O_DIRECTORY | os.O_NOFOLLOW, dir_fd=fd)
                os.close(fd)
                fd = inner
            os.unlink(parts[-1], dir_fd=fd)
        except OSError as err:
            if err.errno in (errno.ENOENT, errno.ELOOP, errno.ENOTDIR):
                return False
            raise
        finally:
            os.close(fd)
        return True

    def _move(self, staging: Path, rel: str) -> None:
        target = self.path / rel
        target.parent.mkdir(parents=True, exist_ok=True)
        os.replace(staging / rel, target)


def _remove_empty_parents(path: Path, root: Path) -> None:
    parent = path.parent
    while parent != root and root in parent.parents:
        try:
            parent.rmdir()
        except OSError:
            return
        parent = parent.parent


def _is_safe_relative(rel: str) -> bool:
    parts = Path(rel).parts
    return bool(parts) and not Path(rel).is_absolute() and ".." not in parts and "\0" not in rel


def _require_safe(rel: str) -> None:
    if not _is_safe_relative(rel):
        raise ValueError(f"output name must be relative to the folder: {rel!r}")


def _read_json(path: Path) -> Any:
    """``path`` parsed as JSON; None when absent, a symlink, not a regular file, over 50 MB
    or not JSON."""
    try:
        return read_json_file(path, 50_000_000)
    except (OSError, ValueError):
        return None


def _looks_like_old_staging(folder: Path) -> bool:
    """An old staging folder holds only the files a render writes (or nothing)."""
    allowed = re.compile(r"^(?:[a-z0-9_]+\.(?:png|exr|json|mat)|\..+\.tmp-[0-9a-f]{12})$")
    return all(p.is_file() and allowed.match(p.name) for p in folder.iterdir())


@contextmanager
def output_folder(path: str | os.PathLike[str]) -> Iterator[OutputFolder]:
    """Open ``path`` as an :class:`OutputFolder` (locked until the block ends)."""
    folder = OutputFolder(path)
    folder.open()
    try:
        yield folder
    finally:
        folder.close()


def write_output_file(
    path: str | os.PathLike[str], data: bytes, is_ours: Callable[[Path], bool]
) -> Path:
    """Write a single output file atomically, refusing to replace a file MatLoom did not write.

    ``is_ours(path)`` decides whether an existing file is MatLoom's (for PNGs: its ``Software``
    text chunk). Symlinks and folders are never replaced.
    """
    target = Path(path).absolute()
    if target.is_dir():
        raise OutputError(f"{target} is a folder; give a file name")
    if os.path.lexists(target) and (target.is_symlink() or not is_ours(target)):
        raise OutputError(
            f"{target} exists and was not written by MatLoom; MatLoom never overwrites such "
            "files: choose another name or remove it"
        )
    try:
        target.parent.mkdir(parents=True, exist_ok=True)
        atomic_write_bytes(target, data)
    except OSError as err:
        raise OutputError(describe_os_error(err, target)) from None
    return target


def save_output_png(path: str | os.PathLike[str], image: Any) -> Path:
    """Save a uint8 image as a standalone output PNG (see :func:`write_output_file`)."""
    import numpy as np

    from matloom.io.png import encode_png8, written_by_matloom

    array = np.asarray(image)
    if array.dtype != np.uint8:
        raise ValueError(f"PNG images must be uint8, got {array.dtype}")
    return write_output_file(path, encode_png8(array), written_by_matloom)
