"""SymPy derivations of moving-bogie: the single source of truth for every formula.

Run ``python -m derivations`` to regenerate ``generated/``; the runtime never imports this package.
"""
