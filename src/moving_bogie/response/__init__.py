"""Vibrations in closed form: residue part, branch-cut part, shapes, and an independent Bromwich check.

Eqs. (41)-(54) of the paper.
"""
