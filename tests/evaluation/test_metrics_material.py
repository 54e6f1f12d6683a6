"""Material metrics (seams, pbr, relight, size, authoring) on programs and maps whose answers
are known, and the metric registry (names, errors, entry points)."""

from __future__ import annotations

import dataclasses
import math
from typing import Any

import numpy as np
import pytest

from matloom.engine.colour import srgb_to_linear
from matloom.engine.evaluate import evaluate
from matloom.engine.tiling import manifest_entry
from matloom.evaluation.metrics import base, registry
from matloom.evaluation.metrics import material_values as V
from matloom.evaluation.metrics.base import MetricUnavailableError, Sample
from matloom.evaluation.metrics.material import FAMILIES, MaterialMetric
from matloom.evaluation.metrics.registry import get_metric
from matloom.io.export import MAP_SPECS

GREY = "Material(Layer(1).basecolor(128, 128, 128).roughness(0.5))"
#: A red ramp across a View that does not repeat: the wrap edge jumps from 255 to 0.
RAMP = "Material(Layer(1).basecolor((X() * 255), 0, 0).roughness(0.5))"
TILING_FBM = (
    "View(0, 0, 2, 2, tileable=True)\nMaterial(Layer(1).basecolor(128, 128, 128).roughness(0.5)"
    ".height((fBm(octaves=4, base_freq=3, to_01=True, seed=3) * 0.05)))"
)
#: Ridges along y: light from the left and from the right shade them differently.
GROOVES = (
    "Material(Layer(1).basecolor(128, 128, 128).roughness(0.5)"
    ".height((Abs(Sin((X() * 40))) * 0.03)))"
)


def sample(program: str, size: int = 32, **kw: Any) -> Sample:
    return Sample(id=kw.pop("id", "s"), prompt="p", program=program, size=size, **kw)


def values(name: str, program: str, size: int = 32, **options: Any) -> dict[str, float]:
    return get_metric(name, options).score([sample(program, size)])[0]


def grey_maps(size: int = 4) -> Any:
    return evaluate(GREY, size, size, backend="numpy")


# --- seams -----------------------------------------------------------------------------------


def test_constant_program_has_seam_ratio_one_on_every_map() -> None:
    got = values("seams", GREY)
    names = [f"seam_ratio.{s.name}" for s in MAP_SPECS]
    assert all(got[n] == 1.0 for n in names)
    assert got["seam_ratio.max"] == 1.0 and got["seam_ratio.tiles"] == 1.0


def test_a_ramp_that_does_not_repeat_has_a_large_seam() -> None:
    got = values("seams", RAMP)
    # 32 texels: the edge jumps by the whole ramp, interior neighbours by 1/31 of it
    assert got["seam_ratio.basecolor"] > 20
    assert got["seam_ratio.max"] == got["seam_ratio.basecolor"]
    assert got["seam_ratio.tiles"] == 0.0


def test_seam_values_match_the_manifest_of_a_tileable_render() -> None:
    got = values("seams", TILING_FBM, size=48)
    maps = evaluate(TILING_FBM, 48, 48)
    recorded = manifest_entry(maps, MAP_SPECS)["seam_ratio"]
    assert {k: got[f"seam_ratio.{k}"] for k in recorded} == recorded
    assert got["seam_ratio.height"] < 2.0 and got["seam_ratio.tiles"] == 1.0


# --- pbr -------------------------------------------------------------------------------------


def test_pbr_shares_of_a_plausible_grey_are_exact() -> None:
    got = values("pbr", GREY)
    assert got["pbr.dielectric_albedo"] == 1.0
    assert math.isnan(got["pbr.metal_albedo"])  # no metal texels
    assert got["pbr.metallic_binary"] == 1.0 and got["pbr.roughness_range"] == 1.0
    assert got["pbr.normal_unit"] == 1.0 and got["pbr.normal_backfacing"] == 0.0
    # a flat normal (0, 0, 1) stores x and y as 128/255: |n| - 1 = (2 (128/255 - 0.5))**2 ...
    off = 128 / 255 * 2 - 1
    assert got["pbr.normal_length_error"] == round(math.sqrt(2 * off * off + 1) - 1, 6)
    assert got["pbr.plausible"] == 1.0


