"""`matloom demo`: the offline main job run by `make demo`."""

from __future__ import annotations

import time
from pathlib import Path

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
@click.option("--size", type=int, default=512, show_default=True)
def demo_cmd(out_dir: str, size: int) -> None:
    """Render the paper's tile program and generate three materials offline."""
    from matloom.engine.evaluate import evaluate, prepare
    from matloom.examples import example_text
    from matloom.io.atomic import atomic_write_bytes
    from matloom.io.export import export_maps
    from matloom.io.png import save_png
    from matloom.lang.printer import format_program
    from matloom.render.preview import shade, tile_image

    root = Path(out_dir).resolve()
    root.mkdir(parents=True, exist_ok=True)
    lines = []
    t0 = time.perf_counter()
    program = prepare(example_text("black_ceramic_tiles"))
    text = format_program(program)
    maps = evaluate(program, size, size)
    dest = root / "paper_tile_program"
    export_maps(maps, dest, program_text=text)
    atomic_write_bytes(dest / "material.mat", (text + "\n").encode())
    swatch = shade(maps)
    save_png(dest / "preview.png", swatch)
    save_png(dest / "preview_tiled.png", tile_image(swatch, 2))
    lines.append(f"paper tile program ({size}x{size}, {time.perf_counter() - t0:.2f} s):")
    lines.append(f"  program  {dest / 'material.mat'}")
    lines.append(f"  maps     {dest}/ (13 maps + material.json)")
    lines.append(f"  preview  {dest / 'preview.png'}")
    lines += _generate_offline(root, size)
    click.echo("\n".join(lines))


def _generate_offline(root: Path, size: int) -> list[str]:
    """Run the `matloom generate` pipeline with no model (the built-in offline author)."""
    from matloom.author.config import AuthorConfig
    from matloom.author.pipeline import author_material

    config = AuthorConfig(scorer="none")
    out = [
        "text to material with `matloom generate` (no model configured: built-in offline author):"
    ]
    for prompt in DEMO_PROMPTS:
        t0 = time.perf_counter()
        slug = "".join(c if c.isalnum() else "_" for c in prompt.lower()).strip("_")[:48]
        dest = root / slug
        if (dest / "record.json").exists():  # a previous demo run: start afresh
            import shutil

            shutil.rmtree(dest)
        result = author_material(prompt, dest, config)
        files = result.record.final.files if result.record.final else {}
        folder = result.folder
        out.append(f'"{prompt}" ({time.perf_counter() - t0:.2f} s):')
        out.append(f"  program  {folder / files.get('program', 'material.mat')}")
        out.append(f"  maps     {folder / files.get('maps', 'maps')}/")
        out.append(f"  preview  {folder / files.get('preview', 'preview.png')}")
        out.append(f"  record   {folder / 'record.json'}")
    return out
