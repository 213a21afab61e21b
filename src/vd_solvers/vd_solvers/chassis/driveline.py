# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The driveline: engine map, gears, axle split and a differential per axle.

* **Engine**: full-load torque against speed (linear between the map's points, zero
  outside idle..redline), scaled by the throttle 0..1.
* **Gearbox and final drive**: the total ratio i = i_gear i_final and an efficiency eta:
  the torque at the driven wheels is T_e i eta, the engine turns at i times the driven
  wheels' mean speed, but not below the map's first speed: pulling away, the clutch (or
  converter) slips and holds the engine there.
* **Driveline inertia**: the parts that turn at engine speed (crankshaft, flywheel,
  converter, gearbox input) take J i^2 eta dw/dt of the drive torque at the wheels while
  the driven wheels' mean speed w rises at dw/dt (:meth:`Driveline.inertia_torque`; none
  while the clutch slips and holds the engine at its first speed).
* **Automatic gear choice** (:meth:`Driveline.gear`): the lowest gear in which the engine
  stays at or below the upshift speed.
* **Axle split**: a fixed front share of the drive torque (0 rear-wheel drive, 1
  front-wheel drive; between: all-wheel drive through a locked-ratio centre coupling).
* **Differential** per axle, torque in T to the left and right wheels:
  ``open`` T / 2 each; ``limited_slip`` a friction clutch that carries up to its locking
  torque from the faster wheel to the slower one, smoothed over SLIP_SCALE of speed
  difference: dT = T_lock tanh(dw / SLIP_SCALE); ``locked`` a stiff viscous coupling of
  the two wheels, dT = c dw (an exact lock would be a constraint; c is stated in the data
  and bounds the speed difference at dT / c).
  The differential's own torque is internal: the two wheel torques always add up to T.

Speeds in rad/s, torques in N m (SI).
"""
from __future__ import annotations

from dataclasses import dataclass, field
import math

import numpy as np

SLIP_SCALE = 0.5  # rad/s: the speed difference over which a limited-slip clutch locks
KINDS = ('open', 'limited_slip', 'locked')


@dataclass(frozen=True)
class Engine:
    """Full-load torque map of an engine or motor (rad/s, N m)."""

    speeds: np.ndarray
    torques: np.ndarray

    def __post_init__(self) -> None:
        speeds = np.asarray(self.speeds, dtype=float)
        torques = np.asarray(self.torques, dtype=float)
        if speeds.ndim != 1 or speeds.size < 2 or torques.shape != speeds.shape:
            raise ValueError('an engine map needs at least two speeds and as many torques')
        if not np.all(np.diff(speeds) > 0.0) or speeds[0] < 0.0:
            raise ValueError('the engine map speeds must be increasing and not negative')
        if not np.all(np.isfinite(torques)) or np.any(torques < 0.0):
            raise ValueError('the engine map torques must be finite and not negative')
        object.__setattr__(self, 'speeds', speeds)
        object.__setattr__(self, 'torques', torques)

    def torque(self, speed: float, throttle: float) -> float:
        """Torque at an engine speed (rad/s) and throttle (0..1), N m."""
        if speed < self.speeds[0] or speed > self.speeds[-1]:
            return 0.0
        return float(np.clip(throttle, 0.0, 1.0) * np.interp(speed, self.speeds, self.torques))


@dataclass(frozen=True)
class Differential:
    """One axle's differential."""

    kind: str = 'open'
    locking_torque: float = 0.0  # N m (limited_slip)
    lock_damping: float = 1000.0  # N m s/rad (locked)

    def __post_init__(self) -> None:
        if self.kind not in KINDS:
            raise ValueError(f"unknown differential '{self.kind}' (one of {', '.join(KINDS)})")
        if self.locking_torque < 0.0 or not self.lock_damping > 0.0:
            raise ValueError('a differential needs a locking torque >= 0 and a positive '
                             'lock damping')

    def split(self, torque: float, left_speed: float, right_speed: float
              ) -> tuple[float, float]:
        """Torque to the left and right wheel of an input torque at the wheels' speeds."""
        dw = left_speed - right_speed
        if self.kind == 'open':
            transfer = 0.0
        elif self.kind == 'limited_slip':
            transfer = self.locking_torque * math.tanh(dw / SLIP_SCALE)
        else:
            transfer = self.lock_damping * dw
        # the faster wheel gives torque to the slower one
        return 0.5 * torque - 0.5 * transfer, 0.5 * torque + 0.5 * transfer


