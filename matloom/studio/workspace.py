"""The folder the studio works in: the only place it reads programs from and writes to.

``matloom studio FILE`` works in FILE's folder with FILE opened; ``matloom studio FOLDER`` in
FOLDER (its first program opened); with no argument in ``./matloom-studio/``, made on first use
with a copy of the demo material (:func:`demo_workspace`), so saving never writes inside the
installed package.

Every path the browser names is relative to the root (``/``-separated). :meth:`Workspace.path`
refuses an absolute path, one that climbs out (``..``), and one that resolves outside the root
through a symlink; programs are ``*.mat`` files only. Saves are atomic
(:mod:`matloom.io.atomic`): a reader sees the old file or the whole new one.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path, PurePosixPath

from matloom.io.atomic import atomic_write_bytes, rewrite_file
from matloom.studio.protocol import MAX_BODY, ApiError

#: The suffix of program files.
PROGRAM_SUFFIX = ".mat"
#: The folder ``matloom studio`` makes (and reuses) when given no argument.
DEMO_FOLDER = "matloom-studio"
#: The example copied into it.
DEMO_EXAMPLE = "black_ceramic_tiles"
#: Listing bounds: folders deeper than this and programs past this count are not listed.
LIST_DEPTH = 4
LIST_MAX = 500
#: The longest path and file name most file systems take (Linux's PATH_MAX and NAME_MAX).
PATH_MAX = 4096
NAME_MAX = 255
#: The most folders deep a path the browser names may go.
PATH_DEPTH = 32


class WorkspaceError(ValueError):
    """The studio cannot open what it was given; one line for the user."""


@dataclass(frozen=True)
class Workspace:
    """The root folder (absolute, symlinks resolved) and the program opened in it (relative
    path) or None."""

    root: Path
    opened: str | None = None

    # ----------------------------------------------------------------------- opening
    @classmethod
    def open(cls, target: str | os.PathLike[str] | None) -> Workspace:
        """The workspace of a ``matloom studio`` argument (see the module docstring)."""
        if target is None:
            return demo_workspace(Path.cwd())
        path = Path(target)
        if path.is_dir():
            root = path.resolve()
            files = cls(root).programs()
            return cls(root, files[0] if files else None)
        if not path.exists():
            raise WorkspaceError(f"{target}: no such file or folder")
        if path.suffix != PROGRAM_SUFFIX:
            raise WorkspaceError(f"{target} is not a program file (*{PROGRAM_SUFFIX})")
        real = path.resolve()  # a link to a program elsewhere: work in that program's folder
        return cls(real.parent, real.name)

    # ----------------------------------------------------------------------- paths
    def path(self, rel: str, *, program: bool = True) -> Path:
        """The absolute path of ``rel`` inside the root; 400 for a path outside it (absolute,
        climbing out, through a symlink leaving it) or, with ``program``, not a ``.mat``."""
        if not isinstance(rel, str) or not rel.strip() or "\0" in rel:
            raise ApiError(400, "give a path relative to the workspace")
        pure = PurePosixPath(rel.replace("\\", "/"))
        if pure.is_absolute() or ".." in pure.parts or (pure.parts and ":" in pure.parts[0]):
            raise ApiError(400, f"{rel!r} is outside the workspace; give a relative path in it")
        if program and pure.suffix != PROGRAM_SUFFIX:
            raise ApiError(400, f"{rel!r} is not a program file (*{PROGRAM_SUFFIX})")
        target = self.root.joinpath(*pure.parts)
        if (
            len(pure.parts) > PATH_DEPTH
            or len(os.fsencode(target)) >= PATH_MAX
            or any(len(os.fsencode(part)) > NAME_MAX for part in pure.parts)
        ):
            raise ApiError(400, f"{rel[:60]!r}... is too long (or deep) a path")
        if not _inside(os.path.realpath(target), self.root):
            raise ApiError(400, f"{rel!r} leads outside the workspace (a symlink); refused")
        return target

    def rel(self, path: Path) -> str:
        return path.relative_to(self.root).as_posix()

    # ----------------------------------------------------------------------- programs
    def programs(self) -> list[str]:
        """The ``*.mat`` files under the root (sorted; hidden folders and links leaving the
        root skipped; at most :data:`LIST_MAX`, :data:`LIST_DEPTH` folders deep)."""
        found: list[str] = []
        for folder, dirs, files in os.walk(self.root, followlinks=False):
            depth = len(Path(folder).relative_to(self.root).parts)
            dirs[:] = sorted(d for d in dirs if not d.startswith(".") and depth < LIST_DEPTH)
            for name in sorted(files):
                if name.endswith(PROGRAM_SUFFIX) and not name.startswith("."):
                    full = Path(folder) / name
                    if _inside(os.path.realpath(full), self.root) and os.path.isfile(full):
                        found.append(self.rel(full))
                        if len(found) >= LIST_MAX:
                            return sorted(found)
        return sorted(found)

    def read(self, rel: str) -> str:
        """The text of the program ``rel``; 404 when missing, 400 when unreadable."""
        target = self.path(rel)
        try:
            if target.stat().st_size > MAX_BODY:
                raise ApiError(400, f"{rel} is over {MAX_BODY:,} bytes: not a program")
            return target.read_text(encoding="utf-8")
        except FileNotFoundError:
            raise ApiError(404, f"{rel}: no such program in the workspace") from None
        except IsADirectoryError:
            raise ApiError(400, f"{rel} is a folder") from None
        except UnicodeDecodeError:
            raise ApiError(400, f"{rel} is not UTF-8 text") from None
        except OSError as err:
            raise ApiError(400, f"cannot read {rel}: {err.strerror or err}") from None

    def save(self, rel: str, text: str) -> int:
        """Write ``text`` (ending in one newline) to the program ``rel`` atomically; its
        folder must exist. Returns the bytes written."""
        target = self.path(rel)
        if not target.parent.is_dir():
            raise ApiError(400, f"{self.rel(target.parent)}: no such folder in the workspace")
        if target.is_dir():
            raise ApiError(400, f"{rel} is a folder")
        data = (text.rstrip("\n") + "\n").encode("utf-8")
        try:
            if target.exists():
                rewrite_file(target, data)  # keeps its permissions (and an in-root symlink)
            else:
                atomic_write_bytes(target, data)
        except OSError as err:
            raise ApiError(400, f"cannot write {rel}: {err.strerror or err}") from None
        return len(data)

    def folder(self, rel: str) -> Path:
        """An output folder ``rel`` inside the root (not the root itself); it may not exist
        yet. Its ownership rules are :class:`~matloom.io.outdir.OutputFolder`'s."""
        target = self.path(rel, program=False)
        if target == self.root:
            raise ApiError(400, "name a folder inside the workspace for the export")
        if target.exists() and not target.is_dir():
            raise ApiError(400, f"{rel} is a file, not a folder")
        return target


def _inside(real: str | os.PathLike[str], root: Path) -> bool:
    real_path = Path(real)
    return real_path == root or root in real_path.parents


def demo_workspace(parent: Path) -> Workspace:
    """``parent/matloom-studio/`` with the demo program in it (copied when missing; an
    existing copy, perhaps edited, is kept)."""
    from matloom.examples import example_text

    root = parent / DEMO_FOLDER
    name = f"{DEMO_EXAMPLE}{PROGRAM_SUFFIX}"
    try:
        root.mkdir(exist_ok=True)
        if not (root / name).exists():
            atomic_write_bytes(root / name, example_text(DEMO_EXAMPLE).encode("utf-8"))
    except OSError as err:
        raise WorkspaceError(
            f"cannot make the demo workspace {root}: {err.strerror or err}; "
            "give a FILE or FOLDER to work in"
        ) from None
    return Workspace(root.resolve(), name)
