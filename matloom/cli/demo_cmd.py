"""`matloom demo`: the offline main job run by `make demo`."""

from __future__ import annotations

import json
import sys
import time
from pathlib import Path
from typing import Any

import click

DEMO_PROMPTS = (
    "black shiny ceramic floor tiles",
    "weathered red brick wall with pale mortar",
    "brushed stainless steel",
)


@click.command("demo")
@click.option(
    "-o",
    "--out",
    "out_dir",
    default="demo-output",
    show_default=True,
    type=click.Path(file_okay=False),
    help="Folder for all demo outputs.",
)
@click.option(
    "--size",
    type=int,
    default=512,
    show_default=True,
    help="Render and export size of every demo material.",
)
def demo_cmd(out_dir: str, size: int) -> None:
    """Render the paper's tile program and generate three materials offline."""
    from matloom.engine.evaluate import prepare
    from matloom.engine.session import Session, use_session
    from matloom.examples import example_text
    from matloom.runtime.cold_start import background_compile
    from matloom.runtime.job import RenderJob
    from matloom.runtime.run import run_render
    from matloom.runtime.sinks import FolderSink

    root = Path(out_dir).resolve()
    notice = _SetupNotice()  # plain words instead of kernels
    session = Session.from_env(reporter=notice, cold_start=background_compile())
    with use_session(session):  # (the offline generate below runs in it too)
        lines = []
        t0 = time.perf_counter()
        program = prepare(example_text("black_ceramic_tiles"))
        dest = root / "paper_tile_program"
        job = RenderJob(program, size, size, previews=("preview", "tiled"))
        result = run_render(job, FolderSink(dest), session)
        first_run = time.perf_counter() - t0 - result.timings["write"]  # evaluate and shade
        setting_up = _setting_up()  # the first run used the slower renderer meanwhile
        lines.append(f"paper tile program ({size}x{size}, {time.perf_counter() - t0:.2f} s):")
        lines.append(f"  program  {dest / 'material.mat'}")
        lines.append(f"  maps     {dest}/ ({len(result.manifest['maps'])} maps + material.json)")
        lines.append(f"  preview  {dest / 'preview.png'}")
        lines += _generate_offline(root, size)
        _finish_setup(notice)
        lines.insert(4, _timings(program, size, first_run, setting_up))
        _finish_setup(notice)  # (the warm run may have started it, where nothing had)
    click.echo("\n".join(lines))


class _SetupNotice:
    """The demo's :class:`~matloom.engine.kernels.compile_report.CompileReporter`: one line,
    in terms of what the user sees, the first time this machine sets up the fast renderer
    (compiles the numba kernels) in this process or in the background."""

    def __init__(self) -> None:
        self.said = False

    def say(self) -> None:
        if not self.said:
            self.said = True
            click.echo(
                "first run on this machine: setting up the fast renderer (once; the maps are "
                "the same without it)",
                err=True,
            )

    def kernel_compiling(self, name: str) -> None:
        self.say()

    def kernel_compiled(self, name: str, seconds: float) -> None:
        pass

    def background_compiling(self, done: int, total: int) -> None:
        self.say()


def _setting_up() -> bool:
    from matloom.runtime import warmup

    return warmup.state().running


#: Seconds the demo waits at most for the background set-up before it stops it.
SETUP_WAIT_S = 600.0


def _finish_setup(notice: _SetupNotice) -> None:
    """Wait until the background set-up of the fast renderer has finished, so that the demo
    leaves no process running (the work is kept for later commands); progress on stderr. One
    the demo started that has not finished after :data:`SETUP_WAIT_S` is stopped (the next
    command restarts it)."""
    from matloom.cli.progress import LazyProgress
    from matloom.runtime import warmup

    if not warmup.state().running:
        return
    notice.say()
    click.echo(
        "finishing the set-up of the fast renderer, so later renders are quick ...", err=True
    )
    start = time.perf_counter()
    with LazyProgress("setting up the fast renderer", enabled=sys.stderr.isatty()) as bar:
        done = warmup.wait(timeout=SETUP_WAIT_S, progress=bar)
    if done.running:
        warmup.stop_background()
        click.echo(
            "the set-up took too long and was stopped; the next render restarts it", err=True
        )
    else:
        warmup.reap()
        click.echo(f"fast renderer ready ({time.perf_counter() - start:.0f} s)", err=True)


def _timings(program: Any, size: int, first_run: float, setting_up: bool) -> str:
    """The tile program's first-run and warm timings (evaluate + shade). The warm run follows
    one untimed run (which loads the fast renderer's code) on the fast renderer where it is
    ready."""
    from matloom.engine.evaluate import evaluate
    from matloom.render.preview import shade
    from matloom.runtime import warmup

    backend = "numba" if warmup.state().ready else "auto"
    note = (
        " (while the fast renderer was being set up: slower, the same maps)" if setting_up else ""
    )
    shade(evaluate(program, size, size, backend=backend), backend=backend)  # loads the code
    t0 = time.perf_counter()
    shade(evaluate(program, size, size, backend=backend), backend=backend)
    warm = time.perf_counter() - t0
    return f"  timings  first run {first_run:.2f} s{note}, warm {warm:.2f} s"


def _generate_offline(root: Path, size: int) -> list[str]:
    """Run the `matloom generate` pipeline with no model (the material library); each
    run folder holds the final material in the layout `matloom render` writes."""
    from matloom.author.config import AuthorConfig
    from matloom.author.pipeline import author_material

    config = AuthorConfig(scorer="none", export_size=size)
    out = ["text to material with `matloom generate` (no model configured: the material library):"]
    for prompt in DEMO_PROMPTS:
        t0 = time.perf_counter()
        slug = "".join(c if c.isalnum() else "_" for c in prompt.lower()).strip("_")[:48]
        dest = root / slug
        if (dest / "record.json").exists():  # a previous demo run: start afresh
            from matloom.io.outdir import OutputFolder

            with OutputFolder(dest) as previous:  # only MatLoom's own, unchanged files go
                previous.remove_owned()
        result = author_material(prompt, dest, config)
        files = result.record.final.files if result.record.final else {}
        folder = result.folder
        manifest = json.loads((folder / files["manifest"]).read_text(encoding="utf-8"))
        out.append(f'"{prompt}" ({time.perf_counter() - t0:.2f} s):')
        out.append(f"  program  {folder / files['program']}")
        out.append(f"  maps     {folder}/ ({len(manifest['maps'])} maps + material.json)")
        out.append(f"  preview  {folder / files['preview']}")
        out.append(f"  record   {folder / 'record.json'}")
    return out
