"""The search of the window, with no starting guesses: tiles that never meet the cut of K (columns between
its arms, tip cells around its folds, cells that follow it), counted one by one, and the cells that meet the
cut counted through it (E_chr continued analytically across the cut).
"""

from moving_bogie.roots.search.continuation import (
    ContinuedRegion,
    count_continued,
    crossing_roots,
    touches_cut,
)
from moving_bogie.roots.search.counting import CountMismatch, TilingCount, count_tiling, frame
from moving_bogie.roots.search.cut_cells import ColumnCell, Edge, Sliver, TipCell
from moving_bogie.roots.search.search_columns import COLUMN_SAMPLES, arms_over, box, column, fill_columns
from moving_bogie.roots.search.search_folds import fold_event
from moving_bogie.roots.search.search_regions import Tiling, tile_window

__all__ = [
    "COLUMN_SAMPLES",
    "ColumnCell",
    "ContinuedRegion",
    "CountMismatch",
    "Edge",
    "Sliver",
    "Tiling",
    "TipCell",
    "arms_over",
    "box",
    "column",
    "count_continued",
    "TilingCount",
    "count_tiling",
    "crossing_roots",
    "fill_columns",
    "fold_event",
    "frame",
    "tile_window",
    "touches_cut",
]
