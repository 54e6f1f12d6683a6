"""How the clauses of one request join: a plan and the plans of the request's other clauses
("paint the panels olive drab, satin finish": a colour and a roughness), read by the rules of
:mod:`matloom.author.edit.rules` (passed in, so this module imports none of them but the
colour rule)."""

from __future__ import annotations

import re
from collections.abc import Callable, Sequence
from dataclasses import replace

from matloom.author.edit.colours import colour_rule
from matloom.author.edit.lexicon import tokens
from matloom.author.edit.plan import Context, EditRefused, Plan
from matloom.author.edit.targets import named_in_program

#: Where a request's clauses part: commas, semicolons, and "and" before a verb of its own
#: ("change the background to blue and make the stripes silver").
AND_VERB = (
    r"\band\s+(?=(?:make|turn|change|paint|set|give|colour|color|mute|darken|lighten|brighten"
    r"|tint|dye|add|put)\b)"
)
_CLAUSE_RE = re.compile(rf"[,;:]|{AND_VERB}")

#: Rules whose plans two clauses of one request may join ("olive drab, satin finish",
#: "wider grout joints, and make the grout a darker grey", "smaller cells, a bit more matte").
_JOINABLE = frozenset({"colour", "roughness", "channel", "relief", "joints", "scale", "contrast"})
#: Words that join two wishes inside one clause ("bigger tiles with thinner joints").
_WISHES_RE = re.compile(r"\b(?:and|with|plus|but)\b")


def join_clauses(
    c: Context, asked: str, plan: Plan, rules: Sequence[Callable[[Context], Plan | None]]
) -> Plan:
    """``plan`` and the plan of another clause of the request (split at commas and
    semicolons) by another joinable rule that changes other parameters: "paint the panels
    olive drab, satin finish" is a colour and a roughness."""
    clauses = [s for s in _CLAUSE_RE.split(asked) if s and s.strip()]
    if plan.view or plan.rule not in _JOINABLE | {"overlay"}:
        return plan  # an overlay joins a clause's colour or finish ("worn, faded")
    if len(clauses) < 2 and plan.rule in ("joints", "scale"):
        # "bigger tiles with thinner joints": two wishes in one clause
        clauses = [s for s in _WISHES_RE.split(asked) if s and s.strip()]
    contrast = plan.rule == "contrast"
    if contrast:
        # "bolder and thicker veins": the whole request without the contrast word, then its
        # clauses ("larger, bolder patina patches": the size is the patches')
        rest = re.sub(rf"\b(?:{'|'.join(map(re.escape, plan.said))})\b", " ", asked)
        clauses = [rest, *clauses] if len(clauses) > 1 else [rest]
    single = len(clauses) < 2 and not contrast
    if single and plan.add:
        return plan
    if single:
        # one clause, two properties: "polished brass" is a finish and a colour
        # ("the joints shallower and not so dark": a relief and a colour)
        clauses = [asked] if plan.rule in ("roughness", "channel", "relief") else []
    for clause in clauses:
        overlay = plan.rule.startswith("overlay")
        if overlay and _describing(tokens(clause)):
            continue  # a clause describing the condition ("rust, the kind you get ...")
        # the condition's own clause: its words and colour are its own ("reddish-brown clay
        # and dirt"); another clause keeps them ("add red rust and make the tiles red")
        words = tokens(clause)
        v = c.vocabulary
        own = (
            overlay
            and bool(plan.said)
            and (
                plan.said[0] in words  # the condition's word ("snow" is a colour name too)
                or any(t in plan.said and v.ish_base(t) not in v.named for t in words)
            )
        )
        sub = replace(c, words=[t for t in words if not own or t not in plan.said])
        if (
            not single
            and (plan.rule.startswith("colour") or overlay)
            and _describes(c, sub.words, comparatives=not overlay)
        ):
            continue  # "the wires rusty, orange-brown": the colour of the same part
        if overlay and not single and not named_in_program(c.program, words, c.ew):
            continue  # "lichen, those pale yellow-green patches": the added condition's look
        try:
            if single:
                if plan.rule == "relief" and not _names_colour(c, sub.words):
                    continue  # "the holes should be deeper": a relief, no darker colour
                other = colour_rule(sub)
            else:
                other = next((p for rule in rules if (p := rule(sub)) is not None), None)
                if (
                    other is not None
                    and other.rule == plan.rule != "colour"
                    and not set(sub.words) & set(c.ew.relief)  # "give it a deeper": no colour
                ):
                    other = colour_rule(sub)  # "darker and a bit shiny": its colour part
        except EditRefused:
            continue
        if contrast and other is not None and "colour" in other.rule and "between" in words:
            continue  # "more contrast between the blue and white yarn": the parts, not a paint
        # "paint the pipes safety yellow and add some rust streaks": a condition added on top
        # of the clause before's change (once: the plan adds nothing yet)
        added = other is not None and other.rule == "overlay" and not plan.add
        if (
            other is None
            or (other.rule not in _JOINABLE and not added)
            or (other.rule == plan.rule and plan.rule != "colour")
            # a relief joins a colour only ("flatten it, nearly smooth" is no gloss)
            or _rule_parts(plan, other) & {"relief", "colour"} == {"relief"}
            # a zoom joins once ("smaller, denser cells and a bit more matte")
            or (other.view and (plan.view or other.rule != "scale"))
            or (other.add and not added)
            or set(other.assignments) & set(plan.assignments)
            or set(other.lines) & set(plan.lines)
        ):
            continue
        plan = _joined(plan, other)
    return plan


