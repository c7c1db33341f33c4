"""Induced frequencies: contours, search tiling, counting, polishing, Table 2 (Eq. (38))."""
