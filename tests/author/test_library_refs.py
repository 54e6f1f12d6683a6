"""`--library-refs N` (the recommended settings: 2): the generator's first turn carries the
material library's programs for the request, to reuse or ignore; `--revision-warnings` (on in
recommended): the revision turn lists the checker's warnings of the program it revises.

Runs against the scripted Chat Completions server on 127.0.0.1 (see chat_server.py); the
expected programs are what :func:`matloom.library.author` writes for the same prompt and seed.
"""

from __future__ import annotations

from pathlib import Path

import pytest
from click.testing import CliRunner
from pydantic import ValidationError

from author.chat_server import ChatServer
from author.conftest import FAST_FLAGS, Script, is_critic, text_of
from matloom.author.config import AuthorConfig
from matloom.author.library_refs import library_references
from matloom.author.prompts.revision import request_message, warning_lines
from matloom.author.records import validate_record_file
from matloom.author.settings_presets import preset_values
from matloom.cli.main import cli
from matloom.lang.api import parse
from matloom.lang.printer import format_program
from matloom.library import author

PROMPT = "weathered red brick wall"


def _generate(server: ChatServer, out: Path, *extra: str) -> None:
    args = ["generate", PROMPT, "-o", str(out), "--model", "test-vision-model"]
    args += ["--base-url", server.base_url, "--retry-backoff", "0.01", "--timeout", "20"]
    args += ["--scorer", "none", "--variants", "0", "--rounds", "0", *FAST_FLAGS, *extra]
    result = CliRunner().invoke(cli, args)
    assert result.exit_code == 0, result.stderr


def test_references_are_the_offline_author_then_the_next_entries() -> None:
    refs = library_references(PROMPT, 3, seed=5)
    assert len(refs) == 3 and len({r.entry for r in refs}) == 3
    best = author(PROMPT, seed=5)
    assert refs[0].entry == best.entry and refs[0].notes[: len(best.adaptations)] == tuple(
        best.adaptations
    )
    # the language the system prompt teaches: no comments, a View of four numbers
    program = parse(refs[0].program)
    assert "#" not in refs[0].program and program.view is not None
    assert not program.view.tileable and program.view.unit_m is None
    same = parse(format_program(best.ast))
    assert program.defines == same.defines and program.layers == same.layers
    ranked = [c.name for c in best.candidates]
    assert [r.entry for r in refs[1:]] == [n for n in ranked if n != best.entry][:2]
    assert library_references(PROMPT, 0) == []


def test_the_first_turn_carries_the_library_programs(server: ChatServer, tmp_path: Path) -> None:
    _generate(server, tmp_path / "run", "--library-refs", "2", "--seed", "3")
    (first,) = [r for r in server.requests if not is_critic(r)]
    text = text_of(first["messages"][1])
    refs = library_references(PROMPT, 2, seed=3)
    assert text == request_message(PROMPT, refs)
    for k, ref in enumerate(refs, start=1):
        assert f'<library_program n="{k}" entry="{ref.entry}">' in text
        assert ref.program.strip() in text
    record = validate_record_file(tmp_path / "run" / "record.json")
    assert record.settings.library_refs == 2
    assert record.conversation[0].text == text  # the turn is recorded as sent


def test_paper_settings_send_the_request_alone(server: ChatServer, tmp_path: Path) -> None:
    _generate(server, tmp_path / "run")
    (first,) = [r for r in server.requests if not is_critic(r)]
    assert text_of(first["messages"][1]) == request_message(PROMPT)
    assert "library_program" not in text_of(first["messages"][1])


def test_recommended_shows_two_and_paper_none() -> None:
    assert AuthorConfig.model_validate(preset_values("recommended")).library_refs == 2
    assert AuthorConfig().library_refs == 0


def test_what_the_library_misses_is_said() -> None:
    refs = library_references("red brick wall with a golden unicorn motif", 1)
    assert refs and refs[0].missing, "the library draws no unicorn: it must say so"
    text = request_message("x", refs)
    assert "does not show" in text and refs[0].missing[0] in text


# ------------------------------------------------------------------ the checker's warnings


SHADOWED = """Define(e, 0.5)
Define(plate, Smoothstep(0.2, 0.3, Worley(base_freq=6, to_01=True, seed=2)))
Material(
  Layer(1).basecolor(120, 100, 80).roughness(0.9),
  Layer((plate * e)).basecolor(200, 180, 150).roughness(0.8)
)
"""


def test_warning_lines_name_a_define_a_builtin_shadows() -> None:
    (line,) = [w for w in warning_lines(SHADOWED) if w.startswith("W005")]
    assert line.startswith("W005 at line 1, column 8:") and "'e'" in line


def test_the_revision_turn_carries_the_warnings(
    script: Script, server: ChatServer, tmp_path: Path
) -> None:
    script.default_generator = lambda body: f"<material>\n{SHADOWED}</material>"
    _generate(server, tmp_path / "run", "--rounds", "1", "--revision-warnings")
    (revision,) = [r for r in server.requests if not is_critic(r)][1:]
    text = text_of(revision["messages"][-1])
    assert "## Checker warnings" in text and "W005 at line 1, column 8" in text
    server.requests.clear()
    _generate(server, tmp_path / "paper", "--rounds", "1")
    (revision,) = [r for r in server.requests if not is_critic(r)][1:]
    assert "Checker warnings" not in text_of(revision["messages"][-1])


def test_a_refused_warning_gets_a_repair_turn(
    script: Script, server: ChatServer, tmp_path: Path
) -> None:
    fixed = SHADOWED.replace("Define(e, 0.5)", "Define(amount, 0.5)").replace("* e)", "* amount)")
    script.generator.extend(
        [f"<material>\n{SHADOWED}</material>", f"<material>\n{fixed}</material>"]
    )
    _generate(server, tmp_path / "run", "--refuse-warning", "W005")
    generator = [r for r in server.requests if not is_critic(r)]
    assert len(generator) == 2  # the shadowed Define was answered with a repair turn
    repair = text_of(generator[1]["messages"][-1])
    assert "W005" in repair and "'e'" in repair
    record = validate_record_file(tmp_path / "run" / "record.json")
    assert "Define(amount, 0.5)" in record.programs[0].text
    assert [a.outcome for a in record.turns[0].attempts] == ["parse_error", "accepted"]


def test_warnings_are_accepted_by_default(
    script: Script, server: ChatServer, tmp_path: Path
) -> None:
    script.generator.append(f"<material>\n{SHADOWED}</material>")
    _generate(server, tmp_path / "run")
    assert len([r for r in server.requests if not is_critic(r)]) == 1


def test_refused_warning_codes_are_checked() -> None:
    assert AuthorConfig(refuse_warnings=("w005",)).refuse_warnings == ("W005",)
    for bad in (("E001",), ("W999",), ("bogus",)):
        with pytest.raises(ValidationError):
            AuthorConfig(refuse_warnings=bad)


def test_the_last_attempt_keeps_a_program_with_only_refused_warnings(
    script: Script, server: ChatServer, tmp_path: Path
) -> None:
    script.generator.extend([f"<material>\n{SHADOWED}</material>"] * 3)
    _generate(server, tmp_path / "run", "--refuse-warning", "W005", "--repair-turns", "1")
    record = validate_record_file(tmp_path / "run" / "record.json")
    assert [a.outcome for a in record.turns[0].attempts] == ["parse_error", "accepted"]
    assert record.status == "finished"
