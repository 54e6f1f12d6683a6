"""`generate --reference PHOTO` and `--polish cmaes` against the scripted server on 127.0.0.1.

Small sizes throughout (32-48 px) and small fit budgets: the CMA-ES tests recover parameter
values a target render was made with; the run tests check what the models receive, what the
record keeps, and the keep-only-if-not-worse guard.
"""

from __future__ import annotations

import base64
import hashlib
import io
import json
import os
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner, Result
from PIL import Image

from author.chat_server import ChatServer
from author.conftest import FAST_FLAGS, Script, image_parts, is_critic, text_of
from matloom.author.records import validate_record_file
from matloom.author.stages.polish_fit import cmaes_minimise, fit_space
from matloom.author.views import Renderer
from matloom.cli.main import cli
from matloom.lang.api import parse
from matloom.render.compare_stats import image_stats, stats_distance

#: The photo's colour: far from every few-shot example's, so it is recognisable in a request.
PHOTO_RGB = (40, 160, 220)


def _photo(path: Path, size: tuple[int, int] = (72, 48)) -> bytes:
    """A blue PNG with light stripes (wider than tall: the crop keeps the middle square)."""
    width, height = size
    pixels = np.empty((height, width, 3), np.uint8)
    pixels[:] = PHOTO_RGB
    pixels[:, ::8] = (90, 200, 240)
    buffer = io.BytesIO()
    Image.fromarray(pixels).save(buffer, format="PNG")
    path.write_bytes(buffer.getvalue())
    return buffer.getvalue()


def _generate(server: ChatServer, out: Path, *extra: str) -> Result:
    flags = ["--model", "test-vision-model", "--base-url", server.base_url]
    flags += ["--retry-backoff", "0.01", "--max-retries", "1", "--timeout", "20"]
    args = ["generate", "blue striped tiles", "-o", str(out), *flags, *FAST_FLAGS, *extra]
    return CliRunner().invoke(cli, args)


def _mean_rgb(part: dict) -> np.ndarray:
    data = base64.b64decode(part["image_url"]["url"].split(",", 1)[1])
    return np.asarray(Image.open(io.BytesIO(data)).convert("RGB"), float).reshape(-1, 3).mean(0)


def _critic_reply(score: int) -> str:
    return json.dumps({"match_score": score, "differences": [], "suggestions": []})


# ------------------------------------------------------------------------------ CMA-ES


def test_cmaes_recovers_a_flat_colour_from_the_photo_statistics() -> None:
    """The reference objective (statistics distance to a target render made with known values)
    brings a colour Delta E 28 off back to within a few units; a seeded fit repeats exactly."""
    from matloom.author.edit.lab import delta_e

    renderer = Renderer()
    target = image_stats(renderer.image("Material(Layer(1).basecolor(170, 110, 60))", 32))
    space = fit_space(parse("Material(Layer(1).basecolor(200, 80, 40))"))
    assert space is not None and [p.address for p in space.params] == ["layer:1.basecolor"]

    def distance(x: np.ndarray) -> float:
        return stats_distance(image_stats(renderer.image(space.text(x), 32)), target)

    fit = cmaes_minimise(distance, space.start(), seed=7, evaluations=100, seconds=60)
    fitted = space.values(fit.x)["layer:1.basecolor"]
    assert delta_e(fitted, (170, 110, 60)) <= 5, fitted  # type: ignore[arg-type]
    assert np.abs(np.subtract(fitted, (170, 110, 60))).max() <= 12, fitted
    assert fit.value < fit.start_value / 5 and fit.evaluations <= 100
    short = [
        cmaes_minimise(distance, space.start(), seed=3, evaluations=14, seconds=60)
        for _ in range(2)
    ]
    assert space.values(short[0].x) == space.values(short[1].x)  # seeded: the same fit twice


def test_cmaes_recovers_a_mortar_width_and_a_roughness_bound_is_respected() -> None:
    """A pixel objective against bricks made with mortar 0.05: the fit starts at 0.03 and
    finds the width within 0.005; every point tried stays inside the windows."""
    program = "View(0, 0, 2, 2)\nMaterial(Layer(1).basecolor(190, 90, 60), Layer(Bricks(mortar={m})).basecolor(220, 220, 210))"
    renderer = Renderer()
    target = renderer.image(program.format(m=0.05), 48).astype(float)
    space = fit_space(parse(program.format(m=0.03)))
    assert space is not None
    mortar = next(d for d in space.dims if d.address.endswith("Bricks.mortar"))
    assert mortar.low <= 0.05 <= mortar.high
    only = [k for k, d in enumerate(space.dims) if d is mortar]
    seen: list[float] = []

    def error(u: np.ndarray) -> float:
        x = space.start()
        x[only] = u
        value = space.values(x)[mortar.address]
        seen.append(float(value))  # type: ignore[arg-type]
        image = renderer.image(space.text(x), 48).astype(float)
        return float(np.mean((image - target) ** 2))

    fit = cmaes_minimise(error, space.start()[only], seed=3, evaluations=30, seconds=60)
    x = space.start()
    x[only] = fit.x
    assert abs(float(space.values(x)[mortar.address]) - 0.05) <= 0.005  # type: ignore[arg-type]
    assert all(mortar.low <= v <= mortar.high for v in seen)


