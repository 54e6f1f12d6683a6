"""The library author's passes, in order (:func:`matloom.library.author.author` runs them):

read (:func:`matloom.library.query.read`: the prompt -> a frozen :class:`~matloom.library.query.
Request`, and :func:`matloom.library.parts.read_parts`: its parts) -> rank (the BM25 index) ->
:mod:`choose` (the entry that :mod:`cover` says covers the parts, or a composition built by
:mod:`composition`) -> :mod:`fit` (how the request
reads against that entry: overlays it absorbs or adds, colours it takes) -> adapt
(:func:`matloom.library.adapt.adapt`: slots and View) -> :mod:`tile` (the View side at which
the program tiles) -> :mod:`compose` (reseed, overlays, unused Defines dropped).

Each pass returns a value (frozen dataclasses) and leaves its inputs untouched; the author
renders the program's text and the explanation from those values at the end.
"""
