# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Aerodynamic drag and lift per axle from C_d A and the axles' lift coefficients.

F_drag = 1/2 rho C_d A v_x |v_x| against the motion (ISO 8855 x), lift on each axle
F_l = 1/2 rho C_l A v_x^2, positive upwards (unloading the axle; a negative C_l is
downforce). The relative air speed is the vehicle's speed (still air).
"""
from __future__ import annotations

from dataclasses import dataclass

AIR_DENSITY = 1.204  # kg/m^3 at 20 degC, 101.325 kPa


@dataclass(frozen=True)
class Aero:
    """Drag area and lift coefficients (SI)."""

    drag_area: float  # C_d A, m^2
    frontal_area: float  # A, m^2 (the lift coefficients' reference)
    lift_front: float = 0.0  # C_l,f
    lift_rear: float = 0.0  # C_l,r
    density: float = AIR_DENSITY  # kg/m^3

    def __post_init__(self) -> None:
        if not self.drag_area >= 0.0 or not self.frontal_area > 0.0 or not self.density > 0.0:
            raise ValueError('aerodynamics need C_d A >= 0, a positive frontal area and density')

    def drag(self, vx: float) -> float:
        """Longitudinal force, N (negative when moving forward)."""
        return -0.5 * self.density * self.drag_area * vx * abs(vx)

    def lift(self, vx: float) -> tuple[float, float]:
        """Lift on the front and rear axle, N (positive up)."""
        q = 0.5 * self.density * vx * vx * self.frontal_area
        return q * self.lift_front, q * self.lift_rear


__all__ = ['AIR_DENSITY', 'Aero']
