# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""Derived metrics: definitions cross-checked, the Chrono samples sane."""
from __future__ import annotations

import numpy as np
import pytest

from vd_solvers.errors import SolverError
from vd_solvers.kc.channels import steering_geometry, wheel_angles
from vd_solvers.kc.events import run_suite
from vd_solvers.kc.metrics import derived_metrics, slope_at
from vd_solvers.kc.model import Curve


@pytest.fixture(scope='module')
def front_suite(request: pytest.FixtureRequest) -> dict:
    inp = request.getfixturevalue('macpherson_front')()
    return {'inp': inp, 'results': run_suite(inp, label='generic-front')}


@pytest.fixture(scope='module')
def rear_suite(request: pytest.FixtureRequest) -> dict:
    inp = request.getfixturevalue('multilink_rear')()
    return {'inp': inp, 'results': run_suite(inp, label='generic-rear')}


def test_front_metrics_are_complete_and_sane(front_suite, generic_wheelbase) -> None:
    inp, results = front_suite['inp'], front_suite['results']
    m = derived_metrics(results, inp.tire_vertical_stiffness, cg_height=0.55,
                        wheelbase=generic_wheelbase)
    for name in ('bump_steer', 'camber_gain', 'wheel_rate', 'ride_rate', 'roll_stiffness',
                 'roll_stiffness_no_bar', 'roll_steer', 'roll_camber',
                 'roll_centre_height_kinematic', 'roll_centre_height_force',
                 'lateral_compliance_steer', 'lateral_stiffness',
                 'longitudinal_stiffness_braking', 'anti_dive', 'anti_lift_traction',
                 'steering_ratio', 'ackermann', 'caster', 'kingpin_inclination', 'scrub_radius',
                 'mechanical_trail', 'fvsa_length', 'svsa_length', 'svsa_angle',
                 'front_view_instant_centre_y', 'side_view_instant_centre_x'):
        assert name in m, name
    assert m['wheel_rate'][1] == 'N/m' and m['roll_stiffness'][1] == 'N*m/rad'
    # MacPherson: strut top rearward and inboard -> positive caster, KPI, trail
    caster, kpi = np.degrees(m['caster'][0]), np.degrees(m['kingpin_inclination'][0])
    assert 3.0 < caster < 12.0 and 5.0 < kpi < 18.0
    assert m['mechanical_trail'][0] > 0.0
    assert -30.0 < np.degrees(m['camber_gain'][0]) < 0.0  # deg/m: top inward in bump
    assert 0.0 < m['roll_centre_height_kinematic'][0] < 0.3
    assert 10.0 < m['steering_ratio'][0] < 30.0
    assert 0.0 < m['ackermann'][0] < 100.0
    # rigid joints and a rigid rack: no compliance
    assert m['lateral_stiffness'][0] == float('inf')
    assert m['lateral_compliance_steer'][0] == pytest.approx(0.0, abs=1e-9)


def test_ride_rate_is_wheel_rate_in_series_with_the_tire(front_suite) -> None:
    inp, results = front_suite['inp'], front_suite['results']
    m = derived_metrics(results, inp.tire_vertical_stiffness)
    kw, kt = m['wheel_rate'][0], inp.tire_vertical_stiffness
    assert m['ride_rate'][0] == pytest.approx(1.0 / (1.0 / kw + 1.0 / kt), rel=1e-12)


@pytest.mark.parametrize('suite', ['front_suite', 'rear_suite'])
def test_roll_centre_from_paths_equals_roll_centre_from_forces(suite: str, request) -> None:
    """
    Check the kinematic roll centre against the force-based one.

    Rigid linkage: instant-centre construction and the pads' jacking under
    lateral force are the same virtual-work statement.
    """
    data = request.getfixturevalue(suite)
    m = derived_metrics(data['results'], data['inp'].tire_vertical_stiffness)
    assert m['roll_centre_height_force'][0] == pytest.approx(
        m['roll_centre_height_kinematic'][0], rel=1e-9)


