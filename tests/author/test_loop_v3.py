"""Critic loop v3 (the ``recommended`` preset) against the scripted Chat Completions server on
127.0.0.1: revising from the best program, the "no visible change" rule on a fixed pair of
programs, the score-only request for the last program, the critic's resolution-and-previews
facts and structural changes; and ``paper`` sending exactly the requests it always sent.

Regenerate the snapshots after an intended change with::

    MATLOOM_UPDATE_SNAPSHOTS=1 .venv/bin/python -m pytest tests/author/test_loop_v3.py
"""

from __future__ import annotations

import hashlib
import json
import os
from pathlib import Path
from typing import Any

from click.testing import CliRunner, Result

from author.chat_server import ChatServer
from author.conftest import FAST_FLAGS, Script, example_program, image_parts, is_critic, text_of
from matloom.cli.main import cli

SNAPSHOTS = Path(__file__).parent / "snapshots"
PAPER_REQUESTS = SNAPSHOTS / "paper_requests.json"


def _snapshot(path: Path, text: str) -> None:
    if os.environ.get("MATLOOM_UPDATE_SNAPSHOTS"):
        path.write_text(text, encoding="utf-8")
    assert path.exists(), "run with MATLOOM_UPDATE_SNAPSHOTS=1 to create the snapshot"
    assert text == path.read_text(encoding="utf-8")


def generate(server: ChatServer, out: Path, *extra: str) -> Result:
    args = [
        "generate", "red brick wall", "-o", str(out), "--model", "vision-model",
        "--base-url", server.base_url, "--retry-backoff", "0.01", "--max-retries", "1",
        "--timeout", "20", "--scorer", "none", *FAST_FLAGS, *extra,
    ]  # fmt: skip
    return CliRunner().invoke(cli, args)


def critique(score: int, **extra: object) -> str:
    body = {
        "match_score": score,
        "differences": ["the mortar is too dark"],
        "suggestions": ["lighten the mortar"],
        **extra,
    }
    return json.dumps(body)


def _request_texts(requests: list[dict[str, Any]]) -> str:
    """Every request as its messages' roles, texts and image counts; a system prompt (tested
    by its own snapshot) as its digest."""
    shown = []
    for request in requests:
        messages = []
        for m in request["messages"]:
            text = text_of(m)
            if m["role"] == "system":
                text = "sha256:" + hashlib.sha256(text.encode()).hexdigest()
            messages.append({"role": m["role"], "text": text, "images": len(image_parts(m))})
        shown.append({"critic": is_critic(request), "messages": messages})
    return json.dumps(shown, indent=1) + "\n"


def test_paper_requests_are_unchanged(server: ChatServer, script: Script, tmp_path: Path) -> None:
    """A two-round paper run (the defaults) sends exactly the requests recorded before loop v3."""
    edits = [{"layer": 0, "channel": "roughness", "change": "0.6 -> 0.3"}]
    script.critic.extend([critique(60, edits=edits), critique(50), critique(70)])
    result = generate(server, tmp_path / "run", "--rounds", "2", "--settings", "paper")
    assert result.exit_code == 0, result.stderr
    assert len(server.requests) == 6  # generate, critique, revise, critique, revise, critique
    _snapshot(PAPER_REQUESTS, _request_texts(server.requests))


def test_paper_critic_system_prompt_is_unchanged() -> None:
    """The paper critic's system prompt (all signals, the flat view, stateless), as before v3."""
    from matloom.author.prompts.critic import critic_system_prompt

    text = critic_system_prompt(["render", "stats", "code"], ("flat",))
    assert hashlib.sha256(text.encode()).hexdigest() in PAPER_REQUESTS.read_text()
    _snapshot(SNAPSHOTS / "critic_system_prompt_paper.txt", text)


# ----------------------------------------------------------------------------- recommended


def recommended(server: ChatServer, out: Path, *extra: str) -> Result:
    """A recommended run with one first draft (the loop rules on one trajectory; the drafts
    are tested in test_drafts.py)."""
    return generate(server, out, "--settings", "recommended", "--drafts", "1", *extra)


