"""`matloom edit FILE "REQUEST"`: edit a material by words, offline or with a model.

Where it writes (never over a file it did not write, unless asked):

* the program: ``-o OUT``; else FILE itself with ``--write``, or when FILE has an edit history
  (edits chain; a change made by hand since the last edit is kept as a version first); else
  ``<stem>.edited.mat`` beside FILE. An existing OUT is replaced only when its history says it
  is ours and unchanged (or it is FILE with ``--write``);
* its history ``OUT.history.json`` (every version; ``--undo`` goes back one);
* a folder ``<OUT stem>.edit/`` with ``edit.json`` (request, edit, changed parameters,
  locality report), ``edit.diff`` (unified diff) and ``before_after.png`` (previews side by
  side).
"""

from __future__ import annotations

import difflib
import json
import sys
from pathlib import Path
from typing import Any

import click

from matloom.cli import params as cli_params
from matloom.cli.generate_options import explicit_flags

#: Side of each preview in before_after.png.
PREVIEW_SIZE = 256
_GAP = 4


def _fail(message: str, code: int = 2) -> None:
    click.echo(f"Error: {message}", err=True)
    sys.exit(code)


def _read(path: Path) -> str:
    try:
        return path.read_text(encoding="utf-8")
    except OSError as e:
        raise click.ClickException(f"cannot read {path}: {e.strerror}") from None
    except UnicodeDecodeError:
        raise click.ClickException(f"{path} is not UTF-8 text") from None


def _out_path(file: Path, out: str | None, write: bool, has_history: bool) -> Path:
    if out is not None:
        return Path(out)
    if write or has_history:
        return file
    name = file.name.removesuffix(".mat")
    return file.with_name(f"{name}.edited.mat")


def _model(params: dict[str, Any], given: set[str]) -> Any:
    """The chat model the flags (and the config file's default profile) describe, or None."""
    from matloom.author.config import ConfigError, one_line
    from matloom.author.llm.base import ModelError
    from matloom.author.llm.providers import get_model
    from matloom.cli.generate_options import _generator_settings

    try:
        settings = _generator_settings(params, given, None)
        if settings is None:
            return None
        where = settings.base_url or "the provider's default endpoint"
        click.echo(f"matloom: editing with {settings.model} at {where}", err=True)
        return get_model(settings)
    except (ConfigError, ModelError, ValueError) as err:
        raise click.ClickException(one_line(err)) from None


def _previews(before: str, after: str) -> bytes:
    """before_after.png: before (left) and after (right), the flat preview above and the lit
    studio (gloss and relief show there) below."""
    import numpy as np

    from matloom.io.png import encode_png
    from matloom.render.api import preview

    a = preview(before, PREVIEW_SIZE, layout="both")
    b = preview(after, PREVIEW_SIZE, layout="both")
    w = a.shape[1] // 2
    gap = np.full((a.shape[0], _GAP, 3), 255, np.uint8)
    flat = np.concatenate([a[:, :w], gap, b[:, :w]], axis=1)
    lit = np.concatenate([a[:, w:], gap, b[:, w:]], axis=1)
    bar = np.full((_GAP, flat.shape[1], 3), 255, np.uint8)
    return encode_png(np.concatenate([flat, bar, lit], axis=0))


def _write_outputs(out: Path, before: str, after: str, record: dict[str, Any]) -> Path:
    from matloom.io.atomic import atomic_write_bytes

    folder = out.with_name(out.name.removesuffix(".mat") + ".edit")
    folder.mkdir(parents=True, exist_ok=True)
    diff = "".join(
        difflib.unified_diff(
            before.splitlines(keepends=True),
            after.splitlines(keepends=True),
            fromfile=f"{out.name} (before)",
            tofile=f"{out.name} (after)",
        )
    )
    atomic_write_bytes(folder / "edit.diff", diff.encode("utf-8"))
    atomic_write_bytes(folder / "before_after.png", _previews(before, after))
    atomic_write_bytes(folder / "edit.json", (json.dumps(record, indent=2) + "\n").encode())
    return folder


def _undo(file: Path, out: Path, as_json: bool) -> None:
    from matloom.author.edit.history import History, HistoryError
    from matloom.io.atomic import atomic_write_bytes

    try:
        history = History.load(out)
        if not history.versions:
            _fail(f"{out} has no edit history: nothing to undo")
        if not out.exists() or not history.manages(_read(out)):
            _fail(f"{out} changed since its last edit; undo would lose that change")
        restored = history.undo()
    except HistoryError as err:
        _fail(str(err))
        return
    atomic_write_bytes(out, restored.encode("utf-8"))
    history.save()
    summary = {"undone": True, "file": str(out), "version": len(history.versions) - 1}
    if as_json:
        click.echo(json.dumps(summary, indent=2))
    click.echo(f"restored version {summary['version']} of {out}", err=True)


