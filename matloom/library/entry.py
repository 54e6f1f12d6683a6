"""Library entries: one ``.mat`` file each, a TOML front matter in comments, then the program.

The front matter is the block of ``#`` comment lines between two ``# ---`` lines at the top of
the file (see docs/library.md for every key). :func:`load_entry` reads and validates it; every
problem raises :class:`LibraryError` naming the file and the key. The program itself is only
parsed when the entry is used (``matloom library check`` and the tests check every one).
"""

from __future__ import annotations

import math
import re
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

CATEGORIES: tuple[str, ...] = (
    "wood",
    "stone",
    "tiles",
    "masonry",
    "metal",
    "fabric",
    "leather",
    "paper",
    "ground",
    "organic",
    "plastic",
    "glass",
    "ceramic",
    "concrete",
    "carpet",
    "scifi",
    "ornament",
    "natural",
)
SCALAR_KINDS = frozenset(
    {"roughness", "wear", "relief", "metallic", "gloss", "gap", "cover", "other"}
)
ROLE_KINDS = frozenset({"base", "grout", "accent", "frame", "material"})
FENCE = "# ---"
NAME_RE = re.compile(r"[a-z0-9]+(-[a-z0-9]+)*")

PresetValue = tuple[int, int, int] | float | str


class LibraryError(ValueError):
    """A library file is malformed; the message names the file and the key."""


@dataclass(frozen=True)
class Entry:
    """One material of the library: its metadata and its program text."""

    name: str
    path: Path
    description: str
    category: str
    tags: tuple[str, ...]
    synonyms: tuple[str, ...]
    size_m: float
    tileable: bool
    colours: tuple[str, ...]
    program: str
    scalars: dict[str, str] = field(default_factory=dict)
    roles: dict[str, str] = field(default_factory=dict)
    presets: dict[str, dict[str, PresetValue]] = field(default_factory=dict)
    preset_sets: tuple[str, ...] = ()
    feature_m: float | None = None
    units: tuple[str, ...] = ()
    absorbs: tuple[str, ...] = ()
    origin: tuple[float, float] | None = None
    note: str = ""

    def role(self, slot: str) -> str:
        """The role of a colour slot (``base`` unless the front matter says otherwise)."""
        return self.roles.get(slot, "base")


def split_front_matter(text: str, path: Path | str) -> tuple[dict[str, Any], str, str]:
    """(parsed front matter, program text, front matter TOML text) of a library file."""
    lines = text.splitlines()
    if not lines or lines[0].strip() != FENCE:
        raise LibraryError(f"{path}: the file must start with a '{FENCE}' front matter line")
    try:
        end = next(i for i in range(1, len(lines)) if lines[i].strip() == FENCE)
    except StopIteration:
        raise LibraryError(f"{path}: the front matter has no closing '{FENCE}' line") from None
    body = []
    for k, line in enumerate(lines[1:end], start=2):
        stripped = line.strip()
        if not stripped.startswith("#"):
            raise LibraryError(f"{path}:{k}: front matter lines must be '#' comments")
        body.append(stripped[2:] if stripped.startswith("# ") else stripped[1:])
    toml_text = "\n".join(body)
    try:
        data = tomllib.loads(toml_text)
    except tomllib.TOMLDecodeError as exc:
        raise LibraryError(f"{path}: front matter is not valid TOML: {exc}") from None
    program = "\n".join(lines[end + 1 :]).strip("\n") + "\n"
    return data, program, toml_text


class FrontMatterReader:
    """Typed access to front matter keys with errors naming the file and the key."""

    def __init__(self, data: dict[str, Any], path: Path | str) -> None:
        self.data = data
        self.path = path
        self.seen: set[str] = set()

    def fail(self, key: str, problem: str) -> LibraryError:
        return LibraryError(f"{self.path}: front matter key '{key}': {problem}")

    def get(self, key: str, default: Any = ..., *, required: bool = True) -> Any:
        self.seen.add(key)
        if key not in self.data:
            if default is ... and required:
                raise self.fail(key, "missing (required)")
            return None if default is ... else default
        return self.data[key]

    def text(self, key: str, default: str | None = None) -> str:
        value = self.get(key, ... if default is None else default)
        if not isinstance(value, str) or (default is None and not value.strip()):
            raise self.fail(key, f"expected a non-empty string, got {value!r}")
        return value.strip()

    def words(self, key: str, *, required: bool = False) -> tuple[str, ...]:
        value = self.get(key, ... if required else [])
        if not isinstance(value, list) or not all(isinstance(v, str) and v.strip() for v in value):
            raise self.fail(key, f"expected a list of non-empty strings, got {value!r}")
        return tuple(v.strip() for v in value)

    def number(self, key: str, *, required: bool = True) -> float | None:
        value = self.get(key, ... if required else None)
        if value is None and not required:
            return None
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise self.fail(key, f"expected a number, got {value!r}")
        if not (math.isfinite(value) and value > 0):
            raise self.fail(key, f"expected a finite number > 0, got {value!r}")
        return float(value)

    def flag(self, key: str) -> bool:
        value = self.get(key)
        if not isinstance(value, bool):
            raise self.fail(key, f"expected true or false, got {value!r}")
        return value

    def table(self, key: str) -> dict[str, Any]:
        value = self.get(key, {})
        if not isinstance(value, dict):
            raise self.fail(key, f"expected a table ([{key}]), got {value!r}")
        return value

    def finish(self) -> None:
        unknown = sorted(set(self.data) - self.seen)
        if unknown:
            raise self.fail(unknown[0], "unknown key (see docs/library.md)")


