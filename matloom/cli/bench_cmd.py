"""`matloom bench`: run the benchmark (`bench PROMPTS ...`, the default subcommand `run`),
pack blind-judging sheets (`bench pack DIR`) and fold judges' scores back (`bench collect`).

Progress and notes go to stderr; errors are one line, never a traceback.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path
from typing import Any

import click


class _DefaultRun(click.Group):
    """``bench ARGS`` means ``bench run ARGS`` unless the first word names a subcommand."""

    def parse_args(self, ctx: click.Context, args: list[str]) -> list[str]:
        if args and args[0] not in self.commands and args[0] not in ("-h", "--help"):
            args = ["run", *args]
        elif not args:
            args = ["run"]
        return super().parse_args(ctx, args)


@click.group("bench", cls=_DefaultRun)
def bench_cmd() -> None:
    """The paper's benchmark: author every prompt x system x run, render, score, report.

    `matloom bench PROMPTS --system NAME=SPEC ... -o DIR` runs it (see `matloom bench run -h`);
    `matloom bench pack DIR` and `matloom bench collect DIR SCORES...` judge it blind.
    """


def _err(err: BaseException) -> click.ClickException:
    return click.ClickException(" ".join(str(err).split()) or type(err).__name__)


def _split(values: tuple[str, ...]) -> list[str]:
    return [v.strip() for item in values for v in item.split(",") if v.strip()]


def _metric_options(given: tuple[str, ...]) -> dict[str, dict[str, str]]:
    out: dict[str, dict[str, str]] = {}
    for item in given:
        head, sep, value = item.partition("=")
        family, dot, key = head.partition(".")
        if not sep or not dot or not family or not key:
            raise click.ClickException(f"--metric-option {item!r}: give FAMILY.KEY=VALUE")
        out.setdefault(family, {})[key] = value
    return out


@bench_cmd.command("run")
@click.argument("prompts", required=False, type=click.Path(dir_okay=False))
@click.option(
    "--system",
    "systems",
    multiple=True,
    help="NAME=SPEC; SPEC is library, profile:NAME, PRESET+profile:NAME or PRESET (repeatable).",
)
@click.option("-o", "--out", required=True, type=click.Path(file_okay=False), help="Bench folder.")
@click.option("--runs", type=int, default=3, show_default=True, help="Runs per prompt and system.")
@click.option("--seeds", default="42,123,2026", show_default=True, help="Seeds of the runs.")
@click.option(
    "--resume", is_flag=True, help="Continue the bench in -o (PROMPTS and --system optional)."
)
@click.option(
    "--metric",
    "metrics",
    multiple=True,
    help="Metric name (repeatable; default: material metrics).",
)
@click.option(
    "--metric-option",
    "metric_options",
    multiple=True,
    help="FAMILY.KEY=VALUE option of a metric, e.g. judge.profile=NAME (repeatable).",
)
@click.option("--layouts", default="quick,flat,staged", show_default=True, help="Image layouts.")
@click.option("--contrast", "contrasts", multiple=True, help="A-B paired contrast (repeatable).")
@click.option(
    "--scheduler",
    default=None,
    help="inline, local (an embedded Dask cluster) or tcp://HOST:PORT; default: local when the "
    "dask extra is installed, else inline.",
)
@click.option("--workers", type=int, default=2, show_default=True, help="Dask local workers.")
@click.option("--jobs", type=int, default=1, show_default=True, help="Cells at once (inline).")
@click.option("--llm-slots", type=int, default=4, show_default=True, help="Model requests at once.")
@click.option("--size", type=int, default=512, show_default=True, help="Quick preview size.")
@click.option(
    "--blender-size", type=int, default=512, show_default=True, help="Blender render size."
)
@click.option(
    "--blender-samples",
    type=click.IntRange(1, 4096),
    default=None,
    help="Cycles samples per Blender render (default: the paper's, 64 flat and 160 staged).",
)
@click.option("--blender", "blender_path", help="Blender executable or a Python with bpy.")
@click.option("--profile", help="Model profile for a SPEC that names only a preset.")
@click.option("--config", "config_file", type=click.Path(dir_okay=False), help="Config file.")
@click.option(
    "--resamples", type=int, default=10_000, show_default=True, help="Bootstrap resamples."
)
@click.option("--quiet", is_flag=True, help="No progress lines.")
def run_cmd(prompts: str | None, out: str, quiet: bool, **kw: Any) -> None:
    """Author, render, score and report PROMPTS x systems x runs into -o DIR."""
    from matloom.evaluation.bench import BenchOptions, run_bench
    from matloom.evaluation.bench_spec import BenchInputError
    from matloom.evaluation.executor import ExecutorUnavailableError, default_scheduler
    from matloom.io.outdir import OutputError

    if kw["size"] < 8 or kw["size"] > 8192:
        raise click.ClickException(f"--size {kw['size']}: give 8 to 8192")
    opts = BenchOptions(
        out=Path(out),
        prompts_file=Path(prompts) if prompts else None,
        systems=kw["systems"],
        runs=kw["runs"],
        seeds=kw["seeds"],
        metrics=[m.strip() for m in kw["metrics"] if m.strip()] or None,
        metric_options=_metric_options(kw["metric_options"]),
        layouts=_split((kw["layouts"],)),
        contrasts=kw["contrasts"],
        scheduler=kw["scheduler"] or default_scheduler(),
        workers=kw["workers"],
        jobs=kw["jobs"],
        llm_slots=kw["llm_slots"],
        size=kw["size"],
        blender_size=kw["blender_size"],
        blender_samples=kw["blender_samples"],
        blender=kw["blender_path"],
        config_file=kw["config_file"],
        profile=kw["profile"],
        resume=kw["resume"],
        resamples=kw["resamples"],
    )
    last = [0.0]

    def say(line: str) -> None:
        click.echo(f"matloom: {line}", err=True)

    def progress(p: Any) -> None:
        now = time.monotonic()
        finished = p.done + p.failed + p.skipped >= p.total
        if not quiet and (now - last[0] > 2.0 or finished):
            last[0] = now
            say(p.line())

    try:
        result = run_bench(opts, say=say, on_progress=progress)
    except (BenchInputError, ExecutorUnavailableError, OutputError) as err:
        raise _err(err) from None
    except Exception as err:  # noqa: BLE001 - the CLI never shows a traceback
        raise click.ClickException(
            f"unexpected {type(err).__name__}: {_err(err).message}"
        ) from None
    c = result.cells
    say(f"{c['done']}/{c['total']} cells, {result.rows} scores; report in {result.out}/report.html")
    if c["missing"]:
        sys.exit(1)


@bench_cmd.command("pack")
@click.argument("folder", type=click.Path(file_okay=False, exists=True))
@click.option(
    "--metric-name", default="judge_blind", show_default=True, help="Name of the judged metric."
)
@click.option("--layout", default="quick", show_default=True, help="Image layout judged.")
@click.option("--per-sheet", type=int, default=6, show_default=True, help="Images per sheet.")
@click.option("--shuffle-seed", type=int, default=7, show_default=True)
def pack_cmd(folder: str, metric_name: str, layout: str, per_sheet: int, shuffle_seed: int) -> None:
    """Write shuffled sheets of the bench's images, with only the descriptions, for judges."""
    from matloom.evaluation.blind import pack
    from matloom.io.outdir import OutputError

    try:
        out = pack(Path(folder), metric_name, layout=layout, per_sheet=per_sheet, seed=shuffle_seed)
    except (ValueError, OSError, OutputError) as err:
        raise _err(err) from None
    click.echo(str(out))


@bench_cmd.command("collect")
@click.argument("folder", type=click.Path(file_okay=False, exists=True))
@click.argument("scores", nargs=-1, required=True, type=click.Path(dir_okay=False, exists=True))
@click.option(
    "--metric-name", default="judge_blind", show_default=True, help="Name of the judged metric."
)
def collect_cmd(folder: str, scores: tuple[str, ...], metric_name: str) -> None:
    """Fold judges' score files (id -> {"score": 0-100, "why": ...}) into results.csv."""
    from matloom.evaluation.bench import require_bench_extra
    from matloom.evaluation.blind import collect
    from matloom.io.outdir import OutputError

    try:
        require_bench_extra()
        n = collect(Path(folder), [Path(s) for s in scores], metric_name)
    except (ValueError, OSError, OutputError) as err:
        raise _err(err) from None
    click.echo(f"matloom: {n} cells scored by {metric_name}; report regenerated", err=True)
