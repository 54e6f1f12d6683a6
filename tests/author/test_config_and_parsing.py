"""Config and profiles, the scripted provider, critique parsing, and the record schema."""

from __future__ import annotations

from pathlib import Path

import pytest
from click.testing import CliRunner
from pydantic import ValidationError

from author.chat_server import ChatServer
from author.conftest import FAST_FLAGS
from matloom.author.config import (
    AuthorConfig,
    ConfigError,
    ModelSettings,
    load_config_file,
    resolve_profile,
)
from matloom.author.llm import ChatMessage, ModelError, get_model
from matloom.author.llm.scripted import register_script
from matloom.author.pipeline import author_material
from matloom.author.records import RunRecord, record_json_schema, validate_record_file
from matloom.author.stages.critique import CritiqueParseError, parse_critique
from matloom.cli.main import cli

TOML = """
[matloom]
profile = "local"

[profiles.local]
model = "qwen3.6-35b-a3b"
base_url = "http://127.0.0.1:1/v1"
reasoning_effort = "low"
extra_body = { reasoning = { enabled = true } }

[profiles.textonly]
model = "deepseek-v4-flash"
images = false
"""


def test_profiles_from_toml(tmp_path: Path) -> None:
    path = tmp_path / "matloom.toml"
    path.write_text(TOML)
    data = load_config_file(path)
    local = resolve_profile(data, None)
    assert local.model == "qwen3.6-35b-a3b" and local.extra_body == {"reasoning": {"enabled": True}}
    assert resolve_profile(data, "textonly").accepts_images is False
    with pytest.raises(ConfigError, match="unknown model profile 'nope'.*local, textonly"):
        resolve_profile(data, "nope")


def test_cli_profile_switches_backbone_with_one_flag(server: ChatServer, tmp_path: Path) -> None:
    (tmp_path / "matloom.toml").write_text(
        f'[profiles.mine]\nmodel = "profile-model"\nbase_url = "{server.base_url}"\n'
    )
    result = CliRunner().invoke(
        cli,
        [
            "generate", "slate", "-o", str(tmp_path / "run"), "--config",
            str(tmp_path / "matloom.toml"), "--profile", "mine", "--rounds", "0",
            "--variants", "0", "--scorer", "none", *FAST_FLAGS,
        ],
    )  # fmt: skip
    assert result.exit_code == 0, result.stderr
    assert server.requests[0]["model"] == "profile-model"
    record = validate_record_file(tmp_path / "run" / "record.json")
    assert record.settings.generator.model == "profile-model"


def test_config_is_frozen_and_validated() -> None:
    config = AuthorConfig(critic_signals="code,render")
    assert config.critic_signals == ("render", "code")
    with pytest.raises(ValidationError):
        config.rounds = 2  # type: ignore[misc]
    with pytest.raises(ValidationError, match="unknown critic signal"):
        AuthorConfig(critic_signals="render,smell")
    text_critic = AuthorConfig(
        generator=ModelSettings(model="gpt-5.6-luna"), critic=ModelSettings(model="glm-5.2")
    )
    assert text_critic.effective_signals() == ("stats", "code")
    assert AuthorConfig(generator=ModelSettings(model="gpt-5.6-luna")).critic_sees_render()


def test_defaults_are_the_papers() -> None:
    c = AuthorConfig()
    assert (c.rounds, c.repair_turns, c.variants) == (5, 3, 1000)
    assert (c.critique_size, c.select_size, c.sweep_size, c.stats_grid) == (512, 512, 256, 128)
    assert c.critic_signals == ("render", "stats", "code") and c.playbook and c.few_shot


def test_scripted_provider_through_the_registry(tmp_path: Path) -> None:
    program = "Material(Layer(1).basecolor(10, 20, 30).roughness(0.4))"
    scripted = register_script("unit-script", [f"<material>{program}</material>"])
    settings = ModelSettings(provider="scripted", model="unit-script")
    assert get_model(settings) is scripted
    config = AuthorConfig(generator=settings, rounds=0, scorer="none", export_size=16,
                          select_size=16)  # fmt: skip
    result = author_material("blue-grey", tmp_path / "run", config)
    assert "basecolor(10, 20, 30)" in result.program
    assert scripted.calls[0][0].role == "system" and "blue-grey" in scripted.calls[0][1].text
    with pytest.raises(ModelError, match="ran out of replies"):
        scripted.complete([ChatMessage("user", "again")])


@pytest.mark.parametrize(
    ("reply", "score", "differences"),
    [
        ('{"match_score": 55, "differences": ["x"], "suggestions": []}', 55, ["x"]),
        ('```json\n{"match_score": 72.6, "differences": "one", "suggestions": ["s"]}\n```', 73,
         ["one"]),
        ('Sure! {"match_score": "64/100", // rough\n "differences": ["a // b"], '
         '"suggestions": [],}', 64, ["a // b"]),
        ('{"match_score": 140, "differences": [], "suggestions": ["brace } in text"]', 100, []),
    ],
)  # fmt: skip
def test_parse_critique_tolerates_near_json(reply: str, score: int, differences: list) -> None:
    critique = parse_critique(reply)
    assert critique.match_score == score and critique.differences == differences


@pytest.mark.parametrize("reply", ["no json here", '{"differences": []}', "[1, 2]"])
def test_parse_critique_rejects_unusable_answers(reply: str) -> None:
    with pytest.raises(CritiqueParseError):
        parse_critique(reply)


def test_record_schema_is_exported_and_strict(tmp_path: Path) -> None:
    schema = record_json_schema()
    assert schema["title"] == "RunRecord" and "durations" in schema["properties"]
    with pytest.raises(ValidationError):
        RunRecord.model_validate({"prompt": "x"})


@pytest.mark.parametrize(
    "reply",
    [
        "Here it is:\n```\n{program}\n```\nHope that helps.",
        "Reasoning first.\n<material>\n```mat\n{program}\n```\n</material>",
        "Sure.\n{program}",
    ],
)
def test_tolerant_extraction_of_the_program(reply: str, tmp_path: Path) -> None:
    program = "Material(Layer(1).basecolor(90, 60, 30).roughness(0.7))"
    register_script("extract-script", [reply.format(program=program)])
    config = AuthorConfig(
        generator=ModelSettings(provider="scripted", model="extract-script"),
        rounds=0, scorer="none", export_size=16, select_size=16,
    )  # fmt: skip
    record = author_material("clay", tmp_path / "run", config).record
    assert len(record.turns[0].attempts) == 1 and "basecolor(90, 60, 30)" in record.final.program


def test_scorer_cli_lists_and_checks() -> None:
    listed = CliRunner().invoke(cli, ["scorer", "list"])
    assert listed.exit_code == 0 and "test-colour" in listed.stdout
    checked = CliRunner().invoke(cli, ["scorer", "check", "test-brightness"])
    assert checked.exit_code == 0 and checked.stdout.startswith("test-brightness\t")
    missing = CliRunner().invoke(cli, ["scorer", "check", "nope"])
    assert missing.exit_code == 1 and "unknown scorer" in missing.stderr