def test_half_metallic_everywhere_scores_zero_on_metallic_near_0_or_1() -> None:
    got = values("pbr", "Material(Layer(1).basecolor(200, 200, 200).metallic(0.5).roughness(0.01))")
    assert got["pbr.metallic_binary"] == 0.0
    assert got["pbr.roughness_range"] == 0.0  # 0.01 is below Filament's 0.045
    assert got["pbr.plausible"] == 0.5


def test_a_too_dark_dielectric_fails_the_albedo_range() -> None:
    got = values("pbr", "Material(Layer(1).basecolor(10, 10, 10).roughness(0.5))")
    assert got["pbr.dielectric_albedo"] == 0.0 and got["pbr.albedo"] == 0.0
    assert got["pbr.plausible"] == 0.75


def test_pbr_shares_per_texel_on_hand_built_maps() -> None:
    maps = grey_maps()
    lo, hi = V.DIELECTRIC_MIN, V.DIELECTRIC_MAX
    metal_lo = V.METAL_MIN
    # columns: dielectric in range, dielectric too bright, metal in range, metal too dark
    metallic = np.tile(np.array([0.0, 0.05, 1.0, 0.95], np.float32), (4, 1))
    luma = np.tile(np.array([(lo + hi) / 2, hi + 0.05, metal_lo + 0.1, metal_lo - 0.1]), (4, 1))
    rough = np.tile(np.array([0.5, 0.02, 0.045, 1.0], np.float32), (4, 1))
    alpha = np.ones((4, 4), np.float32)
    alpha[3] = 0.0  # the last row is uncovered: it does not count
    bad = dataclasses.replace(
        maps,
        metallic=metallic,
        basecolor_linear=np.repeat(luma[..., None], 3, axis=2).astype(np.float32),
        roughness=rough,
        alpha=alpha,
    )
    got = V.pbr_values(bad)
    assert got["pbr.dielectric_albedo"] == 0.5
    assert got["pbr.metal_albedo"] == 0.5
    assert got["pbr.albedo"] == 0.5
    assert got["pbr.metallic_binary"] == 1.0  # 0.05 and 0.95 are near 0 and 1
    assert got["pbr.roughness_range"] == 0.75  # 0.02 is out
    assert got["pbr.plausible"] == round((0.5 + 1.0 + 0.75 + 1.0) / 4, 6)


def test_a_mis_normalised_normal_map_scores_badly() -> None:
    maps = grey_maps()
    half = np.zeros((4, 4, 3), np.float32)
    half[..., 2] = 0.5  # length 0.5
    half[:2, :, 2] = -1.0  # the top half points into the surface
    got = V.pbr_values(dataclasses.replace(maps, normal=half))
    assert got["pbr.normal_backfacing"] == 0.5
    assert got["pbr.normal_unit"] == 0.0
    assert 0.24 < got["pbr.normal_length_error"] < 0.26  # half the texels off by 0.5
    assert got["pbr.plausible"] == 0.75


def test_nan_texels_are_implausible() -> None:
    maps = grey_maps()
    rough = np.full((4, 4), 0.5, np.float32)
    rough[0, 0] = np.nan
    assert V.pbr_values(dataclasses.replace(maps, roughness=rough))["pbr.roughness_range"] == 0.9375


def test_the_ranges_are_the_cited_srgb_levels() -> None:
    assert V.DIELECTRIC_MIN == pytest.approx(float(srgb_to_linear(30 / 255)))
    assert V.DIELECTRIC_MAX == pytest.approx(0.8714, abs=1e-4)
    assert V.METAL_MIN == pytest.approx(0.4564, abs=1e-4)


