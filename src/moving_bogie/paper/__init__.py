"""The paper's tables and figures, rebuilt: ``moving-bogie reproduce``.

:mod:`~moving_bogie.paper.captions` (the captions, verbatim), :mod:`~moving_bogie.paper.registry` (every
artefact with its caption and recipe), :mod:`~moving_bogie.paper.recipe` (what a recipe is given and
returns), :mod:`~moving_bogie.paper.tables` and :mod:`~moving_bogie.paper.figures` (the recipes),
:mod:`~moving_bogie.paper.report` (the outcome of a run), :mod:`~moving_bogie.paper.index_page` (index.html
and index.md) and :mod:`~moving_bogie.paper.reproduce` (the driver).
"""
