"""The ``v3`` few-shot examples of the ``recommended`` settings (issue 26): far from every
development prompt, valid, rendering, free of the tricks the system prompt forbids, and written
in the language 2 and 3 idioms. The paper's six stay as they are (tests/author/test_prompts.py).

Nearness is measured on content words (lower case, letters only, stop words and words under 3
letters dropped, a plural "s" stripped):

* **Jaccard** (shared words over all words of the pair) at most :data:`MAX_JACCARD` = 0.2 with
  every development prompt. A description that copies a prompt shares most of its words (0.5
  and more); 0.2 is one shared word of five, and a short description sharing one of its three
  or four words with a two-word prompt is already over it (the paper's "Polished green marble"
  against "polished concrete": 0.25);
* **no shared phrase**: no two consecutive content words of a description appear
  consecutively in a prompt (the paper's "Glow-in-the-dark stars ..." shares "glow dark" with
  "Glow-in-the-dark concrete ...").

Regenerate the recommended prompt's snapshot after an intended change with
``MATLOOM_UPDATE_SNAPSHOTS=1``.
"""

from __future__ import annotations

import json
import os
import re
from collections.abc import Iterator
from pathlib import Path

import pytest

import matloom
from matloom.author.config import AuthorConfig
from matloom.author.prompts.system import (
    FEW_SHOT_EXAMPLES,
    FEW_SHOT_EXAMPLES_V3,
    FewShotExample,
    system_prompt,
)
from matloom.author.settings_presets import preset_values
from matloom.lang import ast as A

DEV_PROMPTS = Path(__file__).parents[1] / "data" / "prompts-dev.json"
SNAPSHOT = Path(__file__).parent / "snapshots" / "system_prompt_recommended.txt"
MAX_JACCARD = 0.2
#: A literal this large multiplying a sine is the classic "fract(sin(x) * 43758.5453)" hash
#: (above any colour amplitude, 255, so that Sin(...) * 100 + 120 stays allowed).
HASH_FACTOR = 1000.0
_STOP = frozenset(
    """a an the and or of in on with to for by from at as is are be it its this that these
    those there their was were has have had into over under than then so such very some any all
    each other like looks look would could used use using made make also not no but about which
    what who where while your our his her them they we you one two""".split()
)
_TRIG = frozenset({"Sin", "Cos"})
_FRACTIONAL = frozenset({"Fract", "Floor", "Ceil", "Mod"})


def content_words(text: str) -> list[str]:
    words = []
    for word in re.findall(r"[a-z]+", text.lower()):
        if word in _STOP or len(word) < 3:
            continue
        words.append(word[:-1] if word.endswith("s") and not word.endswith("ss") else word)
    return words


def jaccard(a: str, b: str) -> float:
    wa, wb = set(content_words(a)), set(content_words(b))
    return len(wa & wb) / len(wa | wb) if wa | wb else 0.0


def shared_phrases(a: str, b: str) -> set[tuple[str, str]]:
    def pairs(text: str) -> set[tuple[str, str]]:
        words = content_words(text)
        return set(zip(words, words[1:], strict=False))

    return pairs(a) & pairs(b)


def dev_prompts() -> list[str]:
    return [p["text"] for p in json.loads(DEV_PROMPTS.read_text(encoding="utf-8"))["prompts"]]


def too_near(description: str) -> list[str]:
    """Why ``description`` is too near a development prompt (empty: it is not)."""
    problems = []
    for prompt in dev_prompts():
        score = jaccard(description, prompt)
        if score > MAX_JACCARD:
            problems.append(f"Jaccard {score:.2f} with {prompt[:60]!r}")
        for phrase in shared_phrases(description, prompt):
            problems.append(f"phrase {' '.join(phrase)!r} of {prompt[:60]!r}")
    return problems


# --------------------------------------------------------------------------- program walks