# --- relight ---------------------------------------------------------------------------------


def test_image_statistics_of_known_images() -> None:
    white = np.full((4, 4, 3), 255, np.uint8)
    assert V.image_statistics(white) == (pytest.approx(1.0), 0.0, 1 / 3, 1 / 3)
    half = np.zeros((2, 2, 3), np.uint8)
    half[0] = 255  # half white, half black: mean 0.5, std 0.5
    mean, std, r, g = V.image_statistics(half)
    assert (mean, std) == (pytest.approx(0.5), pytest.approx(0.5))
    red = np.zeros((2, 2, 3), np.uint8)
    red[..., 0] = 255
    assert V.image_statistics(red)[2:] == (1.0, 0.0)


def test_relief_with_a_direction_drifts_more_than_a_flat_material() -> None:
    flat = values("relight", GREY, size=48)
    ridges = values("relight", GROOVES, size=48)
    assert flat["relight.mean_drift"] < 0.02 and flat["relight.consistency"] > 0.95
    assert ridges["relight.mean_drift"] > 5 * flat["relight.mean_drift"]
    assert ridges["relight.consistency"] < flat["relight.consistency"]
    assert 0 < ridges["relight.consistency"] <= 1


def test_three_distinct_lights() -> None:
    lights = V.relight_lights()
    assert len({light.direction() for light in lights}) == 3


def test_the_same_program_gives_the_same_numbers() -> None:
    a = values("material", TILING_FBM, size=40)
    b = values("material", TILING_FBM, size=40)
    assert a.keys() == b.keys()
    assert all(a[k] == b[k] or (math.isnan(a[k]) and math.isnan(b[k])) for k in a)


# --- size and authoring ----------------------------------------------------------------------

PROGRAM = """# a comment line
View(0, 0, 2, 2)

Define(n, fBm(octaves=3, seed=1))  # trailing comment
Material(
  Layer(1).basecolor((n * 200), 90, 80),
  Layer(n).roughness(0.4)
)
"""


def test_program_size_counts() -> None:
    got = values("size", PROGRAM)
    assert got["size.characters"] == len(PROGRAM)
    assert got["size.lines"] == 6  # 8 lines: the comment-only and blank ones are not code
    assert got["size.layers"] == 2 and got["size.defines"] == 1
    # define: Call(fBm, octaves=3, seed=1) = 3 nodes; layer 0: alpha 1, (n * 200) = 3, 90, 80;
    # layer 1: alpha n, 0.4
    assert got["size.nodes"] == 3 + 1 + 3 + 1 + 1 + 1 + 1
    assert got["size.calls"] == 1


def test_size_of_text_that_does_not_parse() -> None:
    got = values("size", "Material(Layer(1).basecolor(1, 2")
    assert got["size.characters"] == 32 and got["size.lines"] == 1
    assert math.isnan(got["size.layers"]) and math.isnan(got["size.nodes"])


def test_authoring_from_the_record() -> None:
    metric = get_metric("authoring")
    rec = {"seconds": 12.5, "prompt_tokens": 1000, "completion_tokens": 250}
    got = metric.score([sample(GREY, record=rec), sample(GREY)])
    assert got[0] == {
        "authoring.seconds": 12.5,
        "authoring.prompt_tokens": 1000.0,
        "authoring.completion_tokens": 250.0,
        "authoring.tokens": 1250.0,
    }
    assert all(math.isnan(v) for v in got[1].values())


# --- the metric objects ----------------------------------------------------------------------


def test_material_reports_every_family_from_one_evaluation(monkeypatch: Any) -> None:
    metric = get_metric("material", {"size": 24})
    assert isinstance(metric, MaterialMetric) and metric.families == FAMILIES
    calls = []
    real = MaterialMetric.maps_of
    monkeypatch.setattr(MaterialMetric, "maps_of", lambda self, s: calls.append(s) or real(self, s))
    got = metric.score([sample(GREY)])[0]
    assert len(calls) == 1
    assert {k.split(".")[0] for k in got} == {"seam_ratio", "pbr", "relight", "size", "authoring"}
    assert metric.layouts == ()


