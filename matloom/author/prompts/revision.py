"""Generator-side user turns: the request, the repair turns and the revision turn (§8.3, §8.4).

Every turn asks for the same answer format (:data:`~matloom.author.prompts.system.ANSWER_FORMAT`):
thinking is allowed, and the last ``<material>...</material>`` block of the reply is used.

Critic loop v3 adds sections to the revision turn (none of them in the paper's): which version
the revision continues from and why (:func:`continue_text`), a revision that made no visible
change (:func:`no_change_text`), what the critic said of a dropped attempt, and the critic's
structural changes.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

from matloom.author.library_refs import LibraryReference
from matloom.author.prompts.system import ANSWER_FORMAT
from matloom.author.records import EditRecord
from matloom.lang.diagnostics import Diagnostic

#: At most this many diagnostics are sent in one repair turn (the first errors matter most).
MAX_DIAGNOSTICS = 5


def request_message(description: str, references: Sequence[LibraryReference] = ()) -> str:
    """The first user turn of a generator conversation; ``references`` are the material
    library's programs for the request (``library_refs``), offered to reuse or ignore."""
    text = (
        "Write a layered-material DSL program for this material:\n"
        f"<description>{description}</description>"
    )
    if not references:
        return text
    blocks = [text, _REFERENCES_INTRO]
    for k, ref in enumerate(references, start=1):
        about = [f"Entry: {ref.description}"]
        about += [f"Adapted: {'; '.join(ref.notes)}"] if ref.notes else []
        about += [f"It does not show: {'; '.join(ref.missing)}"] if ref.missing else []
        blocks.append(
            f'<library_program n="{k}" entry="{ref.entry}">\n'
            + "\n".join(about)
            + f"\n<program>\n{ref.program.rstrip()}\n</program>\n</library_program>"
        )
    return "\n\n".join(blocks)


#: What the generator is told about the library's programs (``library_refs``).
_REFERENCES_INTRO = (
    "For reference, MatLoom's material library (hand-written programs, adapted by rules to "
    "the request; they check and render) gives the programs below for this request. They may "
    "be the requested material, a near one or a wrong one, and they may miss requested "
    "details. Reuse what fits the description (structure, scales, colours, conditions), fix "
    "or add what it asks for and they lack, or ignore them. Write your own complete program "
    "for the description."
)


def draft_message(number: int, total: int) -> str:
    """The turn asking for another first draft (``drafts``): draft ``number`` of ``total``,
    a different approach from the earlier drafts the conversation holds."""
    earlier = "draft" if number == 2 else "drafts"
    return (
        f"Write draft {number} of {total} for the same description: a new, complete program "
        f"that takes a different approach from your earlier {earlier} above (another "
        "structure, other primitives or patterns, or another reading of the description), "
        "whichever you think could match the description better. Do not repeat an earlier "
        "draft. Each draft is rendered and reviewed, and the best one is revised further. "
        f"{ANSWER_FORMAT}"
    )


def missing_program_message() -> str:
    """Repair turn when no program could be found in the reply."""
    return f"I could not find a program in your reply. {ANSWER_FORMAT}"


def reply_too_large_message(length: int | None, limit: int) -> str:
    """Repair turn when the reply was over the reply-size cap (only its start is shown);
    ``length`` is None when reading stopped before the reply's end."""
    size = f"{length:,} characters long, " if length is not None else ""
    return (
        f"Your reply was {size}over the limit of {limit:,} characters; only its start "
        f"is shown above and it was not read. Keep it shorter. {ANSWER_FORMAT}"
    )


def diagnostics_message(program: str, diagnostics: Sequence[Diagnostic]) -> str:
    """Repair turn quoting structured diagnostics: code, line:column, caret excerpt, expectation
    and hint for each error, followed by the program as it was read."""
    errors = [d for d in diagnostics if d.is_error] or list(diagnostics)
    shown = errors[:MAX_DIAGNOSTICS]
    more = len(errors) - len(shown)
    blocks = [d.format("program") for d in shown]
    if more > 0:
        blocks.append(f"... and {more} more error(s)")
    body = "\n\n".join(blocks)
    return (
        f"The program does not parse. {len(errors)} error(s), each with its line:column, a caret "
        "under the problem, what was expected and a hint:\n"
        f"<error>\n{body}\n</error>\n"
        f"The program as read:\n<material>\n{program}\n</material>\n"
        f"Fix every error. {ANSWER_FORMAT}"
    )


def _bullets(items: Sequence[str], empty: str) -> str:
    return "\n".join(f"- {item}" for item in items) or f"- ({empty})"


def edit_line(edit: EditRecord) -> str:
    """One edit as a bullet text: ``layer 1 .roughness: 0.6 -> 0.3``, ``Define grain: ...``."""
    where = []
    if edit.define:
        where.append(f"Define {edit.define}")
    if edit.layer is not None:
        where.append(f"layer {edit.layer}")
    if edit.channel:
        where.append(f".{edit.channel}")
    head = " ".join(where)
    return f"{head}: {edit.change}" if head else edit.change


def _score_line(match_score: int, previous_score: int | None) -> str:
    line = f"{match_score}/100"
    if previous_score is not None:
        line += f" (the previous version scored {previous_score}/100)"
    return line


def _views_text(views: Sequence[str]) -> str:
    names = " and ".join(f"the {v}" for v in views)
    noun = "preview" if len(views) == 1 else "previews"
    return (
        f"Attached: {names} {noun} of the program you are revising, as the critic saw "
        f"{'it' if len(views) == 1 else 'them'}."
    )


