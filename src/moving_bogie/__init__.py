"""moving-bogie: stability and vibrations of a bogie moving on an infinite beam on a viscoelastic foundation.

Reference: Z. Dimitrovová, *Instability of a Moving Bogie: Analysis of Vibrations and Possibility of
Instability in Subcritical Velocity Range*, preprint 10.20944/preprints202501.1517.v1 (2025).

The runtime never imports SymPy: formulas come from the generated kernels in
:mod:`moving_bogie.generated`, written by ``python -m derivations``.
"""

from importlib.metadata import PackageNotFoundError, version

from .cases import TABLE1_CASES, table1_case, table2_printed
from .errors import MovingBogieError, MovingBogieWarning, ParameterError
from .params import DimensionlessParams
from .physical import PhysicalParams, Scales

try:
    __version__ = version("moving-bogie")
except PackageNotFoundError:  # running from a source tree that is not installed
    __version__ = "0+unknown"

__all__ = [
    "TABLE1_CASES",
    "DimensionlessParams",
    "MovingBogieError",
    "MovingBogieWarning",
    "ParameterError",
    "PhysicalParams",
    "Scales",
    "__version__",
    "table1_case",
    "table2_printed",
]
