"""Named materials (``library/data/materials/*.toml``): a material a request names, with the
base of its physical class, its typical colours and finish, and optionally the layout and motif
it is made of ("malachite": a green banded mineral, "obsidian": black glossy glass, "vinyl
siding": white plastic in horizontal rows).

:func:`named_material` finds one by its name or an alias (case, hyphens, underscores and
apostrophes do not matter); :func:`named_materials` is the whole table; :func:`named_phrases`
maps every name and alias to its material's name (what a request reader looks phrases up in).
"""

from __future__ import annotations

import functools
import math
import re
import tomllib
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from types import MappingProxyType
from typing import Any

from matloom.library.colour import RGB
from matloom.library.compose.bases import BASES
from matloom.library.compose.layouts import LAYOUTS
from matloom.library.compose.motifs import MOTIFS
from matloom.library.compose.spec import Finish
from matloom.library.entry import LibraryError

MATERIALS_DIR = Path(__file__).resolve().parents[1] / "data" / "materials"
ROLES = ("base", "secondary", "accent")
_KEYS = frozenset(
    {"base", "description", "colours", "roughness", "metallic", "translucency", "size_m", "aliases",
     "layout", "motif"}
)  # fmt: skip


@dataclass(frozen=True)
class NamedMaterial:
    """One row of the table: ``colours`` are (role, rgb) with roles ``base``, ``secondary``,
    ``accent`` in that order (as many as the row gives); ``finish`` holds what it sets."""

    name: str
    base: str
    description: str
    colours: tuple[tuple[str, RGB], ...]
    finish: Finish = Finish()
    aliases: tuple[str, ...] = ()
    size_m: float | None = None
    #: the layout (a key of ``LAYOUTS``) and motif (of ``MOTIFS``) it is made of, used when the
    #: request names none ("vinyl siding": rows; "pressed tin": a grid of embossed flowers)
    layout: str | None = None
    motif: str | None = None

    def colour(self, role: str) -> RGB | None:
        """The colour of ``role``, or None."""
        return next((rgb for r, rgb in self.colours if r == role), None)


def normalise(name: str) -> str:
    """The look-up key of a name: lowercase words joined by single spaces, without
    apostrophes (``"Tiger's-Eye"`` -> ``"tigers eye"``)."""
    text = name.lower().replace("'", "").replace("\u2019", "")
    return " ".join(re.split(r"[\s_\-]+", text)).strip()


def named_material(name: str) -> NamedMaterial | None:
    """The named material ``name`` (its name or an alias), else None."""
    key = named_phrases().get(normalise(name))
    return named_materials()[key] if key is not None else None


@functools.cache
def named_materials() -> Mapping[str, NamedMaterial]:
    """Every named material by name, from every file of :data:`MATERIALS_DIR` in name order
    (read once per process; a malformed row, or a name two rows give, raises
    :class:`~matloom.library.entry.LibraryError` naming the file and the key)."""
    out: dict[str, NamedMaterial] = {}
    where: dict[str, Path] = {}
    for path in sorted(MATERIALS_DIR.glob("*.toml")):
        try:
            with path.open("rb") as f:
                data = tomllib.load(f)
        except (OSError, tomllib.TOMLDecodeError) as exc:
            raise LibraryError(f"{path}: {exc}") from None
        for name, row in data.items():
            if name in out:
                raise LibraryError(f"{path}: [{name}] is already a row of {where[name].name}")
            out[name] = _row(path, name, row)
            where[name] = path
    return MappingProxyType(out)


@functools.cache
def named_phrases() -> Mapping[str, str]:
    """Normalised name or alias -> the material's name (a name wins over another's alias)."""
    table = named_materials()
    out: dict[str, str] = {normalise(n): n for n in table}
    for n, m in table.items():
        for alias in m.aliases:
            out.setdefault(normalise(alias), n)
    return MappingProxyType(out)


def _row(path: Path, name: str, row: Any) -> NamedMaterial:
    def fail(key: str, problem: str) -> LibraryError:
        return LibraryError(f"{path}: [{name}] key '{key}': {problem}")

    if not isinstance(row, dict):
        raise fail("-", "expected a table")
    unknown = sorted(set(row) - _KEYS)
    if unknown:
        raise fail(unknown[0], f"unknown key (known: {', '.join(sorted(_KEYS))})")
    base = row.get("base")
    if base not in BASES:
        raise fail("base", f"{base!r} is not a base ({', '.join(BASES)})")
    description = row.get("description")
    if not isinstance(description, str) or not description.strip():
        raise fail("description", "expected a non-empty string")
    colours = row.get("colours")
    if not isinstance(colours, list) or not 1 <= len(colours) <= len(ROLES):
        raise fail("colours", f"expected 1 to {len(ROLES)} colours [r, g, b]")
    rgbs: list[tuple[str, RGB]] = []
    for role, c in zip(ROLES, colours, strict=False):
        if not (isinstance(c, list) and len(c) == 3 and all(_byte(v) for v in c)):
            raise fail("colours", f"{c!r} is not [r, g, b] with integers 0-255")
        rgbs.append((role, (c[0], c[1], c[2])))
    finish = Finish(
        roughness=_unit(row, "roughness", fail),
        metallic=_unit(row, "metallic", fail),
        translucency=_unit(row, "translucency", fail),
    )
    size = row.get("size_m")
    if size is not None and not (_number(size) and size > 0):
        raise fail("size_m", f"expected a number > 0, got {size!r}")
    aliases = row.get("aliases", [])
    if not isinstance(aliases, list) or not all(isinstance(a, str) and a for a in aliases):
        raise fail("aliases", "expected a list of names")
    layout, motif = row.get("layout"), row.get("motif")
    if layout is not None and layout not in LAYOUTS:
        raise fail("layout", f"{layout!r} is not a layout ({', '.join(sorted(LAYOUTS))})")
    if motif is not None and motif not in MOTIFS:
        raise fail("motif", f"{motif!r} is not a motif ({', '.join(sorted(MOTIFS))})")
    return NamedMaterial(
        name=name,
        base=base,
        description=description.strip(),
        colours=tuple(rgbs),
        finish=finish,
        aliases=tuple(aliases),
        size_m=float(size) if size is not None else None,
        layout=layout,
        motif=motif,
    )


def _byte(v: object) -> bool:
    return isinstance(v, int) and not isinstance(v, bool) and 0 <= v <= 255


def _number(v: object) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)


def _unit(row: dict[str, Any], key: str, fail: Any) -> float | None:
    v = row.get(key)
    if v is None:
        return None
    if not (_number(v) and 0 <= v <= 1):
        raise fail(key, f"expected a number in 0..1, got {v!r}")
    return float(v)