def requests_of(server: ChatServer, critic: bool) -> list[dict[str, Any]]:
    return [r for r in server.requests if is_critic(r) == critic]


def answer(program: str) -> str:
    return f"Here it is.\n<material>\n{program}\n</material>"


#: A fixed brick program and edits of its mortar colour: +2 levels (no visible change) and
#: +40 levels (visible), measured against the recommended threshold below.
BRICK = """View(0, 0, 2, 2)
Define(b, Bricks(brick_width=1, brick_height=0.5, mortar=0.15))
Material(
  Layer(1).basecolor({mortar}).roughness(0.9),
  Layer(b).basecolor(150, 60, 45).roughness(0.7).height(b * 0.02)
)"""
MORTAR = "190, 185, 175"
MORTAR_BELOW = "192, 187, 177"
MORTAR_ABOVE = "230, 225, 215"


def brick(mortar: str = MORTAR) -> str:
    return BRICK.format(mortar=mortar)


def test_the_fixed_pair_falls_either_side_of_the_recommended_threshold() -> None:
    """The no-visible-change rule on a fixed pair of programs at the recommended critique size
    (512 px, both layouts): the +2-level mortar edit is under the threshold, +40 is over it."""
    from matloom.author.settings_presets import NO_CHANGE_THRESHOLD
    from matloom.author.stages.loop import preview_difference
    from matloom.author.views import Renderer

    renderer = Renderer()

    def previews(program: str) -> list[Any]:
        return [renderer.image(program, 512, view) for view in ("flat", "lit")]

    base = previews(brick())
    below = preview_difference(base, previews(brick(MORTAR_BELOW)))
    above = preview_difference(base, previews(brick(MORTAR_ABOVE)))
    assert 0 < below < NO_CHANGE_THRESHOLD < above
    assert preview_difference(base, base) == 0.0


def test_block_difference_sees_a_small_local_change() -> None:
    """A change to one small feature counts: the worst block, not the whole-image mean."""
    import numpy as np

    from matloom.author.stages.loop import block_difference

    a = np.full((64, 64, 3), 100, np.uint8)
    b = a.copy()
    b[10:12, 20:22] = 200  # 4 px of 4096 changed by 100 levels
    assert float(np.mean(np.abs(a.astype(int) - b))) < 0.1
    assert block_difference(a, b) == 100.0  # 2 px blocks at 64 px: one block entirely changed
    assert block_difference(a, a) == 0.0


def test_no_visible_change_is_reported_and_stops_the_loop(
    server: ChatServer, script: Script, tmp_path: Path
) -> None:
    """P1 (+2 levels) is not critiqued and is reported in the next revision turn; P2 (+40
    levels) is critiqued; P3 (+2 over P2) makes the second invisible revision: the loop stops."""
    script.generator.extend(
        [
            answer(brick()),
            answer(brick(MORTAR_BELOW)),
            answer(brick(MORTAR_ABOVE)),
            answer(brick("232, 227, 217")),
        ]
    )
    script.critic.extend([critique(60), critique(70, better_than_previous=True)])
    result = recommended(server, tmp_path / "run", "--rounds", "4")
    assert result.exit_code == 0, result.stderr
    record = json.loads((tmp_path / "run" / "record.json").read_text())
    assert [c["program_index"] for c in record["critiques"]] == [0, 2]
    assert len(record["programs"]) == 4
    assert record["stop_reason"] == "2 revision(s) made no visible change (P1, P3)"
    revisions = requests_of(server, critic=False)[1:]
    assert len(revisions) == 3
    second = text_of(revisions[1]["messages"][-1])
    assert "## No visible change\nYour revision in round 1 changed the previews by" in second
    assert "under the 3 that shows: no visible change, so it was not reviewed" in second
    # P1 looks like P0: the revision continues from P0, with P0's critique.
    assert "Continuing from round 0 (score 60/100), the best so far; round 1 made no visible" in (
        second
    )
    assert "## Score\n60/100" in second and MORTAR_BELOW not in second
    assert "## No visible change" not in text_of(revisions[2]["messages"][-1])
    # P2 is compared with the program it was revised from (P0), not with the invisible P1.
    assert record["critiques"][1]["history"]["previous_index"] == 0