def preset_value(value: Any) -> PresetValue | None:
    """A preset value as stored: an RGB triple, a number or an expression text (else None)."""
    if isinstance(value, list) and len(value) == 3 and all(isinstance(v, int) for v in value):
        if all(0 <= v <= 255 for v in value):
            return (value[0], value[1], value[2])
        return None
    if isinstance(value, bool):
        return None
    if isinstance(value, (int, float)) and math.isfinite(value):
        return float(value)
    if isinstance(value, str) and value.strip():
        return value.strip()
    return None


def read_presets(table: dict[str, Any], fail: Any) -> dict[str, dict[str, PresetValue]]:
    """Validate a ``[presets]``-shaped table: word -> {Define slot -> value}."""
    out: dict[str, dict[str, PresetValue]] = {}
    for word, values in table.items():
        if not isinstance(values, dict) or not values:
            raise fail(f"presets.{word}", "expected a table of slot = value")
        parsed: dict[str, PresetValue] = {}
        for slot, value in values.items():
            v = preset_value(value)
            if v is None:
                raise fail(
                    f"presets.{word}.{slot}",
                    f"expected [r, g, b] (0-255), a number or an expression, got {value!r}",
                )
            parsed[slot] = v
        out[word.lower()] = parsed
    return out


def entry_from_text(text: str, path: Path | str, name: str | None = None) -> Entry:
    """Build and validate an :class:`Entry` from a file's text."""
    path = Path(path)
    data, program, _ = split_front_matter(text, path)
    r = FrontMatterReader(data, path)
    category = r.text("category")
    if category not in CATEGORIES:
        raise r.fail("category", f"{category!r} is not one of {', '.join(CATEGORIES)}")
    colours = r.words("colours", required=True)
    scalars = r.table("scalars")
    for key, kind in scalars.items():
        if kind not in SCALAR_KINDS:
            raise r.fail(f"scalars.{key}", f"kind {kind!r} is not one of {sorted(SCALAR_KINDS)}")
    roles = r.table("roles")
    for key, kind in roles.items():
        if key not in colours:
            raise r.fail(f"roles.{key}", "names no colour slot of 'colours'")
        if kind not in ROLE_KINDS:
            raise r.fail(f"roles.{key}", f"kind {kind!r} is not one of {sorted(ROLE_KINDS)}")
    presets = read_presets(r.table("presets"), r.fail)
    origin = r.get("origin", None, required=False)
    if origin is not None:
        if not (
            isinstance(origin, list)
            and len(origin) == 2
            and all(
                isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)
                for v in origin
            )
        ):
            raise r.fail("origin", f"expected [x, y] (two finite numbers), got {origin!r}")
        origin = (float(origin[0]), float(origin[1]))
    entry = Entry(
        name=name or path.stem,
        path=path,
        description=r.text("description"),
        category=category,
        tags=r.words("tags", required=True),
        synonyms=r.words("synonyms"),
        size_m=r.number("size_m") or 1.0,
        tileable=r.flag("tileable"),
        colours=colours,
        program=program,
        scalars=dict(scalars),
        roles=dict(roles),
        presets=presets,
        preset_sets=r.words("preset_sets"),
        feature_m=r.number("feature_m", required=False),
        units=r.words("units"),
        absorbs=r.words("absorbs"),
        origin=origin,
        note=r.text("note", ""),
    )
    if not NAME_RE.fullmatch(entry.name):
        raise LibraryError(f"{path}: the file name must be lowercase words joined by '-'")
    r.finish()
    if not program.strip():
        raise LibraryError(f"{path}: no program after the front matter")
    return entry


def load_entry(path: Path | str) -> Entry:
    """Read and validate one entry file."""
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise LibraryError(f"{path}: cannot read: {exc}") from None
    return entry_from_text(text, path)
