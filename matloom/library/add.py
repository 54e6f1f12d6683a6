"""A program made into an entry of a user library (``matloom library add``, docs/library.md).

:func:`add_entry` checks the program (errors refused with the checker's diagnostic), measures
whether it tiles (made tileable, it must repeat with its View and keep every map's seam ratio
at most 1.2, as ``matloom library check`` measures: otherwise it is written with
``tileable = false``), labels its parameters in the front matter the way the built-in entries
do (colour slots ``C_r/_g/_b`` as ``colours`` with ``[roles]`` guessed from their names,
constant Defines as ``[scalars]`` with a kind guessed from their names, ``other`` otherwise:
labelled by the Define's name), and writes ``DIR/<name>.mat`` atomically, never over an
existing entry unless asked. The program is written in canonical form with explicit seeds.
"""

from __future__ import annotations

import json
import math
import os
import re
from dataclasses import dataclass, field, replace
from pathlib import Path

from matloom.lang import ast as A
from matloom.lang.api import analyse
from matloom.lang.diagnostics import Diagnostic
from matloom.lang.params import list_params, words
from matloom.lang.printer import format_program
from matloom.lang.seeds import canonicalize_seeds
from matloom.lang.tileable import make_tileable, tileable_warnings
from matloom.library.entry import (
    CATEGORIES,
    FENCE,
    NAME_RE,
    Entry,
    LibraryError,
    entry_from_text,
    split_front_matter,
)
from matloom.library.index import Library

#: Evaluation sizes of the seam-ratio and finite-maps measurement: the library tests' and
#: ``matloom library check``'s default.
MEASURE_SIZES: tuple[int, ...] = (64, 128)
MAX_NAME = 64
#: Corners tried (shares of the View's width and height from its own corner, binary fractions
#: so the View stays exact) when the maps repeat but the seam ratio is over the limit.
CORNERS: tuple[tuple[float, float], ...] = (
    (3 / 128, 5 / 128),
    (11 / 128, 7 / 128),
    (19 / 128, 23 / 128),
    (37 / 128, 29 / 128),
    (53 / 128, 45 / 128),
)
#: Define-name words -> ``[scalars]`` kind (the first match wins; only for values in 0..1
#: except ``relief`` and ``gap``, which the author scales or leaves alone).
_SCALAR_WORDS: tuple[tuple[str, tuple[str, ...], bool], ...] = (
    ("roughness", ("rough", "roughness"), True),
    ("metallic", ("metal", "metallic", "metalness"), True),
    ("gloss", ("gloss", "coat", "clearcoat", "shine"), True),
    ("wear", ("wear", "worn", "damage", "age", "dirt"), True),
    ("cover", ("cover", "coverage"), True),
    ("relief", ("relief", "bump", "depth"), False),
    ("gap", ("gap", "grout", "mortar", "joint"), False),
)
#: Colour slot words -> ``[roles]`` role (others are ``base``).
_ROLE_WORDS: dict[str, tuple[str, ...]] = {
    "grout": ("grout", "mortar", "gap", "joint", "seam"),
    "frame": ("frame", "border", "edge", "rim"),
    "accent": ("accent", "vein", "veins", "stripe", "dot", "dots", "fleck", "speck", "spot"),
}
#: Calls a derived colour slot may use (arithmetic on colours, nothing spatial).
_ARITHMETIC = frozenset({"Mix", "Clamp", "Min", "Max", "Abs"})
_CONTROL = re.compile(r"[\x00-\x1f\x7f]")


class AddError(ValueError):
    """The program or the request cannot become an entry; the message is one line."""


@dataclass(frozen=True)
class AddRequest:
    """What the user gives besides the program (``matloom library add`` flags)."""

    name: str
    tags: tuple[str, ...]
    description: str | None = None
    category: str | None = None
    synonyms: tuple[str, ...] = ()
    size_m: float | None = None
    force: bool = False
    #: where the program came from (a file, a run folder), for messages and the ``note``
    source: str = "<program>"


@dataclass(frozen=True)
class Tiling:
    """The measured tileability: whether it tiles, why (one line) and the seam ratios."""

    tileable: bool
    why: str
    seams: dict[str, float] = field(default_factory=dict)
    #: the View corner that keeps the wrap edge off the pattern's lines (None: the program's)
    origin: tuple[float, float] | None = None


@dataclass
class Added:
    """The entry written and what was decided on the way (notes and warnings, one line each)."""

    path: Path
    entry: Entry
    text: str
    tiling: Tiling
    labels: dict[str, str]
    notes: list[str] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)