def test_paper_critiques_an_invisible_revision_like_any_other(
    server: ChatServer, script: Script, tmp_path: Path
) -> None:
    script.generator.extend([answer(brick()), answer(brick(MORTAR_BELOW))])
    result = generate(server, tmp_path / "run", "--rounds", "1")
    assert result.exit_code == 0, result.stderr
    record = json.loads((tmp_path / "run" / "record.json").read_text())
    assert [c["program_index"] for c in record["critiques"]] == [0, 1]
    assert not any(c["score_only"] for c in record["critiques"])


def test_revision_continues_from_the_best_after_a_regression(
    server: ChatServer, script: Script, tmp_path: Path
) -> None:
    """P1 scored 78, P2 regressed to 70: the revision into P3 quotes P1's text (not P2's),
    says why, shows P1's previews and critique, and P3's critic compares P3 with P1."""
    programs = [example_program(k, strip_seeds=False) for k in range(4)]
    script.generator.extend(answer(p) for p in programs)
    script.critic.extend(
        [
            critique(60),
            critique(78, better_than_previous=True, suggestions=["darken the veins"]),
            json.dumps(
                {
                    "match_score": 70,
                    "differences": ["the new layer hides the pattern"],
                    "suggestions": ["remove the new layer"],
                    "better_than_previous": False,
                }
            ),
            critique(80, better_than_previous=True),
        ]
    )
    result = recommended(server, tmp_path / "run", "--rounds", "3")
    assert result.exit_code == 0, result.stderr
    revisions = requests_of(server, critic=False)[1:]
    turn = text_of(revisions[2]["messages"][-1])
    assert (
        "## Continue from\nContinuing from round 1 (score 78/100), the best so far; round 2: "
        "score 70/100. Revise round 1's program, not your last answer:\n<material>\n"
        + programs[1].strip()
        + "\n</material>"
    ) in turn
    assert programs[2].strip() not in turn  # the worse program is not handed back
    assert "## Dropped attempt\nWhat the critic said of round 2, which is not continued:\n" in turn
    assert "- the new layer hides the pattern" in turn
    assert "## Score\n78/100" in turn and "- darken the veins" in turn
    assert "remove the new layer" not in turn  # P2's suggestions are for P2's text
    # Until the regression each revision continued from the latest program, as it says.
    assert "Continuing from your last answer, round 1 (score 78/100): the best so far." in (
        text_of(revisions[1]["messages"][-1])
    )
    record = json.loads((tmp_path / "run" / "record.json").read_text())
    assert record["conversation"][-2]["images"] == ["renders/p1.png", "renders/p1_lit.png"]
    assert record["critiques"][3]["history"]["previous_index"] == 1
    assert record["critiques"][3]["history"]["previous_score"] == 78


def test_paper_revises_the_latest_program(
    server: ChatServer, script: Script, tmp_path: Path
) -> None:
    programs = [example_program(k, strip_seeds=False) for k in range(4)]
    script.generator.extend(answer(p) for p in programs)
    script.critic.extend([critique(60), critique(78), critique(70), critique(80)])
    result = generate(server, tmp_path / "run", "--rounds", "3")
    assert result.exit_code == 0, result.stderr
    turn = text_of(requests_of(server, critic=False)[3]["messages"][-1])
    assert "## Score\n70/100" in turn and "Continue from" not in turn
    assert programs[1].strip() not in turn


