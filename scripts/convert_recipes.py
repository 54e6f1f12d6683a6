"""One-off conversion of the built-in Python recipes into library entries (dev tool).

Run from the repository root::

    .venv/bin/python scripts/convert_recipes.py [--dry-run] [NAME ...]

Every recipe of ``matloom.author.builtin.recipes.REGISTRY`` is instantiated with its default
slots and written as ``matloom/library/entries/<category>/<name>.mat``:

* colour roles become constant Defines ``<role>_r/_g/_b`` (derived roles and shades are
  arithmetic on them, so changing the main colour moves its shades with it);
* scalar slots (``rough``, ``relief``, ``wear`` ...) become named constant Defines, except
  where the language needs a literal (a static parameter such as ``Bricks(mortar=...)``);
* the Floor-cell ``Sin`` hash idiom becomes ``Hash(...)`` (per-cell values that tile);
* every noise gets an explicit seed; the View is made tileable when nothing in the program
  keeps it from repeating, after trying nearby View sizes that make the patterns divide it;
* word presets become data (shared sets in ``matloom/library/data/presets.toml``, the rest in
  the entry's front matter).

Files that exist and were not written by this script (no ``converted from`` note) are never
overwritten. The script only imports the built-in author, which it converts; the library does
not depend on it.
"""

from __future__ import annotations

import argparse
import re
import sys
from collections.abc import Iterable
from dataclasses import replace
from pathlib import Path

import matloom
from matloom.author.builtin import colours as C
from matloom.author.builtin.compose import derive_seed
from matloom.author.builtin.generic import GENERIC
from matloom.author.builtin.micro import MICROS
from matloom.author.builtin.recipes import REGISTRY, Recipe
from matloom.author.builtin.template import fmt
from matloom.lang.tileable import make_tileable, tileable_warnings

sys.path.insert(0, str(Path(__file__).resolve().parent))
from convert_passes import fract_cells, hash_cells, seam_safe, tileable_view, with_view  # noqa: E402
from convert_tables import (  # noqa: E402
    CATEGORY,
    EXTRA_SYNONYMS,
    EXTRA_TAGS,
    category_of,
    fix_template,
)

ROOT = Path(__file__).resolve().parent.parent
ENTRIES = ROOT / "matloom" / "library" / "entries"
PRESETS_FILE = ROOT / "matloom" / "library" / "data" / "presets.toml"
MARK = "converted from the built-in recipe"

_SLOT_RE = re.compile(r"\{([^{}:]+)(?::([^{}]*))?\}")
_OP_RE = re.compile(r"^([a-z_][a-z_0-9]*)([*+])(-?[0-9.]+)$")
_CH = ("r", "g", "b")
SCALAR_KINDS = {
    "rough": "roughness",
    "relief": "relief",
    "wear": "wear",
    "coat": "gloss",
    "gap": "gap",
    "cover": "cover",
    "cover_amt": "cover",
}


# ----------------------------------------------------------------------------- colours
Affine = tuple[str, float, float]
"""A colour reference as ``channel * m + k`` of a named role."""


def _shade(ref: Affine, amount: float) -> Affine:
    name, m, k = ref
    if amount < 0:
        return name, m * (1 + amount), k * (1 + amount)
    return name, m * (1 - amount), k * (1 - amount) + 255 * amount


def _ref(text: str) -> Affine:
    name, _, amount = text.strip().partition("~")
    ref: Affine = (name, 1.0, 0.0)
    return _shade(ref, float(amount)) if amount else ref


def _num(v: float) -> str:
    return fmt(round(v, 4))


def _affine_text(ref: Affine, ch: str) -> str:
    name, m, k = ref
    base = f"{name}_{ch}"
    if abs(m - 1) > 1e-9:
        base = f"({base} * {_num(m)})"
    if abs(k) > 1e-9:
        base = f"({base} + {_num(k)})"
    return base