def check_name(name: str) -> str:
    """``name`` when it is a safe entry name, else :class:`AddError`."""
    if len(name) > MAX_NAME or not NAME_RE.fullmatch(name):
        raise AddError(
            f"--name {name!r}: use lowercase letters and digits in words joined by '-' "
            f"(at most {MAX_NAME} characters), e.g. house-red-brick"
        )
    return name


def split_list(text: str | None) -> tuple[str, ...]:
    """``a, b ,c`` -> ``("a", "b", "c")`` (whitespace collapsed, empty parts and repeats dropped)."""
    out: list[str] = []
    for part in (text or "").split(","):
        item = " ".join(_CONTROL.sub(" ", part).split())
        if item and item not in out:
            out.append(item)
    return tuple(out)


def _line(d: Diagnostic, source: str) -> str:
    return f"{source}:{d.line}:{d.column}: {d.severity.value} {d.code}: {d.message}"


def checked_program(text: str, source: str) -> tuple[A.Program, list[str]]:
    """(program, notes) of the program text (its front matter dropped, if any);
    :class:`AddError` with the checker's first error."""
    notes: list[str] = []
    if text.lstrip().startswith(FENCE):
        try:
            _, text, _ = split_front_matter(text.lstrip(), source)
        except LibraryError as exc:
            raise AddError(str(exc)) from None
        notes.append("the file's own front matter was replaced")
    program, diags = analyse(text)
    errors = [d for d in diags if d.is_error]
    if program is None or errors:
        more = f" (and {len(errors) - 1} more; `matloom check` shows them)" if errors[1:] else ""
        raise AddError(_line(errors[0], source) + more)
    return program, notes


def measure_tiling(program: A.Program, sizes: tuple[int, ...] = MEASURE_SIZES) -> Tiling:
    """Does ``program``, made tileable, tile? No W009/W010 warning, every map repeats with the
    View (:func:`matloom.library.checks.period_problems`) and no seam ratio over the library's
    limit at each of ``sizes`` (:func:`matloom.library.checks.evaluate_problems`). The seam ratio
    depends on where the wrap edge falls (docs/library.md, "Where the wrap edge falls"): when
    the maps repeat but a line of the pattern lies along the edge, a few corners inside the
    View are tried and the first that passes is the entry's ``origin``."""
    from matloom.library.checks import evaluate_problems, period_problems

    tiled = make_tileable(program)
    warns = tileable_warnings(tiled)
    if warns:
        return Tiling(False, warns[0].message.removeprefix("tileable: "))
    problems = period_problems(tiled)
    if problems:
        return Tiling(False, problems[0])
    x1, y1, x2, y2 = tiled.view_tuple
    first: tuple[list[str], dict[str, float]] | None = None
    for fx, fy in ((0, 0), *CORNERS):
        origin = (x1 + fx * (x2 - x1), y1 + fy * (y2 - y1))
        view = replace(tiled.view, x1=origin[0], y1=origin[1])
        view = replace(view, x2=origin[0] + x2 - x1, y2=origin[1] + y2 - y1)
        moved_program = replace(tiled, view=view)
        problems, seams = [], {}
        for size in sizes:
            problems, seams = evaluate_problems(moved_program, size, True)
            if problems:
                problems = [f"{p} at {size} px" for p in problems]
                break
        first = first or (problems, seams)
        if not problems:
            worst = max(seams.values(), default=0.0)
            at = " and ".join(str(s) for s in sizes)
            why = f"repeats with its View; seam ratio at most {worst:.2f} at {at} px"
            moved = (fx, fy) != (0, 0)
            return Tiling(True, why, seams, origin if moved else None)
        if any(not p.startswith("seam ratio") for p in problems):
            break
    assert first is not None
    return Tiling(False, first[0][0], first[1])


def _constant(node: A.Node) -> float | None:
    if isinstance(node, A.Num) and not isinstance(node.value, bool):
        return float(node.value)
    if isinstance(node, A.Neg) and isinstance(node.operand, A.Num):
        return -float(node.operand.value)
    return None


def _name_words(name: str) -> set[str]:
    return set(words(name).split())


