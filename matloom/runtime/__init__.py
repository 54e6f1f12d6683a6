"""The runtime: what runs the engine for a front end (render jobs and their sinks, the numba
kernels' warm-up). It depends on :mod:`matloom.engine`, :mod:`matloom.render` and
:mod:`matloom.io`, never the reverse: the engine is given what it needs from here through its
:class:`~matloom.engine.session.Session` (e.g. :mod:`.cold_start`). Importing this package
imports no submodule.
"""
