"""`matloom params` (the exposed parameters of a program) and `matloom set` (change them)."""

from __future__ import annotations

import json
import re
import sys
from typing import NoReturn

import click

from matloom.cli.lang_cmds import _read
from matloom.lang.deps import OUTPUTS
from matloom.lang.diagnostics import ProgramError, format_diagnostics
from matloom.lang.layout import keep_layout
from matloom.lang.params import Param, Value, list_params, set_params
from matloom.lang.printer import fmt_num


def parse_value(text: str) -> Value:
    """A value as written on a command line: a number, ``r,g,b`` or ``#rrggbb``."""
    t = text.strip()
    if re.fullmatch(r"#[0-9a-fA-F]{6}", t):
        return (float(int(t[1:3], 16)), float(int(t[3:5], 16)), float(int(t[5:7], 16)))
    try:
        if "," in t:
            parts = [float(x) for x in t.split(",")]
            if len(parts) != 3:
                raise ValueError
            return (parts[0], parts[1], parts[2])
        return int(t) if re.fullmatch(r"[+-]?\d+", t) else float(t)
    except ValueError:
        raise ValueError(f"not a number, r,g,b or #rrggbb: {text!r}") from None


def _fail(message: str) -> NoReturn:
    click.echo(f"Error: {message}", err=True)
    sys.exit(2)


def _labels(text: str, file: str) -> dict[str, str]:
    """An entry file's labels (front matter ``colours``/``[roles]``/``[scalars]``), else none."""
    from matloom.library.entry import FENCE, LibraryError, entry_from_text
    from matloom.library.labels import entry_labels

    if not text.lstrip().startswith(FENCE):
        return {}
    try:
        return entry_labels(entry_from_text(text, file if file != "-" else "stdin.mat"), text)
    except LibraryError:
        return {}  # front matter of another shape: labels from the names


def _value_text(p: Param) -> str:
    if isinstance(p.value, tuple):
        return ", ".join(fmt_num(v) for v in p.value)
    text = fmt_num(p.value)
    if p.metres is not None:
        text += f" ({fmt_num(round(p.metres, 6))} m)"
    return text


def _range_text(p: Param) -> str:
    if p.low is None and p.high is None:
        return ""
    lo = "" if p.low is None else fmt_num(p.low)
    hi = "" if p.high is None else fmt_num(p.high)
    return f"{lo}..{hi}"


def _affects_text(p: Param) -> str:
    if set(p.affects) >= set(OUTPUTS):
        return "all maps"
    return ", ".join(p.affects) if p.affects else "-"


def _table(ps: list[Param]) -> str:
    head = ("address", "value", "unit", "range", "kind", "label", "affects")
    rows = [head] + [
        (
            p.address,
            _value_text(p),
            p.unit or "",
            _range_text(p),
            p.kind,
            p.label,
            _affects_text(p),
        )
        for p in ps
    ]
    widths = [max(len(r[k]) for r in rows) for k in range(len(head) - 1)]
    return "\n".join(
        "  ".join(c.ljust(w) for c, w in zip(r[:-1], widths, strict=True)) + "  " + r[-1]
        for r in rows
    )


def _program_error(err: ProgramError, file: str) -> NoReturn:
    click.echo(format_diagnostics([d for d in err.diagnostics if d.is_error], file), err=True)
    sys.exit(2)


@click.command("params")
@click.argument("file")
@click.option("--json", "as_json", is_flag=True, help="Print the parameters as a JSON list.")
def params_cmd(file: str, as_json: bool) -> None:
    """List the exposed parameters of FILE: named constants, layer channel literals and literal
    static parameters, with their address (for `matloom set`), value, unit, range, kind, label
    and the maps they affect. A library entry's parameters use its front matter's labels."""
    text = _read(file)
    try:
        ps = list_params(text, _labels(text, file))
    except ProgramError as err:
        _program_error(err, file)
    if as_json:
        click.echo(json.dumps([p.to_json() for p in ps], indent=2))
    elif not ps:
        click.echo(f"{file}: no parameters", err=True)
    else:
        click.echo(_table(ps))


@click.command("set")
@click.argument("file")
@click.argument("assignments", nargs=-1, required=True, metavar="ADDRESS=VALUE...")
@click.option("-o", "--out", type=click.Path(dir_okay=False), help="Write the result here.")
@click.option("--write", is_flag=True, help="Rewrite FILE in place (atomically).")
def set_cmd(file: str, assignments: tuple[str, ...], out: str | None, write: bool) -> None:
    """Set parameters of FILE (addresses from `matloom params`) and print the program.

    A colour is `r,g,b` (0-255) or `#rrggbb`. A value outside the parameter's range is clamped,
    with a warning on stderr. Without -o or --write nothing is written.
    """
    if out and write:
        _fail("give -o OUT or --write, not both")
    if write and file == "-":
        _fail("--write needs a file, not stdin")
    values = {}
    for a in assignments:
        address, eq, value = a.partition("=")
        if not eq or not address.strip():
            _fail(f"expected ADDRESS=VALUE, got {a!r}")
        try:
            values[address.strip()] = parse_value(value)
        except ValueError as err:
            _fail(f"{address.strip()}: {err}")
    text = _read(file)
    try:
        new, warnings = set_params(text, values)
        new = keep_layout(text, new)  # the untouched lines as the user wrote them
    except ProgramError as err:
        _program_error(err, file)
    except ValueError as err:
        _fail(str(err))
    for w in warnings:
        click.echo(f"warning: {w}", err=True)
    target = file if write else out
    if target is None:
        click.echo(new)
        return
    from matloom.io.atomic import atomic_write_bytes, rewrite_file

    data = (new + "\n").encode("utf-8")
    try:
        (rewrite_file if write else atomic_write_bytes)(target, data)
    except OSError as err:
        from matloom.io.outdir import describe_os_error

        _fail(describe_os_error(err, target))
    click.echo(f"wrote {target}", err=True)
