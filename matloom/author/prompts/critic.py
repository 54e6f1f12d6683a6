"""Critic prompts (reference-engine.md §8.4): a system prompt and a CO-STAR user message whose
content depends on which signals (render, stats, code) the critic receives, which preview
layouts it is shown (``flat``, ``lit``) and whether it also sees the previous round.

The answer schema shows ``match_score`` as a number, ``edits`` (concrete changes naming a layer
and a channel, or a Define) when the critic reads the code, and ``better_than_previous`` when it
sees the previous round.

Critic loop v3 (:class:`CriticOptions`; all off for the paper, whose texts stay byte-identical):
``previews`` gives the critic the generator's "Resolution and previews" section and the measured
facts of what each layout can and cannot show (:mod:`matloom.author.prompts.previews`);
``structural`` lets it ask for structural changes in their own answer field; a score-only
request (the last program's) asks for ``match_score`` (and ``better_than_previous``) only.
"""

from __future__ import annotations

import json
from collections.abc import Collection, Sequence
from dataclasses import dataclass

from matloom.author.prompts.previews import layout_facts, module_layout_note, previews_section
from matloom.author.prompts.system import dsl_reference

#: Field descriptions of the critic's JSON answer (the first three: paper appendix, verbatim).
CRITIQUE_FIELDS: dict[str, str] = {
    "match_score": "0-100, how well the image matches the description",
    "differences": "Concrete visual mismatches between image and description",
    "suggestions": "Concrete appearance changes that would improve the match",
    "edits": "optional concrete program edits; each names a layer (0 = bottom) and a channel, "
    "or a Define, and the exact change",
    "better_than_previous": "true if this version matches the description better than the "
    "previous one, else false",
    "structural": "structural changes where the look is wrong in kind: a new layer, a different "
    "primitive or pattern, a layer removed or reordered; leave the list empty when numeric "
    "edits suffice",
}


@dataclass(frozen=True)
class CriticOptions:
    """The critic loop v3 parts of the critic's prompts (the defaults: the paper's texts)."""

    #: The "Resolution and previews" facts and what each layout can and cannot show.
    previews: bool = False
    #: Structural changes may be asked for (with the code), not only numeric edits.
    structural: bool = False
    #: The render size the facts are stated for (the critique size).
    size: int = 512


#: The paper's critic prompts.
PAPER = CriticOptions()

_FLAT_NOTE = (
    "The render is a flat, head-on swatch under one fixed light: little relief, reflectance or "
    "transmission is visible in this layout, so do not over-penalise those."
)
_BOTH_NOTE = (
    "The flat render shows colour and pattern under one fixed light, with little relief, "
    "reflectance or transmission; judge gloss, metal, sheen, coat, transmission and relief from "
    "the lit render."
)


#: The flat preview's note in :mod:`matloom.render.lit` starts with this.
_FLAT_NOTE_LEAD = "flat preview"


def _flat_module_note() -> str | None:
    """``FLAT_LAYOUT_NOTE`` of :mod:`matloom.render.lit` without its lead, or None."""
    try:
        from matloom.render.lit import FLAT_LAYOUT_NOTE
    except ImportError:
        return None
    note = str(FLAT_LAYOUT_NOTE).strip()
    lead, sep, rest = note.partition(": ")
    return rest if sep and lead.startswith(_FLAT_NOTE_LEAD) else note


def measured_layout_notes(views: Sequence[str]) -> str:
    """Loop v3's layout notes: the flat preview module's own note when the flat render is shown
    (the lit one is in the "Resolution and previews" section), pointing to the measured facts
    (the paper's notes say the flat render shows "little relief", while steep relief shows
    strongly in it)."""
    notes = []
    flat = _flat_module_note() if "flat" in views else None
    if flat:
        notes.append(f"About the flat render: {flat}")
    notes.append(
        'What each layout can and cannot show is measured under "Resolution and previews" '
        "below: judge each quality from the layout that shows it, and do not blame relief "
        "(shading on slopes) on colour, nor an uncovered patch on the colour of a layer."
    )
    return " ".join(notes)


