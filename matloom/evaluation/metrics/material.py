"""Material metrics: exact measurements of a program and its maps, no weights, no images.

Families (each a metric name; ``material`` computes all five from one evaluation):

``seams``
    ``seam_ratio.<map>`` for each of the 14 exported maps (``basecolor`` ... ``ao``): the
    program evaluated at ``Sample.size`` as a tileable render (``tileable=True``, as
    ``matloom render --tileable`` does), then the mean |difference| across the wrap edges over
    the mean |difference| of interior neighbours (:func:`matloom.engine.tiling.seam_ratio`, the
    number ``material.json`` records). Unitless, >= 0: 1.0 = the wrap edge is as smooth as the
    interior (also any constant map), a visible seam gives 2 to 50, ``inf`` a step on an
    otherwise constant map. ``seam_ratio.max`` is the worst map; ``seam_ratio.tiles`` is 1.0
    when every map is within the export's bound (2.0), else 0.0. Limits: one line of texels
    per edge is compared (docs/tileable.md); option ``tileable=False`` measures the program's
    own View instead.
``pbr``
    PBR plausibility, shares on [0, 1] (coverage-weighted, higher is better):
    ``pbr.dielectric_albedo`` (texels with metallic <= 0.5 whose base colour luminance -- linear
    Rec.709 -- lies within 30..240 sRGB, 0.0130..0.8714 linear; NaN without such texels),
    ``pbr.metal_albedo`` (metallic > 0.5 texels within 180..255 sRGB, 0.4564..1.0 linear),
    ``pbr.albedo`` (each texel against its own range), ``pbr.metallic_binary`` (metallic <= 0.1
    or >= 0.9), ``pbr.roughness_range`` (roughness within 0.045..1), ``pbr.normal_unit``
    (decoded 8-bit ``normal_gl.png`` texels within 0.02 of unit length and facing out);
    ``pbr.normal_length_error`` is the mean | |n| - 1 | of the decoded normals (about 0.002
    from 8-bit quantisation alone) and ``pbr.normal_backfacing`` the share with z < 0 (both
    lower is better). ``pbr.plausible`` = mean of albedo, metallic_binary, roughness_range and
    normal_unit. Limits: ranges from authoring guides (:mod:`.material_values` cites them), not
    measurements; emissive, transmissive and painted materials may leave them on purpose.
``relight``
    The ``lit`` preview (:func:`matloom.render.lit.shade_lit`) under three key lights (the
    studio's, turned by 0, 120 and 240 degrees at 25 degrees elevation; the fill light and
    environment fixed). Per render: mean and standard deviation of linear luminance and the
    mean r, g chromaticity. ``relight.mean_drift`` = (max - min mean) / mean of means,
    ``relight.contrast_drift`` = (max - min std) / mean of means, ``relight.colour_drift`` =
    largest chromaticity distance between two renders; ``relight.luminance`` = mean of means;
    ``relight.consistency`` = exp(-(sum of the three drifts)) on (0, 1]. Good: flat, isotropic
    materials stay below about 0.05 of drift (consistency ~0.95); strong directional relief
    (grooves, ridges) drifts legitimately, so compare systems on the same prompt rather than
    against an absolute bar.
``size``
    ``size.characters``, ``size.lines`` (lines holding code), ``size.tokens`` (DSL tokens),
    ``size.layers``, ``size.defines``, ``size.nodes`` (expression nodes) and ``size.calls``
    (function calls); counts, NaN where the text does not parse.
``authoring``
    ``authoring.seconds``, ``authoring.prompt_tokens``, ``authoring.completion_tokens`` and
    ``authoring.tokens`` from ``Sample.record``; NaN when not recorded (the offline library).

Determinism: maps from the engine's evaluation (``backend`` option, default the session's
choice), reductions exact (:mod:`.material_values`), shares rounded to 6 decimals and seam ratios
to 4. A program that does not evaluate gives NaN for its map values; :attr:`MaterialMetric.errors`
says why, per sample id.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Mapping, Sequence
from typing import Any

from matloom.engine.evaluate import evaluate
from matloom.engine.limits import LimitError
from matloom.engine.maps import MaterialMaps
from matloom.evaluation.metrics import material_values as V
from matloom.evaluation.metrics.base import MetricUnavailableError, Sample, register_metric

#: Families that need the evaluated maps.
MAP_FAMILIES: tuple[str, ...] = ("seams", "pbr", "relight")
#: Every material family, in the order ``material`` reports them.
FAMILIES: tuple[str, ...] = (*MAP_FAMILIES, "size", "authoring")
#: The family that computes all of them.
ALL = "material"
#: Engine and shader backends a material metric may ask for (``auto``: the session's choice).
BACKENDS: tuple[str, ...] = ("auto", "numpy", "numba")
#: Largest evaluation size accepted (a metric is a check, not an export).
MAX_SIZE = 2048


def map_value_names(family: str) -> tuple[str, ...]:
    """The value names a map family reports (what a failed evaluation fills with NaN)."""
    if family == "seams":
        names = [f"seam_ratio.{s.name}" for s in V.MAP_SPECS if s.sources]
        return (*names, "seam_ratio.max", "seam_ratio.tiles")
    if family == "pbr":
        return V.PBR_NAMES
    if family == "relight":
        return V.RELIGHT_NAMES
    raise ValueError(f"{family!r} is not a map family")


class MaterialMetric:
    """One or more material families over a batch of samples."""

    def __init__(
        self,
        name: str,
        families: Sequence[str],
        *,
        size: int | None = None,
        tileable: bool = True,
        backend: str = "auto",
    ) -> None:
        self._name = name
        self.families = tuple(families)
        self.size = size
        self.tileable = tileable
        self.backend = backend
        #: Sample id -> why its maps could not be measured (from the last :meth:`score`).
        self.errors: dict[str, str] = {}

    @property
    def name(self) -> str:
        return self._name

    @property
    def layouts(self) -> tuple[str, ...]:
        return ()

    def maps_of(self, sample: Sample) -> MaterialMaps:
        """The sample's maps at its size (or the ``size`` option), evaluated as configured; the
        sample's own ``maps`` when it carries them at that size."""
        side = self.size or sample.size
        if sample.maps is not None and side == sample.size:
            return sample.maps
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # the numbers say what the warnings would
            return evaluate(
                sample.program, side, side, backend=self.backend, tileable=self.tileable
            )

    def score_one(self, sample: Sample) -> dict[str, float]:
        """Every value of this metric's families for one sample."""
        out: dict[str, float] = {}
        wanted = [f for f in self.families if f in MAP_FAMILIES]
        maps = None
        if wanted:
            try:
                maps = self.maps_of(sample)
            except (ValueError, LimitError, ArithmeticError, MemoryError) as err:
                self.errors[sample.id] = " ".join(str(err).split())[:500]
        for family in self.families:
            if family in MAP_FAMILIES and maps is None:
                out.update(dict.fromkeys(map_value_names(family), math.nan))
            elif family == "seams":
                out.update(V.seam_values(maps))
            elif family == "pbr":
                out.update(V.pbr_values(maps))
            elif family == "relight":
                out.update(V.relight_values(maps, backend=self.backend))
            elif family == "size":
                out.update(V.size_values(sample.program))
            elif family == "authoring":
                out.update(V.authoring_values(sample.record))
        return out

    def score(self, samples: Sequence[Sample]) -> list[dict[str, float]]:
        self.errors = {}
        return [self.score_one(sample) for sample in samples]


