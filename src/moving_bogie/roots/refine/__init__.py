"""From a count to digits: the counted roots of a cell isolated (bisection, Newton's method), then polished
at high precision and their digits confirmed on a precision ladder (Eq. (40) for dE_chr/dq).
"""

from moving_bogie.roots.refine.locate import newton_inside
from moving_bogie.roots.refine.polish import (
    Confirmed,
    PolishError,
    confirming_step,
    fixed_text,
    newton,
    polish_and_confirm,
    split_cluster,
)

__all__ = [
    "Confirmed",
    "PolishError",
    "confirming_step",
    "fixed_text",
    "newton",
    "newton_inside",
    "polish_and_confirm",
    "split_cluster",
]
