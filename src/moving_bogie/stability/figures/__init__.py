"""Drawing the stability analysis: instability lines, maps, their axes in groups or in SI, and the lines of
one vehicle on two tracks side by side.
"""

from moving_bogie.stability.figures.plot_units import (
    PlaneUnits,
    axis_label,
    mark_operating_point,
    unit_suffix,
)
from moving_bogie.stability.figures.plots import (
    end_mark_handles,
    hatch_cells,
    new_figure,
    plot_instability_lines,
    plot_stability_map,
    spacing_colors,
)
from moving_bogie.stability.figures.track_comparison import (
    TrackComparison,
    compare_tracks,
    figure_track_comparison,
)

__all__ = [
    "PlaneUnits",
    "TrackComparison",
    "axis_label",
    "compare_tracks",
    "end_mark_handles",
    "figure_track_comparison",
    "hatch_cells",
    "mark_operating_point",
    "new_figure",
    "plot_instability_lines",
    "plot_stability_map",
    "spacing_colors",
    "unit_suffix",
]