def _bool_option(options: Mapping[str, Any], key: str, default: bool) -> bool:
    value = options.get(key, default)
    if isinstance(value, str):
        lowered = value.strip().lower()
        if lowered in ("1", "true", "yes", "on"):
            return True
        if lowered in ("0", "false", "no", "off"):
            return False
        raise MetricUnavailableError(f"option {key}={value!r}: expected true or false")
    return bool(value)


def _size_option(options: Mapping[str, Any]) -> int | None:
    value = options.get("size")
    if value is None:
        return None
    try:
        side = int(value)
    except (TypeError, ValueError):
        raise MetricUnavailableError(f"option size={value!r}: expected a whole number") from None
    if not 8 <= side <= MAX_SIZE:
        raise MetricUnavailableError(f"option size={side}: expected 8 to {MAX_SIZE}")
    return side


def make_material_metric(name: str, options: Mapping[str, Any]) -> MaterialMetric:
    """A factory for every material family: ``seams``, ``pbr``, ``relight``, ``size``,
    ``authoring`` or ``material`` (all). Options: ``size`` (evaluation side; default each
    sample's size), ``tileable`` (default true), ``backend`` (default ``auto``)."""
    family, _, rest = name.partition(":")
    if rest:
        raise MetricUnavailableError(
            f"metric {name!r}: material metrics take no options in the name (pass size, "
            "tileable or backend as options)"
        )
    families = FAMILIES if family == ALL else (family,)
    if not set(families) <= set(FAMILIES):
        raise MetricUnavailableError(f"unknown material metric {name!r}")
    backend = str(options.get("backend", "auto"))
    if backend not in BACKENDS:
        raise MetricUnavailableError(f"option backend={backend!r}: expected {', '.join(BACKENDS)}")
    return MaterialMetric(
        name,
        families,
        size=_size_option(options),
        tileable=_bool_option(options, "tileable", True),
        backend=backend,
    )


for _family in (*FAMILIES, ALL):
    register_metric(_family, make_material_metric)
