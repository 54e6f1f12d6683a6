"""Per-layer coverage and the sources of the repeating patterns: statistics that need the program.

:mod:`matloom.render.visible_stats` describes the composited maps. Two things a reader of those
statistics cannot get from the maps alone, and which a critic had to guess by eye:

* **Coverage per layer**: the share of the image where each layer is visible after compositing.
  The "over" rule of :mod:`matloom.engine.composite`, from the top layer down with running = 1:
  V_i = a_i * running, running *= 1 - a_i, with a_i the layer's alpha clamped to [0, 1] (NaN
  counts as 0 here). The visible share of layer i is the mean of V_i over the image; the share
  its own mask covers is the mean of a_i (larger when upper layers hide part of it).
* **Pattern sources**: for each repeating pattern the visible statistics report (albedo and
  height), the named parts of the program whose own field has a spectral peak at the same wave
  vector: every Define (a constant or parameterised one has no field of its own and is left
  out), each layer's mask (alpha) and, for an albedo pattern, each layer's colour (Rec.709
  luminance of its r, g, b expressions), for a height pattern each layer's height. Each field is
  evaluated alone on the same grid as the maps, over the same material mask and window
  (:func:`matloom.render.spectrum.power_spectrum`), and carries the pattern when the brightest
  local maximum within one bin of the pattern's wave vector stands out by
  :data:`~matloom.render.spectral_peaks.MIN_PEAK_STRENGTH` (:func:`~matloom.render.spectral_peaks.peak_strengths_at`). A pattern
  no part carries alone comes from combining them (a product of two stripe fields, a warp).

Everything is deterministic: the fields are the interpreter's, at the maps' size, program seed 0
(as :func:`matloom.engine.evaluate.evaluate` and the critic's previews).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

import numpy as np

from matloom.engine.backends import session_backend
from matloom.engine.evaluate import Evaluator, prepare
from matloom.engine.grid import sample_axes
from matloom.engine.maps import MaterialMaps, View
from matloom.engine.session import default_session, running
from matloom.lang import ast as A
from matloom.lang.printer import format_expr
from matloom.render import spectrum, visible_stats
from matloom.render.spectral_peaks import peak_strengths_at
from matloom.render.stats import MASK_THRESHOLD

if TYPE_CHECKING:
    from matloom.engine.session import Session

#: Longest alpha expression quoted in a layer's label (longer ones are cut with an ellipsis).
LABEL_CHARS: int = 40

#: Most sources named per pattern (in program order: Defines, then layers).
MAX_SOURCES: int = 8

#: Rec.709 weights of a layer colour's luminance (on the authored 0..255 scale).
_REC709 = (0.2126, 0.7152, 0.0722)


@dataclass(frozen=True)
class _Parts:
    """An interpreter set up on the maps' grid, and the program it evaluates."""

    ev: Evaluator
    program: A.Program
    shape: tuple[int, int]

    def plane(self, node: A.Node) -> np.ndarray:
        """The field of ``node`` as a finite float64 (H, W) array (NaN/inf -> 0)."""
        values = np.broadcast_to(np.asarray(self.ev.field(node), np.float64), self.shape)
        return np.where(np.isfinite(values), values, 0.0)


def _parts(program_or_text: A.Program | str, width: int, height: int, session: Session) -> _Parts:
    """The interpreter of the program's fields on the grid :func:`evaluate` samples."""
    program = prepare(program_or_text, 0, session=session)
    view = View(*program.view_tuple)
    if program.tileable and not view.tileable:
        view = replace(view, tileable=True)
    x, y = sample_axes(view, width, height)
    backend = session_backend(session, "auto", width * height)
    ev = Evaluator(program, x, y, backend, periods=view.periods)
    return _Parts(ev, program, (height, width))


def _alpha(parts: _Parts, layer: A.Layer) -> np.ndarray:
    """The layer's alpha as composited: clamped to [0, 1], NaN counted as 0."""
    if layer.alpha is None:
        return np.ones(parts.shape)
    return np.clip(parts.plane(layer.alpha), 0.0, 1.0)


def visible_shares(alphas: list[np.ndarray]) -> list[float]:
    """Mean visible coverage of each layer (bottom first) under the "over" rule."""
    running = np.ones_like(alphas[0]) if alphas else np.ones((1, 1))
    shares = [0.0] * len(alphas)
    for i in range(len(alphas) - 1, -1, -1):
        shares[i] = float((alphas[i] * running).mean())
        running = running * (1.0 - alphas[i])
    return shares


def _label(index: int, layer: A.Layer) -> str:
    if layer.alpha is None:
        return f"layer {index}"
    text = format_expr(layer.alpha)
    if len(text) > LABEL_CHARS:
        text = text[: LABEL_CHARS - 1] + "…"
    return f"layer {index} (alpha {text})"


def _is_constant(node: A.Node) -> bool:
    return isinstance(node, A.Num | A.Const)


def _candidates(parts: _Parts, maps: tuple[str, ...]) -> list[tuple[str, str, np.ndarray]]:
    """(name, map, field) of every part that may carry a pattern of the ``albedo`` or
    ``height`` (``maps``: those with patterns); ``map`` is "" for the parts (Defines, masks)
    that may carry either."""
    out: list[tuple[str, str, np.ndarray]] = []
    for define in parts.program.defines:
        if not _is_constant(define.expr):
            out.append((f"Define `{define.name}`", "", parts.plane(A.Ref(define.name))))
    for index, layer in enumerate(parts.program.layers):
        if layer.alpha is not None and not _is_constant(layer.alpha):
            out.append((f"layer {index}'s mask", "", _alpha(parts, layer)))
        colour, height = layer.channel("basecolor"), layer.channel("height")
        if "albedo" in maps and colour is not None and not all(map(_is_constant, colour.args)):
            rgb = [parts.plane(a) for a in colour.args[:3]]
            field = np.asarray(sum(w * c for w, c in zip(_REC709, rgb, strict=True)))
            out.append((f"layer {index}'s colour", "albedo", field))
        if "height" in maps and height is not None and not _is_constant(height.args[0]):
            out.append((f"layer {index}'s height", "height", parts.plane(height.args[0])))
    return out


