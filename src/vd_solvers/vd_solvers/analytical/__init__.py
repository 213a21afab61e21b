"""Analytical models: bicycle and two-track steady state (thesis 3.1)."""
