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
    from matloom.engine.evaluate import evaluate, prepare
    from matloom.examples import example_text
    from matloom.io.atomic import atomic_write_bytes
    from matloom.io.export import MANIFEST_NAME, write_manifest, write_maps
    from matloom.io.outdir import OutputFolder
    from matloom.io.png import save_png
    from matloom.lang.printer import format_program
    from matloom.render.preview import shade, tile_image

    root = Path(out_dir).resolve()
    lines = []
    t0 = time.perf_counter()
    program = prepare(example_text("black_ceramic_tiles"))
    text = format_program(program)
    maps = evaluate(program, size, size)
    dest = root / "paper_tile_program"
    swatch = shade(maps)
    first_run = time.perf_counter() - t0
    compiling = _background_compiling()  # the first run used numpy: kernels not compiled yet
    with OutputFolder(dest) as out, out.batch("render", marker=MANIFEST_NAME) as staging:
        result = write_maps(maps, staging, final_dir=out.path, program_text=text)
        atomic_write_bytes(staging / "material.mat", (text + "\n").encode())
        save_png(staging / "preview.png", swatch)
        save_png(staging / "preview_tiled.png", tile_image(swatch, 2))
        write_manifest(result, staging)
    lines.append(f"paper tile program ({size}x{size}, {time.perf_counter() - t0:.2f} s):")
    lines.append(f"  program  {dest / 'material.mat'}")
    lines.append(f"  maps     {dest}/ ({len(result.manifest['maps'])} maps + material.json)")
    lines.append(f"  preview  {dest / 'preview.png'}")
    lines += _generate_offline(root, size)
    lines.insert(4, _timings(program, size, first_run, compiling))
    click.echo("\n".join(lines))


def _background_compiling() -> bool:
    from matloom.engine.kernels import warmup

    return warmup.state().running


def _timings(program: Any, size: int, first_run: float, compiling: bool) -> str:
    """The tile program's first-run and warm timings (evaluate + shade). When the first run
    used the numpy path because the kernels were compiling in the background, wait until the
    background compiler has the tile program's kernels (progress on stderr; it goes on with
    the others), load them with one untimed numba run, then time the warm run."""
    from matloom.engine.evaluate import evaluate
    from matloom.render.preview import shade

    note, backend = "", "auto"
    if compiling:
        from matloom.cli.progress import COMPILING, LazyProgress
        from matloom.engine.kernels import warmup, warmup_steps

        start = time.perf_counter()
        with LazyProgress(COMPILING, enabled=sys.stderr.isatty()) as bar:
            done = warmup.wait(progress=bar, steps=warmup_steps.TILE_STEPS)
        if done.ready or done.done >= warmup_steps.TILE_STEPS:
            backend = "numba"
            note = (
                " (numpy path: kernels compiling in the background, the tile program's were "
                f"ready {time.perf_counter() - start:.1f} s later)"
            )
        else:
            note = " (numpy path: the kernels could not be compiled)"
        shade(evaluate(program, size, size, backend=backend), backend=backend)  # loads them
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
