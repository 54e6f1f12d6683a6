"""Critic prompts (reference-engine.md §8.4): a system prompt and a CO-STAR user message whose
content depends on which signals (render, stats, code) the critic receives."""

from __future__ import annotations

import json
from collections.abc import Collection

from matloom.author.prompts.system import dsl_reference

#: Field descriptions of the critic's JSON answer (paper appendix, verbatim).
CRITIQUE_FIELDS: dict[str, str] = {
    "match_score": "0-100, how well the image matches the description",
    "differences": "Concrete visual mismatches between image and description",
    "suggestions": "Concrete appearance changes that would improve the match",
}

_LAYOUT_NOTE = (
    "The render is a flat, head-on swatch under one fixed light: little relief, reflectance or "
    "transmission is visible in this layout, so do not over-penalise those."
)


def _shown_list(signals: Collection[str]) -> str:
    items = ["- the target description"]
    if "render" in signals:
        items.append("- a single render of the material on a flat plane seen head-on")
    if "code" in signals:
        items.append("- the program source in the layered-material DSL")
    if "stats" in signals:
        line = "- objective scalars with definitions, computed from the unlit material maps"
        if "render" not in signals:
            line += " (no render is shown)"
        items.append(line)
    return "You are shown:\n" + "\n".join(items)


def _judge_clause(signals: Collection[str]) -> str:
    render, code, stats = "render" in signals, "code" in signals, "stats" in signals
    if render and code:
        return (
            "Judge how well the render matches the description, then give the smallest set of "
            "line-targeted numeric edits: name the layer index in source order (0 = bottom "
            "substrate), the channel, and the exact value change. Do not rewrite the whole "
            "program. " + _LAYOUT_NOTE
        )
    if render:
        return (
            "Judge only from visible appearance (colour, gloss, pattern and structure, scale, "
            "relief, special qualities); never assume anything about the code. Be specific. "
            + _LAYOUT_NOTE
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


def critic_system_prompt(signals: Collection[str]) -> str:
    """System prompt of the stateless critic for the given signal subset."""
    parts = [
        "You are a meticulous material-appearance critic.",
        _shown_list(signals),
        _judge_clause(signals),
    ]
    if "render" in signals and "stats" in signals:
        parts.append(
            "The scalars are objective measurements of the maps; use them to ground your visual "
            "judgment."
        )
    if "code" in signals:
        parts.append("The DSL the program is written in:\n\n" + dsl_reference())
    return "\n\n".join(parts) + "\n"


def _configuration_name(signals: Collection[str]) -> str:
    names = {"render": "a render", "code": "the source code", "stats": "material statistics"}
    given = [names[s] for s in ("render", "code", "stats") if s in signals]
    return " and ".join(given) if given else "the description only"


def response_skeleton() -> str:
    """The JSON skeleton shown to the critic (field descriptions as values)."""
    skeleton = {
        "match_score": f"<integer {CRITIQUE_FIELDS['match_score']}>",
        "differences": [f"<{CRITIQUE_FIELDS['differences']}>"],
        "suggestions": [f"<{CRITIQUE_FIELDS['suggestions']}>"],
    }
    return json.dumps(skeleton, indent=2)


def critic_user_message(
    description: str, signals: Collection[str], *, program: str | None, stats: str | None
) -> str:
    """The CO-STAR user message; the render (if any) is attached as an image after this text."""
    if "render" in signals:
        objective = (
            "Compare the attached render against the description "
            f"<description>{description}</description>."
        )
    else:
        objective = f"Judge how well the material suits <description>{description}</description>."
    if "code" in signals and program is not None:
        objective += (
            f"\n\nThe program:\n<program>\n{program}\n</program>\n"
            "Suggest minimal, line-targeted edits to it."
        )
    if "stats" in signals and stats is not None:
        objective += "\n\n" + stats.strip()
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
        ("Response", "Answer with exactly this structure:\n" + response_skeleton()),
    ]
    return "\n\n".join(f"## {title}\n{body}" for title, body in sections)


def critic_retry_message(error: str) -> str:
    """Follow-up sent when an answer could not be parsed as the critique JSON."""
    return (
        "Your answer could not be parsed as the required JSON "
        f"({error}). Reply again with only the JSON object:\n{response_skeleton()}"
    )
