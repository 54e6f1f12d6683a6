"""Composition: a tileable program built from parts (base, colours, finish, layout, motif) for
requests no library entry covers. See :mod:`matloom.library.compose.spec` (the contract),
:mod:`~matloom.library.compose.build` (:func:`compose`), :mod:`~matloom.library.compose.tables`
(the vocabulary: ``BASES``, ``LAYOUTS``, ``MOTIFS``) and :mod:`~matloom.library.compose.named`
(named materials)."""
