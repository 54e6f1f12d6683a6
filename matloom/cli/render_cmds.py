"""`matloom preview`, `matloom stats`, `matloom sweep`."""

from __future__ import annotations

import contextlib
import json
import sys
from pathlib import Path

import click

from matloom.cli import params
from matloom.cli.engine_cmds import load_program, resolve_size, size_options
from matloom.cli.tileable import apply_tileable, tileable_option


def _light(angles: tuple[float, float] | None):  # noqa: ANN202 - Light | None
    from matloom.render.preview import Light

    return None if angles is None else Light(*angles)


@contextlib.contextmanager
def _limits_as_errors(*also: type[Exception]):  # noqa: ANN202 - a context manager
    """A documented resource limit (LimitError), or one of ``also``, ends the command with its
    one-line message instead of a traceback."""
    from matloom.engine.limits import LimitError

    try:
        yield
    except (LimitError, *also) as e:
        raise click.ClickException(str(e)) from None


def _save_png(path: str | Path, img) -> None:  # noqa: ANN001
    from matloom.io.outdir import save_output_png

    save_output_png(path, img)


@click.command("preview")
@click.argument("file")
@click.option(
    "-o", "--out", "out", required=True, type=click.Path(dir_okay=False), help="Output PNG path."
)
@size_options
@click.option(
    "--light",
    type=params.LIGHT,
    default=None,
    help="Light AZIMUTH,ELEVATION in degrees, elevation -90..90 (default: reference); "
    "in the lit layout it replaces the key light (default 135,25).",
)
@click.option(
    "--tile",
    type=params.TILE,
    default=1,
    show_default=True,
    help="Tile the swatch N x N to show seams.",
)
@click.option("--backend", type=params.BACKEND, default="auto", show_default=True)
@click.option(
    "--layout",
    type=click.Choice(("flat", "lit", "both")),
    default="flat",
    show_default=True,
    help="flat: the reference's fixed-light swatch; lit: PBR shading in a small studio "
    "(docs/preview.md); both: side by side, flat left.",
)
@tileable_option
def preview_cmd(
    file: str,
    out: str,
    size: int | None,
    width: int | None,
    height: int | None,
    light: tuple[float, float] | None,
    tile: int,
    backend: str,
    layout: str,
    tileable: bool,
) -> None:
    """Render the quick head-on shaded preview of FILE to a PNG (--tile 2 --tileable shows
    the repeat, --layout lit|both the studio-lit swatch)."""
    from matloom.render.api import preview

    w, h = resolve_size(size, width, height, 512)
    wide = 2 if layout == "both" else 1
    if max(w * wide, h) * tile > params.MAX_SIDE:
        raise click.BadParameter(
            f"{tile} x {max(w * wide, h)} pixels is more than the maximum image side "
            f"{params.MAX_SIDE}",
            param_hint="'--tile'",
        )
    program, text = load_program(file)
    program = apply_tileable(program, tileable, text, file)
    with _limits_as_errors():
        img = preview(
            program,
            width=w,
            height=h,
            light=_light(light),
            tile=tile,
            backend=backend,
            layout=layout,  # type: ignore[arg-type]
        )
    _save_png(out, img)
    click.echo(str(Path(out).resolve()))


@click.command("stats")
@click.argument("file")
@click.option("--json", "as_json", is_flag=True, help="Machine-readable output.")
@click.option(
    "--grid", type=params.STATS_GRID, default=128, show_default=True, help="Evaluation grid size."
)
def stats_cmd(file: str, as_json: bool, grid: int) -> None:
    """Print the 28 material statistics of FILE (the critic's objective scalars)."""
    from matloom.render.api import stats
    from matloom.render.stats import STAT_DEFINITIONS, format_stats

    program, _ = load_program(file)
    with _limits_as_errors():
        values = stats(program, grid)
    if as_json:
        click.echo(
            json.dumps(
                {k: {"value": v, "definition": STAT_DEFINITIONS[k]} for k, v in values.items()},
                indent=2,
            )
        )
    else:
        click.echo(format_stats(values))


