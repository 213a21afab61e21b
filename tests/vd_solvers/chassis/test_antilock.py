# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The anti-lock controller on a quarter car written in this test.

The trend every ABS must show: a shorter stop than a locked wheel on a low-friction road,
with the wheel kept rolling near the tire's peak slip.

The quarter car: a corner's mass m on one wheel (inertia I, radius R), the braking force
F = F_z mu(s) of a Magic Formula curve, mu(s) = D sin(C atan(B s)) (peak at
C atan(B s) = pi / 2), the wheel braked by the brake torque of the line pressure;
m dv/dt = -F, I dw/dt = F R - T_b. The stop is measured from 25 m/s to 2 m/s, where the
controller hands back to the driver.
"""
from __future__ import annotations

import math

import pytest

from vd_solvers.chassis import antilock
from vd_solvers.chassis.brakes import Caliper

M, I_W, R, G = 400.0, 1.2, 0.3, 9.80665
B, C, D = 12.0, 1.65, 0.3  # a wet-ice-like curve: peak 0.3
CALIPER = Caliper(piston_diameter=0.057, pistons=1, pad_friction=0.38, effective_radius=0.125)
S_PEAK = math.tan(math.pi / 2 / C) / B


def mu(s):
    return D * math.sin(C * math.atan(B * s))


def stop(with_abs: bool, pressure=1.0e7, dt=5e-5):
    v, w = 25.0, 25.0 / R
    x, t, slips = 0.0, 0.0, []
    controller, state = antilock.AntiLock(), antilock.WheelState()
    while v > 2.0:
        s = antilock.braking_slip(v, w, R)
        p = antilock.step(controller, state, dt, pressure, s, v) if with_abs else pressure
        force = M * G * mu(s)
        torque = CALIPER.torque(p) if w > 0.0 else 0.0
        v -= force / M * dt
        w = max(w + (force * R - torque) / I_W * dt, 0.0)
        x += v * dt
        t += dt
        slips.append(s)
    return x, t, slips


def test_the_quarter_car_locks_without_the_controller():
    x, _, slips = stop(with_abs=False)
    assert slips[-1] == pytest.approx(1.0, abs=0.01)
    sliding = (25.0**2 - 2.0**2) / (2 * mu(1.0) * G)
    assert x == pytest.approx(sliding, rel=0.02)  # a locked wheel slides at mu(1)
    assert mu(1.0) < 0.9 * D


def test_the_controller_stops_shorter_and_keeps_the_wheel_rolling():
    locked, _, _ = stop(with_abs=False)
    x, t, slips = stop(with_abs=True)
    peak_distance = (25.0**2 - 2.0**2) / (2 * D * G)
    assert x < 0.92 * locked
    assert x < 1.15 * peak_distance  # within 15 % of braking at the peak all the way
    settled = slips[len(slips) // 10:]
    assert max(settled) < 0.5  # never locked
    mean_slip = sum(settled) / len(settled)
    assert 0.5 * S_PEAK < mean_slip < 1.5 * S_PEAK


def test_the_controller_follows_the_driver_below_the_thresholds():
    controller, state = antilock.AntiLock(), antilock.WheelState()
    assert antilock.step(controller, state, 1e-3, 3.0e6, 0.02, 20.0) == 3.0e6
    assert not state.active
    # lock-up: dump at its rate, then hold between the thresholds, then rebuild
    p = antilock.step(controller, state, 1e-3, 8.0e6, 0.4, 20.0)
    assert state.active and p == pytest.approx(8.0e6 - 1.0e8 * 1e-3)
    assert antilock.step(controller, state, 1e-3, 8.0e6, 0.1, 20.0) == pytest.approx(p)
    assert antilock.step(controller, state, 1e-3, 8.0e6, 0.05, 20.0) == pytest.approx(
        p + 2.0e7 * 1e-3)
    # below the minimum speed the driver's pressure again
    assert antilock.step(controller, state, 1e-3, 8.0e6, 0.4, 1.0) == 8.0e6


def test_bad_thresholds_are_refused():
    with pytest.raises(ValueError, match='build_slip < dump_slip'):
        antilock.AntiLock(dump_slip=0.05, build_slip=0.1)
