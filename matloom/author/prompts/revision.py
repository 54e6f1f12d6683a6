"""Generator-side user turns: the request, the repair turns and the revision turn (§8.3, §8.4)."""

from __future__ import annotations

from collections.abc import Sequence

from matloom.lang.diagnostics import Diagnostic

#: At most this many diagnostics are sent in one repair turn (the first errors matter most).
MAX_DIAGNOSTICS = 5


def request_message(description: str) -> str:
    """The first user turn of a generator conversation."""
    return (
        "Write a layered-material DSL program for this material:\n"
        f"<description>{description}</description>"
    )


def missing_program_message() -> str:
    """Repair turn when no program could be found in the reply."""
    return (
        "I could not find a program in your reply. Reply with only the complete program inside "
        "a single <material>...</material> pair."
    )


def reply_too_large_message(length: int, limit: int) -> str:
    """Repair turn when the reply was over the reply-size cap (only its start is shown)."""
    return (
        f"Your reply was {length:,} characters long, over the limit of {limit:,}; only its start "
        "is shown above and it was not read. Reply with only the complete program inside a "
        "single <material>...</material> pair."
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
        "Fix every error and reply with only the corrected <material>...</material> block."
    )


def revision_message(
    match_score: int, differences: Sequence[str], suggestions: Sequence[str]
) -> str:
    """The revision turn (paper appendix, verbatim wording with the notes as bullets)."""
    notes = "\n".join(f"- {n}" for n in [*differences, *suggestions]) or "- (no notes)"
    return (
        "A critic reviewed your material against the original description and scored the match "
        f"{match_score}/100. Their notes:\n{notes}\n"
        "Revise the material to address these and reply with ONLY the updated "
        "<material>...</material>. When keeping a layer unchanged, copy it exactly, including "
        "any seed= values, so its noise stays the same."
    )


def canonical_assistant_turn(preamble: str, canonical: str) -> str:
    """The rewritten assistant turn after acceptance: reasoning, then the canonical program."""
    head = f"{preamble.strip()}\n\n" if preamble.strip() else ""
    return f"{head}<material>\n{canonical.strip()}\n</material>"
