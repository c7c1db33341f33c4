"""Counting the roots of E_chr in a region (Eq. (48)): the argument principle on a contour, the strip below
the cut of K, and the window that reaches the far-field radius R beyond which no root has Im q < 0.
"""

from moving_bogie.roots.count.contour import (
    BoundingBox,
    EdgeZeroError,
    Rectangle,
    initial_samples,
    piece_points,
    winding_number,
    winding_numbers,
)
from moving_bogie.roots.count.far_field import (
    FarField,
    e_lead,
    far_field_radius,
    kernel_decay,
    leading_gap,
    rho,
    sample_points,
)
from moving_bogie.roots.count.outcomes import Note, Reason, Unlocated, count_mismatch, notes_with
from moving_bogie.roots.count.strip import (
    StripCount,
    branch_point_text,
    branch_points_on_axis,
    pieces_below_axis,
    strip_below_cut,
)
from moving_bogie.roots.count.window import default_window, far_field_window

__all__ = [
    "Note",
    "Reason",
    "Unlocated",
    "count_mismatch",
    "notes_with",
    "BoundingBox",
    "EdgeZeroError",
    "FarField",
    "Rectangle",
    "StripCount",
    "branch_point_text",
    "branch_points_on_axis",
    "default_window",
    "e_lead",
    "far_field_radius",
    "far_field_window",
    "initial_samples",
    "kernel_decay",
    "leading_gap",
    "piece_points",
    "pieces_below_axis",
    "rho",
    "sample_points",
    "strip_below_cut",
    "winding_number",
    "winding_numbers",
]
