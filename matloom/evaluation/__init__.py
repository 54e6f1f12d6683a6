"""Evaluation and scale: ``matloom bench`` (the paper's benchmark as a command), metric plugins,
statistics and reports, blind judging, and ``matloom dataset``, all on one executor (in process,
or a Dask cluster). Level 7: imports ``author``, ``library``, ``blender`` and the levels below,
never ``cli`` or ``studio``. See docs/evaluation.md and docs/datasets.md."""