def _mix_text(a: Affine, b: Affine, field: str, ch: str) -> str:
    field = f"({field.strip()})"
    if a[0] == b[0]:
        dm, dk = b[1] - a[1], b[2] - a[2]
        mul = _num(a[1]) if abs(dm) < 1e-9 else f"({_num(a[1])} + ({field} * {_num(dm)}))"
        out = f"({a[0]}_{ch} * {mul})" if mul != "1" else f"{a[0]}_{ch}"
        if abs(a[2]) > 1e-9 or abs(dk) > 1e-9:
            add = _num(a[2]) if abs(dk) < 1e-9 else f"({_num(a[2])} + ({field} * {_num(dk)}))"
            out = f"({out} + {add})"
        return out
    ta, tb = _affine_text(a, ch), _affine_text(b, ch)
    return f"({ta} + ({field} * ({tb} - {ta})))"


# ----------------------------------------------------------------------------- templates
class Symbolic:
    """Expands a recipe template into program text whose slots are named Defines."""

    def __init__(self, recipe: Recipe, inline: set[str]) -> None:
        self.recipe = recipe
        self.inline = inline
        self.view = float(recipe.slots["view"])
        self.micro = MICROS[recipe.micro] if recipe.micro else None
        self.defaults = {r.name: r.default for r in recipe.colours}
        self.names = slot_names(recipe)

    def scalar(self, head: str) -> str:
        slots = self.recipe.slots
        if head == "view":
            return fmt(self.view)
        if head in slots:
            value = slots[head]
            if head in self.inline:
                return value if isinstance(value, str) else fmt(value)
            return self.names[head]
        m = _OP_RE.match(head)
        if m and (m.group(1) in slots or m.group(1) == "view"):
            name, op, k = m.group(1), m.group(2), float(m.group(3))
            if name == "view" or name in self.inline:
                base = self.view if name == "view" else float(slots[name])
                return fmt(base * k if op == "*" else base + k)
            ref = self.names[name]
            return f"({ref} * {fmt(k)})" if op == "*" else f"({ref} + {fmt(k)})"
        raise ValueError(f"{self.recipe.name}: unknown slot {head!r}")

    def height(self, value: float) -> str:
        if "relief" in self.inline:
            return fmt(value)
        return f"({fmt(value)} * relief)"

    def mcol(self, arg: str) -> str:
        micro = self.micro
        assert micro is not None
        ref = _ref(arg)
        default = self.defaults[ref[0]]
        rgb = C.clamp_rgb(tuple(c * ref[1] + ref[2] for c in default))  # type: ignore[arg-type]
        amount = abs(micro.contrast)
        if C.luminance(rgb) < 0.2 and micro.name in {"marble", "stone", "wood"}:
            other = _shade(ref, amount * 0.6)
        else:
            other = _shade(ref, -amount)
        a, b = (other, ref) if micro.contrast >= 0 else (ref, other)
        return ", ".join(_mix_text(a, b, micro.field, ch) for ch in _CH)

    def expand(self, match: re.Match[str]) -> str:
        head, arg = match.group(1).strip(), match.group(2)
        if arg is None:
            return self.scalar(head)
        if head == "rgb":
            return ", ".join(_affine_text(_ref(arg), ch) for ch in _CH)
        if head == "mix":
            a, b, field = (p.strip() for p in arg.split(",", 2))
            return ", ".join(_mix_text(_ref(a), _ref(b), field, ch) for ch in _CH)
        if head in {"h", "hv"}:
            return self.height(float(arg))
        if head == "mf":
            return fmt(float(arg) / self.view)
        if head == "seed":
            return str(derive_seed("", 0, self.recipe.name, arg.strip()))
        if head == "micro":
            assert self.micro is not None
            return self.micro.parts()[arg]
        if head == "mcol":
            return self.mcol(arg)
        raise ValueError(f"{self.recipe.name}: unknown slot form {head!r}")

    def body(self) -> str:
        text = self.recipe.template
        for _ in range(4):
            new = _SLOT_RE.sub(self.expand, text)
            if new == text:
                break
            text = new
        return text.replace("3.1416", "pi")


def slot_names(recipe: Recipe) -> dict[str, str]:
    """Scalar slot -> Define name (``<slot>_amt`` where the template defines the slot's name)."""
    return {
        name: f"{name}_amt" if f"Define({name}," in recipe.template else name
        for name in recipe.slots
    }


