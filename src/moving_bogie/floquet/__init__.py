"""The (v, M) map of a vehicle on a rail on discrete supports (docs/sleepers.md, (S19)-(S22)).

:mod:`~moving_bogie.floquet.sleeper_map` counts the map column by column from the D-decomposition
crossings (:mod:`~moving_bogie.stability.maps.d_lines`); :mod:`~moving_bogie.floquet.map_figure` draws it
beside the smeared continuous track's map. The rest of the periodic track lives beside its continuous
counterpart: the track in ``kernels/``, the strip search in ``roots/``, the steady bay response in
``response/``.
"""
