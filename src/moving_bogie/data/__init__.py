"""Packaged reference data: the paper's Table 1 (input cases) and Table 2 (printed induced frequencies)."""
