"""The user library options of `matloom library` and `matloom generate` (docs/library.md).

``$MATLOOM_LIBRARY_PATH`` is read here, once per command, and the folders passed down.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import click


def library_option(f: Any) -> Any:
    """``--library DIR`` (repeatable): user library folders added to the built-in entries."""
    return click.option(
        "--library",
        "library_dirs",
        multiple=True,
        type=click.Path(file_okay=False),
        help="A user library folder (repeatable), after those of $MATLOOM_LIBRARY_PATH: its "
        "entries are ranked with the built-in ones and replace those of the same name.",
    )(f)


def user_dirs(flags: tuple[str, ...], *, missing_ok: bool = False) -> tuple[Path, ...]:
    """The user library folders: $MATLOOM_LIBRARY_PATH's, then ``flags`` (a later one wins);
    one-line error for one that is not a folder (``missing_ok``: one not made yet is left
    out)."""
    from matloom.library.entry import LibraryError
    from matloom.library.user import ENV, library_dirs

    try:
        return library_dirs(flags, os.environ.get(ENV), missing_ok=missing_ok)
    except LibraryError as exc:
        raise click.ClickException(str(exc)) from None


def load_library(  # noqa: ANN201 - matloom.library.Library
    flags: tuple[str, ...] = (), *, missing_ok: bool = False
):
    """The built-in library with the user folders' entries; a bad entry is a one-line error."""
    from matloom.library import LibraryError
    from matloom.library.user import library_for

    try:
        return library_for(user_dirs(flags, missing_ok=missing_ok))
    except LibraryError as exc:
        raise click.ClickException(" ".join(str(exc).split())) from None