@dataclass(frozen=True)
class Driveline:
    """Engine, gears, axle split and differentials."""

    engine: Engine
    gears: tuple[float, ...]
    final_drive: float
    efficiency: float = 0.92
    front_share: float = 0.0  # of the drive torque to the front axle
    front: Differential = field(default_factory=Differential)
    rear: Differential = field(default_factory=Differential)
    inertia: float = 0.0  # kg m^2 turning at engine speed

    def __post_init__(self) -> None:
        if not self.inertia >= 0.0:
            raise ValueError(f'the driveline inertia must not be negative (got {self.inertia})')
        if not self.gears or any(not g > 0.0 for g in self.gears) or not self.final_drive > 0.0:
            raise ValueError('the gear and final-drive ratios must be positive')
        if not 0.0 < self.efficiency <= 1.0:
            raise ValueError(f'the driveline efficiency must lie in (0, 1] '
                             f'(got {self.efficiency})')
        if not 0.0 <= self.front_share <= 1.0:
            raise ValueError(f'the front drive share must lie in 0..1 (got {self.front_share})')

    def ratio(self, gear: int) -> float:
        """Total ratio of a gear (1-based), engine speed over driven-wheel speed."""
        if not 1 <= gear <= len(self.gears):
            raise ValueError(f'gear {gear} does not exist (1..{len(self.gears)})')
        return self.gears[gear - 1] * self.final_drive

    def engine_speed(self, gear: int, wheel_speeds: tuple[float, float, float, float]) -> float:
        """Engine speed from the driven wheels' mean speed (FL, FR, RL, RR), rad/s."""
        return max(self.ratio(gear) * self.driven_speed(wheel_speeds),
                   float(self.engine.speeds[0]))

    def driven_speed(self, wheel_speeds: tuple[float, float, float, float]) -> float:
        """Speed of the gearbox output over the final drive: the driven wheels' mean, rad/s."""
        f = 0.5 * (wheel_speeds[0] + wheel_speeds[1])
        r = 0.5 * (wheel_speeds[2] + wheel_speeds[3])
        return self.front_share * f + (1.0 - self.front_share) * r

    def gear(self, wheel_speeds: tuple[float, float, float, float], shift_speed: float) -> int:
        """Return the lowest gear that keeps the engine at or below ``shift_speed`` (rad/s)."""
        driven = self.driven_speed(wheel_speeds)
        for n in range(1, len(self.gears) + 1):
            if self.ratio(n) * driven <= shift_speed:
                return n
        return len(self.gears)

    def available_torque(self, gear: int,
                         wheel_speeds: tuple[float, float, float, float]) -> float:
        """Full-throttle drive torque of all driven wheels together in ``gear``, N m."""
        return (self.engine.torque(self.engine_speed(gear, wheel_speeds), 1.0)
                * self.ratio(gear) * self.efficiency)

    def inertia_torque(self, gear: int, wheel_speeds: tuple[float, float, float, float],
                       driven_acceleration: float) -> float:
        """
        Drive torque at the wheels that spinning up the engine-speed inertia takes, N m.

        J i^2 eta dw/dt with dw/dt the driven wheels' mean angular acceleration (rad/s^2):
        the engine turns at i w and its inertia takes J i dw/dt of its torque, which
        reaches the wheels times i eta. None while the clutch slips (the engine held at
        its map's first speed does not accelerate with the wheels).
        """
        i = self.ratio(gear)
        if i * self.driven_speed(wheel_speeds) < float(self.engine.speeds[0]):
            return 0.0
        return self.inertia * i * i * self.efficiency * driven_acceleration

    def wheel_torques(self, throttle: float, gear: int,
                      wheel_speeds: tuple[float, float, float, float],
                      inertia_torque: float = 0.0) -> tuple[float, float, float, float]:
        """Drive torque of each wheel (FL, FR, RL, RR), N m, less ``inertia_torque``."""
        total = (float(np.clip(throttle, 0.0, 1.0)) * self.available_torque(gear, wheel_speeds)
                 - inertia_torque)
        fl, fr = self.front.split(self.front_share * total, wheel_speeds[0], wheel_speeds[1])
        rl, rr = self.rear.split((1.0 - self.front_share) * total, wheel_speeds[2],
                                 wheel_speeds[3])
        return fl, fr, rl, rr


__all__ = ['SLIP_SCALE', 'KINDS', 'Engine', 'Differential', 'Driveline']
