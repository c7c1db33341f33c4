"""The degree of instability over the (alpha, theta) plane (Section 3.8), column by column: the argument
principle over a whole column of theta, its roots located, the map, and the boundaries of the undamped
limit (eta_f = 0) found by the same column counts.
"""

from moving_bogie.stability.maps.column import (
    ColumnResult,
    at_theta,
    branch_points,
    branch_samples,
    column_window,
    exact,
    settle_cells,
    stability_column,
    top_edge,
)
from moving_bogie.stability.maps.column_count import (
    BoxCount,
    count_box,
    edge_samples,
    horner_pairs,
    horner_rows,
)
from moving_bogie.stability.maps.column_roots import (
    delves_lyness,
    dip_candidates,
    from_power_sums,
    locate_roots,
    polish_roots,
)
from moving_bogie.stability.maps.map import StabilityMap, map_columns, stability_map
from moving_bogie.stability.maps.undamped import (
    CONVENTION,
    DAMPING_PROBE,
    MECHANISMS,
    NEAR_UNDAMPED,
    Boundary,
    UndampedColumn,
    UndampedCounter,
    boundaries,
    parameter_grid,
    regime,
    statement,
    title,
    uncertain_warning,
)

__all__ = [
    "Boundary",
    "BoxCount",
    "CONVENTION",
    "ColumnResult",
    "DAMPING_PROBE",
    "MECHANISMS",
    "NEAR_UNDAMPED",
    "StabilityMap",
    "UndampedColumn",
    "UndampedCounter",
    "at_theta",
    "boundaries",
    "branch_points",
    "branch_samples",
    "column_window",
    "count_box",
    "delves_lyness",
    "dip_candidates",
    "edge_samples",
    "exact",
    "from_power_sums",
    "horner_pairs",
    "horner_rows",
    "locate_roots",
    "map_columns",
    "parameter_grid",
    "polish_roots",
    "regime",
    "settle_cells",
    "stability_column",
    "stability_map",
    "statement",
    "title",
    "top_edge",
    "uncertain_warning",
]
