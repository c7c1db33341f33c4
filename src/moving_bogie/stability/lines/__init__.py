"""Frequency lines (Figure 2) and instability lines (Figures 3, 4, 7, 8; Section 3.5): pseudo-arclength
continuation of the real induced frequencies, why a line ends, the results, and the lines of the undamped
limit.
"""

from moving_bogie.stability.lines.continuation import END_REASONS, PathTracer, covered, evaluate, gauss_newton
from moving_bogie.stability.lines.frequency_lines import FrequencyLine, FrequencyLines
from moving_bogie.stability.lines.line_ends import EXPLANATIONS, PLOT_EDGES, LineEnd, find_folds, line_end
from moving_bogie.stability.lines.line_results import InstabilityBranch, InstabilityLines
from moving_bogie.stability.lines.undamped_lines import KIND_TEXT, undamped_branches

__all__ = [
    "END_REASONS",
    "EXPLANATIONS",
    "FrequencyLine",
    "FrequencyLines",
    "InstabilityBranch",
    "InstabilityLines",
    "KIND_TEXT",
    "LineEnd",
    "PLOT_EDGES",
    "PathTracer",
    "covered",
    "evaluate",
    "find_folds",
    "gauss_newton",
    "line_end",
    "undamped_branches",
]
