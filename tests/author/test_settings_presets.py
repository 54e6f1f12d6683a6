"""Settings presets (`--settings`, matloom.toml) and the recommended profile end to end."""

from __future__ import annotations

from pathlib import Path

import pytest
from click.testing import CliRunner, Result

from author.chat_server import ChatServer
from author.conftest import FAST_FLAGS, image_parts, is_critic, text_of
from matloom.author.config import AuthorConfig, ConfigError
from matloom.author.records import validate_record_file
from matloom.author.settings_presets import (
    BUILTIN_PRESETS,
    default_preset,
    preset_names,
    preset_values,
)
from matloom.cli.main import cli

TOML = """
[matloom]
settings = "quick"

[settings.quick]
base = "recommended"
rounds = 2
variants = 50
"""


def run_cli(*args: str) -> Result:
    return CliRunner().invoke(cli, list(args))


def test_paper_preset_is_the_defaults() -> None:
    paper = AuthorConfig.model_validate(preset_values("paper"))
    assert paper.model_dump(exclude={"settings_preset"}) == AuthorConfig().model_dump(
        exclude={"settings_preset"}
    )
    assert paper.settings_preset == "paper"
    assert (paper.critic_views, paper.critic_history, paper.critic_stats) == (
        "flat",
        False,
        "paper",
    )


def test_recommended_preset() -> None:
    rec = AuthorConfig.model_validate(preset_values("recommended"))
    assert rec.views == ("flat", "lit") and rec.critic_history and rec.critic_stats == "visible"
    assert rec.rounds == 5 and rec.scorer == "auto" and rec.variants > 0


def test_custom_presets_build_on_others(tmp_path: Path) -> None:
    import tomllib

    data = tomllib.loads(TOML)
    assert preset_names(data) == [*BUILTIN_PRESETS, "quick"]
    assert default_preset(data) == "quick"
    quick = AuthorConfig.model_validate(preset_values("quick", data))
    assert (quick.rounds, quick.variants, quick.critic_views) == (2, 50, "both")
    with pytest.raises(ConfigError, match="unknown settings preset 'nope'.*recommended"):
        preset_values("nope", data)
    with pytest.raises(ConfigError, match="cannot set generator"):
        preset_values("bad", {"settings": {"bad": {"generator": {"model": "m"}}}})
    with pytest.raises(ConfigError, match="invalid"):
        preset_values("bad", {"settings": {"bad": {"critic_views": "sideways"}}})
    with pytest.raises(ConfigError, match="too long"):
        preset_values("a", {"settings": {"a": {"base": "b"}, "b": {"base": "a"}}})


def test_cli_settings_flag_and_overrides(tmp_path: Path) -> None:
    out = tmp_path / "run"
    result = run_cli(
        "generate", "slate", "-o", str(out), "--settings", "recommended", "--rounds", "3",
        "--scorer", "none", *FAST_FLAGS,
    )  # fmt: skip
    assert result.exit_code == 0, result.stderr
    settings = validate_record_file(out / "record.json").settings
    assert settings.settings_preset == "recommended" and settings.critic_history
    assert settings.rounds == 3 and settings.critic_views == "both"  # the flag wins


def test_matloom_toml_chooses_the_default_preset(tmp_path: Path) -> None:
    (tmp_path / "matloom.toml").write_text(TOML)
    config = ["--config", str(tmp_path / "matloom.toml")]
    default = run_cli("generate", "slate", "-o", str(tmp_path / "a"), *config, *FAST_FLAGS)
    assert default.exit_code == 0, default.stderr
    settings = validate_record_file(tmp_path / "a" / "record.json").settings
    assert (settings.settings_preset, settings.rounds, settings.variants) == ("quick", 2, 50)
    chosen = run_cli(
        "generate", "slate", "-o", str(tmp_path / "b"), *config, "--settings", "paper",
        *FAST_FLAGS,
    )  # fmt: skip
    assert chosen.exit_code == 0, chosen.stderr
    assert validate_record_file(tmp_path / "b" / "record.json").settings.settings_preset == "paper"
    bad = run_cli("generate", "slate", "-o", str(tmp_path / "c"), "--settings", "nope")
    assert bad.exit_code == 1 and "unknown settings preset 'nope'" in bad.stderr


def test_recommended_profile_end_to_end(server: ChatServer, tmp_path: Path) -> None:
    result = run_cli(
        "generate", "red brick wall", "-o", str(tmp_path / "run"), "--model", "vision-model",
        "--base-url", server.base_url, "--settings", "recommended", "--rounds", "2",
        "--scorer", "none", *FAST_FLAGS,
    )  # fmt: skip
    assert result.exit_code == 0, result.stderr
    critics = [r for r in server.requests if is_critic(r)]
    # three first drafts (no previous round), then two revisions that see the one they revise
    assert [len(image_parts(r["messages"][1])) for r in critics] == [2, 2, 2, 4, 4]
    for request in critics:
        assert text_of(request["messages"][1]).count("Visible statistics (computed on the") == 1
        assert "Appearance scalars" not in text_of(request["messages"][1])
    record = validate_record_file(tmp_path / "run" / "record.json")
    assert [t.kind for t in record.turns] == ["initial", "draft", "draft", "revision", "revision"]
    history = record.critiques[3].history
    assert history is not None and history.previous_index in (0, 1, 2)
    k = history.previous_index
    assert history.previous_renders == [f"renders/p{k}.png", f"renders/p{k}_lit.png"]
    assert "The lit preview (" in record.system_prompt and record.warnings == []
    assert "seed search" not in result.stderr
