# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
An anti-lock brake controller per wheel: slip thresholds with hysteresis.

The pressure is dumped, held and rebuilt.

The logic of the classic first-generation controllers (Burckhardt, Fahrwerktechnik:
Radschlupf-Regelsysteme, 1993; Bosch Automotive Handbook, "Antilock braking system"),
reduced to the wheel slip, which a simulation knows exactly:

* inactive, the wheel gets the driver's pressure; the controller becomes active when the
  braking slip s = (v - omega R) / v exceeds ``dump_slip``;
* active: above ``dump_slip`` the pressure falls at ``dump_rate`` (the outlet valve
  open), below ``build_slip`` it rises again at ``build_rate`` (pulsed inlet valve) up
  to the driver's pressure, and between the two it is held;
* it lets go when the driver's pressure falls below the modulated one, and below
  ``min_speed`` (the wheel slip is not measurable at walking pace; the car stops on the
  driver's pressure).

Pressures in Pa, rates in Pa/s, speeds in m/s. The controller's step is a compiled
function on floats (:func:`controller_step`), the one definition :func:`step` and the
compiled vehicle loop (:func:`vd_solvers.vehicle.drivers.actuate`) call.
"""
from __future__ import annotations

from dataclasses import dataclass

from vd_solvers.compiled import jit


@dataclass(frozen=True)
class AntiLock:
    """The controller's thresholds and valve rates."""

    dump_slip: float = 0.15
    build_slip: float = 0.08
    dump_rate: float = 1.0e8  # Pa/s (1000 bar/s)
    build_rate: float = 2.0e7  # Pa/s (200 bar/s)
    min_speed: float = 2.0  # m/s

    def __post_init__(self) -> None:
        if not 0.0 < self.build_slip < self.dump_slip < 1.0:
            raise ValueError('the anti-lock slips need 0 < build_slip < dump_slip < 1')
        if not (self.dump_rate > 0.0 and self.build_rate > 0.0 and self.min_speed >= 0.0):
            raise ValueError('the anti-lock valve rates must be positive and the minimum '
                             'speed not negative')


@dataclass
class WheelState:
    """One wheel's controller state: active or not, and its modulated pressure."""

    active: bool = False
    pressure: float = 0.0


def braking_slip(speed: float, wheel_speed: float, radius: float) -> float:
    """Braking slip (v - omega R) / v of a wheel, 0 at standstill."""
    return (speed - wheel_speed * radius) / speed if speed > 1e-6 else 0.0


@jit
def controller_step(dump_slip: float, build_slip: float, dump_rate: float, build_rate: float,
                    min_speed: float, active: bool, pressure: float, dt: float,
                    driver_pressure: float, slip: float, speed: float) -> tuple[bool, float]:
    """
    Advance one wheel's controller by ``dt`` s (module doc; the first five as :class:`AntiLock`).

    ``active`` and ``pressure`` are its state before the step; returns them after it, the
    pressure being the one for its brake, Pa.
    """
    driver = max(driver_pressure, 0.0)
    if speed < min_speed or (active and driver < pressure):
        active = False
    if not active:
        if slip > dump_slip and speed >= min_speed:
            active = True
            pressure = driver
        else:
            return False, driver
    if slip > dump_slip:
        pressure = max(pressure - dump_rate * dt, 0.0)
    elif slip < build_slip:
        pressure = min(pressure + build_rate * dt, driver)
    return active, pressure


def step(abs_: AntiLock, state: WheelState, dt: float, driver_pressure: float,
         slip: float, speed: float) -> float:
    """Advance one wheel's controller by ``dt`` s; return the pressure for its brake."""
    state.active, state.pressure = controller_step(
        abs_.dump_slip, abs_.build_slip, abs_.dump_rate, abs_.build_rate, abs_.min_speed,
        state.active, state.pressure, float(dt), float(driver_pressure), float(slip),
        float(speed))
    return state.pressure


__all__ = ['AntiLock', 'WheelState', 'braking_slip', 'step', 'controller_step']
