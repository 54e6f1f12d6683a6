"""`matloom render` and `matloom random`."""

from __future__ import annotations

import sys
from pathlib import Path

import click

from matloom.cli import params
from matloom.cli.lang_cmds import _read
from matloom.cli.naming import default_material_name
from matloom.cli.tileable import tileable_option
from matloom.vocab.spec import LANGUAGE_VERSION


def read_program(path: str):  # noqa: ANN201 - returns (Program, text)
    """Read and parse a program file; exit 2 with diagnostics on errors."""
    from matloom.lang.api import analyse
    from matloom.lang.diagnostics import format_diagnostics

    text = _read(path)
    program, diags = analyse(text)
    if program is None or any(d.is_error for d in diags):
        click.echo(format_diagnostics([d for d in diags if d.is_error], path), err=True)
        sys.exit(2)
    return program, text


def load_program(path: str, program_seed: int = 0):  # noqa: ANN201 - returns (Program, text)
    """Read, parse and seed-canonicalise a program file; exit 2 with diagnostics on errors."""
    from matloom.lang.seeds import canonicalize_seeds, has_seedless_noise

    program, text = read_program(path)
    if has_seedless_noise(program):
        program = canonicalize_seeds(program, program_seed)
        click.echo(
            f"note: omitted noise seeds made explicit from program seed {program_seed}", err=True
        )
    return program, text


def size_options(f):  # noqa: ANN001, ANN201 - click decorator
    """--size / --width / --height, each 1 to the maximum resolution (params.SIZE)."""
    size = params.SIZE
    f = click.option("--height", "height", type=size, default=None, help="Image height in pixels.")(
        f
    )
    f = click.option("--width", "width", type=size, default=None, help="Image width in pixels.")(f)
    f = click.option("--size", type=size, default=None, help="Square size in pixels.")(f)
    return f


def resolve_size(
    size: int | None, width: int | None, height: int | None, default: int
) -> tuple[int, int]:
    if size is not None and (width is not None or height is not None):
        raise click.UsageError("use either --size or --width/--height")
    if size is not None:
        return size, size
    return width or height or default, height or width or default


#: How a refused job field is named to the user (the option, or the program's own View).
JOB_FIELD_HINTS = {
    "ao_radius": "'--ao-radius'",
    "unit_m": "'--unit-m'",
    "program_unit_m": "the program's View(..., unit_m=...)",
}


def preset_option(help_text: str):  # noqa: ANN201 - click decorator
    """``--preset`` (repeatable), the choices from :data:`matloom.io.presets.PRESETS`."""
    from matloom.io.presets import PRESETS

    return click.option(
        "--preset", "presets", multiple=True, type=click.Choice(list(PRESETS)), help=help_text
    )


