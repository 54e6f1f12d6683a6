"""Schedules: how the one interpreter (:mod:`matloom.engine.interpret`) is run over an image.

* :mod:`.dense`: every field of the whole image at once, then the numpy compositing;
* :mod:`matloom.engine.schedules.banded`: bands of rows, deferred arithmetic compiled into the compositing
  kernel, coverage culling of the noise fields;
* :mod:`.seed_batch`: many seed variants of one program at once (leading seed axis), for sweeps;
* :mod:`.sweep`: the seed sweep (seed batches composited and shaded as previews on threads,
  scored by a caller's :class:`~.sweep.Scorer`, shaded with a caller's :class:`~.sweep.Shading`).
"""