def critic_previews_section(size: int, views: Sequence[str]) -> str:
    """The generator's "Resolution and previews" section for ``size`` and ``views``, the measured
    facts of what each layout can and cannot show, and what that means for a critique."""
    pixel = 2.0 / size
    return "\n".join(
        [
            previews_section(size, views),
            layout_facts(views),
            "The generator was told the facts above. Ask only for changes the previews can show: "
            f"features at least 2 px wide ({pixel:.4f} units at View(0, 0, 1, 1)) and value "
            "changes large enough to see; a change the previews cannot show is wasted. A "
            "quality that no layout shown can show is judged from the description and the "
            "code, not penalised.",
        ]
    )


def layout_notes(views: Sequence[str], options: CriticOptions = PAPER) -> str:
    """What the critic should know about the preview layouts it is shown."""
    if options.previews:
        return measured_layout_notes(views)
    if tuple(views) == ("flat",):
        return _FLAT_NOTE
    notes = [_BOTH_NOTE] if "flat" in views else []
    lit = module_layout_note("lit")
    notes.append(f"About the lit render: {lit}" if lit else "The lit render is shaded physically.")
    return " ".join(notes)


def _render_line(views: Sequence[str]) -> str:
    if tuple(views) == ("flat",):
        return "- a single render of the material on a flat plane seen head-on"
    if tuple(views) == ("lit",):
        return "- a single render of the material on a flat plane in the lit studio layout"
    names = " and ".join(f"the {v}" for v in views)
    return f"- {len(views)} renders of the same material on a flat plane: {names} layout"


def _shown_list(signals: Collection[str], views: Sequence[str], history: bool) -> str:
    items = ["- the target description"]
    if "render" in signals:
        items.append(_render_line(views))
    if "code" in signals:
        items.append("- the program source in the layered-material DSL")
    if "stats" in signals:
        line = "- objective scalars with definitions, computed from the unlit material maps"
        if "render" not in signals:
            line += " (no render is shown)"
        items.append(line)
    if history:
        seen = "render(s) and score" if "render" in signals else "score"
        items.append(f"- from the second round on, the previous version's {seen}")
    return "You are shown:\n" + "\n".join(items)


#: What a structural change is (loop v3), in the judge clause.
STRUCTURAL_CLAUSE = (
    "Where the structure is right, give line-targeted numeric edits; where the look is wrong "
    "in kind (a missing feature, the wrong pattern, layering or kind of relief), ask for a "
    "structural change in structural: a new layer, a different primitive or pattern, a layer "
    "removed or reordered. Numeric edits too small to show change nothing."
)


def _judge_clause(
    signals: Collection[str], views: Sequence[str], options: CriticOptions = PAPER
) -> str:
    render, code, stats = "render" in signals, "code" in signals, "stats" in signals
    matches = "render matches" if len(views) == 1 else "renders match"
    notes = layout_notes(views, options)
    if render and code and options.structural:
        return (
            f"Judge how well the {matches} the description, then give the changes that would "
            "improve the match most. Name the layer index in source order (0 = bottom "
            "substrate), the channel, and the exact value change. " + STRUCTURAL_CLAUSE + " "
            "Do not rewrite the whole program. " + notes
        )
    if render and code:
        return (
            f"Judge how well the {matches} the description, then give the smallest set of "
            "line-targeted numeric edits: name the layer index in source order (0 = bottom "
            "substrate), the channel, and the exact value change. Do not rewrite the whole "
            "program. " + notes
        )
    if render:
        return (
            "Judge only from visible appearance (colour, gloss, pattern and structure, scale, "
            "relief, special qualities); never assume anything about the code. Be specific. "
            + notes
        )
    if code and options.structural:
        return (
            "Judge the source"
            + (" and the scalars" if stats else "")
            + "; give line-targeted edits (layer index, channel, exact values). "
            + STRUCTURAL_CLAUSE
            + " No render is available."
        )
    if code and stats:
        return (
            "Judge the source and the scalars; give line-targeted edits (layer index, channel, "
            "exact values). Cross-check the scalars against the code: for example, a zero height "
            "range despite a non-constant height expression means the noise is too flat. No "
            "render is available."
        )
    if code:
        return (
            "Read the source statically. Flag contradictions with the description such as metal "
            "for a dielectric, constant height where relief is wanted, or a badly scaled View. "
            "Give line-targeted edits."
        )
    return "Judge whether the scalars suit the description and suggest concrete changes."


