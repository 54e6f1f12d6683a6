"""`matloom render` and `matloom random`."""

from __future__ import annotations

import sys
import time
from pathlib import Path

import click

from matloom.cli.lang_cmds import _read


def load_program(path: str, program_seed: int = 0):  # noqa: ANN201 - returns (Program, text)
    """Read, parse and seed-canonicalise a program file; exit 2 with diagnostics on errors."""
    from matloom.lang.api import analyse
    from matloom.lang.diagnostics import format_diagnostics
    from matloom.lang.seeds import canonicalize_seeds, has_seedless_noise

    text = _read(path)
    program, diags = analyse(text)
    if program is None or any(d.is_error for d in diags):
        click.echo(format_diagnostics([d for d in diags if d.is_error], path), err=True)
        sys.exit(2)
    if has_seedless_noise(program):
        program = canonicalize_seeds(program, program_seed)
        click.echo(
            f"note: omitted noise seeds made explicit from program seed {program_seed}", err=True
        )
    return program, text


def size_options(f):  # noqa: ANN001, ANN201 - click decorator
    f = click.option("--height", "height", type=int, default=None, help="Image height in pixels.")(
        f
    )
    f = click.option("--width", "width", type=int, default=None, help="Image width in pixels.")(f)
    f = click.option("--size", type=int, default=None, help="Square size in pixels.")(f)
    return f


def resolve_size(
    size: int | None, width: int | None, height: int | None, default: int
) -> tuple[int, int]:
    if size is not None and (width is not None or height is not None):
        raise click.UsageError("use either --size or --width/--height")
    if size is not None:
        return size, size
    return width or height or default, height or width or default


@click.command("render")
@click.argument("file")
@click.option(
    "-o",
    "--out",
    "out_dir",
    required=True,
    type=click.Path(file_okay=False),
    help="Output folder (replaced atomically).",
)
@size_options
@click.option(
    "--format",
    "float_format",
    type=click.Choice(["exr", "png16"]),
    default="exr",
    show_default=True,
    help="Float maps as EXR; png16 also writes a 16-bit height PNG.",
)
@click.option(
    "--maps", "maps_csv", default=None, help="Comma-separated subset, e.g. basecolor,normal."
)
@click.option(
    "--ao-radius",
    type=float,
    default=None,
    help="AO radius in coordinate units (default: the reference's 8 texels).",
)
@click.option(
    "--preview/--no-preview",
    default=True,
    show_default=True,
    help="Also write preview.png (the quick shaded swatch).",
)
@click.option(
    "--backend", default="auto", show_default=True, help="Kernel backend: auto, numba, numpy."
)
@click.option(
    "--program-seed", type=int, default=0, show_default=True, help="Seed for omitted noise seeds."
)
@click.option("--json", "as_json", is_flag=True, help="Print the manifest as JSON on stdout.")
def render_cmd(
    file: str,
    out_dir: str,
    size: int | None,
    width: int | None,
    height: int | None,
    float_format: str,
    maps_csv: str | None,
    ao_radius: float | None,
    preview: bool,
    backend: str,
    program_seed: int,
    as_json: bool,
) -> None:
    """Evaluate FILE and export its maps (13 maps + material.json) into a folder."""
    import json

    from matloom.engine.evaluate import EvalStats, evaluate
    from matloom.engine.limits import LimitError
    from matloom.io.export import MAP_NAMES, export_maps
    from matloom.lang.printer import format_program

    w, h = resolve_size(size, width, height, 512)
    subset = [m.strip() for m in maps_csv.split(",") if m.strip()] if maps_csv else None
    if subset:
        unknown = [m for m in subset if m not in MAP_NAMES]
        if unknown:
            raise click.UsageError(
                f"unknown map(s) {', '.join(unknown)}; choose from {', '.join(MAP_NAMES)}"
            )
    program, _ = load_program(file, program_seed)
    t0 = time.perf_counter()
    stats = EvalStats()
    try:
        maps = evaluate(program, w, h, backend=backend, ao_radius_units=ao_radius, stats=stats)
    except LimitError as e:
        raise click.ClickException(str(e)) from None
    t_eval = time.perf_counter() - t0
    canonical = format_program(program)
    result = export_maps(
        maps,
        out_dir,
        float_format=float_format,
        maps_subset=subset,
        program_text=canonical,
        extra_meta={"ao_radius_units": ao_radius, "source": str(file)},
    )
    if preview:
        from matloom.io.png import save_png
        from matloom.render.preview import shade

        save_png(Path(out_dir) / "preview.png", shade(maps))
    from matloom.io.atomic import atomic_write_bytes as _write

    _write(Path(out_dir) / "material.mat", (canonical + "\n").encode("utf-8"))
    for name, n in result.nonfinite_counts.items():
        click.echo(f"warning: {n} non-finite texel value(s) in {name}", err=True)
    if stats.zero_divisions:
        click.echo(f"note: {stats.zero_divisions} division(s) by exactly 0 returned 0", err=True)
    click.echo(f"rendered {w}x{h} in {t_eval * 1000:.0f} ms -> {Path(out_dir).resolve()}", err=True)
    if as_json:
        click.echo(json.dumps(result.manifest, indent=2, default=str))
    else:
        click.echo(str(Path(out_dir).resolve()))


@click.command("random")
@click.option("--seed", type=int, default=0, show_default=True, help="Generator seed.")
@click.option("--layers", type=int, default=None, help="Exact number of layers.")
@click.option("--defines", type=int, default=None, help="Exact number of Defines.")
@click.option("--count", type=int, default=1, show_default=True, help="Number of programs.")
def random_cmd(seed: int, layers: int | None, defines: int | None, count: int) -> None:
    """Print random always-valid programs built from the registry (for fuzzing)."""
    from matloom.lang.random_program import random_program

    for k in range(count):
        if count > 1:
            click.echo(f"# program {k} (seed {seed + k})")
        click.echo(random_program(seed + k, layers=layers, defines=defines))
        if count > 1:
            click.echo("")