def children(node: A.Node) -> Iterator[A.Node]:
    if isinstance(node, A.Call):
        yield from (arg.value for arg in node.args)
        yield from node.extra
    elif isinstance(node, A.BinOp):
        yield from (node.left, node.right)
    elif isinstance(node, A.Neg):
        yield node.operand


def nodes(program: A.Program) -> Iterator[A.Node]:
    roots = [d.expr for d in program.defines]
    for layer in program.layers:
        roots += [layer.alpha] if layer.alpha is not None else []
        roots += [arg for channel in layer.channels for arg in channel.args]
    stack = list(roots)
    while stack:
        node = stack.pop()
        yield node
        stack.extend(children(node))


def contains_trig(
    node: A.Node, defines: dict[str, A.Node], seen: frozenset[str] = frozenset()
) -> bool:
    """Whether a Sin or Cos feeds ``node`` (through Define names too)."""
    if isinstance(node, A.Call) and node.func in _TRIG:
        return True
    if isinstance(node, A.Ref) and node.name in defines and node.name not in seen:
        return contains_trig(defines[node.name], defines, seen | {node.name})
    return any(contains_trig(child, defines, seen) for child in children(node))


def is_trig(node: A.Node, defines: dict[str, A.Node]) -> bool:
    """A Sin or Cos call, or a Define name holding one."""
    if isinstance(node, A.Ref) and node.name in defines:
        node = defines[node.name]
    return isinstance(node, A.Call) and node.func in _TRIG


def forbidden_tricks(text: str) -> list[str]:
    """The sine-hash tricks the system prompt's "Cells, instances and angles" section tells
    models to replace by Hash, cell values and Tile: a sine multiplied by a literal of at least
    :data:`HASH_FACTOR` (``Sin(...) * 43758.5453``), or the fractional part, floor or modulo of
    anything a sine feeds (``Fract(Sin(...) * k)``, ``h - Floor(h)``)."""
    program = matloom.parse(text)
    defines = {d.name: d.expr for d in program.defines}
    found = []
    for node in nodes(program):
        if isinstance(node, A.BinOp) and node.op == "*":
            for trig, factor in ((node.left, node.right), (node.right, node.left)):
                big = isinstance(factor, A.Num) and abs(factor.value) >= HASH_FACTOR
                if big and is_trig(trig, defines):
                    found.append(f"a sine times {factor.value}")
        if isinstance(node, A.Call) and node.func in _FRACTIONAL and node.args:
            if contains_trig(node.args[0].value, defines):
                found.append(f"{node.func} of a sine")
    return found


def named_static_values(program: A.Program) -> set[str]:
    """Defines of a constant used as a static parameter (``Bricks(mortar=grout)``)."""
    constants = {d.name for d in program.defines if isinstance(d.expr, A.Num) and not d.params}
    used = set()
    for node in nodes(program):
        if isinstance(node, A.Call):
            for arg in node.args:
                if isinstance(arg.value, A.Ref) and arg.value.name in constants:
                    used.add(arg.value.name)
    return used


def features(program: A.Program) -> set[str]:
    """The language 3 features a program uses."""
    out = {"parameterised Define" for d in program.defines if d.params}
    for node in nodes(program):
        if not isinstance(node, A.Call):
            continue
        keywords = {arg.param: arg.value for arg in node.args}
        output = keywords.get("output")
        if node.func == "Choose":
            out.add("Choose")
        if node.func in ("Min", "Max") and node.extra:
            out.add("n-ary Min/Max")
        if node.func == "Tile" and isinstance(output, A.Str) and output.value != "mask":
            out.add("Tile output")
        if node.func == "Weave" and ("weft_width" in keywords or output == A.Str("thread_value")):
            out.add("Weave weft/thread value")
        if node.func == "Worley" and "smoothness" in keywords:
            out.add("smooth Worley")
    return out


# --------------------------------------------------------------------------- tests


@pytest.mark.parametrize("example", FEW_SHOT_EXAMPLES_V3, ids=lambda e: e.file_name)
def test_v3_description_is_far_from_every_dev_prompt(example: FewShotExample) -> None:
    assert len(dev_prompts()) == 71
    assert too_near(example.description) == []


