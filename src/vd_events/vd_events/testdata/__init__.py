"""Measured data (K&C rigs, vehicle-test logs) into vd bags: column maps and readers."""