@click.command("sweep")
@click.argument("file")
@click.option(
    "--variants", "-k", type=params.VARIANTS, required=True, help="Number of seed variants K."
)
@click.option("--size", type=params.SIZE, default=256, show_default=True)
@click.option("--scorer", default=None, help="Registered text-image scorer name.")
@click.option("--prompt", default=None, help="Text the scorer compares against.")
@click.option("--seed", type=int, default=0, show_default=True, help="Variant RNG seed.")
@click.option(
    "--jobs",
    type=params.JOBS,
    default=0,
    show_default=True,
    help="Shading threads (0 = all cores).",
)
@click.option(
    "-o",
    "--out",
    "out_dir",
    type=click.Path(file_okay=False),
    default=None,
    help="Write best.mat, report.json and previews here.",
)
@click.option(
    "--sheet",
    type=click.Path(dir_okay=False),
    default=None,
    help="Contact sheet PNG of the top candidates.",
)
@click.option(
    "--top", type=params.TOP, default=8, show_default=True, help="Candidates on the sheet."
)
@click.option("--json", "as_json", is_flag=True)
@tileable_option
def sweep_cmd(
    file: str,
    variants: int,
    size: int,
    scorer: str | None,
    prompt: str | None,
    seed: int,
    jobs: int,
    out_dir: str | None,
    sheet: str | None,
    top: int,
    as_json: bool,
    tileable: bool,
) -> None:
    """Render the original and K seed variants of FILE; with a scorer, keep the best."""
    from matloom.author.scorers.base import ScorerUnavailableError
    from matloom.author.scorers.lookup import get_scorer
    from matloom.cli.progress import LazyProgress
    from matloom.engine.schedules.sweep import run_sweep
    from matloom.io.outdir import OutputFolder
    from matloom.lang.printer import format_program
    from matloom.render.preview import ShadeParams

    if scorer and not prompt:
        raise click.UsageError("--scorer needs --prompt")
    program, source = load_program(file)
    program = apply_tileable(program, tileable, source, file)
    text = format_program(program)
    with contextlib.ExitStack() as stack:  # the folder is locked before the work starts
        out = stack.enter_context(OutputFolder(out_dir)) if out_dir else None
        with _limits_as_errors(ScorerUnavailableError), LazyProgress("sweep") as bar:
            res = run_sweep(
                text,
                variants=variants,
                shading=ShadeParams.of(),
                size=size,
                scorer=get_scorer(scorer) if scorer else None,
                prompt=prompt,
                seed=seed,
                jobs=jobs,
                keep=top,
                progress=bar,
            )
        if res.message:
            click.echo(res.message, err=True)
        report = {
            "candidates": res.n_candidates,
            "seconds": round(res.seconds, 3),
            "candidates_per_second": round(res.rate, 1),
            "best_index": res.best_index,
            "best_score": res.candidates[res.best_index].score,
            "scorer": scorer,
            "seed": seed,
            "size": size,
            "scores": [c.score for c in res.candidates] if scorer else None,
        }
        if out is not None:
            _write_sweep_folder(out, res, report)
        if sheet:
            from matloom.render.sheet import contact_sheet

            labels = [
                f"#{i}"
                + (f" {res.candidates[i].score:.1f}" if res.candidates[i].score is not None else "")
                for i, _ in res.top_images
            ]
            _save_png(sheet, contact_sheet([im for _, im in res.top_images], labels))
        click.echo(
            f"{res.n_candidates} candidates in {res.seconds:.2f} s "
            f"({res.rate:.0f}/s); best #{res.best_index}",
            err=True,
        )
        if as_json:
            click.echo(json.dumps(report, indent=2))
        else:
            click.echo(res.best_program)
        sys.stdout.flush()


def _write_sweep_folder(out, res, report: dict) -> None:  # noqa: ANN001
    """best.mat, report.json and the top candidates' previews, staged into the folder."""
    from matloom.io.atomic import atomic_write_bytes
    from matloom.io.png import save_png

    with out.batch("sweep", marker="report.json") as staging:
        atomic_write_bytes(staging / "best.mat", (res.best_program + "\n").encode())
        for idx, img in res.top_images:
            save_png(staging / f"candidate_{idx:04d}.png", img)
        atomic_write_bytes(staging / "report.json", json.dumps(report, indent=2).encode())
