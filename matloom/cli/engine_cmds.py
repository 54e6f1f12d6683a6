"""`matloom render` and `matloom random`."""

from __future__ import annotations

import sys
import time
from pathlib import Path

import click

from matloom.cli import params
from matloom.cli.lang_cmds import _read
from matloom.cli.naming import default_material_name
from matloom.cli.tileable import apply_tileable, tileable_option
from matloom.vocab.spec import LANGUAGE_VERSION


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


def check_ao_radius(units: float, view: tuple[float, float, float, float], w: int, h: int) -> None:
    """Refuse an AO radius wider than the largest image side (in texels of this View and size)."""
    from matloom.engine.maps import View

    dx, dy = View(*view).texel_size(w, h)  # > 0: the checker refuses zero and tiny Views
    texels = units / min(dx, dy)
    if texels > params.MAX_SIDE:
        raise click.BadParameter(
            f"{units:g} units is {texels:.3g} texels at {w}x{h} with this View; the radius may "
            f"be at most {params.MAX_SIDE} texels ({params.MAX_SIDE * min(dx, dy):.6g} units)",
            param_hint="'--ao-radius'",
        )


def check_unit_m(
    unit_m: float | None, program_unit_m: float | None, view: tuple[float, float, float, float]
) -> None:
    """Before any work: the physical size (``--unit-m``, else the program's ``unit_m``) must be
    one the presets can store; a ``--unit-m`` that replaces a different program ``unit_m`` is
    said on stderr (one line naming both)."""
    from matloom.io.presets.common import physical_size_problem, unit_m_override_note

    effective = unit_m if unit_m is not None else program_unit_m
    if effective is None:
        return
    x1, y1, x2, y2 = view
    problem = physical_size_problem(effective, (abs(x2 - x1), abs(y2 - y1)))
    if problem is not None:
        hint = "'--unit-m'" if unit_m is not None else "the program's View(..., unit_m=...)"
        raise click.BadParameter(problem, param_hint=hint)
    note = unit_m_override_note(unit_m, program_unit_m, abs(x2 - x1))
    if note is not None:
        click.echo(note, err=True)


#: ``--preset`` choices (the registry is imported lazily; this list is checked by a test).
PRESET_NAMES = ("gltf", "mtlx", "usd", "unreal", "unity", "godot")


def square_texel_view(
    view: tuple[float, float, float, float], w: int, h: int, stretch: bool
) -> tuple[tuple[float, float, float, float], dict | None]:
    """The View to render ``w`` x ``h`` with square texels: the program's View widened about
    its centre along the short side (only when ``w != h`` and not ``stretch``), and a note for
    the manifest (None when the View is used as it is)."""
    x1, y1, x2, y2 = view
    dx, dy = abs(x2 - x1) / w, abs(y2 - y1) / h
    if w == h or abs(dx - dy) <= 1e-9 * max(dx, dy):
        return view, None
    if stretch:
        return view, {"program_view": list(view), "note": "--stretch: texels are not square"}
    texel = max(dx, dy)
    cx, cy = (x1 + x2) / 2, (y1 + y2) / 2
    half_w = texel * w / 2 * (1 if x2 >= x1 else -1)
    half_h = texel * h / 2 * (1 if y2 >= y1 else -1)
    widened = (cx - half_w, cy - half_h, cx + half_w, cy + half_h)
    note = {
        "program_view": list(view),
        "note": "the View was widened about its centre so that texels stay square "
        "(--stretch keeps the program's View)",
    }
    return widened, note


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
@click.option(
    "--preset",
    "presets",
    multiple=True,
    type=click.Choice(PRESET_NAMES),
    help="Also write an engine/interchange preset into DIR/<preset>/ (repeatable).",
)
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

    from matloom.engine.evaluate import EvalStats, evaluate
    from matloom.engine.limits import EVALUATE, LimitError, Usage
    from matloom.io.atomic import atomic_write_bytes
    from matloom.io.export import (
        MANIFEST_NAME,
        MAP_NAMES,
        Encoding,
        planned_files,
        write_manifest,
        write_maps,
    )
    from matloom.io.outdir import OutputFolder
    from matloom.lang.printer import format_program

    w, h = resolve_size(size, width, height, 512)
    subset = [m.strip() for m in maps_csv.split(",") if m.strip()] if maps_csv else None
    if subset:
        unknown = [m for m in subset if m not in MAP_NAMES]
        if unknown:
            raise click.UsageError(
                f"unknown map(s) {', '.join(unknown)}; choose from {', '.join(MAP_NAMES)}"
            )
    encoding = Encoding(
        float_format,
        int(bits),
        exr_precision,
        ("gl", "dx") if normal_conv == "both" else (normal_conv,),
        constants_as_values,
    )
    program, text = load_program(file, program_seed)
    program = apply_tileable(program, tileable, text, file)
    view, view_note = square_texel_view(program.view_tuple, w, h, stretch)
    if ao_radius is not None:
        check_ao_radius(ao_radius, view, w, h)
    check_unit_m(unit_m, program.unit_m, view)
    canonical = format_program(program)
    name = material_name or default_material_name(Path(file))
    with OutputFolder(out_dir) as out:  # locked before the work starts: a second writer fails
        out.check_writable(planned_files(subset, float_format, preview, encoding))
        t0 = time.perf_counter()
        stats = EvalStats()
        try:
            maps = evaluate(
                program,
                w,
                h,
                backend=backend,
                view=view,
                ao_radius_units=ao_radius,
                stats=stats,
                usage=Usage(preview_tile=1) if preview else EVALUATE,  # shading counted too
            )
        except LimitError as e:
            raise click.ClickException(str(e)) from None
        t_eval = time.perf_counter() - t0
        with out.batch("render", marker=MANIFEST_NAME) as staging:
            result = write_maps(
                maps,
                staging,
                final_dir=out.path,
                maps_subset=subset,
                program_text=canonical,
                extra_meta={"ao_radius_units": ao_radius, "source": str(file)},
                encoding=encoding,
                unit_m=unit_m,
                presets=presets,
                name=name,
            )
            if view_note:
                result.manifest["view_adjusted"] = view_note
            if preview:
                from matloom.io.png import save_png
                from matloom.render.preview import shade

                save_png(staging / "preview.png", shade(maps))
            atomic_write_bytes(staging / "material.mat", (canonical + "\n").encode("utf-8"))
            write_manifest(result, staging)
    for name, n in result.nonfinite_counts.items():
        click.echo(f"warning: {n} non-finite texel value(s) in {name}", err=True)
    if stats.zero_divisions:
        click.echo(f"note: {stats.zero_divisions} division(s) by exactly 0 returned 0", err=True)
    click.echo(f"rendered {w}x{h} in {t_eval * 1000:.0f} ms -> {out.path}", err=True)
    if as_json:
        click.echo(json.dumps(result.manifest, indent=2, default=str))
    else:
        click.echo(str(out.path))


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