def test_with_a_scorer_the_best_is_the_scorers(
    server: ChatServer, script: Script, tmp_path: Path
) -> None:
    """With a scorer, "best" is the scorer's (as in selection): the brightest program here,
    though the critic prefers another."""
    bright, dark, mid = (
        f"Material(Layer(1).basecolor({v}, {v}, {v}).roughness(0.5))" for v in (230, 40, 120)
    )
    script.generator.extend(answer(p) for p in (bright, dark, mid, dark))
    script.critic.extend([critique(50), critique(90), critique(60), critique(55)])
    result = recommended(
        server, tmp_path / "run", "--rounds", "3", "--scorer", "test-brightness", "--variants", "0"
    )
    assert result.exit_code == 0, result.stderr
    turns = [text_of(r["messages"][-1]) for r in requests_of(server, critic=False)[1:]]
    assert (
        turns[0].startswith("A critic reviewed") and "Continuing from your last answer" in turns[0]
    )
    assert "Continuing from round 0 (test-brightness score " in turns[1]
    assert ", critic 50/100), the best so far; round 1: test-brightness score " in turns[1]
    assert bright in turns[1] and "## Score\n50/100" in turns[1]


def test_the_last_program_gets_a_score_only_request(
    server: ChatServer, script: Script, tmp_path: Path
) -> None:
    script.critic.extend([critique(50), json.dumps({"match_score": 80})])
    result = recommended(server, tmp_path / "run", "--rounds", "1")
    assert result.exit_code == 0, result.stderr
    first, last = requests_of(server, critic=True)
    assert text_of(first["messages"][0]) == text_of(last["messages"][0])  # same system prompt
    asked = text_of(last["messages"][1])
    response = asked.split("## Response\n", 1)[1]
    assert response.startswith(
        'Answer with exactly this structure:\n{\n  "match_score": <number 0-100, how well the '
        'image matches the description>,\n  "better_than_previous": <true or false>\n}\n'
    )
    assert "Only the score is asked for" in response
    assert '"suggestions"' not in asked and '"edits"' not in asked
    assert "Only the score is asked for this time." in asked.split("## Objective", 1)[1]
    assert '"suggestions"' in text_of(first["messages"][1])
    assert len(image_parts(last["messages"][1])) == 4  # the same previews, and P0's
    record = json.loads((tmp_path / "run" / "record.json").read_text())
    assert [c["score_only"] for c in record["critiques"]] == [False, True]
    # The score-only score is used in selection.
    assert record["selection"]["method"] == "critic"
    assert record["selection"]["scores"] == [50.0, 80.0] and record["selection"]["index"] == 1


def test_structural_changes_reach_the_revision(
    server: ChatServer, script: Script, tmp_path: Path
) -> None:
    script.critic.extend(
        [
            critique(
                40,
                structural=["add a top layer of thin dark cracks masked by Worley edges", ""],
                edits=[{"layer": 0, "channel": "roughness", "change": "0.3 -> 0.6"}],
            ),
            json.dumps({"match_score": 60}),
        ]
    )
    result = recommended(server, tmp_path / "run", "--rounds", "1")
    assert result.exit_code == 0, result.stderr
    asked = text_of(requests_of(server, critic=True)[0]["messages"][1])
    assert '"structural": ["<a structural change: a new layer, a different primitive' in asked
    assert "structural changes where the look is wrong in kind" in asked
    turn = text_of(requests_of(server, critic=False)[1]["messages"][-1])
    assert (
        "## Structural changes\n- add a top layer of thin dark cracks masked by Worley edges\n\n"
        "## Concrete edits\n- layer 0 .roughness: 0.3 -> 0.6"
    ) in turn
    record = json.loads((tmp_path / "run" / "record.json").read_text())
    assert record["critiques"][0]["structural"] == [
        "add a top layer of thin dark cracks masked by Worley edges"
    ]


def test_structural_changes_alone_are_not_satisfaction(
    server: ChatServer, script: Script, tmp_path: Path
) -> None:
    only = json.dumps({"match_score": 70, "structural": ["add a moss layer"]})
    script.critic.extend([only, json.dumps({"match_score": 75})])
    result = recommended(server, tmp_path / "run", "--rounds", "1")
    assert result.exit_code == 0, result.stderr
    record = json.loads((tmp_path / "run" / "record.json").read_text())
    assert len(record["programs"]) == 2 and record["stop_reason"] == "all 1 revision rounds used"