@click.command("edit")
@click.argument("file", type=click.Path(dir_okay=False))
@click.argument("request", required=False)
@click.option("-o", "--out", help="Write the edited program here (see below for the default).")
@click.option("--write", is_flag=True, help="Write the edited program into FILE itself.")
@click.option("--undo", is_flag=True, help="Restore the version before the last edit.")
@click.option("--json", "as_json", is_flag=True, help="Print edit.json on stdout.")
@click.option(
    "--repair-turns",
    type=click.IntRange(0, 10),
    default=2,
    show_default=True,
    help="With a model: answers sent back (failed check, changed seeds, a leak).",
)
@click.option(
    "--size",
    type=cli_params.SIZE,
    default=256,
    show_default=True,
    help="Grid side for the locality check.",
)
@click.option("--profile", help="Model profile from matloom.toml.")
@click.option("--config", "config_file", type=click.Path(dir_okay=False), help="Config file.")
@click.option("--model", help="Model id (OpenAI-compatible); without one the edit is offline.")
@click.option("--base-url", help="Chat Completions endpoint, e.g. http://localhost:8000/v1.")
@click.option("--temperature", type=float)
@click.option("--reasoning-effort")
@click.option("--extra-body", help="JSON object merged into each request body.")
@click.option("--timeout", type=float, help="Seconds per model request.")
@click.option("--max-retries", type=int, help="Retries on 429/5xx/timeouts.")
@click.option("--retry-backoff", type=float, help="First retry delay in seconds.")
@click.pass_context
def edit_cmd(
    ctx: click.Context,
    file: str,
    request: str | None,
    out: str | None,
    write: bool,
    undo: bool,
    as_json: bool,
    repair_turns: int,
    size: int,
    **_: Any,
) -> None:
    """Edit program FILE by REQUEST ("wider grout", "blue glaze", "rougher").

    Offline (no --model or profile) common requests map to parameter changes; others are
    refused with the parameters that could change. The program goes to -o OUT, else
    <stem>.edited.mat beside FILE (FILE itself with --write, or when FILE has an edit
    history); OUT.history.json keeps every version (--undo);
    <OUT stem>.edit/ holds edit.json, edit.diff and before_after.png. Exit 0 when the edit
    stayed in its channels, 1 when it leaked (written and reported), 2 on errors.
    """
    from matloom.author.edit import EditError, EditRefused, edit
    from matloom.author.edit.history import History, HistoryError
    from matloom.io.atomic import atomic_write_bytes
    from matloom.lang.diagnostics import ProgramError

    path = Path(file)
    text = _read(path)
    try:
        own = History.load(path)
    except HistoryError as err:
        _fail(str(err))
        return
    target = _out_path(path, out, write, bool(own.versions))
    if undo:
        if request is not None:
            raise click.UsageError("--undo takes no REQUEST")
        _undo(path, target, as_json)
        return
    if not request or not request.strip():
        raise click.UsageError('give a REQUEST, e.g. matloom edit tiles.mat "wider grout"')
    try:
        history = own if target == path else History.load(target)
    except HistoryError as err:
        _fail(str(err))
        return
    if target.exists() and not (target == path and (write or own.versions)):
        if not history.manages(_read(target)):
            _fail(f"{target} exists and was not written by matloom edit; choose -o or --write")
    model = _model(ctx.params, explicit_flags(ctx))
    try:
        result = edit(text, request, model, repair_turns=repair_turns, size=size)
    except EditRefused as err:
        _fail(str(err))
        return
    except (EditError, ProgramError, ValueError) as err:
        _fail(" ".join(str(err).split()))
        return
    if history.current != text:  # a starting point, or a hand edit since the last version
        history.add(text, None, source=str(path))
    record = result.report.to_json()
    program = result.program.rstrip("\n") + "\n"  # a program file ends with one newline
    history.add(program, request, mode=record["mode"], changed=record["changed"])
    atomic_write_bytes(target, program.encode("utf-8"))
    history.save()
    record["program"] = str(target)
    record["history"] = str(history.path)
    record["version"] = len(history.versions) - 1
    folder = _write_outputs(target, text, program, record)
    if as_json:
        click.echo(json.dumps(record, indent=2))
    report = result.report
    for w in report.warnings:
        click.echo(f"warning: {w}", err=True)
    changed = ", ".join(c.address for c in report.changes) or "nothing"
    click.echo(f"edited {target} (version {record['version']}): {changed}", err=True)
    click.echo(f"locality: {report.locality.describe()}; report in {folder}", err=True)
    if not report.ok:
        sys.exit(1)
