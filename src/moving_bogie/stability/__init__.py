"""Stability: critical velocity, frequency and instability lines, D-decomposition, maps (Sections 3.5-3.8)."""
