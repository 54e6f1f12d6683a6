"""Noise seeds: deterministic canonicalisation and the seed-variant generator (§5.3, §5.4)."""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from matloom.lang import ast as A
from matloom.lang.lexer import Lexer
from matloom.lang.rewrite import map_program
from matloom.vocab import FUNCTIONS

SEED_LIMIT = 2**31
"""Drawn seeds lie in [0, 2**31), as in the reference."""

_MASK64 = (1 << 64) - 1


def derive_seed(program_seed: int, position: int) -> int:
    """Seed for the ``position``-th seedless noise call: a splitmix64 hash, never global state."""
    z = (program_seed * 0x9E3779B97F4A7C15 + (position + 1) * 0xBF58476D1CE4E5B9) & _MASK64
    z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & _MASK64
    z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & _MASK64
    z ^= z >> 31
    return int(z % SEED_LIMIT)


def has_seedless_noise(program: A.Program) -> bool:
    return any(
        isinstance(n, A.Call) and _is_noise(n) and n.arg("seed") is None
        for _, e in A.program_expressions(program)
        for n in A.walk(e)
    )


def _is_noise(call: A.Call) -> bool:
    return uses_seed(call)


def uses_seed(call: A.Call) -> bool:
    """Whether ``call``'s value depends on a seed: a function with a seed parameter, unless
    that seed is used only for some values of another parameter (``ParamSpec.used_when``,
    e.g. Bricks' output="cell_value") and the call has none of them."""
    spec = FUNCTIONS.get(call.func)
    seed = next((p for p in spec.params if p.is_seed), None) if spec is not None else None
    if seed is None:
        return False
    if seed.used_when is None:
        return True
    name, values = seed.used_when
    node = call.arg(name)
    if node is None:
        p = spec.param(name)  # type: ignore[union-attr]
        return p is not None and p.default in values
    return isinstance(node, A.Str | A.Lit) and node.value in values


def canonicalize_seeds(program: A.Program, program_seed: int = 0) -> A.Program:
    """Make every omitted noise seed explicit.

    The n-th seedless call, counted in the reference's construction order (Defines first, then
    each layer in fixed channel order, post-order within an expression), gets
    ``derive_seed(program_seed, n)``. A Define'd noise is drawn once and shared by its references.
    """
    counter = [0]

    def fill(node: A.Node) -> A.Node:
        if isinstance(node, A.Call) and _is_noise(node) and node.arg("seed") is None:
            seed = derive_seed(program_seed, counter[0])
            counter[0] += 1
            args = tuple(a for a in node.args) + (A.Arg("seed", A.Num(seed), True),)
            order = FUNCTIONS[node.func].param_names
            args = tuple(sorted(args, key=lambda a: order.index(a.param)))
            return replace(node, args=args)
        return node

    return map_program(program, fill)


def seed_literal_spans(text: str) -> list[tuple[int, int, int]]:
    """(start, end, value) of every ``seed=N`` literal in program text (token based)."""
    toks = Lexer(text).tokens()
    out = []
    for k in range(len(toks) - 2):
        if toks[k].kind == "IDENT" and toks[k].text == "seed" and toks[k + 1].text == "=":
            j = k + 2
            neg = toks[j].kind == "OP" and toks[j].text == "-"
            if neg:
                j += 1
            if toks[j].kind == "NUM" and isinstance(toks[j].value, int):
                start = toks[k + 2].span.start
                value = -int(toks[j].value) if neg else int(toks[j].value)
                out.append((start, toks[j].span.end, value))
    return out


def seed_assignments(text: str, variants: int, seed: int = 0) -> list[dict[int, int]]:
    """Old->new seed maps for variants 1..K (variant 0, the original, is the identity).

    Distinct old values are sorted and each gets ``rng.integers(0, 2**31)`` from
    ``numpy.random.default_rng(seed)``, drawn in sorted order, exactly as the reference does.
    Equal seeds stay equal; negative seeds are remapped to non-negative values.
    """
    olds = sorted({v for _, _, v in seed_literal_spans(text)})
    if not olds or variants <= 0:
        return []
    rng = np.random.default_rng(seed)
    return [{old: int(rng.integers(0, SEED_LIMIT)) for old in olds} for _ in range(variants)]


def apply_seed_map(
    text: str, mapping: dict[int, int], spans: list[tuple[int, int, int]] | None = None
) -> str:
    """Replace each seed literal by its new value; every other byte is unchanged."""
    spans = seed_literal_spans(text) if spans is None else spans
    parts, last = [], 0
    for start, end, value in spans:
        parts.append(text[last:start])
        parts.append(str(mapping.get(value, value)))
        last = end
    parts.append(text[last:])
    return "".join(parts)


def seed_variants(text: str, variants: int, seed: int = 0) -> list[str]:
    """The original program text followed by ``variants`` seed variants (§5.4)."""
    spans = seed_literal_spans(text)
    return [text] + [apply_seed_map(text, m, spans) for m in seed_assignments(text, variants, seed)]
