"""Parameter sweeps: any parameters, on Dask (a laptop to a cluster), results as an xarray Dataset in zarr.

:func:`sweep` (Python) and ``moving-bogie sweep`` (command line) compute the stability verdict at every
point of a grid or a quasi-random design; :func:`open_sweep` reads a store back. See docs/sweeps.md.
"""

from moving_bogie.sweep.api import make_spec, sweep
from moving_bogie.sweep.store import open_sweep

__all__ = ["make_spec", "open_sweep", "sweep"]
