"""Induced frequencies (Eq. (48)): counted (:mod:`~moving_bogie.roots.count`), searched over a window tiled
around the cut of K (:mod:`~moving_bogie.roots.search`), located and polished
(:mod:`~moving_bogie.roots.refine`), proven (:mod:`~moving_bogie.roots.proof`); the entries
:mod:`~moving_bogie.roots.frequencies`, :mod:`~moving_bogie.roots.table2` (Eq. (38)) and the verdict."""
