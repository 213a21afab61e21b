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

Speeds in rad/s, torques in N m (SI). The physics is compiled functions on arrays and
floats (:func:`engine_torque`, :func:`engine_speed`, :func:`driven_speed`,
:func:`choose_gear`,
:func:`available_torque`, :func:`inertia_torque`, :func:`split`, :func:`drive_torques`),
the one definition the classes' methods and the compiled vehicle loop
(:func:`vd_solvers.vehicle.drivers.actuate`) call; a differential is there its kind's
index in KINDS, its locking torque and its lock damping (:meth:`Differential.values`).
"""
from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property
import math

import numpy as np

from vd_solvers.compiled import jit

SLIP_SCALE = 0.5  # rad/s: the speed difference over which a limited-slip clutch locks
KINDS = ('open', 'limited_slip', 'locked')


@jit
def engine_torque(speeds: np.ndarray, torques: np.ndarray, speed: float, throttle: float
                  ) -> float:
    """Torque (N m) of the map ``speeds``, ``torques`` at an engine speed and throttle 0..1."""
    if speed < speeds[0] or speed > speeds[-1]:
        return 0.0
    return min(max(throttle, 0.0), 1.0) * np.interp(speed, speeds, torques)


@jit
def driven_speed(front_share: float, spin: np.ndarray) -> float:
    """Return the driven wheels' mean speed (spin FL FR RL RR, rad/s) at a front share, rad/s."""
    f = 0.5 * (spin[0] + spin[1])
    r = 0.5 * (spin[2] + spin[3])
    return front_share * f + (1.0 - front_share) * r


@jit
def choose_gear(ratios: np.ndarray, driven: float, shift_speed: float) -> int:
    """Return the lowest gear (1-based; total ``ratios``) keeping the engine <= ``shift_speed``."""
    for n in range(ratios.size):
        if ratios[n] * driven <= shift_speed:
            return n + 1
    return ratios.size


@jit
def engine_speed(idle: float, ratio: float, driven: float) -> float:
    """Engine speed at a total ratio and driven speed, not below the map's first, rad/s."""
    return max(ratio * driven, idle)


@jit
def available_torque(speeds: np.ndarray, torques: np.ndarray, ratio: float, efficiency: float,
                     driven: float) -> float:
    """Full-throttle drive torque (N m) of all driven wheels at a total ratio, at their speed."""
    return (engine_torque(speeds, torques, engine_speed(speeds[0], ratio, driven), 1.0)
            * ratio * efficiency)


@jit
def inertia_torque(inertia: float, idle: float, ratio: float, efficiency: float,
                   driven: float, driven_acceleration: float) -> float:
    """J i^2 eta dw/dt, N m; none while the clutch slips (``driven`` i below ``idle``)."""
    if ratio * driven < idle:
        return 0.0
    return inertia * ratio * ratio * efficiency * driven_acceleration


@jit
def split(kind: int, locking_torque: float, lock_damping: float, torque: float,
          left_speed: float, right_speed: float) -> tuple[float, float]:
    """Torque to the left and right wheel of a differential (KINDS[kind]) (module doc)."""
    dw = left_speed - right_speed
    if kind == 0:
        transfer = 0.0
    elif kind == 1:
        transfer = locking_torque * math.tanh(dw / SLIP_SCALE)
    else:
        transfer = lock_damping * dw
    # the faster wheel gives torque to the slower one
    return 0.5 * torque - 0.5 * transfer, 0.5 * torque + 0.5 * transfer


