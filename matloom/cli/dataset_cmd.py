"""`matloom dataset`: build a training set of materials (docs/datasets.md)."""

from __future__ import annotations

import sys
import time
from typing import Any

import click

from matloom.cli import params
from matloom.cli.library_opts import library_option, load_library


def _csv(text: str | None) -> list[str]:
    return [part.strip() for part in (text or "").split(",") if part.strip()]


class _ProgressLine:
    """The executor's progress on stderr, at most once a second (and the last one)."""

    def __init__(self) -> None:
        self.last = 0.0

    def __call__(self, progress: Any) -> None:
        now = time.monotonic()
        final = progress.running == 0 and progress.done + progress.failed + progress.skipped >= (
            progress.total
        )
        if final or now - self.last >= 1.0:
            self.last = now
            click.echo(f"dataset: {progress.line()}", err=True)


@click.command("dataset")
@click.option(
    "-o",
    "--out",
    "out_dir",
    required=True,
    type=click.Path(file_okay=False),
    help="Dataset folder (made if missing; continued with --resume).",
)
@click.option("--all-entries", "all_entries", is_flag=True, help="Every library entry.")
@library_option
@click.option("--entries", default=None, help="Library entries, comma-separated.")
@click.option("--tags", default=None, help="Library entries with any of these tags.")
@click.option(
    "--programs",
    "programs_dir",
    type=click.Path(file_okay=False),
    default=None,
    help="A folder of .mat programs.",
)
@click.option(
    "--prompts",
    "prompts_file",
    type=click.Path(dir_okay=False),
    default=None,
    help="A JSON prompts file (as generate --prompts reads).",
)
@click.option(
    "--profile",
    default=None,
    help="Write --prompts with this model profile (matloom.toml); default: the "
    "offline library author.",
)
@click.option(
    "--variants",
    "-k",
    type=click.IntRange(1, 100_000),
    default=1,
    show_default=True,
    help="Samples per program: the program and K-1 seed variants.",
)
@click.option(
    "--size",
    "sizes",
    type=params.SIZE,
    multiple=True,
    help="Map size in pixels (repeatable; default 512).",
)
@click.option(
    "--seed", type=int, default=0, show_default=True, help="Seed of the variants' seed draw."
)
@click.option(
    "--filter",
    "filters",
    multiple=True,
    help="Keep samples with COLUMN OP NUMBER, e.g. 'pbr.plausible>=0.8' (repeatable).",
)
@click.option(
    "--metrics",
    default="seams,pbr,size",
    show_default=True,
    help="Metric families measured per sample (comma-separated; 'none' for none).",
)
@click.option(
    "--scheduler",
    default=None,
    help="inline, local (an embedded Dask cluster; the default when Dask is "
    "installed) or tcp://HOST:PORT.",
)
@click.option(
    "--workers",
    type=click.IntRange(1, 4096),
    default=2,
    show_default=True,
    help="Worker processes of --scheduler local.",
)
@click.option(
    "--jobs",
    type=click.IntRange(1, 256),
    default=1,
    show_default=True,
    help="Threads of --scheduler inline.",
)
@click.option(
    "--llm-slots",
    type=click.IntRange(1, 1024),
    default=4,
    show_default=True,
    help="Model requests at once, across all workers.",
)
@click.option("--backend", type=params.BACKEND, default="auto", show_default=True)
@click.option(
    "--resume", is_flag=True, help="Continue the dataset in --out (finished samples are skipped)."
)
def dataset_cmd(  # noqa: PLR0913 - one flag each
    out_dir: str,
    all_entries: bool,
    library_dirs: tuple[str, ...],
    entries: str | None,
    tags: str | None,
    programs_dir: str | None,
    prompts_file: str | None,
    profile: str | None,
    variants: int,
    sizes: tuple[int, ...],
    seed: int,
    filters: tuple[str, ...],
    metrics: str,
    scheduler: str | None,
    workers: int,
    jobs: int,
    llm_slots: int,
    backend: str,
    resume: bool,
) -> None:
    """Build a training set: every program of the sources (library entries, a program folder,
    a prompt list) at K seed variants and each size; per sample the maps, program, parameters,
    per-layer masks, preview and a metadata row (metadata.jsonl, metadata.parquet)."""
    from matloom.evaluation.dataset import DatasetError, DatasetOptions, build_dataset
    from matloom.evaluation.dataset_filter import FilterError
    from matloom.evaluation.dataset_sources import SourceError
    from matloom.evaluation.executor import (
        ExecutorUnavailableError,
        default_scheduler,
        make_executor,
    )

    if not (all_entries or entries or tags or programs_dir or prompts_file):
        raise click.UsageError(
            "give a source: --library, --entries, --tags, --programs or --prompts"
        )
    if profile and not prompts_file:
        raise click.UsageError("--profile writes the --prompts: give --prompts FILE")
    chosen = [m for m in _csv(metrics) if m != "none"]
    try:
        options = DatasetOptions(
            variants,
            tuple(dict.fromkeys(sizes or (512,))),
            seed,
            tuple(filters),
            tuple(chosen),
            backend,
        )
        options.conditions  # noqa: B018 - parse the filters before any work
        executor = make_executor(
            scheduler or default_scheduler(), workers=workers, jobs=jobs, llm_slots=llm_slots
        )
    except (FilterError, ValueError, ExecutorUnavailableError) as err:
        raise click.ClickException(str(err)) from None
    try:
        sources = _sources(all_entries, entries, tags, programs_dir, library_dirs)
        if prompts_file:
            sources += _prompt_sources(prompts_file, profile, executor, out_dir, llm_slots)
        summary = build_dataset(
            out_dir,
            sources,
            options,
            executor,
            resume=resume,
            on_progress=_ProgressLine(),
            notify=lambda line: click.echo(line, err=True),
        )
    except (DatasetError, SourceError) as err:
        raise click.ClickException(str(err)) from None
    finally:
        executor.close()
    click.echo(
        f"{summary.kept} samples in {summary.out} ({summary.skipped} already there, "
        f"{summary.dropped} dropped, {summary.failed} failed, {summary.duplicates} duplicates)",
        err=True,
    )
    click.echo(str(summary.out))
    sys.stdout.flush()
    if summary.failed:
        sys.exit(1)


