"""How a wet look changes colours: darker as the surface soaks water up ("make it wet" on soil
darkens it; on a glazed tile it only adds gloss)."""

from __future__ import annotations

import numpy as np

from matloom.engine.evaluate import evaluate
from matloom.lang import ast as A

#: The comparative a wet look is read as ("wet": "wetter overall, glossier"): darker as
#: the surface is porous (:func:`porosity`).
SOAKED = "wetter"
#: Mean roughness at which a wet surface darkens not at all (a glaze, a polished stone), and
#: at which it darkens as much as "darker" (sand, soil, concrete, cloth).
_SEALED, _POROUS = 0.3, 0.8
#: The least share of the darkening: the mean roughness is the whole material's, and the
#: rough grout between glazed tiles does darken (with none, "make it wet" on tiles changed
#: too little to show and was refused).
_LEAST = 0.3


def porosity(program: A.Program) -> float:
    """How much a wet look darkens ``program``, 0 .. 1, from its mean roughness (a sealed,
    glossy surface stays its colour when wet; a rough, porous one darkens): water darkens
    what it soaks into."""
    r = float(np.mean(np.asarray(evaluate(program, 32, 32).roughness, np.float64)))
    return min(1.0, max(_LEAST, (r - _SEALED) / (_POROUS - _SEALED)))
