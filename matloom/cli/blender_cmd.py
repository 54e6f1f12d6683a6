"""`matloom blender`: the paper's flat and staged Cycles renders, and ready `.blend` materials.

Blender runs as a separate process (``matloom.blender.runner``); every output goes through
:class:`matloom.io.outdir.OutputFolder` (staged, locked, never replacing a foreign file).
"""

from __future__ import annotations

import signal
import sys
import threading
import time
from collections.abc import Iterator
from concurrent.futures import ThreadPoolExecutor
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import click

from matloom.cli import params


@click.command("blender")
@click.argument("sources", nargs=-1, required=True)
@click.option(
    "--layout",
    type=click.Choice(["flat", "staged", "both"]),
    default="flat",
    show_default=True,
    help="flat: the head-on swatch; staged: the three-quarter studio scene; both.",
)
@click.option(
    "-o",
    "--out",
    "out_dir",
    required=True,
    type=click.Path(),
    help="Output folder (staged; files MatLoom did not write are never touched), or a .png "
    "file for one source, one layout and one view.",
)
@click.option("--size", type=params.SIZE, default=512, show_default=True, help="Image size.")
@click.option(
    "--samples",
    type=click.IntRange(1, 1 << 16),
    default=None,
    help="Cycles samples (default: the reference's 64 flat / 160 staged).",
)
@click.option(
    "--views",
    type=click.Choice(["1", "all"]),
    default="1",
    show_default=True,
    help="all: 4 flat views (the world turned 90 degrees each) / 6 staged camera angles.",
)
@click.option(
    "--displacement",
    type=click.Choice(["true", "bump", "off"]),
    default="true",
    show_default=True,
    help="true: subdivided true displacement (+ bump); bump: bump only; off: no height.",
)
@click.option(
    "--save",
    "save",
    default=None,
    metavar="NAME.blend",
    help="Also save the scene(s) with the material, images packed, into the output folder.",
)
@click.option(
    "--save-material-only",
    is_flag=True,
    help="Also save material.blend holding just the material (marked as an asset).",
)
@click.option(
    "--jobs",
    type=click.IntRange(1, 64),
    default=1,
    show_default=True,
    help="Blender processes at once (batch).",
)
@click.option(
    "--blender",
    "blender_path",
    default=None,
    help="Blender executable, or a Python with the bpy module (default: $MATLOOM_BLENDER, "
    "$MATLOOM_BLENDER_PYTHON, blender on PATH, .venv-blender).",
)
@click.option(
    "--device",
    type=click.Choice(["auto", "cpu"]),
    default="auto",
    show_default=True,
    help="auto: the GPU when Cycles finds one (OptiX, CUDA, HIP, Metal), else the CPU.",
)
@click.option(
    "--unit-m",
    type=params.POSITIVE,
    default=None,
    help="For program sources: metres per coordinate unit (physical size and displacement).",
)
def blender_cmd(
    sources: tuple[str, ...],
    layout: str,
    out_dir: str,
    size: int,
    samples: int | None,
    views: str,
    displacement: str,
    save: str | None,
    save_material_only: bool,
    jobs: int,
    blender_path: str | None,
    device: str,
    unit_m: float | None,
) -> None:
    """Render each SOURCE (a program file or a folder written by `matloom render`) with
    Blender Cycles in the paper's flat and/or staged layout; optionally save a ready .blend.

    -o names a folder (flat.png, staged.png, one subfolder per SOURCE when there are several)
    or, for one SOURCE, one layout and one view, a single .png file."""
    from matloom.blender.job import BlenderJobError, RenderOptions, check_source, render_names
    from matloom.blender.runner import BlenderError, check_version, find_blender

    options = RenderOptions(
        layouts=("flat", "staged") if layout == "both" else (layout,),
        size=size,
        samples=samples,
        views=views,
        displacement=displacement,
        save=save,
        save_material_only=save_material_only,
        device=device,
    )
    try:
        options.validate()
    except BlenderJobError as err:
        raise click.UsageError(str(err)) from None
    single = out_dir.lower().endswith(".png") and not Path(out_dir).is_dir()
    if single and len(sources) > 1:
        raise click.UsageError(
            f"-o {out_dir} names one image, but {len(sources)} sources were given: "
            "give a folder for -o"
        )
    if single and len(render_names(options)) > 1:
        raise click.UsageError(
            f"-o {out_dir} names one image, but --layout {layout} --views {views} make "
            f"{len(render_names(options))}: give a folder for -o"
        )
    try:  # cheap checks first: a folder without a manifest fails before Blender is looked for
        for source in sources:
            check_source(source)
    except BlenderJobError as err:
        raise click.ClickException(str(err)) from None
    try:
        blender = find_blender(blender_path)
        version = check_version(blender)
    except BlenderError as err:
        raise click.ClickException(str(err)) from None
    shown = ".".join(map(str, version)) if version else "bpy module"
    click.echo(f"blender: {blender.path} ({shown})", err=True)
    with _stop_blender_on_sigterm():
        if single:
            _single(sources[0], options, Path(out_dir), blender, unit_m)
        else:
            _batch(sources, options, out_dir, jobs, blender, unit_m)


