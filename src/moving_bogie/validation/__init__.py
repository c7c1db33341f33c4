"""Validation on a long finite beam by modal expansion (Section 3.4)."""