def test_a_program_that_does_not_evaluate_gives_nan_and_says_why() -> None:
    metric = get_metric("material")
    got = metric.score([sample("Material(Layer(1).basecolor(1, 2", id="broken")])[0]
    assert all(math.isnan(got[k]) for k in got if k.startswith(("seam_ratio", "pbr", "relight")))
    assert "E010" in metric.errors["broken"]
    assert got["size.characters"] == 32


def test_bad_options_are_one_line_errors() -> None:
    for name, options in [
        ("seams", {"size": "big"}),
        ("pbr", {"tileable": "maybe"}),
        ("seams:x", {}),
    ]:
        with pytest.raises(MetricUnavailableError) as err:
            get_metric(name, options)
        assert "\n" not in str(err.value)


# --- registry --------------------------------------------------------------------------------


def test_registry_knows_the_material_families() -> None:
    names = registry.metric_names()
    assert {"seams", "pbr", "relight", "size", "authoring", "material", "judge"} <= set(names)
    for name in ("seams", "pbr", "relight", "size", "authoring", "material"):
        metric = get_metric(name)
        assert metric.name == name and isinstance(metric, base.Metric)


def test_unknown_metric_is_a_one_line_error() -> None:
    with pytest.raises(MetricUnavailableError) as err:
        get_metric("no-such-metric:opt")
    message = str(err.value)
    assert "no-such-metric" in message and "seams" in message and "\n" not in message


class _EntryPoint:
    def __init__(self, name: str, factory: Any) -> None:
        self.name = name
        self._factory = factory

    def load(self) -> Any:
        return self._factory


def test_entry_points_add_metrics(monkeypatch: pytest.MonkeyPatch) -> None:
    class Constant:
        name = "const"
        layouts = ()

        def score(self, samples: Any) -> list[dict[str, float]]:
            return [{"const.value": 7.0} for _ in samples]

    seen: list[tuple[str, dict[str, Any]]] = []

    def factory(name: str, options: dict[str, Any]) -> Constant:
        seen.append((name, options))
        return Constant()

    groups: list[str] = []

    def entry_points(group: str) -> list[_EntryPoint]:
        groups.append(group)
        return [_EntryPoint("const", factory), _EntryPoint("seams", lambda n, o: None)]

    registry.load_builtin_metrics()
    monkeypatch.setattr(registry, "FACTORIES", dict(base.FACTORIES))
    monkeypatch.setitem(registry._STATE, "loaded", False)
    monkeypatch.setattr(registry.metadata, "entry_points", entry_points)
    metric = get_metric("const:abc", {"k": 1})
    assert groups == [base.ENTRY_POINT_GROUP]
    assert seen == [("const:abc", {"k": 1})]
    assert metric.score([sample(GREY)]) == [{"const.value": 7.0}]
    # a built-in keeps its name: the entry point called "seams" does not replace it
    assert isinstance(get_metric("seams"), MaterialMetric)


def test_maps_carried_by_the_sample_are_used_at_their_size() -> None:
    """``matloom dataset`` hands its rendered maps over: the metric measures them, not the text
    (here the text is a seamless grey and the maps a seamed ramp); at another size it evaluates."""
    ramp = evaluate(RAMP, 32, 32, backend="numpy")
    carried = get_metric("seams", {"tileable": "false"}).score([sample(GREY, 32, maps=ramp)])[0]
    assert carried == values("seams", RAMP, 32, tileable="false")
    assert carried["seam_ratio.max"] > 2
    other_size = get_metric("seams", {"tileable": "false", "size": 16})
    assert other_size.score([sample(GREY, 32, maps=ramp)])[0]["seam_ratio.max"] <= 1.01