def test_recommended_critic_system_prompt() -> None:
    """The critic gets the generator's "Resolution and previews" section and the measured
    layout facts through the same functions (not a copy), and no "little relief"."""
    from matloom.author.prompts.critic import CriticOptions, critic_system_prompt
    from matloom.author.prompts.previews import layout_facts, previews_section

    views = ("flat", "lit")
    options = CriticOptions(previews=True, structural=True, size=512)
    text = critic_system_prompt(["render", "stats", "code"], views, history=True, options=options)
    assert previews_section(512, views) in text and layout_facts(views) in text
    assert "uncovered areas" in text and "little relief" not in text
    assert "About the flat render:" in text and "About the lit render:" not in text
    assert text.count("a sky gradient") == 1  # the lit note once, in the previews section
    assert "structural change in structural" in text
    assert "features at least 2 px wide (0.0039 units at View(0, 0, 1, 1))" in text
    paper = critic_system_prompt(["render", "stats", "code"], views, history=True)
    assert "# Resolution and previews" not in paper and "little relief" in paper
    _snapshot(SNAPSHOTS / "critic_system_prompt_recommended.txt", text)


def test_parse_structural_forms() -> None:
    from matloom.author.stages.critique_parse import parse_critique

    answer_ = parse_critique(
        '{"match_score": 50, "structural": ["a", {"change": "b"}, {"x": 1}, "", null, 3]}'
    )
    assert answer_.structural == ["a", "b", "3"]
    assert parse_critique('{"match_score": 5, "structural": "one"}').structural == ["one"]
    assert parse_critique('{"match_score": 5}').structural == []


def test_a_resumed_run_continues_from_the_same_best(
    server: ChatServer, script: Script, tmp_path: Path
) -> None:
    """The loop's decisions are rebuilt from the record: a run that failed while asking for P3
    resumes with the same revision turn (from P1, after P2's regression)."""
    programs = [example_program(k, strip_seeds=False) for k in range(4)]
    script.generator.extend(answer(p) for p in programs[:3])
    script.critic.extend([critique(60), critique(78), critique(70), critique(80)])

    def down(body: dict[str, Any]) -> str:
        raise RuntimeError("the generator is down")

    script.default_generator = down
    run = tmp_path / "run"
    first = recommended(server, run, "--rounds", "3")
    assert first.exit_code == 1 and "--resume" in first.stderr
    failed = text_of(server.requests[-1]["messages"][-1])
    script.default_generator = lambda body: answer(programs[3])
    critiques = len(requests_of(server, critic=True))
    resumed = CliRunner().invoke(
        cli, ["generate", "--resume", "-o", str(run), "--base-url", server.base_url]
    )
    assert resumed.exit_code == 0, resumed.stderr
    assert len(requests_of(server, critic=True)) == critiques + 1  # only P3's critique is new
    again = text_of(requests_of(server, critic=False)[-1]["messages"][-1])
    assert again == failed and "Continuing from round 1 (score 78/100)" in again


def test_presets_turn_the_loop_on_only_in_recommended() -> None:
    from matloom.author.config import AuthorConfig
    from matloom.author.settings_presets import NO_CHANGE_THRESHOLD, preset_values
    from matloom.author.stages.loop import latest_best

    fields = (
        "critic_previews",
        "critic_structural",
        "revise_from_best",
        "no_change_threshold",
        "score_only_last",
    )
    paper = AuthorConfig.model_validate(preset_values("paper"))
    rec = AuthorConfig.model_validate(preset_values("recommended"))
    assert [getattr(paper, f) for f in fields] == [False, False, False, None, False]
    assert [getattr(rec, f) for f in fields] == [True, True, True, NO_CHANGE_THRESHOLD, True]
    assert latest_best([60, 78, None, 78, 70]) == 3  # a tie is no regression: the latest
    assert latest_best([None, None]) is None