def _single(source: str, options: Any, target: Path, blender: Any, unit_m: float | None) -> None:
    """One image to one file (`-o out.png`)."""
    from matloom.blender.job import BlenderJobError
    from matloom.blender.render import render_to_file
    from matloom.blender.runner import BlenderError

    progress = _Progress(1)
    name = target.stem
    t0 = time.perf_counter()
    try:
        files = render_to_file(
            source,
            options,
            target,
            blender,
            unit_m=unit_m,
            on_event=lambda e: progress.event(name, e),
        )
    except (BlenderJobError, BlenderError) as err:
        diagnostics = getattr(err, "diagnostics", None)
        if diagnostics:
            click.echo(diagnostics, err=True)
            sys.exit(2)
        raise click.ClickException(str(err)) from None
    progress.material_done(name, time.perf_counter() - t0)
    for path in files:
        click.echo(str(path))


def _batch(
    sources: tuple[str, ...],
    options: Any,
    out_dir: str,
    jobs: int,
    blender: Any,
    unit_m: float | None,
) -> None:
    """Every source into the folder `out_dir` (a subfolder each when there are several)."""
    from matloom.blender.job import BlenderJobError, material_name, planned_files
    from matloom.blender.runner import BlenderError, stop_all
    from matloom.io.outdir import OutputFolder

    prefixes = _prefixes(sources, material_name)
    planned = [p + f for p in prefixes for f in planned_files(options)]
    failures: list[str] = []
    t0 = time.perf_counter()
    with OutputFolder(out_dir) as out:
        out.check_writable(planned)
        progress = _Progress(len(sources))
        install_lock = threading.Lock()

        def one(index: int) -> None:
            source, prefix = sources[index], prefixes[index]
            try:
                _render_one(out, install_lock, blender, source, prefix, options, unit_m, progress)
            except (BlenderJobError, BlenderError) as err:
                message = getattr(err, "diagnostics", None) or str(err)
                failures.append(f"{source}: {message}")
                progress.line(f"failed: {source}: {message}")

        if jobs == 1 or len(sources) == 1:
            for index in range(len(sources)):
                one(index)
        else:
            pool = ThreadPoolExecutor(max_workers=jobs)
            try:
                list(pool.map(one, range(len(sources))))
            except BaseException:  # Ctrl-C or SIGTERM: stop every Blender, then the threads
                stop_all()
                raise
            finally:
                pool.shutdown(wait=True, cancel_futures=True)
    elapsed = time.perf_counter() - t0
    done = len(sources) - len(failures)
    click.echo(f"rendered {done} of {len(sources)} material(s) in {elapsed:.1f} s", err=True)
    if failures:
        if len(failures) == 1:
            program_error = "\n" in failures[0]
            click.echo(f"Error: {failures[0]}", err=True)
            sys.exit(2 if program_error else 1)
        raise click.ClickException(f"{len(failures)} of {len(sources)} materials failed (above)")
    click.echo(str(out.path))


@contextmanager
def _stop_blender_on_sigterm() -> Iterator[None]:
    """SIGTERM ends the command like Ctrl-C: Blender is stopped and staging folders removed
    (the worker also ends itself when MatLoom is killed outright)."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return

    def terminate(signum: int, frame: Any) -> None:
        raise SystemExit(128 + signum)

    previous = signal.signal(signal.SIGTERM, terminate)
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, previous)


def _prefixes(sources: tuple[str, ...], name_of: Any) -> list[str]:
    """'' for a single source, else a distinct '<name>/' folder per source."""
    if len(sources) == 1:
        return [""]
    seen: dict[str, int] = {}
    prefixes = []
    for source in sources:
        name = name_of(source)
        seen[name] = seen.get(name, 0) + 1
        prefixes.append(f"{name}/" if seen[name] == 1 else f"{name}-{seen[name]}/")
    return prefixes


class _Progress:
    def __init__(self, total: int) -> None:
        self.total = total
        self.lock = threading.Lock()
        self.finished = 0

    def line(self, text: str) -> None:
        with self.lock:
            click.echo(text, err=True)

    def event(self, name: str, event: dict[str, Any]) -> None:
        from matloom.blender.render import describe_event

        text = describe_event(event)
        if text is not None:
            self.line(f"  {name}: {text}")

    def material_done(self, name: str, seconds: float) -> None:
        with self.lock:
            self.finished += 1
            click.echo(f"[{self.finished}/{self.total}] {name} in {seconds:.1f} s", err=True)


@contextmanager
def _serial_install(out: Any, group: str, lock: threading.Lock) -> Iterator[Path]:
    """``out.batch(group)`` whose set-up and install run one at a time (``--jobs N``)."""
    with lock:
        batch = out.batch(group)
        staging = batch.__enter__()
    try:
        yield staging
    except BaseException:
        with lock:
            if not batch.__exit__(*sys.exc_info()):
                raise
        return
    with lock:
        batch.__exit__(None, None, None)


def _render_one(
    out: Any,
    lock: threading.Lock,
    blender: Any,
    source_path: str,
    prefix: str,
    options: Any,
    unit_m: float | None,
    progress: _Progress,
) -> None:
    from matloom.blender.job import load_source
    from matloom.blender.render import render_source

    t0 = time.perf_counter()
    source = load_source(source_path, size=options.size, unit_m=unit_m)
    label = prefix.rstrip("/") or source.name
    try:
        # one install group per source and layouts: rendering `--layout staged` after
        # `--layout flat` keeps flat.png; re-rendering a layout replaces its own files
        group = f"blender:{prefix}{'+'.join(options.layouts)}"
        with _serial_install(out, group, lock) as staging:
            target = staging / prefix if prefix else staging
            target.mkdir(parents=True, exist_ok=True)
            render_source(
                source, options, target, blender, on_event=lambda e: progress.event(label, e)
            )
    finally:
        source.cleanup()
    progress.material_done(label, time.perf_counter() - t0)
