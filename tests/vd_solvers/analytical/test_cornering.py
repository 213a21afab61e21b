# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""The two-track wheel by wheel: balances recomputed from the returned state, limits."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from vd_data_server.study import load_study
from vd_solvers.analytical import bicycle, cornering
from vd_solvers.analytical.budget import understeer_budget
from vd_solvers.analytical.from_config import cornering_vehicle, vehicle_params
from vd_solvers.analytical.kc_link import kc_inputs
from vd_solvers.vehicle_data import static_wheel_loads

STUDIES = Path(__file__).resolve().parents[3] / 'src' / 'vd_data_server' / 'data' / 'studies'


@pytest.fixture(scope='module')
def sedan():
    config = load_study(STUDIES / 'sedan.yaml').configurations['baseline']
    kc = kc_inputs(config, static_wheel_loads(config))
    p = vehicle_params(config, kc.suspension, kc.compliance)
    return p, cornering_vehicle(config, p)


def test_a_steady_state_balances_its_own_wheel_forces(sedan):
    """
    Recompute the balances from the returned state, not from the solver's residual.

    Each wheel's force and aligning moment are its Magic Formula's at the returned load,
    slip angle and inclination; the body-axis sums give m r u laterally and no yaw
    moment about the CoG.
    """
    p, vehicle = sedan
    point = cornering.steady_state(vehicle, 2.0, 40.0)
    r = point.speed / point.radius
    u = point.speed * math.cos(point.sideslip)
    x = np.array([p.cog_to_front_axle] * 2 + [-p.cog_to_rear_axle] * 2)
    y = 0.5 * np.array([p.track_front, -p.track_front, p.track_rear, -p.track_rear])
    cs, sn = np.cos(point.steer), np.sin(point.steer)
    fxb = point.force_x * cs - point.force_y * sn
    fyb = point.force_x * sn + point.force_y * cs
    assert fyb.sum() == pytest.approx(p.mass * r * u, rel=1e-8)
    yaw = np.sum(x * fyb - y * fxb) + point.aligning_moment.sum()
    assert abs(yaw) < 1e-6 * p.mass * p.g * p.wheelbase
    for w, tire in enumerate((vehicle.tires[0],) * 2 + (vehicle.tires[1],) * 2):
        mirror = 1.0 if w % 2 == 0 else -1.0  # both files measured on the left
        pure = tire.steady_state(point.load[w], 0.0, -point.slip_angle[w],
                                 point.inclination[w], 10.0, mirror=mirror)
        # the drive's small slip ratio (tens of N of F_x) moves F_y by far less than 1 %
        assert point.force_y[w] == pytest.approx(float(pure.fy), rel=1e-2)
    # left turn: the outer (right) wheels carry more
    assert point.load[1] > point.load[0] and point.load[3] > point.load[2]


@pytest.fixture(scope='module')
def hmmwv():
    config = load_study(STUDIES / 'hmmwv.yaml').configurations['baseline']
    kc = kc_inputs(config, static_wheel_loads(config))
    p = vehicle_params(config, kc.suspension, kc.compliance)
    return p, cornering_vehicle(config, p)


def test_the_rolling_resistance_moments_load_the_rear_axle(hmmwv):
    """
    Recompute the body's pitch balance about the CoG from the returned state.

    Forces at the ground, h below the CoG, and the tires' rolling-resistance moments M_y
    about their spin axes (the HMMWV's .tir has QSY1 = 0.008):
    sum x_i F_zi = -h sum F_x,body + sum M_y cos(delta) with sum F_x,body = -m r v.
    The moments are nose-up: the front axle carries less than its static share.
    """
    p, vehicle = hmmwv
    point = cornering.steady_state(vehicle, 2.0, 40.0)
    r = point.speed / point.radius
    v = point.speed * math.sin(point.sideslip)
    x = np.array([p.cog_to_front_axle] * 2 + [-p.cog_to_rear_axle] * 2)
    moments = point.rolling_moment * np.cos(point.steer)
    assert np.all(point.rolling_moment < 0.0)
    assert point.load.sum() == pytest.approx(p.mass * p.g, rel=1e-12)
    assert np.sum(x * point.load) == pytest.approx(
        p.cog_height * p.mass * r * v + moments.sum(), abs=1e-6 * p.mass * p.g)
    at_rest = vehicle.with_effects(longitudinal=False)
    assert point.load[:2].sum() < cornering.steady_state(at_rest, 2.0, 40.0).load[:2].sum()


def test_the_budget_holds_the_rolling_resistance_pitch_of_the_wheel_by_wheel_model(hmmwv):
    """
    The budget's rolling_resistance_pitch is the wheel-by-wheel model's at a_y -> 0.

    At static loads (no lateral transfer, so the rolling resistance has no yaw moment)
    the wheel-by-wheel model's longitudinal forces and moments change its slope at
    a_y -> 0 by the pitch term, with the Magic Formula instead of the budget's fitted
    tire and the drive forces' small lateral components: within 10 %.
    """
    p, vehicle = hmmwv
    static = vehicle.with_effects(load_transfer=False)
    with_moments = cornering.gradients(static, 40.0, cornering.ORIGIN_RANGE).understeer
    without = cornering.gradients(static.with_effects(longitudinal=False), 40.0,
                                  cornering.ORIGIN_RANGE).understeer
    term = understeer_budget(p).term('rolling_resistance_pitch').value
    assert term > 0.0
    assert with_moments - without == pytest.approx(term, rel=0.10)


def test_the_wheel_by_wheel_model_reduces_to_the_bicycle_at_vanishing_lateral_acceleration(
        sedan):
    """
    Check the slope at a_y -> 0 at static loads against the linear budget.

    The two differ by what only the wheel-by-wheel model holds (Ackermann of the steering
    map, static toe and camber, the .tir's shifts): a few percent on the sedan.
    """
    p, vehicle = sedan
    origin = cornering.gradients(vehicle.with_effects(load_transfer=False), 40.0,
                                 cornering.ORIGIN_RANGE).understeer
    assert origin == pytest.approx(bicycle.understeer_gradient(p), rel=0.05)