def test_steering_ratio_from_the_rack_ratio(front_suite) -> None:
    inp, results = front_suite['inp'], front_suite['results']
    steer = results['steering']
    m = derived_metrics(results, inp.tire_vertical_stiffness)
    rate = steer.rate_up
    road_per_rack = abs(rate['steer_angle'].mean() / rate['rack_travel'])
    assert m['steering_ratio'][0] == pytest.approx(
        1.0 / (road_per_rack * inp.steering.rack_ratio), rel=1e-9)
    # the former fit over +-5 mm of rack within its bias
    mean = steer.channels['steer_angle'].mean(axis=1)
    fit = abs(slope_at(steer.channels['rack_travel'], mean, 0.0, 0.005))
    assert fit == pytest.approx(road_per_rack, rel=1e-3)


def test_rear_metrics(rear_suite) -> None:
    inp, results = rear_suite['inp'], rear_suite['results']
    m = derived_metrics(results, inp.tire_vertical_stiffness, cg_height=0.55, wheelbase=2.46)
    assert 'steering_ratio' not in m and 'anti_squat' in m and 'anti_lift_braking' in m
    assert m['roll_stiffness'][0] > m['roll_stiffness_no_bar'][0] > 0.0
    assert m['wheel_rate'][0] == pytest.approx(
        120000.0 * m['installation_ratio'][0] ** 2, rel=0.05
    )  # preload and unsprung weight shift it slightly


def test_anti_percentages_need_cg_height_and_wheelbase(rear_suite) -> None:
    m = derived_metrics(rear_suite['results'], rear_suite['inp'].tire_vertical_stiffness)
    assert 'anti_squat' not in m and 'svsa_angle_traction' in m


def test_angle_conventions() -> None:
    toe, camber = np.radians(0.3), np.radians(-1.5)
    left = [np.sin(toe) * np.cos(camber), np.cos(toe) * np.cos(camber), -np.sin(camber)]
    right = [left[0], -left[1], left[2]]
    a = wheel_angles(np.array([[left, right]]))
    np.testing.assert_allclose(a['toe'], [[toe, toe]])
    np.testing.assert_allclose(a['camber'], [[camber, camber]])
    np.testing.assert_allclose(a['steer_angle'], [[-toe, toe]])
    # axis through (0, 0.7, 0.5) and (0.02, 0.75, 0.1): top rearward and inboard
    upper = np.array([[[0.0, 0.7, 0.5], [0.0, -0.7, 0.5]]])
    lower = np.array([[[0.02, 0.75, 0.1], [0.02, -0.75, 0.1]]])
    contact = np.array([[[0.0, 0.80, 0.0], [0.0, -0.80, 0.0]]])
    g = steering_geometry(upper, lower, contact, np.array([[[0, 1.0, 0], [0, -1.0, 0]]]))
    np.testing.assert_allclose(g['caster'], np.arctan2(0.02, 0.4))
    np.testing.assert_allclose(g['kingpin_inclination'], np.arctan2(0.05, 0.4))
    np.testing.assert_allclose(g['scrub_radius'], 0.80 - (0.75 + 0.05 / 4), atol=1e-12)
    np.testing.assert_allclose(g['mechanical_trail'], 0.02 + 0.02 / 4, atol=1e-12)


def test_curve_integral_and_extrapolation() -> None:
    c = Curve(np.array([-1.0, 0.0, 2.0]), np.array([-2.0, 0.0, 2.0]))
    assert c.value(1.0) == pytest.approx(1.0)
    assert c.value(4.0) == pytest.approx(4.0)  # linear extrapolation
    assert c.integral(2.0) == pytest.approx(2.0)
    assert c.integral(-1.0) == pytest.approx(1.0)
    work, value, slope = c.evaluate(np.array([3.0]))
    assert (work[0], value[0], slope[0]) == pytest.approx((4.5, 3.0, 1.0))
    with pytest.raises(SolverError, match='strictly increasing'):
        Curve(np.array([0.0, 0.0]), np.array([0.0, 1.0]))