@click.command("render")
@click.argument("file")
@click.option(
    "-o",
    "--out",
    "out_dir",
    required=True,
    type=click.Path(file_okay=False),
    help="Output folder (staged; files MatLoom did not write are never touched).",
)
@size_options
@click.option(
    "--format",
    "float_format",
    type=click.Choice(["png", "exr", "png16"]),
    default="png",
    show_default=True,
    help="png: PNG maps (ior/height/emissive as float32 EXR); exr: every map as EXR; "
    "png16: png plus a normalised 16-bit height16.png.",
)
@click.option(
    "--bits",
    type=click.Choice(["8", "16"]),
    default="8",
    show_default=True,
    help="Bit depth of every PNG map (normal, base colour, roughness, ...).",
)
@click.option(
    "--exr-precision",
    type=click.Choice(["half", "float"]),
    default="half",
    show_default=True,
    help="Sample type of --format exr files (float = float32).",
)
@click.option(
    "--normal",
    "normal_conv",
    type=click.Choice(["gl", "dx", "both"]),
    default="gl",
    show_default=True,
    help="Normal map convention(s): normal_gl (OpenGL, +Y) and/or normal_dx (DirectX).",
)
@click.option(
    "--constants-as-values",
    is_flag=True,
    help="Record constant maps in material.json instead of writing their files.",
)
@preset_option("Also write an engine/interchange preset into DIR/<preset>/ (repeatable).")
@click.option(
    "--unit-m",
    type=params.POSITIVE,
    default=None,
    help="Metres per coordinate unit: physical size and displacement in metres (each side "
    "1e-9 to 1e9 m); replaces the program's View unit_m, with a note on stderr.",
)
@click.option(
    "--name",
    "material_name",
    type=params.NAME,
    default=None,
    help="Material name for preset files (default: the name in the material.json beside "
    "FILE when FILE is a run folder's material.mat, else FILE's stem).",
)
@click.option(
    "--stretch",
    is_flag=True,
    help="With --width != --height keep the program's View (non-square texels) instead of "
    "widening it.",
)
@click.option(
    "--maps", "maps_csv", default=None, help="Comma-separated subset, e.g. basecolor,normal."
)
@click.option(
    "--ao-radius",
    type=params.NON_NEGATIVE,
    default=None,
    help="AO radius in coordinate units, >= 0 (default: the reference's 8 texels).",
)
@click.option(
    "--preview/--no-preview",
    default=True,
    show_default=True,
    help="Also write preview.png (the quick shaded swatch).",
)
@click.option(
    "--backend", type=params.BACKEND, default="auto", show_default=True, help="Kernel backend."
)
@click.option(
    "--program-seed", type=int, default=0, show_default=True, help="Seed for omitted noise seeds."
)
@click.option("--json", "as_json", is_flag=True, help="Print the manifest as JSON on stdout.")
@tileable_option
def render_cmd(
    file: str,
    out_dir: str,
    size: int | None,
    width: int | None,
    height: int | None,
    float_format: str,
    bits: str,
    exr_precision: str,
    normal_conv: str,
    constants_as_values: bool,
    presets: tuple[str, ...],
    unit_m: float | None,
    material_name: str | None,
    stretch: bool,
    maps_csv: str | None,
    ao_radius: float | None,
    preview: bool,
    backend: str,
    program_seed: int,
    as_json: bool,
    tileable: bool,
) -> None:
    """Evaluate FILE and export its maps (one per channel, normal, AO) and material.json into a
    folder, plus any --preset (gltf, mtlx, usd, unreal, unity, godot) in its subfolder."""
    import json

    from matloom.engine.limits import LimitError
    from matloom.io.encode import Encoding
    from matloom.io.export import MAP_NAMES
    from matloom.runtime.job import RenderJob, RenderJobError
    from matloom.runtime.run import run_render
    from matloom.runtime.sinks import FolderSink

    w, h = resolve_size(size, width, height, 512)
    subset = [m.strip() for m in maps_csv.split(",") if m.strip()] if maps_csv else None
    if subset:
        unknown = [m for m in subset if m not in MAP_NAMES]
        if unknown:
            raise click.UsageError(
                f"unknown map(s) {', '.join(unknown)}; choose from {', '.join(MAP_NAMES)}"
            )
    program, text = read_program(file)
    job = RenderJob(
        program,
        w,
        h,
        tileable=tileable,
        stretch=stretch,
        encoding=Encoding(
            float_format,
            int(bits),
            exr_precision,
            ("gl", "dx") if normal_conv == "both" else (normal_conv,),
            constants_as_values,
        ),
        presets=presets,
        unit_m=unit_m,
        name=material_name or default_material_name(Path(file)),
        map_names=tuple(subset) if subset else None,
        ao_radius=ao_radius,
        previews=("preview",) if preview else (),
        program_seed=program_seed,
        backend=backend,
        extra={"ao_radius_units": ao_radius, "source": str(file)},
        source=file,
        source_text=text,
    )
    try:
        result = run_render(
            job, FolderSink(out_dir), notify=lambda line: click.echo(line, err=True)
        )
    except RenderJobError as e:
        if e.field in JOB_FIELD_HINTS:
            raise click.BadParameter(str(e), param_hint=JOB_FIELD_HINTS[e.field]) from None
        raise click.ClickException(str(e)) from None
    except LimitError as e:
        raise click.ClickException(str(e)) from None
    t_eval = result.timings["evaluate"]
    click.echo(f"rendered {w}x{h} in {t_eval * 1000:.0f} ms -> {result.root}", err=True)
    if as_json:
        click.echo(json.dumps(result.manifest, indent=2, default=str))
    else:
        click.echo(str(result.root))


@click.command("random")
@click.option("--seed", type=int, default=0, show_default=True, help="Generator seed.")
@click.option("--layers", type=params.LAYERS, default=None, help="Exact number of layers.")
@click.option("--defines", type=params.DEFINES, default=None, help="Exact number of Defines.")
@click.option(
    "--count", type=params.COUNT, default=1, show_default=True, help="Number of programs."
)
@click.option(
    "--language",
    type=click.IntRange(1, LANGUAGE_VERSION),
    default=LANGUAGE_VERSION,
    show_default=True,
    help="Language version to draw from (1: the reference's vocabulary, its programs exactly).",
)
def random_cmd(
    seed: int, layers: int | None, defines: int | None, count: int, language: int
) -> None:
    """Print random always-valid programs built from the registry (for fuzzing)."""
    from matloom.lang.random_program import RandomConfig, random_program

    config = RandomConfig(language=language)
    for k in range(count):
        if count > 1:
            click.echo(f"# program {k} (seed {seed + k})")
        click.echo(random_program(seed + k, layers=layers, defines=defines, config=config))
        if count > 1:
            click.echo("")
