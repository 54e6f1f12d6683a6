"""The system prompt's "Resolution and previews" section: facts measured, not written down.

What a generator must know to be judged fairly from a preview: the render size and the size of
one pixel in View units (features under about 2 px alias), how much relief shows, and which
channels a preview layout cannot show. The pixel facts come from the run's render size. The
preview facts are measured once per process by shading small probe materials with the preview
itself (:func:`matloom.author.views.shade_view`): a mid-grey swatch with each single-value
channel of the registry at the low end, middle and high end of its search range, and tilted
planes of known slope. So the text always describes the shading that will be used, whatever
the preview modules do, and a new channel in the registry is measured without a change here.
"""

from __future__ import annotations

from collections.abc import Sequence
from functools import cache

import numpy as np

from matloom.vocab import CHANNELS
from matloom.vocab.spec import ChannelSpec

#: The probe swatch: mid-grey, fairly glossy, half anisotropic (so that the anisotropy
#: direction can show); every other channel at its default.
PROBE_BASE = "Layer(1).basecolor(128, 128, 128).roughness(0.3).anisotropy(0.5)"
#: A channel whose range changes the probe by fewer levels (of 255) "cannot show".
VISIBLE_LEVELS = 16
#: Slopes (height units per coordinate unit) whose brightness change is reported.
PROBE_SLOPES = (0.05, 0.2, 1.0)
#: A relief the text converts into a slope at the render size, as an example.
EXAMPLE_STEP = 0.0012
_PROBE_SIZE = 32
_NOT_PROBED = frozenset({"alpha", "height"})


def _probed_channels() -> list[ChannelSpec]:
    """The single-value channels with a search range (colours are visible by construction)."""
    return [
        c
        for c in CHANNELS.values()
        if c.name not in _NOT_PROBED and c.arity == 1 and not c.colour_args and c.search
    ]


@cache
def _image(view: str, layer: str) -> np.ndarray:
    """A probe material shaded in preview layout ``view`` (float, to take differences)."""
    from matloom.author.views import shade_view
    from matloom.engine.evaluate import evaluate

    maps = evaluate(f"Material({layer})", width=_PROBE_SIZE, height=_PROBE_SIZE, backend="numpy")
    try:
        image = shade_view(maps, view, backend="numpy")
    except ValueError:  # a layout without a numpy path
        image = shade_view(maps, view)
    return image.astype(np.float64)


def _difference(view: str, a: str, b: str) -> int:
    """How much two probe materials differ in ``view``: the 95th percentile of the per-pixel
    difference in levels of 255 (a highlight band counts, a stray pixel does not)."""
    return round(float(np.percentile(np.abs(_image(view, a) - _image(view, b)), 95)))


@cache
def channel_changes(view: str) -> dict[str, int]:
    """Per probed channel: the largest :func:`_difference` between the probe swatch with the
    channel at the low end, the middle and the high end of its search range."""
    changes = {}
    for channel in _probed_channels():
        lo, hi = channel.search  # type: ignore[misc]
        layers = [f"{PROBE_BASE}.{channel.name}({v:g})" for v in (lo, (lo + hi) / 2, hi)]
        changes[channel.name] = max(
            _difference(view, a, b) for i, a in enumerate(layers) for b in layers[i + 1 :]
        )
    return changes


@cache
def slope_changes(view: str) -> dict[float, int]:
    """Per probe slope: the largest :func:`_difference` from the flat swatch when it is tilted
    in one of the four axis directions."""
    changes = {}
    for slope in PROBE_SLOPES:
        tilts = [f"{sign}{axis}() * {slope:g}" for axis in ("X", "Y") for sign in ("", "-")]
        changes[slope] = max(
            _difference(view, PROBE_BASE, f"{PROBE_BASE}.height({t})") for t in tilts
        )
    return changes


def module_layout_note(view: str) -> str | None:
    """What the preview module says of layout ``view`` (``LIT_LAYOUT_NOTE`` of
    :mod:`matloom.render.lit`, without its "lit preview: " lead), or None when it says
    nothing."""
    if view != "lit":
        return None
    try:
        from matloom.render.lit import LIT_LAYOUT_NOTE
    except ImportError:
        return None
    note = str(LIT_LAYOUT_NOTE).strip()
    prefix = f"{view} preview: "
    return note[len(prefix) :] if note.lower().startswith(prefix) else note


def _layout_description(view: str) -> str:
    """The layout in words: the preview module's note (``<VIEW>_LAYOUT_NOTE``) when it has one."""
    if view == "flat":
        return "a head-on plane under one fixed light, with no environment to reflect"
    return (module_layout_note(view) or f"the {view} layout").rstrip(".")


def _view_lines(view: str) -> list[str]:
    changes = channel_changes(view)
    listed = ", ".join(f"{name} {levels}" for name, levels in changes.items())
    hidden = [name for name, levels in changes.items() if levels < VISIBLE_LEVELS]
    slopes = " / ".join(str(v) for v in slope_changes(view).values())
    lines = [
        f"- The {view} preview ({_layout_description(view)}). Over its range each channel "
        "changes a mid-grey swatch by (levels of 255, in its most changed 5 % of pixels) "
        f"{listed}; a slope of {' / '.join(f'{s:g}' for s in PROBE_SLOPES)} by {slopes}."
    ]
    if hidden:
        lines.append(
            f"  It cannot show {', '.join(hidden)} (under {VISIBLE_LEVELS} levels): set them "
            "from the description, not to please the preview."
        )
    return lines


