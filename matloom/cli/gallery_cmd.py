"""`matloom gallery PROMPTS.json -o DIR`: author every prompt from the material library (offline)
and write a gallery."""

from __future__ import annotations

import statistics
import sys
from typing import TYPE_CHECKING

import click

from matloom.cli import params

if TYPE_CHECKING:
    from matloom.library.author import LibraryResult


@click.command("gallery")
@click.argument("prompts_file", type=click.Path(exists=True, dir_okay=False))
@click.option(
    "-o",
    "--out",
    "out_dir",
    required=True,
    type=click.Path(file_okay=False),
    help="Output folder (index.html, contact_sheet.png, previews/, programs/).",
)
@click.option(
    "--seed",
    type=int,
    default=0,
    show_default=True,
    help="Author seed (0 keeps each entry's own noise seeds; others re-derive them).",
)
@click.option(
    "--size", type=params.GALLERY_SIZE, default=256, show_default=True, help="Preview size."
)
@click.option(
    "--columns", type=params.COLUMNS, default=8, show_default=True, help="Contact-sheet columns."
)
def gallery_cmd(prompts_file: str, out_dir: str, seed: int, size: int, columns: int) -> None:
    """Author each prompt of PROMPTS_FILE from the material library and write a gallery.

    PROMPTS_FILE is JSON: {"prompts": [{"id", "source", "text"}, ...]} or a list of strings.
    Each row of the page shows the preview, a 2x2 tiled preview, the program and the library's
    explanation (candidates, entry, adaptations, ignored words). Ids become
    file names: unsafe characters are replaced by "_", and an id whose files would collide
    with an earlier one's (a/b and a_b) gets a short hash suffix; an id given twice is an error.
    """
    from matloom.engine.limits import LimitError
    from matloom.library.gallery import (
        PromptFileError,
        build_gallery,
        library_author,
        load_prompts,
    )

    try:
        prompts = load_prompts(prompts_file)
    except PromptFileError as e:
        raise click.BadParameter(str(e), param_hint="PROMPTS_FILE") from None
    if not prompts:
        raise click.BadParameter(f"no prompts found in {prompts_file}", param_hint="PROMPTS_FILE")
    with click.progressbar(length=len(prompts), label="authoring", file=sys.stderr) as bar:

        def counted(text: str, s: int) -> LibraryResult:
            bar.update(1)
            return library_author(text, s)

        try:
            entries = build_gallery(
                prompts, out_dir, seed=seed, size=size, columns=columns, author_fn=counted
            )
        except LimitError as e:  # e.g. the memory budget at a large --size: one line
            raise click.ClickException(str(e)) from None
    times = [e.author_ms for e in entries]
    lines = [e.lines for e in entries]
    click.echo(f"{len(entries)} materials -> {out_dir}/index.html and contact_sheet.png")
    click.echo(
        f"median authoring time {statistics.median(times):.1f} ms, "
        f"median program length {statistics.median(lines):g} lines"
    )
