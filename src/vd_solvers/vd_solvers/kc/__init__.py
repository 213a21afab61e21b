"""Quasi-static kinematics & compliance suspension model (thesis 3.2)."""
