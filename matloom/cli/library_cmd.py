"""`matloom library`: browse, render and check the material library (docs/library.md)."""

from __future__ import annotations

import click

from matloom.cli import params
from matloom.cli.engine_cmds import preset_option, render_cmd
from matloom.library.entry import CATEGORIES


def _library():  # noqa: ANN202 - matloom.library.Library
    from matloom.library import LibraryError, library

    try:
        return library()
    except LibraryError as exc:
        raise click.ClickException(str(exc)) from None


def _entry(name: str):  # noqa: ANN202 - matloom.library.Entry
    try:
        return _library().entry(name)
    except KeyError as exc:
        raise click.ClickException(str(exc.args[0])) from None


@click.group("library")
def library_cmd() -> None:
    """Browse, render and check the material library the offline author draws from."""


@library_cmd.command("search")
@click.argument("words", nargs=-1, required=True)
@click.option("--top", type=click.IntRange(1, 100), default=10, show_default=True)
def search_cmd(words: tuple[str, ...], top: int) -> None:
    """The entries that best match WORDS, with their retrieval scores."""
    from matloom.library import search

    lib = _library()
    candidates = search(" ".join(words), lib)
    if not candidates:
        click.echo("no entry matched", err=True)
        raise SystemExit(1)
    for k, c in enumerate(candidates[:top], start=1):
        e = lib.entry(c.name)
        click.echo(f"{k:3}. {c.score:7.2f}  {c.name:28} [{e.category}] {e.description}")
        click.echo(f"{'':14}matched: {', '.join(c.matched)}")


@library_cmd.command("show")
@click.argument("name")
def show_cmd(name: str) -> None:
    """Print entry NAME: its front matter and its program (the file as written)."""
    entry = _entry(name)
    click.echo(f"# {entry.path}")
    click.echo(entry.path.read_text(encoding="utf-8"), nl=False)


@library_cmd.command("list")
@click.option("--category", type=click.Choice(list(CATEGORIES)), default=None, help="One category.")
@click.option("--stats", is_flag=True, help="Print the coverage table by category instead.")
def list_cmd(category: str | None, stats: bool) -> None:
    """List the entries (name, category, tileable, description)."""
    lib = _library()
    if stats:
        from matloom.library.coverage import coverage_table

        click.echo(coverage_table(lib))
        return
    for e in lib.by_category(category):
        mark = "T" if e.tileable else " "
        click.echo(f"{e.category:9} {mark} {e.name:30} {e.description}")


@library_cmd.command("render")
@click.argument("name")
@click.option("-o", "--out", "out_dir", required=True, type=click.Path(file_okay=False))
@click.option("--size", type=params.SIZE, default=None, help="Square size in pixels (512).")
@preset_option("Also write a preset (as matloom render).")
@click.pass_context
def render_entry_cmd(
    ctx: click.Context, name: str, out_dir: str, size: int | None, presets: tuple[str, ...]
) -> None:
    """Render entry NAME into DIR through `matloom render` (maps, material.json, preview), with
    its physical size (size_m over the View's width) as --unit-m."""
    from matloom.library.overlay import view_width

    entry = _entry(name)
    unit_m = entry.size_m / view_width(_library().ast(entry.name))
    ctx.invoke(
        render_cmd, file=str(entry.path), out_dir=out_dir, size=size, unit_m=unit_m, presets=presets
    )


@library_cmd.command("check")
@click.argument("names", nargs=-1)
@click.option(
    "--size",
    type=params.SIZE,
    default=128,
    show_default=True,
    help="Evaluation size of the finite-maps and seam-ratio checks.",
)
def check_cmd(names: tuple[str, ...], size: int) -> None:
    """Validate every entry (or NAMES) and the overlays: parses clean (no warnings), front
    matter matches the program, finite maps, and tileable entries repeat with the View (the
    View moved by one period gives the same maps, at 40 x 40) with a seam ratio <= 1.2 per map
    at --size."""
    from matloom.library.checks import check_entry, overlay_reports

    lib = _library()
    entries = [_entry(n) for n in names] if names else lib.by_category()
    failed = 0
    for e in entries:
        report = check_entry(lib, e, size)
        if not report.ok:
            failed += 1
            click.echo(f"FAIL {e.name} ({e.path})")
            for p in report.problems:
                click.echo(f"     {p}")
    bad_overlays = {k: v for k, v in overlay_reports(lib).items() if v} if not names else {}
    for name, problems in bad_overlays.items():
        failed += 1
        click.echo(f"FAIL overlay {name}: {'; '.join(problems)}")
    checked = len(entries) + (0 if names else len(lib.overlays))
    click.echo(f"{checked - failed} of {checked} passed", err=True)
    if failed:
        raise SystemExit(1)