def colour_slots(program: A.Program) -> list[str]:
    """The colour slots, in source order: three Defines ``C_r``, ``C_g``, ``C_b`` (no Define
    ``C``), each a constant or arithmetic on constants and earlier slots (a derived shade,
    ``wood_dark_r = wood_r * 0.58``, as the built-in entries write them): no coordinates, no
    noise, nothing that varies over the surface."""
    constants = {d.name for d in program.defines if _constant(d.expr) is not None}
    slots: list[str] = []
    parts: set[str] = set()
    for d in program.defines:
        slot = d.name[:-2]
        if not d.name.endswith("_r") or program.define(slot) is not None:
            continue
        triple = [program.define(f"{slot}_{c}") for c in "rgb"]
        if any(t is None for t in triple):
            continue
        if all(_plain(t.expr, constants | parts) for t in triple if t is not None):
            slots.append(slot)
            parts |= {f"{slot}_{c}" for c in "rgb"}
    return slots


def _plain(expr: A.Node, known: set[str]) -> bool:
    for n in A.walk(expr):
        if isinstance(n, A.Ref) and n.name not in known:
            return False
        if isinstance(n, A.Call) and n.func not in _ARITHMETIC:
            return False
    return True


def labels_of(program: A.Program) -> tuple[list[str], dict[str, str], dict[str, str]]:
    """(colour slots, ``[roles]``, ``[scalars]``) of the program's exposed parameters."""
    params = list_params(program)
    colours = colour_slots(program)
    roles: dict[str, str] = {}
    for slot in colours:
        found = _name_words(slot)
        role = next((r for r, ws in _ROLE_WORDS.items() if found & set(ws)), None)
        if role is not None and slot != colours[0]:
            roles[slot] = role
    components = {f"{s}_{c}" for s in colours for c in "rgb"}
    scalars: dict[str, str] = {}
    for p in params:
        name = p.address.removeprefix("define:")
        if not p.address.startswith("define:") or "." in name or name in components:
            continue
        d = program.define(name)
        value = _constant(d.expr) if d is not None else None
        if value is None or p.kind == "seed" or not p.affects:  # a seed, or reaching no map
            continue
        found = _name_words(name)
        kind = "other"
        for k, ws, unit in _SCALAR_WORDS:
            if found & set(ws) and (not unit or 0.0 <= value <= 1.0):
                kind = k
                break
        scalars[name] = kind
    return colours, roles, scalars


def _q(text: str) -> str:
    """A TOML basic string."""
    return json.dumps(" ".join(_CONTROL.sub(" ", text).split()), ensure_ascii=False)


def _list(items: tuple[str, ...] | list[str]) -> str:
    return "[" + ", ".join(_q(i) for i in items) + "]"


def front_matter(
    req: AddRequest,
    description: str,
    category: str,
    size_m: float,
    tiling: Tiling,
    labels: tuple[list[str], dict[str, str], dict[str, str]],
) -> str:
    """The front matter block (``# ---`` lines included)."""
    colours, roles, scalars = labels
    lines = [
        f"description = {_q(description)}",
        f"category = {_q(category)}",
        f"tags = {_list(req.tags)}",
    ]
    if req.synonyms:
        lines.append(f"synonyms = {_list(req.synonyms)}")
    lines += [
        f"size_m = {size_m:.6g}",
        f"tileable = {'true' if tiling.tileable else 'false'}",
        f"colours = {_list(colours)}",
        f"note = {_q(f'added with matloom library add from {req.source}; {tiling.why}')}",
    ]
    for table, values in (("roles", roles), ("scalars", scalars)):
        if values:
            lines.append(f"[{table}]")
            lines += [f"{k} = {_q(v)}" for k, v in values.items()]
    return "\n".join([FENCE, *(f"# {ln}" for ln in lines), FENCE]) + "\n"


def guess_category(req: AddRequest, description: str, lib: Library) -> tuple[str, str]:
    """(category, note): ``--category``, else the category of the entry the name, tags and
    description retrieve first."""
    if req.category is not None:
        if req.category not in CATEGORIES:
            raise AddError(f"--category {req.category!r}: one of {', '.join(CATEGORIES)}")
        return req.category, ""
    from matloom.library.author import search

    text = " ".join([req.name.replace("-", " "), *req.tags, description])
    found = search(text, lib)
    if not found:
        raise AddError(
            "give --category: no entry matched the name, tags or description to guess it from "
            f"(one of {', '.join(CATEGORIES)})"
        )
    category = lib.entry(found[0].name).category
    return category, f"category {category} (that of {found[0].name}; --category to choose)"


def existing(target: Path, name: str) -> list[Path]:
    """The files of entry ``name`` already in the user library folder ``target``."""
    places = [target / f"{name}.mat", *(target / c / f"{name}.mat" for c in CATEGORIES)]
    return [p for p in places if os.path.lexists(p)]


