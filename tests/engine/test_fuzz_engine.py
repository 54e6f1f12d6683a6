"""Fuzz: programs from the random generator always evaluate (no unhandled exception)."""

from __future__ import annotations

import numpy as np
import pytest

from matloom.engine.evaluate import evaluate
from matloom.lang.random_program import random_program

N_PROGRAMS = 2000
SHARDS = 8


@pytest.mark.parametrize("shard", range(SHARDS))
def test_random_programs_evaluate(shard):
    for seed in range(shard, N_PROGRAMS, SHARDS):
        text = random_program(seed)
        maps = evaluate(text, 64, 64)
        assert maps.basecolor_linear.shape == (64, 64, 3)
        assert maps.normal.dtype == np.float32
        # non-finite values are allowed (Sqrt/Log/Div/Pow) but must be counted, never crash
        assert isinstance(maps.nonfinite_counts(), dict)