def continue_text(
    base: int,
    latest: int,
    standings: dict[int, str | None],
    program: str | None = None,
    names: Mapping[int, str] | None = None,
) -> str:
    """Which version a revision continues from and why: the best so far, ``base``, and the
    later rounds (``standings``: round -> its score in words, None for a round with no visible
    change); ``program`` (the base's own text) when the base is not the last answer.
    ``names``: what to call a version other than ``round k`` (the drafts: ``draft 2``)."""
    name = (names or {}).get

    def called(j: int) -> str:
        return name(j) or f"round {j}"

    if base == latest:
        return (
            f"Continuing from your last answer, {called(base)} ({standings[base]}): "
            "the best so far."
        )
    later = "; ".join(
        f"{called(j)} made {NO_CHANGE}"
        if standings.get(j) is None
        else f"{called(j)}: {standings[j]}"
        for j in range(base + 1, latest + 1)
    )
    text = f"Continuing from {called(base)} ({standings[base]}), the best so far; {later}."
    if program is not None:
        text += (
            f" Revise {called(base)}'s program, not your last answer:\n"
            f"<material>\n{program.strip()}\n</material>"
        )
    return text


#: How a round whose previews did not change visibly is named.
NO_CHANGE = "no visible change"


def no_change_text(
    round_index: int, difference: float, threshold: float, name: str | None = None
) -> str:
    """The note for a revision whose previews barely changed (``difference``: the mean absolute
    difference in levels of 255, under ``threshold``); ``name``: what to call it other than
    ``round k`` (``revision 1`` after drafts)."""
    called = name or f"round {round_index}"
    return (
        f"Your revision in {called} changed the previews by {difference:.2f} levels "
        f"of 255 on average, under the {threshold:g} that shows: {NO_CHANGE}, so it was not "
        "reviewed. Make changes large enough to see at the render size, or a structural one "
        "(a new layer, a different primitive or pattern) where values alone do not get there."
    )


def revision_message(  # noqa: PLR0913 - one keyword per optional section
    match_score: int,
    differences: Sequence[str],
    suggestions: Sequence[str],
    *,
    edits: Sequence[EditRecord] = (),
    views: Sequence[str] = (),
    added_seeds: Sequence[str] = (),
    previous_score: int | None = None,
    continue_from: str | None = None,
    no_change: str | None = None,
    dropped: tuple[str, Sequence[str]] | None = None,
    structural: Sequence[str] = (),
    warnings: Sequence[str] = (),
) -> str:
    """The revision turn: the critic's score, what differs, what to change and its concrete
    edits under their own headings; the attached previews (``views``, when images go with the
    turn); the seeds the render gave to noise the model left unseeded; the answer format.

    Loop v3 sections, first: which version it continues from (``continue_from``), a revision
    with no visible change (``no_change``), what the critic said of a dropped round
    (``dropped``: its name, ``round 2``, and differences); and the critic's ``structural`` changes.
    ``warnings``: the checker's warnings of the program being revised (``revision_warnings``),
    e.g. a Define a built-in shadows, which the render silently ignores."""
    sections = []
    if continue_from:
        sections.append(("Continue from", continue_from))
    if no_change:
        sections.append(("No visible change", no_change))
    if dropped is not None:
        name, said = dropped
        sections.append(
            (
                "Dropped attempt",
                f"What the critic said of {name}, which is not continued:\n"
                + _bullets(said, "none noted"),
            )
        )
    sections += [
        ("Score", _score_line(match_score, previous_score)),
        ("What differs", _bullets(differences, "none noted")),
        ("What to change", _bullets(suggestions, "no suggestions")),
    ]
    if structural:
        sections.append(("Structural changes", _bullets(structural, "")))
    if edits:
        sections.append(("Concrete edits", _bullets([edit_line(e) for e in edits], "")))
    if warnings:
        sections.append(
            (
                "Checker warnings",
                "The checker accepted the program with these warnings; each may mean that "
                "what you wrote is not what renders:\n" + _bullets(warnings, ""),
            )
        )
    if views:
        sections.append(("Preview", _views_text(views)))
    if added_seeds:
        sections.append(
            (
                "Seeds",
                "Your program left these noise seeds out (positions in your program); the render "
                "used:\n"
                + _bullets(added_seeds, "")
                + "\nWrite them as seed= values to keep that noise unchanged.",
            )
        )
    sections.append(
        (
            "Answer",
            "Revise the material to fix what differs, following what to change. When keeping "
            "a layer unchanged, copy it exactly, including any seed= values, so its noise stays "
            f"the same. {ANSWER_FORMAT}",
        )
    )
    body = "\n\n".join(f"## {title}\n{text}" for title, text in sections)
    return "A critic reviewed your material against the original description.\n\n" + body


#: At most this many checker warnings go with one revision turn.
MAX_WARNINGS = 6


def warning_lines(source: str) -> list[str]:
    """The checker's warnings of ``source`` as ``W005 at line 3, column 8: ... (hint)``, at
    most :data:`MAX_WARNINGS`."""
    from matloom.lang.api import analyse

    _, diagnostics = analyse(source)
    out = []
    for d in diagnostics:
        if d.is_error:
            continue
        hint = f" ({d.hint})" if d.hint else ""
        out.append(f"{d.code} at line {d.line}, column {d.column}: {d.message}{hint}")
    return out[:MAX_WARNINGS]


def canonical_assistant_turn(preamble: str, canonical: str) -> str:
    """An assistant turn showing a program: reasoning, then the program in a material block
    (used for a P0 written by the material library, which has no reply of its own)."""
    head = f"{preamble.strip()}\n\n" if preamble.strip() else ""
    return f"{head}<material>\n{canonical.strip()}\n</material>"
