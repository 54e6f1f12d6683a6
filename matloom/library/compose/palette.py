"""Colour slots of a composed program: which requested colour goes where, the defaults for the
rest, and what could not be shown.

Slots are written as three Defines ``S_r``, ``S_g``, ``S_b`` (a colour parameter of ``matloom
params``): a literal colour, or arithmetic on another slot (a derived shade that follows its
source when it is edited). Roles of a :class:`~matloom.library.compose.spec.CompositionSpec`:
``base`` the ground (a second ``base`` is the second colour of a two-colour layout, else the
secondary), ``secondary`` the structure's second colour (grain, bands; the second colour of a
two-colour layout when no ``stripe`` is given), ``accent`` the base's accents (veins, speckles,
chips; else the motif), ``grout`` joints, gaps and the void under holes, ``motif``, ``stripe``.
"""

from __future__ import annotations

from dataclasses import dataclass

from matloom.library.colour import RGB, clamp_rgb, luminance, mix, saturation, with_lightness
from matloom.library.compose.bases import BaseSpec
from matloom.library.compose.layouts import LayoutSpec
from matloom.library.compose.named import NamedMaterial
from matloom.library.compose.writer import Writer, num


@dataclass(frozen=True)
class Slot:
    """A colour slot: a literal ``rgb``, or ``source`` slot scaled per channel by ``scale``
    (``lighten`` > 0: moved that far toward white instead)."""

    name: str
    role: str
    rgb: RGB
    source: str | None = None
    scale: tuple[float, float, float] = (1.0, 1.0, 1.0)
    lighten: float = 0.0

    def write(self, w: Writer) -> None:
        for k, c in enumerate("rgb"):
            if self.source is None:
                w.define(f"{self.name}_{c}", self.rgb[k])
            elif self.lighten:
                src = f"{self.source}_{c}"
                w.define(f"{self.name}_{c}", f"({src} + ((255 - {src}) * {num(self.lighten)}))")
            else:
                w.define(f"{self.name}_{c}", f"({self.source}_{c} * {num(self.scale[k], 3)})")


@dataclass(frozen=True)
class Palette:
    """The slots by name (``base`` and ``secondary`` always; ``accent``, ``grout``,
    ``motif`` and the layout's second colour when used), what was shown and dropped."""

    slots: dict[str, Slot]
    shown: tuple[str, ...]
    dropped: tuple[str, ...]

    def ratio(self, slot: str) -> tuple[float, float, float]:
        """Per-channel secondary / base ratio, to shade another colour like the base."""
        b, s = self.slots["base"].rgb, self.slots["secondary"].rgb
        return tuple(min(2.0, s[k] / max(b[k], 1)) for k in range(3))  # type: ignore[return-value]


def _rgb_text(rgb: RGB) -> str:
    return f"({rgb[0]}, {rgb[1]}, {rgb[2]})"


def _scale(a: RGB, b: RGB) -> tuple[float, float, float]:
    return tuple(round(min(2.0, b[k] / max(a[k], 1)), 3) for k in range(3))  # type: ignore[return-value]


