"""User libraries: a studio's own entries, ranked with the built-in ones (docs/library.md).

A user library is a folder of entries: ``.mat`` files with the front matter of the built-in
ones, either flat (``DIR/<name>.mat``) or in category folders (``DIR/<category>/<name>.mat``,
the folder named after the front matter's ``category``). Only those two levels are read:
other folders, hidden files and other suffixes are left alone, and a file or folder that is a
symlink leading out of ``DIR`` is not followed (it is listed in :attr:`Library.skipped`).

:func:`library_for` is the built-in library with the entries of each folder added in order, in
one index: an entry replaces the built-in entry, or an earlier folder's, of the same name
(:attr:`Library.replaced`). The folders are given explicitly: the command line reads
``MATLOOM_LIBRARY_PATH`` (:func:`library_dirs`) and passes them down; nothing here reads the
environment. Loaded libraries are cached by their folders and the names, sizes and times of
the files read, so an entry added or edited since is read again.
"""

from __future__ import annotations

import functools
import os
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path

from matloom.lang import ast as A
from matloom.lang.api import analyse
from matloom.library.data import words
from matloom.library.entry import CATEGORIES, Entry, LibraryError, entry_from_text
from matloom.library.index import Library, library

#: The environment variable the command line reads: folders separated by ``os.pathsep``.
ENV = "MATLOOM_LIBRARY_PATH"
#: The largest entry file read (the parser's program size limit plus a front matter).
MAX_ENTRY_BYTES = 2_100_000


def split_path(value: str | None) -> tuple[str, ...]:
    """The folders of a ``MATLOOM_LIBRARY_PATH`` value (empty parts dropped)."""
    return tuple(part for part in (value or "").split(os.pathsep) if part.strip())


def library_dirs(
    given: Iterable[str | os.PathLike[str]] = (),
    env: str | None = None,
    *,
    missing_ok: bool = False,
) -> tuple[Path, ...]:
    """The user library folders, resolved, in precedence order (a later one wins): those of
    the ``MATLOOM_LIBRARY_PATH`` value ``env``, then those ``given`` (``--library``). A folder
    named twice keeps its last place. :class:`LibraryError` for one that is not a folder (one
    that does not exist is left out with ``missing_ok``: ``library add`` creates it)."""
    out: list[Path] = []
    for raw in (*split_path(env), *given):
        path = Path(raw).expanduser()
        if missing_ok and not path.exists():
            continue
        if not path.is_dir():
            why = "does not exist" if not path.exists() else "is not a folder"
            raise LibraryError(f"library folder {raw} {why}")
        resolved = path.resolve()
        if resolved in out:
            out.remove(resolved)
        out.append(resolved)
    return tuple(out)


@dataclass(frozen=True)
class _Listing:
    """The entry files of one folder (with what makes them change) and what was skipped."""

    root: Path
    files: tuple[tuple[Path, int, int], ...]
    skipped: tuple[str, ...]


def _inside(path: Path, root: Path) -> bool:
    try:
        return path.resolve().is_relative_to(root)
    except (OSError, RuntimeError):  # a symlink loop
        return False


def _entry_files(root: Path) -> tuple[list[Path], list[str]]:
    """``root/*.mat`` and ``root/<category>/*.mat`` (sorted), and the symlinks out skipped."""
    found: list[Path] = []
    skipped: list[str] = []

    def visible(folder: Path) -> list[Path]:
        try:
            return sorted(p for p in folder.iterdir() if not p.name.startswith("."))
        except OSError as exc:
            raise LibraryError(f"{folder}: cannot list: {exc.strerror or exc}") from None

    def take(path: Path) -> None:
        if not _inside(path, root):
            skipped.append(f"{path}: a symlink leading out of {root}; not followed")
        elif path.is_file():
            found.append(path)

    for item in visible(root):
        if item.suffix == ".mat":
            take(item)
        elif item.name in CATEGORIES and item.is_dir():
            if not _inside(item, root):
                skipped.append(f"{item}: a symlink leading out of {root}; not followed")
                continue
            for sub in visible(item):
                if sub.suffix == ".mat":
                    take(sub)
    return found, skipped


