"""The evaluation engine: a checked program -> sampled fields -> composited, relief-mapped maps.

:mod:`.evaluate` is the entry point (``matloom.evaluate``); :mod:`.session` holds the runtime
state an evaluation uses (backend policy, reporter, lock, caches). :mod:`.interpret` runs a
program's op graph, :mod:`.schedules` decide how it is run over an image (dense, banded, seed
batch), :mod:`.composite` and :mod:`.relief` make the maps, :mod:`.kernels` and
:mod:`.backends` hold the numpy and numba implementations.

This package sits above :mod:`matloom.lang` and below :mod:`matloom.render` and
:mod:`matloom.io`; importing it imports no submodule.
"""
