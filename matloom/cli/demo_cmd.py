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
    from matloom.io.png import encode_png8
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
    atomic_write_bytes(dest / "preview.png", encode_png8(shade(maps)))
    atomic_write_bytes(dest / "preview_tiled.png", encode_png8(tile_image(shade(maps), 2)))
    lines.append(f"paper tile program ({size}x{size}, {time.perf_counter() - t0:.2f} s):")
    lines.append(f"  program  {dest / 'material.mat'}")
    lines.append(f"  maps     {dest}/ (13 maps + material.json)")
    lines.append(f"  preview  {dest / 'preview.png'}")
    lines += _generate_offline(root, size)
    click.echo("\n".join(lines))


def _generate_offline(root: Path, size: int) -> list[str]:
    try:
        from matloom.author.builtin import author
    except ImportError:
        return ["(built-in offline author not installed: skipped text-to-material)"]
    from matloom.engine.evaluate import evaluate
    from matloom.io.atomic import atomic_write_bytes
    from matloom.io.export import export_maps
    from matloom.io.png import encode_png8
    from matloom.render.preview import shade

    out = []
    for prompt in DEMO_PROMPTS:
        t0 = time.perf_counter()
        result = author(prompt)
        slug = "".join(c if c.isalnum() else "_" for c in prompt.lower()).strip("_")[:48]
        dest = root / slug
        maps = evaluate(result.program, size, size)
        export_maps(maps, dest, program_text=result.program, extra_meta={"prompt": prompt})
        atomic_write_bytes(dest / "material.mat", (result.program + "\n").encode())
        atomic_write_bytes(dest / "preview.png", encode_png8(shade(maps)))
        out.append(f'"{prompt}" (offline author, {time.perf_counter() - t0:.2f} s):')
        out.append(f"  program  {dest / 'material.mat'}")
        out.append(f"  maps     {dest}/")
        out.append(f"  preview  {dest / 'preview.png'}")
    return out
