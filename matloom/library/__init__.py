"""The material library: programs as data, retrieved and adapted to a request.

``matloom/library/entries/<category>/<name>.mat`` holds one material per file: an ordinary
MatLoom program with a TOML front matter in comments (description, tags, synonyms, category,
physical size, tileability and named slots). :func:`author` picks the entry that best matches
a prompt (BM25 over descriptions, tags and synonyms), adapts its slots (colours, presets,
finish, scale), composes overlays ("mossy", "rusty", "wet" ...) and explains what it did.
See docs/library.md.
"""

from __future__ import annotations

from matloom.library.author import LibraryResult, author, search
from matloom.library.entry import CATEGORIES, Entry, LibraryError, load_entry
from matloom.library.index import Library, library, load_library
from matloom.library.retrieval import Candidate

__all__ = [
    "CATEGORIES",
    "Candidate",
    "Entry",
    "Library",
    "LibraryError",
    "LibraryResult",
    "author",
    "library",
    "load_entry",
    "load_library",
    "search",
]
