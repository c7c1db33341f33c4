"""Generated kernels (written by python -m derivations)."""