def _wave_vector(pattern: dict[str, Any], spec: spectrum.Spectrum) -> tuple[float, float]:
    """(kx, ky) in bins of ``spec`` of a visible-statistics pattern (period, orientation)."""
    angle = math.radians(pattern["orientation_deg"])
    period = pattern["period_px"]
    return math.cos(angle) * spec.width / period, math.sin(angle) * spec.height / period


def _sources(
    patterns: list[tuple[str, dict[str, Any]]],
    candidates: list[tuple[str, str, np.ndarray]],
    mask: np.ndarray,
) -> list[list[str]]:
    """Per (map, pattern), the names of the candidates of that map whose field has a peak at
    the pattern's wave vector (each field's spectrum taken once)."""
    names: list[list[str]] = [[] for _ in patterns]
    for name, where, field in candidates:
        tested = [k for k, (what, _) in enumerate(patterns) if where in ("", what)]
        if not tested or float(np.ptp(field)) == 0.0:
            continue
        spec = spectrum.power_spectrum(field, mask)
        if spec is None or spec.total <= 0.0:
            continue
        vectors = [_wave_vector(patterns[k][1], spec) for k in tested]
        for k, strength in zip(tested, peak_strengths_at(spec, vectors), strict=True):
            if strength > 0.0:
                names[k].append(name)
    return names


def layer_stats(
    program_or_text: A.Program | str,
    maps: MaterialMaps,
    visible: dict[str, Any],
    *,
    session: Session | None = None,
) -> dict[str, Any]:
    """Coverage per layer and the sources of ``visible``'s patterns (the dict of
    :func:`matloom.render.visible_stats.visible_stats` of ``maps``, the program's maps).

    Keys: ``layers``, a list (bottom first) of {label, visible_share, mask_share}; ``sources``,
    a list of {map: "albedo" | "height", period_px, orientation_deg, sources: [names]} in the
    order the patterns are reported.
    """
    s = session or default_session()
    with s.lock, running(s), warnings.catch_warnings(), np.errstate(all="ignore"):
        warnings.simplefilter("ignore", RuntimeWarning)
        parts = _parts(program_or_text, maps.width, maps.height_px, s)
        alphas = [_alpha(parts, layer) for layer in parts.program.layers]
        shares = visible_shares(alphas)
        layers = [
            {"label": _label(i, layer), "visible_share": v, "mask_share": float(a.mean())}
            for i, (layer, v, a) in enumerate(
                zip(parts.program.layers, shares, alphas, strict=True)
            )
        ]
        mask = np.asarray(maps.alpha, np.float64) > MASK_THRESHOLD
        patterns = [
            (what, pattern)
            for what, section in (("albedo", "albedo"), ("height", "relief"))
            for pattern in (visible.get(section) or {}).get("patterns") or []
        ]
        maps_with = tuple(dict.fromkeys(what for what, _ in patterns))
        sources = _sources(patterns, _candidates(parts, maps_with), mask) if patterns else []
        found = [
            {
                "map": what,
                "period_px": pattern["period_px"],
                "orientation_deg": pattern["orientation_deg"],
                "sources": names,
            }
            for (what, pattern), names in zip(patterns, sources, strict=True)
        ]
    return {"layers": layers, "sources": found}


def format_layer_stats(stats: dict[str, Any]) -> str:
    """The text block of :func:`layer_stats` for a prompt."""
    lines = [
        "Layers (0 = bottom; visible = where the layer shows once the layers above it are laid "
        "over it, the compositing's over rule):"
    ]
    for layer in stats["layers"]:
        visible, own = layer["visible_share"] * 100.0, layer["mask_share"] * 100.0
        hidden = f" (its mask covers {own:.0f} %)" if round(own) != round(visible) else ""
        lines.append(f"- {layer['label']}: visible on {visible:.0f} % of the image{hidden}")
    if stats["sources"]:
        lines.append(
            "Pattern sources (the Defines and layer parts whose own field repeats at the "
            "pattern's period and orientation):"
        )
    for item in stats["sources"]:
        names = item["sources"]
        shown = ", ".join(names[:MAX_SOURCES]) + (", …" if len(names) > MAX_SOURCES else "")
        where = shown or "no part alone (it comes from combining them)"
        angle = round(item["orientation_deg"]) % 180
        lines.append(
            f"- {item['map']} pattern every {item['period_px']:.1f} px at {angle}° "
            f"({visible_stats.orientation_words(item['orientation_deg'])}): {where}"
        )
    return "\n".join(lines)


def visible_stats_text(
    program_or_text: A.Program | str, maps: MaterialMaps, *, session: Session | None = None
) -> str:
    """The visible statistics of ``maps`` followed by the program's layer coverage and pattern
    sources (``maps`` are the program's, evaluated at the critique size)."""
    visible = visible_stats.visible_stats(maps)
    text = visible_stats.format_visible_stats(visible)
    if maps.n_layers == 0 or not visible.get("coverage"):
        return text
    return (
        text
        + "\n"
        + format_layer_stats(layer_stats(program_or_text, maps, visible, session=session))
    )
