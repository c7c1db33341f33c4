"""Floquet induced frequencies of a vehicle on a rail on discrete supports (docs/sleepers.md).

:mod:`~moving_bogie.floquet.track` the rail's symbol, supports and lattice sum at one parameter set;
:mod:`~moving_bogie.floquet.receptance` the receptance between (contact, harmonic) pairs;
:mod:`~moving_bogie.floquet.hill` the truncated Hill determinant; :mod:`~moving_bogie.floquet.strip` the
roots in one strip of width Omega_0 by the argument principle, converged in the number of harmonics;
:mod:`~moving_bogie.floquet.inputs` the parameters of a sleeper track from SI values;
:mod:`~moving_bogie.floquet.steady` the steady periodic response under the constant loads over a bay.
"""