def resolve(
    colours: tuple[tuple[str, RGB], ...],
    motif_colour: RGB | None,
    base: BaseSpec,
    layout: LayoutSpec | None,
    has_motif: bool,
    named: NamedMaterial | None,
) -> Palette:
    """Assign the requested ``colours`` (and the motif's own colour) to slots; fill the rest."""
    two = layout is not None and layout.two_colour
    ground = layout is not None and layout.shows_ground
    has_accent = base.accent_share > 0
    given: dict[str, RGB] = {}
    shown: list[str] = []
    dropped: list[str] = []

    def take(slot: str, role: str, rgb: RGB, what: str) -> None:
        given[slot] = rgb
        shown.append(f"colour {role} {_rgb_text(rgb)} -> {what}")

    alt = layout.alt_slot if layout is not None else "second"
    for role, rgb in colours:
        if role == "base" and "base" not in given:
            take("base", role, rgb, "the base colour")
        elif (
            role in ("base", "stripe", "secondary")
            and two
            and alt not in given
            and (role != "secondary" or not any(r == "stripe" for r, _ in colours))
        ):
            take(alt, role, rgb, f"the {alt} colour")
        elif role in ("base", "secondary") and "secondary" not in given:
            take("secondary", role, rgb, "the secondary colour")
        elif role == "accent" and has_accent and "accent" not in given:
            take("accent", role, rgb, "the accents")
        elif role in ("accent", "motif") and has_motif and "motif" not in given:
            take("motif", role, rgb, "the motif")
        elif role == "grout" and ground and "grout" not in given:
            where = "the holes" if layout.holes else "the gaps" if layout.gaps else "the joints"  # type: ignore[union-attr]
            take("grout", role, rgb, where)
        else:
            dropped.append(f"colour {role} {_rgb_text(rgb)}: {_why(role, base, layout, has_motif)}")
    if motif_colour is not None:
        if has_motif and "motif" not in given:
            take("motif", "motif", motif_colour, "the motif")
        elif not has_motif:
            dropped.append(f"colour motif {_rgb_text(motif_colour)}: no motif is drawn")

    ref = named.colours if named is not None else ()
    ref_base = dict(ref).get("base", base.colours[0])
    ref_sec = dict(ref).get("secondary")
    if ref_sec is None:
        ref_sec = mix(ref_base, (0, 0, 0), 0.25) if named is not None else base.colours[1]
    ref_acc = dict(ref).get("accent", base.colours[2])

    slots: dict[str, Slot] = {}
    b = given.get("base", ref_base)
    slots["base"] = Slot("base", "base", b)
    if two:
        slots[alt] = _alt(alt, b, given.get(alt), layout.alt_contrast)  # type: ignore[union-attr]
    if "secondary" in given:
        slots["secondary"] = Slot("secondary", "base", given["secondary"])
    else:
        scale = _scale(ref_base, ref_sec)
        sec = clamp_rgb(tuple(b[k] * scale[k] for k in range(3)))  # type: ignore[arg-type]
        slots["secondary"] = Slot("secondary", "base", sec, "base", scale)
    if has_accent:
        acc = given.get("accent", ref_acc)
        if "accent" not in given and "base" in given and abs(luminance(acc) - luminance(b)) < 0.2:
            acc = mix(b, (250, 250, 250) if luminance(b) < 0.5 else (20, 20, 20), 0.65)
        slots["accent"] = Slot("accent", "accent", acc)
    if ground:
        slots["grout"] = Slot("grout", "grout", given.get("grout", _grout(b, layout, base)))  # type: ignore[arg-type]
    if has_motif and not (layout is not None and layout.holes):
        motif = given.get("motif") or _named_motif(named, has_accent, b) or _contrast(b)
        slots["motif"] = Slot("motif", "accent", motif)
    return Palette(slots, tuple(shown), tuple(dropped))


def _named_motif(named: NamedMaterial | None, has_accent: bool, base: RGB) -> RGB | None:
    """A named material's accent colour for its motif when its base shows no accents
    (pepperoni on a pizza, cobalt flowers on Iznik ware), if it stands out on ``base``."""
    acc = named.colour("accent") if named is not None and not has_accent else None
    if acc is None or abs(luminance(acc) - luminance(base)) + _rgb_gap(acc, base) < 0.15:
        return None
    return acc


def _rgb_gap(a: RGB, b: RGB) -> float:
    """The mean channel difference of two colours, 0..1."""
    return sum(abs(x - y) for x, y in zip(a, b, strict=True)) / (3 * 255)


def _alt(name: str, base: RGB, rgb: RGB | None, contrast: float) -> Slot:
    if rgb is not None:
        return Slot(name, "base", rgb)
    if luminance(base) > 0.45:
        f = round(1 - 0.75 * contrast, 3)
        return Slot(name, "base", clamp_rgb((base[0] * f, base[1] * f, base[2] * f)), "base",
                    (f, f, f))  # fmt: skip
    t = round(0.75 * contrast, 3)
    return Slot(name, "base", mix(base, (255, 255, 255), t), "base", lighten=t)


#: base categories whose joints are dark gaps (boards, panels, seams), not mortar or grout
DARK_GAPS = frozenset({"wood", "metal", "plastic", "leather", "fabric", "organic", "glass"})


def _grout(base: RGB, layout: LayoutSpec, spec: BaseSpec) -> RGB:
    if layout.holes or layout.gaps:
        return mix(base, (20, 20, 22), 0.85)
    if spec.category in DARK_GAPS:
        return mix(base, (20, 18, 16), 0.7)
    if luminance(base) > 0.5:
        return mix(base, (112, 110, 106), 0.6)
    return mix(base, (204, 202, 196), 0.6)


def _contrast(base: RGB) -> RGB:
    """A motif colour that stands out on ``base``: a deep or a pale shade of its hue."""
    if saturation(base) < 0.15:
        return (38, 38, 42) if luminance(base) > 0.45 else (236, 234, 228)
    return with_lightness(base, 0.22 if luminance(base) > 0.45 else 0.85)


def _why(role: str, base: BaseSpec, layout: LayoutSpec | None, has_motif: bool) -> str:
    if role == "grout":
        return "the layout has no joints" if layout is not None else "no layout with joints"
    if role == "motif":
        return "no motif is drawn"
    if role == "accent":
        return f"{base.noun} shows no accents and no motif is drawn"
    if role == "stripe":
        return "the layout has no stripes" if layout is not None else "no striped layout"
    if role in ("base", "secondary"):
        return "more colours than the material and its layout have places for"
    return f"unknown colour role {role!r}"