# ------------------------------------------------------------------------------ --reference


def test_reference_photo_reaches_generator_and_critic_and_the_record_keeps_only_its_hash(
    server: ChatServer, tmp_path: Path
) -> None:
    data = _photo(tmp_path / "photo.png")
    photo = str(tmp_path / "photo.png")
    result = _generate(server, tmp_path / "run", "--reference", photo, "--rounds", "1")
    assert result.exit_code == 0, result.stderr

    generator = [r for r in server.requests if not is_critic(r)]
    critic = [r for r in server.requests if is_critic(r)]
    assert generator and critic
    for body in generator + critic:
        last = [m for m in body["messages"] if m["role"] == "user"][-1]
        parts = image_parts(last)
        assert parts, "the photo goes with the newest user turn"
        assert np.abs(_mean_rgb(parts[-1]) - PHOTO_RGB).max() < 25  # the photo, last
        assert "Reference photo: the last attached image" in text_of(last)
    first = [m for m in generator[0]["messages"] if m["role"] == "user"][-1]
    assert len(image_parts(first)) == 1  # P0's request: the photo only, no preview yet
    assert len(image_parts([m for m in critic[0]["messages"] if m["role"] == "user"][-1])) == 2
    assert "Render vs reference photo" in text_of(critic[0]["messages"][-1])

    run = tmp_path / "run"
    record = validate_record_file(run / "record.json")
    assert record.reference is not None
    assert record.reference.sha256 == hashlib.sha256(data).hexdigest()
    assert (record.reference.width, record.reference.height) == (72, 48)
    assert record.final is not None and "tileable=True" in record.final.program  # by default
    text = (run / "record.json").read_text()
    assert "base64" not in text and base64.b64encode(data[:64]).decode()[:40] not in text
    for path in run.rglob("*"):  # no copy of the photo anywhere in the run folder
        if path.is_file():
            assert hashlib.sha256(path.read_bytes()).hexdigest() != record.reference.sha256


def _one_line_error(result: Result) -> str:
    assert result.exit_code != 0
    assert "Traceback" not in result.output + result.stderr
    lines = result.stderr.strip().splitlines()
    assert len(lines) >= 1 and lines[-1].startswith("Error: ")
    return lines[-1]


@pytest.mark.parametrize("case", ["missing", "not_image", "symlink_out", "too_large"])
def test_bad_reference_photo_is_a_one_line_error_before_any_request(
    server: ChatServer, tmp_path: Path, monkeypatch: pytest.MonkeyPatch, case: str
) -> None:
    folder = tmp_path / "photos"
    folder.mkdir()
    photo = folder / "photo.png"
    expected = {
        "missing": "does not exist",
        "not_image": "not a PNG or JPEG",
        "symlink_out": "symlink out of its folder",
        "too_large": "pixel limit",
    }[case]
    if case == "not_image":
        photo.write_text("not an image\n")
    elif case == "symlink_out":
        _photo(tmp_path / "elsewhere.png")
        os.symlink(tmp_path / "elsewhere.png", photo)
    elif case == "too_large":
        _photo(photo)
        monkeypatch.setattr("matloom.author.reference.MAX_PIXELS", 1000)
    result = _generate(server, tmp_path / "run", "--reference", str(photo))
    assert expected in _one_line_error(result)
    assert server.requests == [] and not (tmp_path / "run").exists()


def test_a_resumed_run_refuses_a_photo_that_changed(tmp_path: Path) -> None:
    from matloom.author.config import AuthorConfig
    from matloom.author.records import RunRecord
    from matloom.author.reference import ReferencePhotoError, open_reference

    path = tmp_path / "photo.png"
    data = _photo(path)
    settings = AuthorConfig(reference=str(path))
    assert settings.tileable  # a material from a photo is tileable by default
    record = RunRecord(matloom_version="0", prompt="p", author="library", settings=settings)
    assert open_reference(record) is not None
    assert record.reference is not None
    assert record.reference.sha256 == hashlib.sha256(data).hexdigest()
    _photo(path, (64, 64))  # another photo at the same path
    with pytest.raises(ReferencePhotoError, match="changed since the run started"):
        open_reference(record)


