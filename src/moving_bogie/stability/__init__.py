"""Stability (Sections 3.5-3.8): the critical velocity (:mod:`~moving_bogie.stability.velocity`), maps and
their columns (:mod:`~moving_bogie.stability.maps`), frequency and instability lines
(:mod:`~moving_bogie.stability.lines`), the critical stiffness (:mod:`~moving_bogie.stability.stiffness`)
and the figures (:mod:`~moving_bogie.stability.figures`)."""
