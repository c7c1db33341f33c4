"""Kernels: roots in p, K(xi, q) and dK/dq by residues, the cut of K, E_chr (Eqs. (27)-(40))."""
