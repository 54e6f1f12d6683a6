"""`matloom library add`: a program, or a `generate` run's result, into a user library."""

from __future__ import annotations

from pathlib import Path

import click

from matloom.cli.library_opts import library_option, load_library

#: The longest description taken from a run's prompt (words beyond it are dropped).
PROMPT_DESCRIPTION_CHARS = 300


def _read_program(path: str) -> str:
    from matloom.library.user import MAX_ENTRY_BYTES

    p = Path(path)
    try:
        if p.stat().st_size > MAX_ENTRY_BYTES:
            raise click.ClickException(f"{path} is larger than {MAX_ENTRY_BYTES:,} bytes")
        return p.read_text(encoding="utf-8")
    except OSError as exc:
        raise click.ClickException(f"cannot read {path}: {exc.strerror or exc}") from None
    except UnicodeDecodeError:
        raise click.ClickException(f"{path} is not UTF-8 text") from None


def _from_run(folder: str) -> tuple[str, str]:
    """(final program, prompt) of a `matloom generate -o RUN` folder."""
    from matloom.author.config import one_line
    from matloom.author.records import RECORD_NAME, RecordStore

    record_path = Path(folder) / RECORD_NAME
    if not record_path.is_file():
        raise click.ClickException(
            f"{folder} holds no {RECORD_NAME}: give the folder `matloom generate -o RUN` wrote"
        )
    try:
        record = RecordStore.load(folder).record
    except (OSError, ValueError) as exc:
        raise click.ClickException(f"cannot read {record_path}: {one_line(exc)}") from None
    if record.final is None:
        raise click.ClickException(
            f"{folder}: the run has no final program (status {record.status}); finish it with "
            f"`matloom generate -o {folder} --resume`"
        )
    return record.final.program, record.prompt


def _target(to: str | None, library_dirs: tuple[str, ...]) -> Path:
    """``--to``, else the first ``--library``, else the first folder of the environment's."""
    import os

    from matloom.library.user import ENV, split_path

    if to is not None:
        return Path(to)
    if library_dirs:
        return Path(library_dirs[0])
    env = split_path(os.environ.get(ENV))
    if env:
        return Path(env[0])
    raise click.ClickException(
        f"no user library to add to: give --to DIR (or --library DIR, or set {ENV})"
    )


def _description(prompt: str) -> str:
    text = " ".join(prompt.split())
    if len(text) <= PROMPT_DESCRIPTION_CHARS:
        return text
    return text[:PROMPT_DESCRIPTION_CHARS].rsplit(" ", 1)[0]


@click.command("add")
@click.argument("program", required=False, type=click.Path(dir_okay=False))
@click.option("--name", required=True, help="Entry name: lowercase words joined by '-'.")
@click.option("--tags", required=True, help="Comma-separated words a user would type.")
@click.option("--description", help="One sentence (default: the run's prompt, or the name).")
@click.option(
    "--category", help="One of the library's categories (default: that of the closest entry)."
)
@click.option("--synonyms", help="Comma-separated other names, may be several words each.")
@click.option(
    "--size-m",
    type=float,
    default=None,
    help="Metres the View's width spans (default: from the View's unit_m, else 1).",
)
@click.option(
    "--to",
    "to",
    type=click.Path(file_okay=False),
    help="The user library folder written (default: the first --library, else the first "
    "folder of $MATLOOM_LIBRARY_PATH); created if missing.",
)
@click.option(
    "--from-run",
    "from_run",
    type=click.Path(file_okay=False),
    help="Take the final program (and the prompt, as the description) of a `matloom "
    "generate -o RUN` folder instead of PROGRAM.",
)
@click.option("--force", is_flag=True, help="Replace an entry of that name in the folder.")
@library_option
def add_cmd(
    program: str | None,
    name: str,
    tags: str,
    description: str | None,
    category: str | None,
    synonyms: str | None,
    size_m: float | None,
    to: str | None,
    from_run: str | None,
    force: bool,
    library_dirs: tuple[str, ...],
) -> None:
    """Add PROGRAM (a .mat file) as entry NAME of a user library: checked (errors refused),
    its tileability measured (tileable = true only when it repeats with its View and every
    seam ratio is <= 1.2), its parameters labelled in the front matter; prints the file."""
    from matloom.library.add import AddError, AddRequest, add_entry, split_list

    if (program is None) == (from_run is None):
        raise click.UsageError("give PROGRAM or --from-run RUN (one of them)")
    target = _target(to, library_dirs)
    if from_run is not None:
        text, prompt = _from_run(from_run)
        source = f"run {from_run}"
        description = description or _description(prompt)
    else:
        assert program is not None
        text, source = _read_program(program), program
    lib = load_library(library_dirs, missing_ok=True)  # the target may not exist yet
    req = AddRequest(
        name=name,
        tags=tuple(t.lower() for t in split_list(tags)),
        description=description,
        category=category,
        synonyms=split_list(synonyms),
        size_m=size_m,
        force=force,
        source=source,
    )
    try:
        added = add_entry(text, req, target, lib)
    except AddError as exc:
        raise click.ClickException(str(exc)) from None
    for note in added.notes:
        click.echo(f"matloom: {note}", err=True)
    t = added.tiling
    click.echo(f"matloom: tileable: {'yes' if t.tileable else 'no'} ({t.why})", err=True)
    labels = ", ".join(f"{a.removeprefix('define:')} = {v}" for a, v in added.labels.items())
    click.echo(f"matloom: labels: {labels or 'none (no colour slot or constant Define)'}", err=True)
    for warning in added.warnings:
        click.echo(f"matloom: warning: {warning}", err=True)
    click.echo(str(added.path))