def _sources(  # noqa: ANN202
    all_entries: bool,
    entries: str | None,
    tags: str | None,
    programs: str | None,
    library_dirs: tuple[str, ...] = (),
):
    from matloom.evaluation.dataset_sources import folder_sources, library_sources

    out = []
    if all_entries or entries or tags:
        lib = load_library(library_dirs)
        out += library_sources(_csv(entries) or None, _csv(tags) or None, lib)
    if programs:
        out += folder_sources(programs)
    return out


def _prompt_sources(path: str, profile: str | None, executor: Any, out_dir: str, slots: int):  # noqa: ANN202
    from pathlib import Path

    from matloom.evaluation.dataset_sources import model_sources, prompt_sources

    if profile is None:
        return prompt_sources(path)
    from matloom.author.config import AuthorConfig, ConfigError, load_config_file, resolve_profile
    from matloom.io.outdir import OutputFolder

    try:
        config = AuthorConfig(generator=resolve_profile(load_config_file(), profile), scorer="none")
    except ConfigError as err:
        raise click.ClickException(str(err)) from None
    with OutputFolder(out_dir) as folder:  # checked and locked while the model writes
        folder.check_writable(["programs/x"])
        root = Path(folder.path) / "programs"
        root.mkdir(exist_ok=True)
        found, failed = model_sources(path, config, executor, root, _ProgressLine())
    for outcome in failed:
        click.echo(f"dataset: prompt not authored: {outcome.error}", err=True)
    return found
