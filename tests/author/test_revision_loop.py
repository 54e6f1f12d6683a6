"""The critique -> revision loop against the scripted Chat Completions server on 127.0.0.1: labelled
revision turns, previews attached to the generator, critic edits, string scores, critic history,
critic views, the last <material> block, parse hints, and quiet offline runs."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from click.testing import CliRunner, Result

import matloom
from author.chat_server import ChatServer
from author.conftest import (
    FAST_FLAGS,
    Script,
    example_program,
    image_parts,
    is_critic,
    text_of,
)
from matloom.author.records import validate_record_file
from matloom.cli.main import cli
from matloom.lang.api import analyse


def generate(server: ChatServer, out: Path, *extra: str, model: str = "vision-model") -> Result:
    args = [
        "generate", "red brick wall", "-o", str(out), "--model", model,
        "--base-url", server.base_url, "--retry-backoff", "0.01", "--max-retries", "1",
        "--timeout", "20", "--scorer", "none", *FAST_FLAGS, *extra,
    ]  # fmt: skip
    return CliRunner().invoke(cli, args)


def generator_requests(server: ChatServer) -> list[dict]:
    return [r for r in server.requests if not is_critic(r)]


def critic_requests(server: ChatServer) -> list[dict]:
    return [r for r in server.requests if is_critic(r)]


def critique(score: object = 55, **extra: object) -> str:
    body = {
        "match_score": score,
        "differences": ["the mortar is too dark"],
        "suggestions": ["lighten the mortar"],
        **extra,
    }
    return json.dumps(body)


def test_revision_turn_has_labelled_sections(
    server: ChatServer, script: Script, tmp_path: Path
) -> None:
    script.critic.append(
        json.dumps(
            {
                "match_score": 64,
                "differences": ["the bricks are a good red", "the mortar lines are missing"],
                "suggestions": ["add 2 px mortar lines between the bricks"],
            }
        )
    )
    assert generate(server, tmp_path / "run", "--rounds", "1").exit_code == 0
    revision = text_of(generator_requests(server)[1]["messages"][-1])
    sections = dict(part.split("\n", 1) for part in revision.split("## ")[1:])
    assert sections["Score"].strip() == "64/100"
    assert "- the bricks are a good red" in sections["What differs"]
    assert "- the mortar lines are missing" in sections["What differs"]
    assert sections["What to change"].strip() == "- add 2 px mortar lines between the bricks"
    assert "the last one is used" in sections["Answer"] and "Concrete edits" not in sections


def test_image_capable_generator_gets_the_preview_in_the_revision(
    server: ChatServer, tmp_path: Path
) -> None:
    assert generate(server, tmp_path / "run", "--rounds", "2").exit_code == 0
    first, *revisions = generator_requests(server)
    assert image_parts(first["messages"][-1]) == []  # the request itself has no image
    record = validate_record_file(tmp_path / "run" / "record.json")
    for k, request in enumerate(revisions):
        (part,) = image_parts(request["messages"][-1])
        assert part["image_url"]["url"].startswith("data:image/jpeg;base64,")
        assert "## Preview" in text_of(request["messages"][-1])
        # Earlier turns are resent as text only.
        assert all(image_parts(m) == [] for m in request["messages"][:-1])
        user_turn = record.conversation[2 + 2 * k]
        assert user_turn.images == [f"renders/p{k}.png"]


@pytest.mark.parametrize("flags", [["--no-images"], ["--no-revision-images"]])
def test_no_images_for_a_text_only_generator_or_when_turned_off(
    server: ChatServer, tmp_path: Path, flags: list[str]
) -> None:
    result = generate(server, tmp_path / "run", "--rounds", "1", *flags)
    assert result.exit_code == 0, result.stderr
    for request in generator_requests(server):
        assert all(image_parts(m) == [] for m in request["messages"])
    assert "## Preview" not in text_of(generator_requests(server)[1]["messages"][-1])


def test_text_only_model_gets_no_images_anywhere(server: ChatServer, tmp_path: Path) -> None:
    assert generate(server, tmp_path / "run", "--rounds", "1", model="glm-5.2").exit_code == 0
    assert all(image_parts(m) == [] for r in server.requests for m in r["messages"])


def test_critic_edits_and_a_string_score_reach_the_revision(
    server: ChatServer, script: Script, tmp_path: Path
) -> None:
    edits = [
        {"layer": 1, "channel": "roughness", "change": "0.6 -> 0.3"},
        {"define": "grain", "change": "base_freq 14 -> 30"},
        "make the glaze glossier",
    ]
    script.critic.append(critique("72/100", edits=edits))
    assert generate(server, tmp_path / "run", "--rounds", "1").exit_code == 0
    record = validate_record_file(tmp_path / "run" / "record.json")
    first = record.critiques[0]
    assert first.match_score == 72
    assert [(e.layer, e.channel, e.define, e.change) for e in first.edits] == [
        (1, "roughness", None, "0.6 -> 0.3"),
        (None, None, "grain", "base_freq 14 -> 30"),
        (None, None, None, "make the glaze glossier"),
    ]
    revision = text_of(generator_requests(server)[1]["messages"][-1])
    edits_text = revision.split("## Concrete edits\n", 1)[1].split("\n\n", 1)[0]
    assert edits_text.splitlines() == [
        "- layer 1 .roughness: 0.6 -> 0.3",
        "- Define grain: base_freq 14 -> 30",
        "- make the glaze glossier",
    ]
    assert "## Score\n72/100" in revision
    # The critic is asked for a number, and for edits since it reads the code.
    asked = text_of(critic_requests(server)[0]["messages"][1])
    assert '"match_score": <number' in asked and '"edits": [{"layer"' in asked


@pytest.mark.parametrize("score", ["72", 72, 72.0, "72/100", " 72 % "])
def test_score_forms_are_accepted(
    server: ChatServer, script: Script, tmp_path: Path, score: object
) -> None:
    script.critic.append(critique(score))
    assert generate(server, tmp_path / "run", "--rounds", "1").exit_code == 0
    assert validate_record_file(tmp_path / "run" / "record.json").critiques[0].match_score == 72


def test_critic_history_shows_the_previous_preview_and_score(
    server: ChatServer, script: Script, tmp_path: Path
) -> None:
    script.critic.extend(
        [
            critique(55),
            critique(70, better_than_previous=True),
            critique(60, better_than_previous="no"),
        ]
    )
    result = generate(server, tmp_path / "run", "--rounds", "2", "--critic-history")
    assert result.exit_code == 0, result.stderr
    first, second, third = critic_requests(server)
    assert len(image_parts(first["messages"][1])) == 1  # round 0: nothing before it
    assert "better_than_previous" not in text_of(first["messages"][1])
    for request, before in ((second, 55), (third, 70)):
        user = request["messages"][1]
        assert len(image_parts(user)) == 2  # this round's preview, then the previous one
        said = f"The previous version (its render is attached after this version's) scored {before}"
        assert said in text_of(user)
        assert '"better_than_previous": <true or false>' in text_of(user)
    record = validate_record_file(tmp_path / "run" / "record.json")
    assert record.settings.critic_history is True and record.critiques[0].history is None
    histories = [c.history for c in record.critiques[1:]]
    assert [(h.previous_index, h.previous_score, h.better) for h in histories] == [
        (0, 55, True),
        (1, 70, False),
    ]
    assert histories[0].previous_renders == ["renders/p0.png"]
    # The revision of P1 also says how the previous version scored.
    assert "## Score\n70/100 (the previous version scored 55/100)" in text_of(
        generator_requests(server)[2]["messages"][-1]
    )


def test_without_history_the_critic_is_stateless(server: ChatServer, tmp_path: Path) -> None:
    assert generate(server, tmp_path / "run", "--rounds", "1").exit_code == 0
    for request in critic_requests(server):
        assert len(image_parts(request["messages"][1])) == 1
        assert "previous version" not in text_of(request["messages"][1])
    record = validate_record_file(tmp_path / "run" / "record.json")
    assert all(c.history is None for c in record.critiques)


@pytest.mark.parametrize(
    ("views", "files"),
    [("flat", ["p0.png"]), ("lit", ["p0_lit.png"]), ("both", ["p0.png", "p0_lit.png"])],
)
def test_critic_views(server: ChatServer, tmp_path: Path, views: str, files: list[str]) -> None:
    result = generate(server, tmp_path / "run", "--rounds", "1", "--critic-views", views)
    assert result.exit_code == 0, result.stderr
    for request in critic_requests(server):
        assert len(image_parts(request["messages"][1])) == len(files)
    record = validate_record_file(tmp_path / "run" / "record.json")
    first = record.critiques[0]
    assert first.views == (["flat", "lit"] if views == "both" else [views])
    assert first.renders == [f"renders/{f}" for f in files] and first.render == first.renders[0]
    assert all((tmp_path / "run" / r).is_file() for r in first.renders)
    assert record.settings.critic_views == views and record.warnings == []
    system = text_of(critic_requests(server)[0]["messages"][0])
    assert ("About the lit render" in system) == (views != "flat")
    # The generator's revision carries the same views.
    assert len(image_parts(generator_requests(server)[1]["messages"][-1])) == len(files)


def test_the_last_material_block_is_used(
    server: ChatServer, script: Script, tmp_path: Path
) -> None:
    draft, final = example_program(0, strip_seeds=False), example_program(2, strip_seeds=False)
    reply = (
        f"A first idea:\n<material>\n{draft}\n</material>\nOn reflection the scale is wrong; "
        f"here is the answer.\n<material>\n{final}\n</material>"
    )
    script.generator.append(reply)
    assert generate(server, tmp_path / "run", "--rounds", "0").exit_code == 0
    record = validate_record_file(tmp_path / "run" / "record.json")
    assert record.programs[0].text == matloom.format(final) != matloom.format(draft)
    assert record.conversation[-1].text == reply  # the model's own text stays in the history


def test_bracket_diagnostics_reach_the_model(
    server: ChatServer, script: Script, tmp_path: Path
) -> None:
    broken = "View(0, 0, 1, 1)\nMaterial(\n  Layer(1).basecolor(200, 90, 60).roughness(0.5)))\n"
    script.generator.append(f"<material>\n{broken}</material>")
    assert generate(server, tmp_path / "run", "--rounds", "0").exit_code == 0
    _, diagnostics = analyse(broken.strip())
    errors = [d for d in diagnostics if d.is_error]
    assert errors
    repair = text_of(generator_requests(server)[1]["messages"][-1])
    for d in errors[:5]:
        assert d.format("program") in repair
    assert "the last one is used" in repair


def offline(out: Path, *extra: str) -> Result:
    return CliRunner().invoke(cli, ["generate", "oak planks", "-o", str(out), *FAST_FLAGS, *extra])


def test_quiet_offline_generate_prints_no_seed_search_line(tmp_path: Path) -> None:
    result = offline(tmp_path / "quiet")
    assert result.exit_code == 0, result.stderr
    assert "seed search" not in result.stderr
    assert validate_record_file(tmp_path / "quiet" / "record.json").seed_search.skipped


def test_a_requested_seed_search_says_why_it_was_skipped(tmp_path: Path) -> None:
    skipped = offline(tmp_path / "skipped", "--scorer", "none", "--variants", "20")
    assert skipped.exit_code == 0, skipped.stderr
    assert "seed search skipped: no scorer configured" in skipped.stderr
    ran = offline(tmp_path / "ran", "--scorer", "test-colour", "--variants", "2")
    assert ran.exit_code == 0, ran.stderr
    assert "seed search" not in ran.stderr
    assert validate_record_file(tmp_path / "ran" / "record.json").seed_search.sweeps
