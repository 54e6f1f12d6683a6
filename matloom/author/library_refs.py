"""The material library's programs for a request, shown to the generator as references.

With ``library_refs = N`` (the ``recommended`` settings: 2), the generator's first turn carries
the programs the offline author (:func:`matloom.library.author`) writes for the request from
its N best candidates: hand-written entries adapted to the request's colours, finish, scale and
conditions. The model may reuse their structure, fix what they miss or ignore them; the
program it writes is still its own (it is checked, critiqued and selected like any other).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

from matloom.lang import ast as A


@dataclass(frozen=True)
class LibraryReference:
    """One library program offered to the generator."""

    entry: str
    description: str
    #: the program in the language the generator's system prompt teaches: no comments, a
    #: View of four numbers (the library's ``tileable=True, unit_m=...`` left out)
    program: str
    #: requested parts the library says this program does not show
    missing: tuple[str, ...] = ()
    #: how the library adapted the entry to the request, and the overlays it added
    notes: tuple[str, ...] = ()


def _as_prompted(program: A.Program) -> str:
    from matloom.lang.printer import format_program

    view = program.view
    if view is not None:
        program = replace(program, view=replace(view, tileable=False, unit_m=None))
    return format_program(program)


def library_references(
    prompt: str, count: int, *, seed: int = 0, library_dirs: tuple[str, ...] = ()
) -> list[LibraryReference]:
    """``count`` library programs for ``prompt``: what the offline author writes, then the
    ranking's next entries (fewer when it has fewer; the same entry is never offered twice). A bad user library entry raises
    :class:`~matloom.library.errors.LibraryError` (one line), as for ``--start library``."""
    from matloom.library import author
    from matloom.library.user import library_for

    if count <= 0:
        return []
    lib = library_for(library_dirs)
    refs: list[LibraryReference] = []
    seen: set[str] = set()
    # the offline author's own choice first (it may compose), then the ranking's entries
    for pick in (None, *range(1, count + 1)):
        if len(refs) == count:
            break
        try:
            result = author(prompt, seed=seed, pick=pick, tileable=True, lib=lib)
        except ValueError:  # fewer candidates than asked for
            break
        if result.entry in seen:
            continue
        seen.add(result.entry)
        refs.append(
            LibraryReference(
                entry=result.entry,
                description=result.description,
                program=_as_prompted(result.ast),
                missing=tuple(result.dropped),
                notes=tuple([*result.adaptations, *result.overlay_notes]),
            )
        )
    return refs