def _used(text: str, name: str) -> bool:
    return re.search(rf"\b{re.escape(name)}\b", text) is not None


def _colour_defines(recipe: Recipe, body: str) -> tuple[list[str], list[str], list[str]]:
    """(Define lines, slot names, derived names) of the colour roles the body references."""
    roles = {r.name: r for r in recipe.colours}
    needed: list[str] = []

    def need(name: str) -> None:
        if name in needed:
            return
        role = roles[name]
        if role.derive is not None:
            need(role.derive[0])
        needed.append(name)

    for r in recipe.colours:
        if any(_used(body, f"{r.name}_{ch}") for ch in _CH):
            need(r.name)
    lines: list[str] = []
    slots: list[str] = []
    derived: list[str] = []
    for name in needed:
        role = roles[name]
        if role.derive is None:
            slots.append(name)
            lines += [f"Define({name}_{ch}, {v})" for ch, v in zip(_CH, role.default, strict=True)]
            continue
        derived.append(name)
        src, amount = role.derive[0], float(role.derive[1])
        if len(role.derive) > 2:  # "contrast": lighten instead when the source is dark
            if not any(line.startswith(f"Define({src}_dark,") for line in lines):
                lines.append(
                    f"Define({src}_lum, ((({src}_r * 0.2126) + ({src}_g * 0.7152)) + "
                    f"({src}_b * 0.0722)))"
                )
                lines.append(f"Define({src}_dark, Clamp(((76.5 - {src}_lum) * 1000), 0, 1))")
            k = 1 - abs(amount)
            lines += [
                f"Define({name}_{ch}, (({src}_{ch} * {_num(k)}) + ({src}_dark * "
                f"{_num(255 * abs(amount))})))"
                for ch in _CH
            ]
        else:
            lines += [
                f"Define({name}_{ch}, {_affine_text(_shade((src, 1.0, 0.0), amount), ch)})"
                for ch in _CH
            ]
    return lines, slots, derived


def _scalar_defines(recipe: Recipe, body: str, inline: set[str]) -> tuple[list[str], list[str]]:
    lines, names = [], []
    for slot, value in recipe.slots.items():
        name = slot_names(recipe)[slot]
        if slot == "view" or slot in inline or not _used(body, name):
            continue
        names.append(name)
        lines.append(f"Define({name}, {value if isinstance(value, str) else fmt(value)})")
    return lines, names


def _assemble(body: str, head: list[str]) -> str:
    view, _, rest = body.partition("\n")
    return "\n".join([view, *head, rest])


def render(recipe: Recipe) -> tuple[str, list[str], list[str], list[str]]:
    """Program text, colour slots, derived colours and scalar slots of ``recipe``."""
    inline: set[str] = set()
    for _ in range(8):
        sym = Symbolic(recipe, inline)
        body = sym.body()
        c_lines, c_slots, derived = _colour_defines(recipe, body)
        s_lines, s_names = _scalar_defines(recipe, body, inline)
        text = _assemble(body, c_lines + s_lines)
        _, diags = matloom.analyse(text)
        static = [d for d in diags if d.code == "E045"]
        if not static:
            errors = [d for d in diags if d.is_error]
            if errors:
                raise ValueError(f"{recipe.name}: {errors[0]}")
            return text, c_slots, derived, s_names
        for d in static:
            snippet = text[d.span.start : d.span.end]
            hit = [n for n in [*recipe.slots, "relief"] if _used(snippet, n)]
            if not hit:
                raise ValueError(f"{recipe.name}: {d}")
            inline.update(hit)
    raise ValueError(f"{recipe.name}: could not resolve static parameters")


# ----------------------------------------------------------------------------- front matter
def toml_value(value: object) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, float)):
        return fmt(float(value))
    if isinstance(value, str):
        return '"' + value.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(toml_value(v) for v in value) + "]"
    raise TypeError(value)


