"""The Gauss-Kronrod (7, 15) rule on [-1, 1] (Piessens et al., QUADPACK), shared by the quadratures of the
Floquet receptance (:mod:`moving_bogie.kernels.periodic_receptance`) and of the soil's strip stiffness
(:mod:`moving_bogie.soil.strip`): the 15 Kronrod nodes, their weights, and the weights of the 7-point Gauss
rule on the same nodes (zero on the even-indexed ones); the difference of the two sums estimates the error.
"""

from __future__ import annotations

import numpy as np

__all__ = ["GAUSS", "KRONROD", "NODES"]

_XGK = np.array(
    [
        0.991455371120812639206854697526329,
        0.949107912342758524526189684047851,
        0.864864423359769072789712788640926,
        0.741531185599394439863864773280788,
        0.586087235467691130294144845693013,
        0.405845151377397166906606412076961,
        0.207784955007898467600689403773245,
        0.0,
    ]
)
_WGK = np.array(
    [
        0.022935322010529224963732008058970,
        0.063092092629978553290700663189204,
        0.104790010322250183839876322541518,
        0.140653259715525918745189590510238,
        0.169004726639267902826583426598550,
        0.190350578064785409913256402421014,
        0.204432940075298892414161999234649,
        0.209482141084727828012999174891714,
    ]
)
_WG = np.array(
    [
        0.129484966168869693270611432679082,
        0.279705391489276667901467771423780,
        0.381830050505118944950369775488975,
        0.417959183673469387755102040816327,
    ]
)
#: the 15 Kronrod nodes on [-1, 1], their weights, and the 7-point Gauss weights on the same nodes
NODES = np.concatenate([-_XGK[:-1], _XGK[::-1]])
KRONROD = np.concatenate([_WGK[:-1], _WGK[::-1]])
GAUSS = np.zeros(15)
GAUSS[[1, 3, 5, 7, 9, 11, 13]] = np.concatenate([_WG[:-1], _WG[::-1]])