def _listing(root: Path) -> _Listing:
    files, skipped = _entry_files(root)
    stamped = []
    for path in files:
        st = path.stat()
        stamped.append((path, st.st_mtime_ns, st.st_size))
    return _Listing(root, tuple(stamped), tuple(skipped))


def read_entry(path: Path, root: Path) -> tuple[Entry, A.Program]:
    """One user entry and its parsed program, validated like a built-in one, its program
    checked (no errors) and its preset sets and overlays known; :class:`LibraryError` in one
    line naming the file."""
    from matloom.io.reading import read_regular_bytes

    try:
        text = read_regular_bytes(path.resolve(), MAX_ENTRY_BYTES).decode("utf-8")
    except UnicodeDecodeError:
        raise LibraryError(f"{path}: cannot read: not UTF-8 text") from None
    except OSError as exc:
        raise LibraryError(f"{path}: cannot read: {exc.strerror or exc}") from None
    entry = entry_from_text(text, path)
    if path.parent != root and path.parent.name != entry.category:
        raise LibraryError(
            f"{path}: front matter key 'category': {entry.category!r} but the file is in "
            f"{path.parent.name}/"
        )
    sets = words().preset_sets
    for name in entry.preset_sets:
        if name not in sets:
            raise LibraryError(f"{path}: front matter key 'preset_sets': no set {name!r}")
    program, diags = analyse(text)  # the front matter is comments: lines count from the top
    errors = [d for d in diags if d.is_error]
    if program is None or errors:
        d = errors[0]
        more = f" (and {len(errors) - 1} more)" if len(errors) > 1 else ""
        raise LibraryError(f"{path}:{d.line}:{d.column}: error {d.code}: {d.message}{more}")
    return entry, program


@functools.lru_cache(maxsize=8)
def _combined(listings: tuple[_Listing, ...]) -> Library:
    base = library()
    entries = dict(base.entries)
    sources: dict[str, str] = {}
    replaced: dict[str, str] = {}
    skipped: list[str] = []
    asts: dict[str, A.Program] = {}
    for listing in listings:
        seen: dict[str, Path] = {}
        for path, _, _ in listing.files:
            entry, program = read_entry(path, listing.root)
            if entry.name in seen:
                raise LibraryError(f"{path}: entry name {entry.name!r} is also {seen[entry.name]}")
            for name in entry.absorbs:
                if name not in base.overlays:
                    raise LibraryError(f"{path}: front matter key 'absorbs': no overlay {name!r}")
            seen[entry.name] = path
            if entry.name in entries:
                replaced[entry.name] = str(entries[entry.name].path)
            entries[entry.name] = entry
            asts[entry.name] = program
            sources[entry.name] = str(listing.root)
        skipped += listing.skipped
    lib = Library(
        entries, base.overlays, sources=sources, replaced=replaced, skipped=tuple(skipped)
    )
    lib._asts.update(asts)
    return lib


def library_for(dirs: Sequence[str | os.PathLike[str]] = ()) -> Library:
    """The built-in library with the entries of the user library folders ``dirs`` (resolved
    folders in precedence order, as :func:`library_dirs` returns them) added; the built-in
    library itself when there are none. :class:`LibraryError` (one line, naming the file) for
    a bad entry."""
    if not dirs:
        return library()
    roots = library_dirs(dirs)
    return _combined(tuple(_listing(root) for root in roots))


def user_entries(lib: Library) -> list[Entry]:
    """The entries that came from user library folders, by folder then name."""
    names = sorted(lib.sources, key=lambda n: (lib.sources[n], n))
    return [lib.entries[n] for n in names]
