# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Hydraulic disc brakes: line pressure to wheel brake torque, per axle.

A caliper clamps the disc with the line pressure on its pistons, F = p A (A the piston
area on one side of the disc: n pi d^2 / 4), and both pads rub with the pad friction mu at
the effective radius r: the torque is T = 2 mu p A r (Limpert, Brake Design and Safety,
3rd ed. 2011, ch. 3). The rear line pressure passes a proportioning valve: equal to the
master-cylinder pressure up to the knee pressure, then rising with the valve's slope
(ch. 7). A pedal force reaches the master cylinder through the pedal ratio and the
booster's gain: p = F_pedal i_pedal g_booster / A_master.

Torques are magnitudes (N m) opposing the wheel's rotation; the vehicle model gives them
their sign. The valve and the pressure of a total brake torque are compiled functions on
floats (:func:`rear_line_pressure`, :func:`master_pressure_for_torque`), the one
definition the methods below and the compiled vehicle loop
(:func:`vd_solvers.vehicle.drivers.actuate`) call.
"""
from __future__ import annotations

from dataclasses import dataclass
import math

from vd_solvers.compiled import jit


@jit
def rear_line_pressure(pressure: float, knee: float, slope: float) -> float:
    """Rear line pressure (Pa) after a valve with its knee (Pa) and slope (-) (module doc)."""
    p = max(pressure, 0.0)
    if p <= knee:
        return p
    return knee + slope * (p - knee)


@jit
def master_pressure_for_torque(total: float, front_gain: float, rear_gain: float, knee: float,
                               slope: float) -> float:
    """
    Master pressure (Pa) at which four brakes give ``total`` N m together.

    ``front_gain`` and ``rear_gain`` are one wheel's torque per line pressure (N m / Pa).
    """
    front, rear = 2.0 * front_gain, 2.0 * rear_gain
    total = max(total, 0.0)
    if total <= (front + rear) * knee:
        return total / (front + rear)
    # above the knee: total = front p + rear (p_k + s (p - p_k))
    return (total - rear * knee * (1.0 - slope)) / (front + rear * slope)


@dataclass(frozen=True)
class Caliper:
    """One axle's wheel brake (SI: m, -)."""

    piston_diameter: float  # m
    pistons: int  # per side of the disc (1 on a floating caliper)
    pad_friction: float  # -
    effective_radius: float  # m, from the wheel axis to the pads' centre of pressure

    def __post_init__(self) -> None:
        for name in ('piston_diameter', 'pad_friction', 'effective_radius'):
            if not getattr(self, name) > 0.0:
                raise ValueError(f'brake {name} must be positive (got {getattr(self, name)})')
        if self.pistons < 1:
            raise ValueError(f'a caliper needs at least one piston per side (got {self.pistons})')

    @property
    def piston_area(self) -> float:
        """A = n pi d^2 / 4, m^2 (one side of the disc)."""
        return self.pistons * math.pi * self.piston_diameter**2 / 4.0

    @property
    def gain(self) -> float:
        """Torque per line pressure, N m / Pa: 2 mu A r."""
        return 2.0 * self.pad_friction * self.piston_area * self.effective_radius

    def torque(self, pressure: float) -> float:
        """Brake torque at a line pressure (Pa; none below zero), N m."""
        return self.gain * max(pressure, 0.0)


@dataclass(frozen=True)
class BrakeSystem:
    """Front and rear calipers, the rear proportioning valve and the pedal path."""

    front: Caliper
    rear: Caliper
    knee_pressure: float = math.inf  # Pa: the rear valve's knee (inf: no valve)
    knee_slope: float = 1.0  # -: rear pressure rise per master pressure above the knee
    master_diameter: float = 0.0254  # m
    pedal_ratio: float = 4.0  # -
    booster_gain: float = 1.0  # -

    def __post_init__(self) -> None:
        if not 0.0 <= self.knee_slope <= 1.0:
            raise ValueError(f'the proportioning slope must lie in 0..1 (got {self.knee_slope})')
        if not self.knee_pressure > 0.0:
            raise ValueError(f'the knee pressure must be positive (got {self.knee_pressure})')
        for name in ('master_diameter', 'pedal_ratio', 'booster_gain'):
            if not getattr(self, name) > 0.0:
                raise ValueError(f'brake {name} must be positive (got {getattr(self, name)})')

    def rear_pressure(self, pressure: float) -> float:
        """Rear line pressure after the proportioning valve, Pa."""
        return rear_line_pressure(float(pressure), self.knee_pressure, self.knee_slope)

    def pressure_from_pedal(self, force: float) -> float:
        """Master-cylinder pressure of a pedal force (N), Pa."""
        area = math.pi * self.master_diameter**2 / 4.0
        return max(force, 0.0) * self.pedal_ratio * self.booster_gain / area

    def torques(self, pressure: float) -> tuple[float, float]:
        """Brake torque of one front and one rear wheel at a master pressure, N m."""
        return self.front.torque(pressure), self.rear.torque(self.rear_pressure(pressure))

    def pressure_for_torque(self, total: float) -> float:
        """Master pressure at which the four brakes together give ``total`` N m, Pa."""
        return master_pressure_for_torque(float(total), self.front.gain, self.rear.gain,
                                          self.knee_pressure, self.knee_slope)

    def front_share(self, pressure: float) -> float:
        """Return the front axle's share of the brake torque at a master pressure, -."""
        front, rear = self.torques(pressure)
        return front / (front + rear) if front + rear > 0.0 else \
            self.front.gain / (self.front.gain + self.rear.gain)


__all__ = ['Caliper', 'BrakeSystem', 'rear_line_pressure', 'master_pressure_for_torque']