def previews_section(size: int, views: Sequence[str] = ("flat",)) -> str:
    """The section for renders of ``size`` x ``size`` px judged in preview layouts ``views``."""
    pixel = 1.0 / size
    return "\n".join(
        [
            "# Resolution and previews",
            f"- Programs are rendered at {size} x {size} px: one pixel is (x2 - x1) / {size} View "
            f"units ({pixel:.5f} for View(0, 0, 1, 1), {6 * pixel:.4f} for View(0, 0, 6, 6)). "
            "Features thinner than about 2 px alias into noise or vanish: keep lines, grout, "
            f"fibres and threads at least 2 px wide, at most about {size // 4} repeats across "
            "the View (base_freq x View width for noise).",
            "- Relief shows only through slopes (height change / distance), never through the "
            "height itself, so a tall smooth bump shows less than a low sharp edge. A hard edge "
            f"rises within one pixel: at View(0, 0, 1, 1) a step of {EXAMPLE_STEP:g} units is a "
            f"slope of {EXAMPLE_STEP * size:.2f}.",
            *(line for view in views for line in _view_lines(view)),
        ]
    )


# ------------------------------------------------------------------ what each layout can show

#: The sheen probe: a dark red cloth (sheen shows most on dark colours), flat and on a 45 degree
#: slope (slope 1) in each axis direction.
SHEEN_PROBE = "Layer(1).basecolor(120, 20, 40).roughness(0.8)"
#: The uncovered probe: a layer of coverage 0 (a vivid colour and a slope, so that anything of
#: it showing through would be seen).
UNCOVERED_PROBE = "Layer(0).basecolor(200, 30, 30).height(X() * 0.5)"


@cache
def sheen_changes(view: str) -> tuple[int, int]:
    """(flat, slope): how much sheen 1 changes the sheen probe against sheen 0 in ``view``
    (levels of 255, :func:`_difference`) on a flat swatch, and the least change over the
    four directions of a 45 degree slope."""
    flat = _difference(view, SHEEN_PROBE, f"{SHEEN_PROBE}.sheen(1)")
    tilts = [f".height({sign}{axis}() * 1)" for axis in ("X", "Y") for sign in ("", "-")]
    slope = min(
        _difference(view, SHEEN_PROBE + tilt, f"{SHEEN_PROBE}.sheen(1){tilt}") for tilt in tilts
    )
    return flat, slope


@cache
def uncovered_look(view: str) -> str:
    """How texels of coverage 0 look in ``view``, measured on :data:`UNCOVERED_PROBE`: one flat
    colour, or a checker (its two colours and cells across the image)."""
    image = _image(view, UNCOVERED_PROBE).astype(np.uint8)
    colours = np.unique(image.reshape(-1, 3), axis=0)
    names = " and ".join(f"sRGB ({', '.join(str(int(c)) for c in colour)})" for colour in colours)
    if len(colours) == 1:
        grey = len(set(colours[0].tolist())) == 1
        return f"flat {'grey ' if grey else ''}{names}"
    row = image[_PROBE_SIZE // 2, :, 0]
    cells = 1 + int(np.count_nonzero(np.diff(row.astype(np.int16))))
    return f"a checker of {names}, {cells} cells across the image"


#: Short descriptions of the layouts for :func:`layout_facts` (the long ones are the preview
#: modules' notes, which the critic prompt may also quote).
_SHORT_DESCRIPTIONS: dict[str, str] = {
    "flat": "the reference's swatch: Blinn-Phong under one fixed light, no environment",
    "lit": "shaded physically in a small studio, grazing key light from the upper left",
}


def _sheen_text(view: str) -> str:
    flat, slope = sheen_changes(view)
    if slope >= VISIBLE_LEVELS and slope > 1.25 * flat:
        return (
            f"sheen shows as a bright rim where the relief slopes steeply (sheen 1 changes a 45° "
            f"slope of dark cloth by {slope} levels) and as a soft lift on flat cloth ({flat} "
            "levels): give cloth thread or pile relief for the rim to show"
        )
    if max(flat, slope) >= VISIBLE_LEVELS:
        return (
            f"sheen shows only as a lift of the colour ({flat} levels flat, {slope} on a 45° slope)"
        )
    return f"sheen barely shows ({flat} levels flat, {slope} on a 45° slope of dark cloth)"


def _layout_facts(view: str) -> str:
    changes = {k: v for k, v in channel_changes(view).items() if k != "sheen"}
    shown = [name for name, levels in changes.items() if levels >= VISIBLE_LEVELS]
    hidden = [name for name, levels in changes.items() if levels < VISIBLE_LEVELS]
    relief = ", ".join(f"slope {s:g}: {levels}" for s, levels in slope_changes(view).items())
    description = _SHORT_DESCRIPTIONS.get(view) or _layout_description(view)
    lines = [
        f"- {view} ({description}):",
        f"  shows base colour and pattern; {', '.join(shown) or 'no single-value channel'} "
        f"(each changes it by at least {VISIBLE_LEVELS} levels of 255 over its range); relief "
        f"through its slopes ({relief} levels): steep relief shows strongly and can be "
        "mistaken for colour;",
        f"  {_sheen_text(view)};",
    ]
    if hidden:
        lines.append(f"  cannot show {', '.join(hidden)} (under {VISIBLE_LEVELS} levels);")
    lines.append(
        f"  uncovered areas (alpha 0) appear as {uncovered_look(view)}, and partly covered ones "
        "blend toward it: such a patch is a hole in the layers, not a colour to fix by "
        "repainting."
    )
    return "\n".join(lines)


def layout_facts(views: Sequence[str] = ("flat", "lit")) -> str:
    """What each preview layout of ``views`` can and cannot show, measured with the preview
    itself: the channels that change it, relief, sheen and how uncovered areas look (for the
    critic's system prompt; docs/preview.md says the same in prose)."""
    return "\n".join(
        ["What each preview layout can and cannot show (measured on probe swatches):"]
        + [_layout_facts(view) for view in views]
    )