def front_matter(items: Iterable[tuple[str, object]], tables: dict[str, dict]) -> list[str]:
    lines = [f"{k} = {toml_value(v)}" for k, v in items]
    for table, content in tables.items():
        if not content:
            continue
        if all(not isinstance(v, dict) for v in content.values()):
            lines.append(f"[{table}]")
            lines += [f"{k} = {toml_value(v)}" for k, v in content.items()]
            continue
        for key, sub in content.items():
            name = key if re.fullmatch(r"[a-z0-9_-]+", key) else toml_value(key)
            lines.append(f"[{table}.{name}]")
            lines += [f"{k} = {toml_value(v)}" for k, v in sub.items()]
    return ["# ---", *(f"# {line}" for line in lines), "# ---"]


def _shared_presets() -> dict[str, tuple[str, dict]]:
    """Preset tables used by two or more recipes -> (set name, presets)."""
    seen: dict[str, list[str]] = {}
    tables: dict[str, dict] = {}
    for r in REGISTRY.values():
        if not r.presets:
            continue
        key = repr(sorted((w, sorted(p.items())) for w, p in r.presets.items()))
        seen.setdefault(key, []).append(r.name)
        tables[key] = dict(r.presets)
    out: dict[str, tuple[str, dict]] = {}
    for key, names in seen.items():
        if len(names) < 2:
            continue
        slots = {k for p in tables[key].values() for k in p}
        name = {"wood": "wood-species", "metal": "metals", "axiscross": "orientation"}.get(
            "".join(sorted(slots)), "-".join(sorted(slots)) + "-presets"
        )
        if name in {s for s, _ in out.values()}:
            name = f"{name}-{names[0]}"
        table = tables[key]
        used = set.intersection(
            *(
                {k for k in REGISTRY[n].slots if "{" + k in REGISTRY[n].template}
                | {r.name for r in REGISTRY[n].colours}
                for n in names
            )
        )
        table = {w: {k: v for k, v in p.items() if k in used} for w, p in table.items()}
        for n in names:
            out[n] = (name, table)
    return out


def preset_value(value: object) -> object:
    return list(value) if isinstance(value, tuple) else value


def write_presets(shared: dict[str, tuple[str, dict]], dry: bool) -> None:
    sets: dict[str, dict] = {}
    for set_name, table in shared.values():
        sets[set_name] = table
    lines = [
        "# Shared word presets of the library: [<set>.<word>] -> Define slot values.",
        "# An entry lists the sets it takes in `preset_sets`; written by scripts/convert_recipes.py.",
        "",
    ]
    for set_name in sorted(sets):
        for word, values in sets[set_name].items():
            key = word if re.fullmatch(r"[a-z0-9_-]+", word) else toml_value(word)
            lines.append(f"[{set_name}.{key}]")
            lines += [f"{k} = {toml_value(preset_value(v))}" for k, v in values.items()]
        lines.append("")
    if not dry:
        PRESETS_FILE.parent.mkdir(parents=True, exist_ok=True)
        PRESETS_FILE.write_text("\n".join(lines).rstrip() + "\n")


def tags_and_synonyms(recipe: Recipe) -> tuple[list[str], list[str]]:
    tags: list[str] = []
    synonyms: list[str] = []
    for tag, weight in sorted(recipe.tags.items(), key=lambda kv: -kv[1]):
        if weight < 1 or tag in recipe.presets:
            continue
        (synonyms if " " in tag else tags).append(tag)
    tags += [t for t in EXTRA_TAGS.get(recipe.name, ()) if t not in tags]
    synonyms += [s for s in EXTRA_SYNONYMS.get(recipe.name, ()) if s not in synonyms]
    return tags, synonyms


def describe(recipe: Recipe) -> str:
    text = recipe.summary.strip()
    return text[:1].upper() + text[1:]