def critic_system_prompt(
    signals: Collection[str],
    views: Sequence[str] = ("flat",),
    *,
    history: bool = False,
    options: CriticOptions = PAPER,
) -> str:
    """System prompt of the critic for the given signals, preview layouts and history
    (``options``: the loop v3 parts)."""
    parts = [
        "You are a meticulous material-appearance critic.",
        _shown_list(signals, views, history),
        _judge_clause(signals, views, options),
    ]
    if "render" in signals and "stats" in signals:
        parts.append(
            "The scalars are objective measurements of the maps; use them to ground your visual "
            "judgment."
        )
    if history:
        parts.append(
            "When the previous version is shown, score this version on its own merits, then say "
            "whether it matches the description better than the previous one; name any "
            "regression in the differences."
        )
    if "code" in signals:
        parts.append("The DSL the program is written in:\n\n" + dsl_reference())
    if options.previews and "render" in signals:
        parts.append(critic_previews_section(options.size, views))
    return "\n\n".join(parts) + "\n"


def _configuration_name(signals: Collection[str]) -> str:
    names = {"render": "a render", "code": "the source code", "stats": "material statistics"}
    given = [names[s] for s in ("render", "code", "stats") if s in signals]
    return " and ".join(given) if given else "the description only"


def response_skeleton(
    *, edits: bool = True, history: bool = False, structural: bool = False, score_only: bool = False
) -> str:
    """The answer structure shown to the critic: JSON with descriptions in angle brackets
    (``match_score`` and ``layer`` unquoted: they are numbers); ``score_only``: the score (and
    the verdict on the previous version) only."""
    lines = [f'  "match_score": <number {CRITIQUE_FIELDS["match_score"]}>']
    if score_only:
        if history:
            lines.append('  "better_than_previous": <true or false>')
        return "{\n" + ",\n".join(lines) + "\n}"
    lines += [
        f'  "differences": [{json.dumps("<" + CRITIQUE_FIELDS["differences"] + ">")}]',
        f'  "suggestions": [{json.dumps("<" + CRITIQUE_FIELDS["suggestions"] + ">")}]',
    ]
    if edits and structural:
        lines.append(
            '  "structural": ["<a structural change: a new layer, a different primitive or '
            'pattern, a layer removed or reordered>"]'
        )
    if edits:
        lines.append(
            '  "edits": [{"layer": <layer index, 0 = bottom>, "channel": "<channel name>", '
            '"change": "<exact change, e.g. 0.6 -> 0.3>"}, {"define": "<Define name>", '
            '"change": "<exact change>"}]'
        )
    if history:
        lines.append('  "better_than_previous": <true or false>')
    return "{\n" + ",\n".join(lines) + "\n}"


def _response_notes(
    *, edits: bool, history: bool, structural: bool = False, score_only: bool = False
) -> str:
    notes = ["match_score is a number, not a string."]
    if score_only:
        notes.append("Only the score is asked for: no differences, suggestions or edits.")
        edits = False
    if edits and structural:
        notes.append(f"structural: {CRITIQUE_FIELDS['structural']}.")
    if edits:
        notes.append(f"edits: {CRITIQUE_FIELDS['edits']}; leave the list empty if none.")
    if history:
        notes.append(
            f"better_than_previous: {CRITIQUE_FIELDS['better_than_previous']} "
            "(omit it when no previous version is shown)."
        )
    return " ".join(notes)


