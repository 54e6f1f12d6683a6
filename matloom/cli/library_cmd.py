"""`matloom library`: browse, render and check the material library (docs/library.md)."""

from __future__ import annotations

import click

from matloom.cli import params
from matloom.cli.engine_cmds import preset_option, render_cmd
from matloom.cli.library_add import add_cmd
from matloom.cli.library_opts import library_option
from matloom.cli.library_opts import load_library as _library
from matloom.library.entry import CATEGORIES


def _entry(lib, name: str):  # noqa: ANN001, ANN202 - matloom.library.Library, Entry
    try:
        return lib.entry(name)
    except KeyError as exc:
        raise click.ClickException(str(exc.args[0])) from None


def _origin(lib, name: str) -> str:  # noqa: ANN001 - matloom.library.Library
    """Which library entry ``name`` came from, and what it replaced."""
    where = lib.source(name)
    if name in lib.replaced:
        where += f", replacing {lib.replaced[name]}"
    return where


def _say_skipped(lib) -> None:  # noqa: ANN001 - matloom.library.Library
    for line in lib.skipped:
        click.echo(f"matloom: skipped {line}", err=True)


@click.group("library")
def library_cmd() -> None:
    """Browse, render and check the material library the offline author draws from."""


@library_cmd.command("search")
@click.argument("words", nargs=-1, required=True)
@click.option("--top", type=click.IntRange(1, 100), default=10, show_default=True)
@library_option
def search_cmd(words: tuple[str, ...], top: int, library_dirs: tuple[str, ...]) -> None:
    """The entries that best match WORDS, with their retrieval scores (user entries ranked
    with the built-in ones; theirs say which library they came from)."""
    from matloom.library import search

    lib = _library(library_dirs)
    candidates = search(" ".join(words), lib)
    if not candidates:
        click.echo("no entry matched", err=True)
        raise SystemExit(1)
    for k, c in enumerate(candidates[:top], start=1):
        e = lib.entry(c.name)
        mine = f" ({lib.sources[c.name]})" if c.name in lib.sources else ""
        click.echo(f"{k:3}. {c.score:7.2f}  {c.name:28} [{e.category}] {e.description}{mine}")
        click.echo(f"{'':14}matched: {', '.join(c.matched)}")


@library_cmd.command("show")
@click.argument("name")
@library_option
def show_cmd(name: str, library_dirs: tuple[str, ...]) -> None:
    """Print entry NAME: its file, the library it came from, then its front matter and its
    program (the file as written)."""
    lib = _library(library_dirs)
    entry = _entry(lib, name)
    click.echo(f"# {entry.path}")
    click.echo(f"# library: {_origin(lib, name)}")
    click.echo(entry.path.read_text(encoding="utf-8"), nl=False)


@library_cmd.command("list")
@click.option("--category", type=click.Choice(list(CATEGORIES)), default=None, help="One category.")
@click.option("--stats", is_flag=True, help="Print the coverage table by category instead.")
@library_option
def list_cmd(category: str | None, stats: bool, library_dirs: tuple[str, ...]) -> None:
    """List the entries (category, T when tileable, name, description; then the library of
    each user entry, and what it replaced)."""
    lib = _library(library_dirs)
    _say_skipped(lib)
    if stats:
        from matloom.library.coverage import coverage_table

        click.echo(coverage_table(lib))
        return
    for e in lib.by_category(category):
        mark = "T" if e.tileable else " "
        mine = f"  ({_origin(lib, e.name)})" if e.name in lib.sources else ""
        click.echo(f"{e.category:9} {mark} {e.name:30} {e.description}{mine}")


@library_cmd.command("render")
@click.argument("name")
@click.option("-o", "--out", "out_dir", required=True, type=click.Path(file_okay=False))
@click.option("--size", type=params.SIZE, default=None, help="Square size in pixels (512).")
@preset_option("Also write a preset (as matloom render).")
@library_option
@click.pass_context
def render_entry_cmd(
    ctx: click.Context,
    name: str,
    out_dir: str,
    size: int | None,
    presets: tuple[str, ...],
    library_dirs: tuple[str, ...],
) -> None:
    """Render entry NAME into DIR through `matloom render` (maps, material.json, preview), with
    its physical size (size_m over the View's width) as --unit-m."""
    from matloom.library.overlay import view_width

    lib = _library(library_dirs)
    entry = _entry(lib, name)
    unit_m = entry.size_m / view_width(lib.ast(entry.name))
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
@library_option
def check_cmd(names: tuple[str, ...], size: int, library_dirs: tuple[str, ...]) -> None:
    """Validate every entry (or NAMES) and the overlays: parses clean (no warnings), front
    matter matches the program, finite maps, and tileable entries repeat with the View (the
    View moved by one period gives the same maps, at 40 x 40) with a seam ratio <= 1.2 per map
    at --size. With user libraries (--library, $MATLOOM_LIBRARY_PATH) and no NAMES: their
    entries only."""
    from matloom.library.checks import check_entry, overlay_reports
    from matloom.library.user import user_entries

    lib = _library(library_dirs)
    _say_skipped(lib)
    mine = not names and bool(lib.sources)
    if names:
        entries = [_entry(lib, n) for n in names]
    else:
        entries = user_entries(lib) if mine else lib.by_category()
    failed = 0
    for e in entries:
        report = check_entry(lib, e, size)
        if not report.ok:
            failed += 1
            click.echo(f"FAIL {e.name} ({e.path})")
            for p in report.problems:
                click.echo(f"     {p}")
    whole = not names and not mine
    bad_overlays = {k: v for k, v in overlay_reports(lib).items() if v} if whole else {}
    for name, problems in bad_overlays.items():
        failed += 1
        click.echo(f"FAIL overlay {name}: {'; '.join(problems)}")
    checked = len(entries) + (len(lib.overlays) if whole else 0)
    click.echo(f"{checked - failed} of {checked} passed", err=True)
    if failed:
        raise SystemExit(1)


library_cmd.add_command(add_cmd)