def convert(recipe: Recipe, shared: dict[str, tuple[str, dict]]) -> tuple[str, str, list[str]]:
    """(category, file text, notes) for one recipe."""
    notes: list[str] = []
    recipe = fix_template(recipe)
    text, c_slots, derived, s_names = render(recipe)
    program = fract_cells(hash_cells(matloom.parse(text), recipe.name))
    view0 = float(recipe.slots["view"])
    side = tileable_view(program, view0)
    if side is not None:
        program = make_tileable(with_view(program, side))
        if side != view0:
            notes.append(f"View {fmt(view0)} -> {fmt(side)} so that it tiles")
    else:
        warn = tileable_warnings(make_tileable(program))
        notes.append("not tileable: " + warn[0].message.removeprefix("tileable: "))
        side = view0
    if program.tileable:
        program, shifted = seam_safe(program)
        if shifted is None:
            program = replace(program, view=replace(program.view, tileable=False))
            notes.append("not tileable: seam ratio over 1.2 at every View origin tried")
    out = matloom.format(program)
    diags = matloom.check(out)
    if diags:
        raise ValueError(f"{recipe.name}: {diags[0]}")
    per_coord = recipe.unit_m / recipe.repeat
    tags, synonyms = tags_and_synonyms(recipe)
    items: list[tuple[str, object]] = [
        ("description", describe(recipe)),
        ("category", category_of(recipe)),
        ("tags", tags),
        ("synonyms", synonyms),
        ("size_m", round(side * per_coord, 4) if per_coord > 0 else 1.0),
        ("tileable", program.tileable),
        ("colours", c_slots + derived),
    ]
    if recipe.unit_m > 0:
        items.append(("feature_m", recipe.unit_m))
    if recipe.count_nouns:
        items.append(("units", sorted(recipe.count_nouns)))
    if recipe.absorbs:
        items.append(("absorbs", sorted(recipe.absorbs)))
    if recipe.name in shared:
        items.append(("preset_sets", [shared[recipe.name][0]]))
    items.append(("note", f"{MARK} {recipe.name}" + (f"; {'; '.join(notes)}" if notes else "")))
    roles = {
        r.name: r.kind
        for r in recipe.colours
        if r.name in c_slots + derived and r.kind in {"grout", "accent", "frame", "material"}
    }
    scalars = {
        n: SCALAR_KINDS.get(n.removesuffix("_amt"), "other")
        for n in s_names
        if not isinstance(recipe.slots.get(n.removesuffix("_amt")), str)
    }
    names = slot_names(recipe)
    defined = {d.name for d in program.defines}
    presets = {}
    if recipe.name not in shared:
        for word, values in recipe.presets.items():
            kept = {
                names.get(k, k): preset_value(v)
                for k, v in values.items()
                if names.get(k, k) in defined or f"{k}_r" in defined
            }
            if kept:
                presets[word] = kept
            else:
                notes.append(f"preset '{word}' dropped (it sets literals only)")
    tables = {"roles": roles, "scalars": scalars, "presets": presets}
    head = front_matter(items, tables)
    return category_of(recipe), "\n".join(head) + "\n" + out.rstrip("\n") + "\n", notes


def existing_names() -> dict[str, Path]:
    return {p.stem: p for p in ENTRIES.glob("*/*.mat")}


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("names", nargs="*", help="recipes to convert (default: all)")
    ap.add_argument("--dry-run", action="store_true", help="convert and check, write nothing")
    args = ap.parse_args(argv)
    shared = _shared_presets()
    names = args.names or [*REGISTRY, GENERIC.name]
    have = existing_names()
    tiles = 0
    for name in names:
        recipe = GENERIC if name == GENERIC.name else REGISTRY[name]
        category, text, notes = convert(recipe, shared)
        tiles += "tileable = true" in text
        target = ENTRIES / category / f"{name}.mat"
        old = have.get(name)
        if old is not None and MARK not in old.read_text():
            print(f"skip {name}: {old} exists and was not converted by this script")
            continue
        if not args.dry_run:
            if old is not None and old != target:
                old.unlink()
            target.parent.mkdir(parents=True, exist_ok=True)
            target.write_text(text)
        print(f"{category}/{name}: {'; '.join(notes) or 'ok'}")
    write_presets(shared, args.dry_run)
    print(f"{len(names)} recipes, {tiles} tileable; categories: {sorted(set(CATEGORY.values()))}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