@jit
def drive_torques(speeds: np.ndarray, torques: np.ndarray, ratio: float, efficiency: float,
                  front_share: float, front: np.ndarray, rear: np.ndarray, throttle: float,
                  spin: np.ndarray, inertia: float) -> np.ndarray:
    """
    Drive torque of each wheel FL FR RL RR (N m), less the inertia's ``inertia`` N m.

    ``front`` and ``rear`` are the differentials' (kind, locking torque, lock damping).
    """
    total = (min(max(throttle, 0.0), 1.0)
             * available_torque(speeds, torques, ratio, efficiency,
                                driven_speed(front_share, spin)) - inertia)
    out = np.empty(4)
    out[0], out[1] = split(int(front[0]), front[1], front[2], front_share * total, spin[0],
                           spin[1])
    out[2], out[3] = split(int(rear[0]), rear[1], rear[2], (1.0 - front_share) * total,
                           spin[2], spin[3])
    return out


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
        return float(engine_torque(self.speeds, self.torques, float(speed), float(throttle)))


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
        return split(KINDS.index(self.kind), float(self.locking_torque),
                     float(self.lock_damping), float(torque), float(left_speed),
                     float(right_speed))

    def values(self) -> np.ndarray:
        """(kind's index in KINDS, locking torque, lock damping): the compiled form (3,)."""
        return np.array([KINDS.index(self.kind), self.locking_torque, self.lock_damping],
                        dtype=float)


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

    @cached_property
    def ratios(self) -> np.ndarray:
        """The total ratio of each gear, i_gear i_final (n_gears,)."""
        return np.array(self.gears, dtype=float) * self.final_drive

    def ratio(self, gear: int) -> float:
        """Total ratio of a gear (1-based), engine speed over driven-wheel speed."""
        if not 1 <= gear <= len(self.gears):
            raise ValueError(f'gear {gear} does not exist (1..{len(self.gears)})')
        return float(self.ratios[gear - 1])

    def engine_speed(self, gear: int, wheel_speeds: tuple[float, float, float, float]) -> float:
        """Engine speed from the driven wheels' mean speed (FL, FR, RL, RR), rad/s."""
        return float(engine_speed(float(self.engine.speeds[0]), self.ratio(gear),
                                  self.driven_speed(wheel_speeds)))

    def driven_speed(self, wheel_speeds: tuple[float, float, float, float]) -> float:
        """Speed of the gearbox output over the final drive: the driven wheels' mean, rad/s."""
        return float(driven_speed(float(self.front_share), _spin(wheel_speeds)))

    def gear(self, wheel_speeds: tuple[float, float, float, float], shift_speed: float) -> int:
        """Return the lowest gear that keeps the engine at or below ``shift_speed`` (rad/s)."""
        return int(choose_gear(self.ratios, self.driven_speed(wheel_speeds),
                               float(shift_speed)))

    def available_torque(self, gear: int,
                         wheel_speeds: tuple[float, float, float, float]) -> float:
        """Full-throttle drive torque of all driven wheels together in ``gear``, N m."""
        return float(available_torque(self.engine.speeds, self.engine.torques,
                                      self.ratio(gear), self.efficiency,
                                      self.driven_speed(wheel_speeds)))

    def inertia_torque(self, gear: int, wheel_speeds: tuple[float, float, float, float],
                       driven_acceleration: float) -> float:
        """
        Drive torque at the wheels that spinning up the engine-speed inertia takes, N m.

        J i^2 eta dw/dt with dw/dt the driven wheels' mean angular acceleration (rad/s^2):
        the engine turns at i w and its inertia takes J i dw/dt of its torque, which
        reaches the wheels times i eta. None while the clutch slips (the engine held at
        its map's first speed does not accelerate with the wheels).
        """
        return float(inertia_torque(float(self.inertia), float(self.engine.speeds[0]),
                                    self.ratio(gear), self.efficiency,
                                    self.driven_speed(wheel_speeds),
                                    float(driven_acceleration)))

    def wheel_torques(self, throttle: float, gear: int,
                      wheel_speeds: tuple[float, float, float, float],
                      inertia_torque: float = 0.0) -> tuple[float, float, float, float]:
        """Drive torque of each wheel (FL, FR, RL, RR), N m, less ``inertia_torque``."""
        fl, fr, rl, rr = drive_torques(self.engine.speeds, self.engine.torques,
                                       self.ratio(gear), self.efficiency,
                                       float(self.front_share), self.front.values(),
                                       self.rear.values(), float(throttle),
                                       _spin(wheel_speeds), float(inertia_torque))
        return float(fl), float(fr), float(rl), float(rr)


def _spin(wheel_speeds: tuple[float, float, float, float] | np.ndarray) -> np.ndarray:
    return np.ascontiguousarray(wheel_speeds, dtype=float)


__all__ = ['SLIP_SCALE', 'KINDS', 'Engine', 'Differential', 'Driveline', 'engine_torque',
           'engine_speed', 'driven_speed', 'choose_gear', 'available_torque', 'inertia_torque',
           'split', 'drive_torques']
