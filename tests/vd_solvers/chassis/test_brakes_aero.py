# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Brakes and aerodynamics against hand calculations and a closed-form coast-down.

Brake torque T = 2 mu p A r (Limpert, Brake Design and Safety, ch. 3) with numbers written
out here; a proportioning valve's knee; the coast-down under drag alone,
m dv/dt = -k v^2 with k = rho C_d A / 2: v(t) = v0 / (1 + k v0 t / m).
"""
from __future__ import annotations

import math

import pytest
from scipy.integrate import solve_ivp

from vd_solvers.chassis.aero import Aero
from vd_solvers.chassis.brakes import BrakeSystem, Caliper

FRONT = Caliper(piston_diameter=0.057, pistons=1, pad_friction=0.38, effective_radius=0.125)
REAR = Caliper(piston_diameter=0.038, pistons=1, pad_friction=0.35, effective_radius=0.115)


def test_caliper_torque_by_hand():
    # 60 bar on a 57 mm piston: F = 6e6 * pi * 0.057^2 / 4 = 15 310.6 N per pad
    clamp = 6.0e6 * math.pi * 0.057**2 / 4
    assert FRONT.torque(6.0e6) == pytest.approx(2 * 0.38 * clamp * 0.125, rel=1e-12)
    assert FRONT.torque(-1.0e6) == 0.0


def test_proportioning_valve_knee_and_balance():
    brakes = BrakeSystem(FRONT, REAR, knee_pressure=3.0e6, knee_slope=0.3)
    assert brakes.rear_pressure(2.0e6) == pytest.approx(2.0e6)
    assert brakes.rear_pressure(8.0e6) == pytest.approx(3.0e6 + 0.3 * 5.0e6)
    below = brakes.front_share(2.0e6)
    assert below == pytest.approx(FRONT.gain / (FRONT.gain + REAR.gain))
    assert brakes.front_share(8.0e6) > below  # the valve moves the balance forward


def test_pedal_to_pressure():
    brakes = BrakeSystem(FRONT, REAR, master_diameter=0.0254, pedal_ratio=4.0, booster_gain=6.0)
    # 300 N x 4 x 6 on a 25.4 mm master cylinder
    assert brakes.pressure_from_pedal(300.0) == pytest.approx(
        300.0 * 4 * 6 / (math.pi * 0.0254**2 / 4), rel=1e-12)


def test_coast_down_under_drag_is_the_closed_form():
    aero = Aero(drag_area=0.32 * 2.2, frontal_area=2.2)
    m, v0 = 1500.0, 40.0
    sol = solve_ivp(lambda t, v: [aero.drag(v[0]) / m], (0.0, 60.0), [v0], rtol=1e-10,
                    atol=1e-12, dense_output=True)
    k = 0.5 * aero.density * aero.drag_area
    for t in (10.0, 30.0, 60.0):
        assert sol.sol(t)[0] == pytest.approx(v0 / (1 + k * v0 * t / m), rel=1e-7)
    assert aero.drag(-10.0) > 0.0  # against the motion when reversing


def test_lift_per_axle():
    aero = Aero(drag_area=0.7, frontal_area=2.2, lift_front=0.05, lift_rear=-0.1)
    q = 0.5 * aero.density * 50.0**2 * 2.2
    assert aero.lift(50.0) == pytest.approx((0.05 * q, -0.1 * q))


@pytest.mark.parametrize('kwargs, message', [
    ({'piston_diameter': 0.0}, 'piston_diameter must be positive'),
    ({'pistons': 0}, 'at least one piston'),
])
def test_bad_brakes_are_refused(kwargs, message):
    args = {'piston_diameter': 0.05, 'pistons': 1, 'pad_friction': 0.4, 'effective_radius': 0.1}
    args.update(kwargs)
    with pytest.raises(ValueError, match=message):
        Caliper(**args)
    with pytest.raises(ValueError, match='proportioning slope'):
        BrakeSystem(FRONT, REAR, knee_pressure=3e6, knee_slope=1.5)