def add_entry(
    program_text: str,
    req: AddRequest,
    target: Path,
    lib: Library,
    sizes: tuple[int, ...] = MEASURE_SIZES,
) -> Added:
    """Check, measure, label and write ``program_text`` as entry ``req.name`` of the user
    library folder ``target`` (created if missing); ``lib`` is the library it joins (for the
    category guess and the notes on precedence). :class:`AddError` (one line) when refused."""
    check_name(req.name)
    if not req.tags:
        raise AddError("--tags: give at least one word a user would type, e.g. --tags brick,red")
    if req.size_m is not None and not (math.isfinite(req.size_m) and req.size_m > 0):
        raise AddError(f"--size-m {req.size_m}: a number of metres > 0")
    there = existing(target, req.name)
    if there and not req.force:
        raise AddError(f"{there[0]} already exists; pass --force to replace it")
    program, notes = checked_program(program_text, req.source)
    program = canonicalize_seeds(program, 0)
    view = program.view or A.ViewDecl(0.0, 0.0, 1.0, 1.0)
    width = abs(view.x2 - view.x1)
    if req.size_m is not None:
        size_m = req.size_m
    elif view.unit_m is not None:
        size_m = view.unit_m * width
        notes.append(f"size_m {size_m:.6g} (the View's unit_m x its width)")
    else:
        size_m = 1.0
        notes.append("size_m 1 (the View has no unit_m; --size-m to give the metres it spans)")
    program = replace(program, view=replace(view, unit_m=None))
    tiling = measure_tiling(program, sizes)
    view = replace(program.view, tileable=tiling.tileable)
    if tiling.origin is not None:
        x, y = tiling.origin
        view = replace(view, x1=x, y1=y, x2=x + view.x2 - view.x1, y2=y + view.y2 - view.y1)
        notes.append(f"View moved to start at ({x:g}, {y:g}), off the pattern's lines")
    program = replace(program, view=view)
    if not tiling.tileable:
        from matloom.library.checks import evaluate_problems

        problems, _ = evaluate_problems(program, sizes[0], False)
        if problems:
            raise AddError(f"{req.source}: {problems[0]} at {sizes[0]} px")
    description = " ".join((req.description or "").split())
    description = description or req.name.replace("-", " ").capitalize()
    if not req.description:
        notes.append(f"description {description!r} (--description to write one)")
    category, note = guess_category(req, description, lib)
    if note:
        notes.append(note)
    labels = labels_of(program)
    body = format_program(program).rstrip("\n") + "\n"
    text = front_matter(req, description, category, size_m, tiling, labels) + body
    flat = target / f"{req.name}.mat"
    path = next((p for p in there if p.parent.name == category), flat)
    try:
        entry = entry_from_text(text, path)
    except LibraryError as exc:  # a bug here, not the user's: say what it was
        raise AddError(f"could not write a valid entry: {exc}") from None
    warnings = [_line(d, str(path)) for d in analyse(text)[1]]  # as written, made tileable
    warnings += _static_warnings(entry, program, lib, warnings)
    _write(path, text, [p for p in there if p != path], target)
    if req.name in lib.entries and lib.entry(req.name).path != path:
        notes.append(
            f"the {lib.source(req.name)} entry {req.name} ({lib.entry(req.name).path}) has "
            "this name: the new one replaces it wherever its folder is a library"
        )
    return Added(path, entry, text, tiling, _labels(entry, program), notes, warnings)


def _labels(entry: Entry, program: A.Program) -> dict[str, str]:
    from matloom.library.labels import entry_labels

    return entry_labels(entry, program)


def _static_warnings(entry: Entry, program: A.Program, lib: Library, known: list[str]) -> list[str]:
    """What ``matloom library check`` will say about the entry beyond the checker's warnings."""
    from matloom.library.checks import static_problems

    solo = Library({entry.name: entry}, lib.overlays)
    solo._asts[entry.name] = program
    out = []
    for problem in static_problems(solo, entry):
        if not any(problem.split(": ", 1)[-1] in k for k in known):
            out.append(f"matloom library check will report: {problem}")
    return out


def _write(path: Path, text: str, old: list[Path], target: Path) -> None:
    from matloom.io.atomic import atomic_write_bytes

    try:
        target.mkdir(exist_ok=True)  # one level: a mistyped path is not made
        atomic_write_bytes(path, text.encode("utf-8"))
        for p in old:  # --force: the replaced entry was in another category folder
            p.unlink()
    except OSError as exc:
        raise AddError(f"cannot write {path}: {exc.strerror or exc}") from None
