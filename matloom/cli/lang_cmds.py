"""`matloom check`, `matloom fmt`, `matloom seeds`."""

from __future__ import annotations

import sys
from pathlib import Path

import click

from matloom.cli import params
from matloom.lang.api import analyse
from matloom.lang.diagnostics import format_diagnostics


def _read(path: str) -> str:
    if path == "-":
        return sys.stdin.read()
    try:
        return Path(path).read_text(encoding="utf-8")
    except OSError as e:
        raise click.ClickException(f"cannot read {path}: {e.strerror}") from None
    except UnicodeDecodeError:
        raise click.ClickException(f"{path} is not UTF-8 text") from None


@click.command("check")
@click.argument("files", nargs=-1, required=True)
@click.option("--strict", is_flag=True, help="Exit 1 when there are warnings (and no errors).")
@click.option("--json", "as_json", is_flag=True, help="Print diagnostics as JSON on stdout.")
def check_cmd(files: tuple[str, ...], strict: bool, as_json: bool) -> None:
    """Check program FILES. Exit 0 clean, 1 warnings only (with --strict), 2 errors."""
    import json

    worst = 0
    report = []
    for f in files:
        _, diags = analyse(_read(f))
        if diags:
            click.echo(format_diagnostics(diags, f), err=True)
        errors = sum(d.is_error for d in diags)
        warnings = len(diags) - errors
        report.append(
            {
                "file": f,
                "errors": errors,
                "warnings": warnings,
                "diagnostics": [d.to_dict() for d in diags],
            }
        )
        if errors:
            worst = 2
        elif warnings and strict:
            worst = max(worst, 1)
    if as_json:
        click.echo(json.dumps(report, indent=2))
    total_e = sum(r["errors"] for r in report)
    total_w = sum(r["warnings"] for r in report)
    click.echo(f"{len(files)} file(s): {total_e} error(s), {total_w} warning(s)", err=True)
    sys.exit(worst)


@click.command("fmt")
@click.argument("file")
@click.option("--inline", is_flag=True, help="Replace Define references by their expressions.")
@click.option(
    "--check",
    "check_only",
    is_flag=True,
    help="Exit 1 if FILE is not already canonical; print nothing.",
)
@click.option("--write", is_flag=True, help="Rewrite FILE in place (atomically).")
@click.option(
    "--seed",
    type=int,
    default=None,
    help="Make omitted noise seeds explicit, derived from this program seed.",
)
def fmt_cmd(file: str, inline: bool, check_only: bool, write: bool, seed: int | None) -> None:
    """Print FILE in canonical form, keeping its `#` comments."""
    from matloom.lang.inline import inline_defines
    from matloom.lang.printer import format_program
    from matloom.lang.seeds import canonicalize_seeds

    text = _read(file)
    program, diags = analyse(text)
    if program is None or any(d.is_error for d in diags):
        click.echo(format_diagnostics([d for d in diags if d.is_error], file), err=True)
        sys.exit(2)
    if seed is not None:
        program = canonicalize_seeds(program, seed)
    if inline:
        from matloom.lang.diagnostics import ProgramError

        try:
            program = inline_defines(program)
        except ProgramError as e:
            click.echo(format_diagnostics(e.diagnostics, file), err=True)
            sys.exit(2)
    out = format_program(program, comments=True)  # fmt keeps every `#` comment
    if check_only:
        sys.exit(0 if text.strip() == out else 1)
    if write:
        if file == "-":
            raise click.UsageError("--write needs a file, not stdin")
        from matloom.io.atomic import rewrite_file

        try:
            rewrite_file(file, (out + "\n").encode("utf-8"))
        except OSError as err:
            from matloom.io.outdir import describe_os_error

            raise click.ClickException(describe_os_error(err, file)) from None
        click.echo(f"formatted {file}", err=True)
        return
    click.echo(out)


@click.command("seeds")
@click.argument("file")
@click.option(
    "--variants", "-k", type=params.VARIANTS, required=True, help="Number of seed variants K."
)
@click.option("--seed", type=int, default=0, show_default=True, help="Seed of the variant RNG.")
@click.option(
    "--program-seed",
    type=int,
    default=0,
    show_default=True,
    help="Program seed used to make omitted noise seeds explicit first.",
)
@click.option(
    "-o",
    "--out",
    "out_dir",
    type=click.Path(file_okay=False),
    default=None,
    help="Write variant_0000.mat (the original) ... into this folder.",
)
def seeds_cmd(file: str, variants: int, seed: int, program_seed: int, out_dir: str | None) -> None:
    """Print (or write) the original program and K seed variants of FILE."""
    from matloom.lang.constants import plain_numbers
    from matloom.lang.printer import format_program
    from matloom.lang.seeds import canonicalize_seeds, seed_variants

    program, diags = analyse(_read(file))
    if program is None or any(d.is_error for d in diags):
        click.echo(format_diagnostics([d for d in diags if d.is_error], file), err=True)
        sys.exit(2)
    # reference text: named static values (a named seed too) written as plain numbers
    text = format_program(plain_numbers(canonicalize_seeds(program, program_seed)))
    texts = seed_variants(text, variants, seed)
    if len(texts) == 1:
        click.echo("no noise seeds in this program: only the original is produced", err=True)
    if out_dir:
        from matloom.io.outdir import OutputFolder

        with OutputFolder(out_dir) as out, out.batch("seeds") as staging:
            for i, t in enumerate(texts):
                (staging / f"variant_{i:04d}.mat").write_text(t + "\n", encoding="utf-8")
        click.echo(f"wrote {len(texts)} program(s) to {out.path}", err=True)
        return
    for i, t in enumerate(texts):
        click.echo(f"# variant {i}" + (" (original)" if i == 0 else ""))
        click.echo(t)
        click.echo("")