def test_the_nearness_rules_catch_the_papers_near_examples() -> None:
    near = {e.description: too_near(e.description) for e in FEW_SHOT_EXAMPLES}
    assert near["Polished green marble"]  # Jaccard 0.25 with "polished concrete"
    assert any(
        "glow dark" in p for p in near["Glow-in-the-dark stars with a crescent moon and a comet"]
    )


@pytest.mark.parametrize("example", FEW_SHOT_EXAMPLES_V3, ids=lambda e: e.file_name)
def test_v3_example_checks_renders_and_uses_no_forbidden_trick(example: FewShotExample) -> None:
    text = example.program()
    assert matloom.check(text) == []  # no errors and no warnings
    assert matloom.format(text) == text  # canonical: the model sees what it will get back
    assert forbidden_tricks(text) == []
    program = matloom.parse(text)
    assert named_static_values(program), "no named value used as a parameter"
    for node in nodes(program):  # the prompt: to_01=True whenever noise drives a value
        if isinstance(node, A.Call) and node.func == "fBm":
            assert any(a.param == "to_01" and a.value == A.Lit(True) for a in node.args)
    image = matloom.preview(text, 64)
    assert image.shape == (64, 64, 3) and image.std() > 2.0  # a pattern, not a flat swatch


def test_the_trick_rule_catches_the_papers_stars() -> None:
    stars = next(e for e in FEW_SHOT_EXAMPLES if e.file_name.startswith("6_")).program()
    assert "a sine times 43758.5453" in forbidden_tricks(stars)
    assert "Floor of a sine" in forbidden_tricks(stars)
    assert forbidden_tricks("Material(Layer(1).basecolor(Sin(X() * 40) * 100 + 120, 0, 0))") == []
    hashed = "Define(h, Sin(X() * 12.9898) * 2000)\nMaterial(Layer(Fract(h)))"
    assert sorted(forbidden_tricks(hashed)) == ["Fract of a sine", "a sine times 2000"]


def test_v3_set_shows_the_language_3_features() -> None:
    used = set().union(*(features(matloom.parse(e.program())) for e in FEW_SHOT_EXAMPLES_V3))
    assert used == {
        "parameterised Define",
        "Choose",
        "n-ary Min/Max",
        "Tile output",
        "Weave weft/thread value",
        "smooth Worley",
    }
    layers = sorted(len(matloom.parse(e.program()).layers) for e in FEW_SHOT_EXAMPLES_V3)
    assert layers[0] == 1 and layers[-1] >= 3


def test_recommended_uses_v3_and_paper_keeps_its_examples() -> None:
    assert AuthorConfig().examples == "paper"
    assert AuthorConfig(**preset_values("recommended")).examples == "v3"
    v3 = system_prompt(examples="v3")
    paper = system_prompt()
    for example in FEW_SHOT_EXAMPLES_V3:
        assert f"Description: {example.description}\n" in v3 and example.description not in paper
    for example in FEW_SHOT_EXAMPLES:
        assert example.description not in v3
    assert v3.count("<material>") == paper.count("<material>") == 1 + len(FEW_SHOT_EXAMPLES)


def test_recommended_system_prompt_snapshot() -> None:
    cfg = AuthorConfig(**preset_values("recommended"))
    text = system_prompt(
        playbook=cfg.playbook,
        few_shot=cfg.few_shot,
        render_size=cfg.critique_size,
        views=cfg.views,
        examples=cfg.examples,
    )
    if os.environ.get("MATLOOM_UPDATE_SNAPSHOTS"):
        SNAPSHOT.write_text(text, encoding="utf-8")
    assert SNAPSHOT.exists(), "run with MATLOOM_UPDATE_SNAPSHOTS=1 to create the snapshot"
    assert text == SNAPSHOT.read_text(encoding="utf-8")