def test_a_symlink_inside_its_folder_is_followed(tmp_path: Path) -> None:
    from matloom.author.reference import load_reference

    data = _photo(tmp_path / "photo.png")
    os.symlink("photo.png", tmp_path / "link.png")
    photo = load_reference(tmp_path / "link.png")
    assert photo.sha256 == hashlib.sha256(data).hexdigest()
    assert photo.at(32).shape == (32, 32, 3)


# ------------------------------------------------------------------------------ --polish


POLISH = ["--polish", "cmaes", "--polish-evaluations", "8", "--polish-size", "32"]
POLISH += ["--rounds", "0", "--scorer", "test-colour", "--variants", "0"]


@pytest.mark.parametrize(("before", "after", "kept"), [(70, 40, False), (40, 70, True)])
def test_polish_is_kept_only_when_the_critic_does_not_score_it_lower(
    server: ChatServer, script: Script, tmp_path: Path, before: int, after: int, kept: bool
) -> None:
    script.critic.extend([_critic_reply(before), _critic_reply(after)])
    result = _generate(server, tmp_path / "run", *POLISH)
    assert result.exit_code == 0, result.stderr
    record = validate_record_file(tmp_path / "run" / "record.json")
    polish = record.polish
    assert polish is not None and polish.done and polish.objective == "scorer"
    assert 2 <= polish.evaluations <= 8
    assert polish.objective_after is not None and polish.objective_before is not None
    assert polish.objective_after > polish.objective_before  # the scorer objective improved
    assert (polish.critic_before, polish.critic_after) == (before, after)
    assert len([r for r in server.requests if is_critic(r)]) == 2  # the guard's two calls
    assert polish.parameters and any(p.after != p.before for p in polish.parameters)
    assert polish.kept is kept
    assert record.final is not None
    unfitted = record.programs[polish.program_index].text
    assert polish.program is not None and polish.program != unfitted
    expected = polish.program if kept else unfitted
    assert (tmp_path / "run" / "material.mat").read_text().strip() == expected.strip()


def test_polish_needs_the_cma_package(
    server: ChatServer, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    import sys

    monkeypatch.setitem(sys.modules, "cma", None)  # import cma -> ImportError
    result = _generate(server, tmp_path / "run", *POLISH)
    assert "pip install 'matloom[polish]'" in _one_line_error(result)
    assert server.requests == []


@pytest.mark.parametrize(("extra", "objective"), [((), "critic"), (("--reference",), "reference")])
def test_polish_objective_without_a_scorer(
    server: ChatServer, tmp_path: Path, extra: tuple[str, ...], objective: str
) -> None:
    """No scorer: the photo statistics with --reference, else the critic, at most
    --polish-critic-calls calls (plus the guard's two)."""
    args = [*POLISH[:6], "--rounds", "0", "--scorer", "none", "--polish-critic-calls", "3"]
    if extra:
        _photo(tmp_path / "photo.png")
        args += ["--reference", str(tmp_path / "photo.png")]
    result = _generate(server, tmp_path / "run", *args)
    assert result.exit_code == 0, result.stderr
    polish = validate_record_file(tmp_path / "run" / "record.json").polish
    assert polish is not None and polish.objective == objective
    assert polish.better == ("lower" if objective == "reference" else "higher")
    calls = len([r for r in server.requests if is_critic(r)])
    guard = 2 if polish.guard else 0
    if objective == "critic":
        assert 2 <= polish.evaluations <= 3 and calls == polish.evaluations + guard
    else:
        assert polish.evaluations > 3 and calls == guard  # renders, not critic calls


def test_offline_a_fit_to_a_photo_is_recorded_but_not_exported(tmp_path: Path) -> None:
    """With no critic to check it (the offline library author), a fit to a photo's statistics
    is not exported: judged blind, such fits looked less like the photo than the unfitted
    programs. The record keeps the fit and says why."""
    photo = tmp_path / "photo.png"
    rgb = np.zeros((64, 64, 3), np.uint8)
    rgb[..., 0], rgb[..., 1], rgb[..., 2] = 40, 70, 140  # a blue the brick entry is not
    Image.fromarray(rgb).save(photo)
    out = tmp_path / "run"
    res = CliRunner().invoke(
        cli,
        ["generate", "brick wall", "-o", str(out), "--reference", str(photo), "--polish", "cmaes",
         "--polish-evaluations", "12"],
    )  # fmt: skip
    assert res.exit_code == 0, res.output
    record = json.loads((out / "record.json").read_text())
    polish = record["polish"]
    assert polish["objective"] == "reference" and polish["program"]
    assert polish["kept"] is False and "no critic" in polish["reason"]
    assert record["final"]["program"] != polish["program"]
