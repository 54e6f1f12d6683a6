"""The loaded library: every entry and overlay, by name, read once per process.

:func:`library` returns the cached :class:`Library` of the installed entries
(``matloom/library/entries/<category>/<name>.mat``) and overlays
(``matloom/library/overlays/<name>.mat``); :func:`load_library` reads any other folder (tests).
Only front matter is read at load time; programs are parsed when an entry is used.
"""

from __future__ import annotations

import functools
from collections import Counter
from dataclasses import dataclass, field
from pathlib import Path

from matloom.lang import ast as A
from matloom.lang.api import parse
from matloom.library.data import words
from matloom.library.entry import CATEGORIES, Entry, LibraryError, PresetValue, load_entry
from matloom.library.overlay import OVERLAY_DIR, Overlay, load_overlay
from matloom.library.retrieval import Index

ENTRY_DIR = Path(__file__).resolve().parent / "entries"
#: :meth:`Library.source` of the installed entries
BUILTIN = "built-in"


@dataclass
class Library:
    """Entries and overlays by name, with their parsed programs cached on demand."""

    entries: dict[str, Entry]
    overlays: dict[str, Overlay]
    _asts: dict[str, A.Program] = field(default_factory=dict, repr=False)
    #: entry name -> the user library folder it came from (built-in entries are not listed;
    #: :mod:`matloom.library.user`)
    sources: dict[str, str] = field(default_factory=dict)
    #: entry name -> the file of the entry it replaced (a built-in or an earlier folder's)
    replaced: dict[str, str] = field(default_factory=dict)
    #: what a user library folder held that was not read, one line each (symlinks out of it)
    skipped: tuple[str, ...] = ()

    def source(self, name: str) -> str:
        """Where entry ``name`` came from: ``built-in`` or its user library folder."""
        return self.sources.get(name, BUILTIN)

    def entry(self, name: str) -> Entry:
        """The entry called ``name``; KeyError naming close matches when there is none."""
        try:
            return self.entries[name]
        except KeyError:
            close = [n for n in self.entries if name in n or n in name][:5]
            hint = f" (did you mean {', '.join(close)}?)" if close else ""
            raise KeyError(f"no library entry {name!r}{hint}") from None

    def ast(self, name: str) -> A.Program:
        """The parsed program of entry ``name`` (cached)."""
        if name not in self._asts:
            self._asts[name] = parse(self.entry(name).program)
        return self._asts[name]

    def by_category(self, category: str | None = None) -> list[Entry]:
        """Entries (of one category, or all) sorted by category then name."""
        out = [e for e in self.entries.values() if category is None or e.category == category]
        return sorted(out, key=lambda e: (CATEGORIES.index(e.category), e.name))

    def counts(self) -> Counter[str]:
        """Number of entries per category."""
        return Counter(e.category for e in self.entries.values())

    def presets(self, entry: Entry, sets: dict[str, dict[str, dict[str, PresetValue]]]) -> dict:
        """Every word preset the entry takes: its shared sets, then its own (which win)."""
        out: dict[str, dict[str, PresetValue]] = {}
        for name in entry.preset_sets:
            if name not in sets:
                raise LibraryError(f"{entry.path}: front matter key 'preset_sets': no set {name!r}")
            out.update(sets[name])
        out.update(entry.presets)
        return out

    @functools.cached_property
    def triggers(self) -> dict[str, str]:
        """Overlay word or phrase -> overlay name (the overlays' triggers, then the extra overlay
        words of ``data/words.toml``)."""
        out: dict[str, str] = {}
        for ov in sorted(self.overlays.values(), key=lambda o: o.name):
            for t in (*ov.triggers, *ov.weak):
                out.setdefault(t, ov.name)
        for t, name in sorted(words().overlay_words.items()):
            if name in self.overlays:
                out.setdefault(t, name)
        return out

    @functools.cached_property
    def index(self) -> Index:
        """The BM25 index of the entries (built on first use)."""
        w = words()
        presets = {
            e.name: list(self.presets(e, w.preset_sets))
            for e in self.entries.values()
            if e.preset_sets or e.presets
        }
        return Index(self.entries.values(), presets, w)

    @functools.cached_property
    def weak_triggers(self) -> set[str]:
        """Overlay words that count only in the prompt's head clause ("old")."""
        return {t for ov in self.overlays.values() for t in ov.weak}


def load_library(
    entry_dir: Path | str = ENTRY_DIR, overlay_dir: Path | str = OVERLAY_DIR
) -> Library:
    """Read every entry and overlay; raise :class:`LibraryError` on the first bad file or on
    two entries with the same name."""
    entries: dict[str, Entry] = {}
    for path in sorted(Path(entry_dir).glob("*/*.mat")):
        entry = load_entry(path)
        if entry.name in entries:
            raise LibraryError(
                f"{path}: entry name {entry.name!r} is also {entries[entry.name].path}"
            )
        if path.parent.name != entry.category:
            raise LibraryError(
                f"{path}: front matter key 'category': {entry.category!r} but the file is in "
                f"{path.parent.name}/"
            )
        entries[entry.name] = entry
    overlays = {p.stem: load_overlay(p) for p in sorted(Path(overlay_dir).glob("*.mat"))}
    for entry in entries.values():
        for name in entry.absorbs:
            if name not in overlays:
                raise LibraryError(f"{entry.path}: front matter key 'absorbs': no overlay {name!r}")
    return Library(entries, overlays)


@functools.cache
def library() -> Library:
    """The installed library (read once per process)."""
    return load_library()