@dataclass(frozen=True)
class PreviousView:
    """What the critic is told about the previous round (its images go after this round's)."""

    index: int
    score: int | None
    images: int


def _images_line(views: Sequence[str], previous: PreviousView | None) -> str:
    shown = [f"this version, {v} layout" for v in views]
    if previous is not None:
        shown += [f"the previous version, {v} layout" for v in views][: previous.images]
    if len(shown) == 1:
        return ""
    listed = "; ".join(f"{i}. {what}" for i, what in enumerate(shown, 1))
    return f"\nThe attached images, in order: {listed}."


def _previous_text(previous: PreviousView) -> str:
    score = f"{previous.score}/100" if previous.score is not None else "no usable score"
    seen = ""
    if previous.images:
        seen = " (its render is" if previous.images == 1 else " (its renders are"
        seen += " attached after this version's)"
    return (
        f"\n\nThe previous version{seen} scored {score}. Say in better_than_previous whether "
        "this version matches the description better."
    )


def critic_user_message(
    description: str,
    signals: Collection[str],
    *,
    program: str | None,
    stats: str | None,
    views: Sequence[str] = ("flat",),
    previous: PreviousView | None = None,
    history: bool = False,
    structural: bool = False,
    score_only: bool = False,
) -> str:
    """The CO-STAR user message; the render(s), if any, are attached as images after this text.

    ``history`` says that the critic is asked about history (the schema then has
    ``better_than_previous``); ``previous`` is the previous round, when there is one;
    ``structural`` asks for structural changes too; ``score_only`` for the score only.
    """
    if "render" in signals:
        noun = "render" if len(views) == 1 else "renders"
        objective = (
            f"Compare the attached {noun} against the description "
            f"<description>{description}</description>."
        )
        objective += _images_line(views, previous)
    else:
        objective = f"Judge how well the material suits <description>{description}</description>."
    if previous is not None:
        objective += _previous_text(previous)
    code = "code" in signals and program is not None
    if code:
        objective += f"\n\nThe program:\n<program>\n{program}\n</program>\n" + _code_request(
            structural, score_only
        )
    if "stats" in signals and stats is not None:
        objective += "\n\n" + stats.strip()
    edits = "code" in signals
    sections = [
        ("Context", f"You review one material using {_configuration_name(signals)}."),
        ("Objective", objective),
        (
            "Style",
            "JSON only: no preamble, no markdown, no missing or extra fields; complete and "
            "well-formed.",
        ),
        ("Tone", "Neutral."),
        ("Audience", "A program that will strictly parse your JSON."),
        (
            "Response",
            "Answer with exactly this structure:\n"
            + response_skeleton(
                edits=edits, history=history, structural=structural, score_only=score_only
            )
            + "\n"
            + _response_notes(
                edits=edits, history=history, structural=structural, score_only=score_only
            ),
        ),
    ]
    return "\n\n".join(f"## {title}\n{body}" for title, body in sections)


def _code_request(structural: bool, score_only: bool) -> str:
    if score_only:
        return "Only the score is asked for this time."
    if structural:
        return (
            "Suggest line-targeted edits to it, and structural changes where the look is wrong "
            "in kind."
        )
    return "Suggest minimal, line-targeted edits to it."


def critic_retry_message(
    error: str,
    *,
    edits: bool = True,
    history: bool = False,
    structural: bool = False,
    score_only: bool = False,
) -> str:
    """Follow-up sent when an answer could not be parsed as the critique JSON."""
    skeleton = response_skeleton(
        edits=edits, history=history, structural=structural, score_only=score_only
    )
    return (
        "Your answer could not be parsed as the required JSON "
        f"({error}). Reply again with only the JSON object:\n"
        f"{skeleton}"
    )