def _joined(plan: Plan, other: Plan) -> Plan:
    """One plan making both plans' changes ("roughness+colour")."""
    return Plan(
        f"{plan.rule}+{other.rule}",
        f"{plan.note}; {other.note}",
        assignments={**plan.assignments, **other.assignments},
        intended=tuple(dict.fromkeys(plan.intended + other.intended)),
        lines={**plan.lines, **other.lines},
        view=dict(plan.view or other.view),
        add=tuple(plan.add) + tuple(other.add),
        graded=plan.graded and other.graded,
        exact=plan.exact or other.exact,
    )


def with_contrast(c: Context, plan: Plan, contrast: Plan | None) -> Plan:
    """``plan`` joined by the contrast rule's plan of the same request ("a satin finish with a
    bit more visible grain": the finish leads, the grain joins), when it changes other lines."""
    if (
        contrast is None
        or "contrast" in plan.rule.split("+")
        or plan.view
        or plan.add
        or set(contrast.lines) & set(plan.lines)
    ):
        return plan
    return _joined(plan, contrast)


def _rule_parts(*plans: Plan) -> set[str]:
    """The rules the plans are made of ("relief+colour": relief, colour)."""
    return {part for plan in plans for part in plan.rule.split("+")}


def _names_colour(c: Context, words: list[str]) -> bool:
    """Whether the words name a colour, a tone or a colour comparative other than a relief's
    ("deeper" is both)."""
    v = c.vocabulary
    return any(
        (t not in c.ew.relief)
        and (t in v.named or t in v.tones or t in c.ew.comparative or t in c.ew.towards)
        for t in words
    )


#: Words that open a clause describing the clause before it ("..., like a dark walnut stain").
_SIMILE = frozenset({"like", "as"})
#: Words that open a clause describing an added condition ("a water stain, that yellow-brown
#: ring"; "rust, the kind you get near the coast")
RELATIVE = frozenset({"that", "those", "which", "kind", "sort"})


def _describing(words: list[str]) -> bool:
    """Whether a clause opens by describing the thing before it (a simile or a relative)."""
    lead = [w for w in words[:3] if w not in ("the", "a", "an")]
    return bool(lead) and (lead[0] in _SIMILE or lead[0] in RELATIVE)


def _describes(c: Context, words: list[str], comparatives: bool = True) -> bool:
    """Whether a clause only describes the colour of the one before: a simile, or colour and
    tone words with no part of its own ("orange-brown", "a deep one"); ``comparatives``: a bare
    comparative describes too (after an overlay, "slightly lighter" is a change of its own)."""
    if not words:
        return True
    if words[0] in _SIMILE:
        return True
    v = c.vocabulary
    return all(
        t in c.ew["filler"]
        or v.ish_base(t) in v.named
        or t in v.tones
        or (comparatives and t in c.ew.comparative)
        for t in words
    )


#: A sentence describing how the material looks now ("The rings look like dull grey plastic.",
#: "right now the reflections are distracting"): not what to change, when another sentence
#: asks for it; one that says "too" is a request ("the bars look too dull").
_STATE_RE = re.compile(
    r"\s*(?:(?:right\s+now|currently|at\s+the\s+moment|at\s+present)\b"
    r"|(?:the|this|these|that|those|it|they|its|their)\b.*\b(?:looks?|reads?|seems?)\s+like\b)",
    re.IGNORECASE,
)
_TOO_RE = re.compile(r"\btoo\b", re.IGNORECASE)


def without_state(request: str) -> str:
    """The request without its sentences that only describe the material as it is, when
    another sentence is left ("The rings look like dull grey plastic. Make them shinier")."""
    sentences = [s for s in re.split(r"(?<=[.;!?])\s+", request.strip()) if s.strip()]
    kept = [s for s in sentences if not _STATE_RE.match(s) or _TOO_RE.search(s)]
    return " ".join(kept) if kept and len(kept) < len(sentences) else request
