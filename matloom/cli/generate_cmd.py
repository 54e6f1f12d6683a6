"""`matloom generate`, `matloom prompt`, `matloom scorer`: the LLM authoring pipeline's CLI.

stdout carries only the result (the program, or JSON with ``--json``); progress, notices and
errors go to stderr, and errors never show a traceback.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path
from typing import Any

import click

from matloom.author.config import AuthorConfig, ConfigError, one_line
from matloom.cli.generate_options import (
    SEARCH_FLAGS,
    build_config,
    explicit_flags,
    model_options,
    pipeline_options,
)


class ProgressView:
    """Live progress on stderr: a rich status line on a terminal, plain lines otherwise."""

    def __init__(self, enabled: bool = True) -> None:
        from rich.console import Console

        self.enabled = enabled
        self.console = Console(stderr=True)
        self._status: Any = None
        self._last: str | None = None

    def __enter__(self) -> ProgressView:
        if self.enabled and self.console.is_terminal:
            self._status = self.console.status("starting")
            self._status.__enter__()
        return self

    def __exit__(self, *exc: object) -> None:
        if self._status is not None:
            self._status.__exit__(*exc)
            self._status = None

    def update(self, event: Any) -> None:
        """Show one :class:`~matloom.author.pipeline.ProgressEvent`."""
        if not self.enabled:
            return
        text = f"[{event.run}] {event.stage}: {event.message}"
        if event.round is not None:
            text += f" (round {event.round})"
        if event.total:
            text += f" {event.done}/{event.total}"
        if event.eta_s is not None:
            text += f" ETA {event.eta_s:.0f}s"
        if self._status is not None:
            self._status.update(text)
        elif event.done is None or event.done == event.total:
            line = f"[{event.run}] {event.stage}: {event.message}"
            if line != self._last:
                self.console.print(line, markup=False, highlight=False)
                self._last = line

    def batch_done(self, outcome: Any) -> None:
        if self.enabled:
            state = "done" if outcome.result else f"failed: {outcome.error}"
            self.console.print(f"[{outcome.item.id}] {state}", markup=False, highlight=False)


@click.command("generate")
@click.argument("prompt", required=False)
@click.option(
    "-o",
    "--out",
    "out_dir",
    required=True,
    type=click.Path(file_okay=False),
    help="Run folder (with --prompts: the parent of one folder per prompt).",
)
@click.option(
    "--prompts",
    "prompts_file",
    type=click.Path(exists=True, dir_okay=False),
    help="JSON file of prompts to author as a batch.",
)
@click.option("--jobs", type=int, default=1, show_default=True, help="Prompts authored at once.")
@click.option("--resume", is_flag=True, help="Continue an interrupted run (or batch).")
@click.option(
    "--trust-record",
    is_flag=True,
    help="With --resume: use the model servers and key variables that record.json names "
    "(only for a run folder you made; otherwise give --base-url/--profile again).",
)
@click.option("--json", "as_json", is_flag=True, help="Print the result as JSON.")
@click.option("--quiet", is_flag=True, help="No progress display.")
@click.option(
    "--explain",
    is_flag=True,
    help="Print (on stderr) how the library chose the program: the top candidates with "
    "scores, the chosen entry, the adaptations applied and the words it ignored.",
)
@model_options
@pipeline_options
@click.pass_context
def generate_cmd(
    ctx: click.Context,
    prompt: str | None,
    out_dir: str,
    prompts_file: str | None,
    jobs: int,
    resume: bool,
    trust_record: bool,
    as_json: bool,
    quiet: bool,
    explain: bool,
    **_: Any,
) -> None:
    """Author a material program for PROMPT (text -> program -> critique -> selection -> seeds).

    With no model configured (no --model, --profile or default profile) the program comes from
    the material library (offline, deterministic): see --explain and --pick.
    """
    from matloom.author.pipeline import check_inputs, check_prompt, check_sizes

    given = explicit_flags(ctx)
    try:
        if prompt is not None:
            check_prompt(prompt)
        base = _resumed_settings(out_dir) if resume and not prompts_file else None
        config = build_config(
            ctx.params, given, base, trust_record=trust_record, library_env=_library_env()
        )
        check_sizes(config)
        check_inputs(config)  # --reference readable, --polish's package installed
        _user_library(config)
    except (ConfigError, ValueError) as err:
        raise click.ClickException(one_line(err)) from None
    if prompt is None and prompts_file is None and base is None:
        raise click.UsageError("give a PROMPT, --prompts FILE, or --resume an existing run")
    _say_model_access(ctx.params, given, config, fresh=base is None)
    if config.generator is None:
        click.echo(
            "matloom: no model configured (--model/--profile); using the material library",
            err=True,
        )
        if "start" in given:
            click.echo("matloom: --start is irrelevant without a model; ignored", err=True)
    elif "pick" in given and config.start != "library":
        click.echo("matloom: --pick applies only with --start library; ignored", err=True)
    if prompt is not None and not prompts_file and base is None:
        _check_pick(prompt, config)
    view = ProgressView(enabled=not quiet)
    if prompts_file:
        _run_batch(prompts_file, out_dir, config, jobs, resume, as_json, view)
    else:
        asked = bool(SEARCH_FLAGS & given) and not (
            "variants" not in given and config.scorer == "none"
        )
        _run_single(prompt, out_dir, config, resume, as_json, view, explain, asked)


def _say_model_access(
    params: dict[str, Any], given: set[str], config: AuthorConfig, *, fresh: bool
) -> None:
    """Name on stderr, always, the server and the key variable each model's requests use, and
    the config file a default profile came from (so no file turns a run into requests
    silently); say when ./matloom.toml is not read."""
    from matloom.author.access import describe_access
    from matloom.author.config import (
        default_profile_name,
        find_config_file,
        ignored_local_config,
        load_config_file,
    )

    used = find_config_file(params["config_file"])
    local = ignored_local_config(used)
    if local is not None:
        click.echo(
            f"matloom: {local} is not read: a config in the current folder is used only with "
            f"--config {local}",
            err=True,
        )
    if config.generator is None:
        return
    note = ""
    if fresh and not {"profile", "model"} & given and used is not None:
        name = default_profile_name(load_config_file(used))
        note = f" (default profile {name!r} of {used})" if name else ""
    click.echo(f"matloom: {describe_access('generator', config.generator)}{note}", err=True)
    if config.critic is not None:
        click.echo(f"matloom: {describe_access('critic', config.critic)}", err=True)


def _library_env() -> str | None:
    """``$MATLOOM_LIBRARY_PATH`` (read here, once, and passed down)."""
    import os

    from matloom.library.user import ENV

    return os.environ.get(ENV)


def _user_library(config: AuthorConfig) -> Any:
    """The library the run draws from (with the user folders' entries), read before anything
    is written: a bad user entry is a one-line error naming its file."""
    from matloom.library.user import library_for

    return library_for(config.library_dirs)


def _check_pick(prompt: str, config: AuthorConfig) -> None:
    """Refuse a --pick past the library's candidates before anything is written."""
    if config.pick is None or (config.generator is not None and config.start != "library"):
        return
    from matloom.library import search

    count = len(search(prompt, _user_library(config)))
    if config.pick > count:
        found = f"only {count} candidate{'s' if count != 1 else ''}" if count else "no entry"
        raise click.ClickException(
            f"--pick {config.pick}: {found} matched the prompt "
            "(`matloom library search PROMPT` lists them)"
        )


def _resumed_settings(out_dir: str) -> AuthorConfig | None:
    from matloom.author.records import RECORD_NAME, RecordStore

    path = Path(out_dir) / RECORD_NAME
    if not path.exists():
        return None
    try:
        return RecordStore.load(out_dir).record.settings
    except (OSError, ValueError) as err:  # pydantic's ValidationError and JSON errors included
        reason = one_line(err)
        raise ConfigError(f"cannot resume: {path} is not a valid run record ({reason})") from None


def _run_single(
    prompt: str | None,
    out_dir: str,
    config: AuthorConfig,
    resume: bool,
    as_json: bool,
    view: ProgressView,
    explain: bool = False,
    search_asked: bool = False,
) -> None:
    from matloom.author.pipeline import AuthoringError, RunRequestError, author_material
    from matloom.io.outdir import OutputError

    try:
        with view:
            result = author_material(prompt, out_dir, config, resume=resume, progress=view.update)
    except (OutputError, RunRequestError) as err:  # nothing was done
        raise click.ClickException(str(err)) from None
    except AuthoringError as err:
        raise click.ClickException(f"{err}{_record_note(err.folder)}") from None
    except Exception as err:  # noqa: BLE001 - the CLI never shows a traceback
        from matloom.author.redact import Redactor

        raise click.ClickException(
            Redactor.for_config(config).text(f"unexpected {type(err).__name__}: {err}")
            + _record_note(Path(out_dir))
        ) from None
    if explain:
        _say_explanation(result.record)
    if as_json:
        click.echo(json.dumps(result.summary(), indent=2))
    else:
        click.echo(result.program)
    if search_asked:
        _say_scorer_note(result.record)
    _say_warnings(result.record)


def _record_note(folder: Path) -> str:
    """Where the failed run's record is, when there is one to resume."""
    from matloom.author.records import RECORD_NAME

    path = Path(folder) / RECORD_NAME
    if not path.is_file():
        return ""
    return f"\n(the record is kept in {path}; fix the cause and rerun with --resume)"


def _say_explanation(record: Any) -> None:
    """The library's explanation on stderr (of P0 when a model revised it)."""
    explanation = record.library_explanation
    if explanation is None:
        explanation = "(no library explanation: an LLM wrote this program)"
    elif record.author == "llm" and record.final is not None:
        explanation = (
            "P0 came from the material library; the result is "
            f"P{record.final.program_index}. P0's explanation:\n{explanation}"
        )
    click.echo(explanation, err=True)


def _say_warnings(record: Any, prefix: str = "matloom") -> None:
    """The run's warnings (e.g. a material with non-finite maps) on stderr."""
    for warning in record.warnings:
        click.echo(f"{prefix}: warning: {warning}", err=True)


def _say_scorer_note(record: Any) -> None:
    """Why the seed search was skipped (only said when the user asked for a scorer or a
    search: otherwise the record keeps it)."""
    search = record.seed_search
    if search is not None and search.skipped:
        click.echo(f"matloom: seed search skipped: {search.skipped}", err=True)


def _run_batch(
    prompts_file: str,
    out_dir: str,
    config: AuthorConfig,
    jobs: int,
    resume: bool,
    as_json: bool,
    view: ProgressView,
) -> None:
    from matloom.author.batch import author_batch, read_prompts

    try:
        items = read_prompts(prompts_file)
    except (OSError, ValueError) as err:
        raise click.ClickException(str(err)) from None
    with view:
        outcomes = author_batch(
            items,
            out_dir,
            config,
            jobs=jobs,
            resume=resume,
            progress=view.update,
            on_done=view.batch_done,
        )
    rows = [
        {
            "id": o.item.id,
            "prompt": o.item.text,
            "folder": str(o.folder),
            "status": "finished" if o.result else "failed",
            "error": o.error,
        }
        for o in outcomes
    ]
    if as_json:
        click.echo(json.dumps(rows, indent=2))
    else:
        for row in rows:
            click.echo(f"{row['id']}\t{row['status']}\t{row['folder']}")
    for o in outcomes:
        if o.result is not None:
            _say_warnings(o.result.record, prefix=f"matloom: [{o.item.id}]")
    failed = sum(o.result is None for o in outcomes)
    if failed:
        click.echo(f"matloom: {failed} of {len(outcomes)} prompt(s) failed", err=True)
        sys.exit(1)


@click.command("prompt")
@click.option("--print", "do_print", is_flag=True, default=True, help="Print the system prompt.")
@click.option("--playbook/--no-playbook", default=True, show_default=True)
@click.option("--few-shot/--no-few-shot", default=True, show_default=True)
@click.option(
    "--examples",
    type=click.Choice(["paper", "v3"]),
    default="paper",
    show_default=True,
    help="The few-shot examples (as --examples of generate; v3 with --settings recommended).",
)
@click.option(
    "--critic",
    "critic_signals",
    default=None,
    help="Print the critic system prompt for these signals instead (e.g. render,code).",
)
@click.option(
    "--views",
    type=click.Choice(["flat", "lit", "both"]),
    default="flat",
    show_default=True,
    help="The preview layouts the critic sees (as --critic-views of generate).",
)
@click.option(
    "--size",
    type=int,
    default=AuthorConfig().critique_size,
    show_default=True,
    help="The render size the prompt states (--critique-size of generate).",
)
@click.option("--history", is_flag=True, help="With --critic: the critic sees the previous round.")
def prompt_cmd(  # noqa: PLR0913 - one flag each
    do_print: bool,
    playbook: bool,
    few_shot: bool,
    examples: str,
    critic_signals: str | None,
    views: str,
    size: int,
    history: bool,
) -> None:
    """Print the generator system prompt (rendered from the vocabulary registry)."""
    from matloom.author.config import CRITIC_VIEWS

    shown = CRITIC_VIEWS[views]
    if critic_signals is not None:
        from matloom.author.prompts.critic import critic_system_prompt

        signals = [s.strip() for s in critic_signals.split(",") if s.strip()]
        click.echo(critic_system_prompt(signals, shown, history=history), nl=False)
        return
    from matloom.author.prompts.system import system_prompt

    text = system_prompt(
        playbook=playbook, few_shot=few_shot, render_size=size, views=shown, examples=examples
    )
    click.echo(text, nl=False)


@click.group("scorer")
def scorer_cmd() -> None:
    """Text-image scorers used for selection and seed search."""


@scorer_cmd.command("list")
def scorer_list() -> None:
    """List registered scorer names."""
    from matloom.author.scorers.lookup import scorer_names

    for name in scorer_names():
        click.echo(name)


@scorer_cmd.command("check")
@click.argument("name", default="mobileclip2")
@click.option("--text", default="red brick wall", show_default=True)
def scorer_check(name: str, text: str) -> None:
    """Load scorer NAME and score a grey test image (tells whether weights are available)."""
    import numpy as np

    from matloom.author.scorers.base import ScorerUnavailableError
    from matloom.author.scorers.lookup import get_scorer

    try:
        scorer = get_scorer(name)
    except ScorerUnavailableError as err:
        raise click.ClickException(str(err)) from None
    image = np.full((256, 256, 3), 128, dtype=np.uint8)
    click.echo(f"{scorer.name}\t{float(scorer.score([image], text)[0]):.3f}")
