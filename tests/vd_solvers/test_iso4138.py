# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
ISO 4138 constant radius on a quasi-steady run of a linear single-track model.

Expected gradients are the model's closed forms (Gillespie, Fundamentals of Vehicle
Dynamics, ch. 6): understeer gradient K = m/L (b/C_f - a/C_r), sideslip gradient
-m a / (L C_r), and the roll gradient the fixture's roll mode has.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

import vbox_logs as vb
from vd_solvers.standards import iso4138

DEG = math.pi / 180.0


@pytest.fixture(scope='module')
def circle() -> vb.Truth:
    return vb.circle_truth(radius=40.0)


def test_gradients_of_the_linear_model(circle) -> None:
    c = vb.CAR
    wheelbase = c['a'] + c['b']
    g = iso4138.grade_circle(circle.time, circle.steering_wheel_angle,
                             circle.lateral_acceleration, circle.yaw_rate, circle.speed,
                             roll=circle.roll, sideslip=circle.sideslip,
                             steering_ratio=c['ratio'], wheelbase=wheelbase)
    k = vb.understeer_gradient()
    assert g.radius == pytest.approx(40.0, rel=0.005) and g.direction == 1
    assert g.understeer_gradient == pytest.approx(k, rel=0.02)
    assert g.steering_gradient == pytest.approx(c['ratio'] * k, rel=0.02)
    assert g.roll_gradient == pytest.approx(c['roll_gradient'], rel=0.02)
    assert g.sideslip_gradient == pytest.approx(-c['m'] * c['a'] / (wheelbase * c['cr']),
                                                rel=0.02)
    assert g.max_lateral_acceleration == pytest.approx(4.5, abs=0.1)
    assert g.valid


def test_without_the_wheelbase_the_radius_is_taken_as_constant(circle) -> None:
    g = iso4138.grade_circle(circle.time, circle.steering_wheel_angle,
                             circle.lateral_acceleration, circle.yaw_rate, circle.speed,
                             steering_ratio=vb.CAR['ratio'])
    assert g.understeer_gradient == pytest.approx(vb.understeer_gradient(), rel=0.02)
    assert g.ackermann.startswith('constant radius')


def test_a_right_hand_circle_gives_the_same_gradients(circle) -> None:
    left = iso4138.grade_circle(circle.time, circle.steering_wheel_angle,
                                circle.lateral_acceleration, circle.yaw_rate, circle.speed)
    right = iso4138.grade_circle(circle.time, -circle.steering_wheel_angle,
                                 -circle.lateral_acceleration, -circle.yaw_rate, circle.speed)
    assert right.direction == -1
    assert right.steering_gradient == pytest.approx(left.steering_gradient, rel=1e-9)


def test_a_radius_not_held_is_invalid() -> None:
    """Steering held at the start's angle while the speed rises: an understeering car widens."""
    c = vb.CAR
    wheelbase = c['a'] + c['b']
    swa = c['ratio'] * (wheelbase / 40.0 + vb.understeer_gradient() * 0.5)
    run = vb.simulate(40.0, vb.constant(swa), lambda t: np.sqrt((0.5 + 0.1 * t) * 40.0),
                      steady_start=True)
    g = iso4138.grade_circle(run.time, run.steering_wheel_angle, run.lateral_acceleration,
                             run.yaw_rate, run.speed)
    assert not g.checks['radius_held'] and not g.valid
    assert 'FAILED' in g.describe_checks()[0]


def test_a_run_that_stops_short_of_the_linear_range_is_invalid(circle) -> None:
    keep = circle.lateral_acceleration <= 2.0
    g = iso4138.grade_circle(circle.time[keep], circle.steering_wheel_angle[keep],
                             circle.lateral_acceleration[keep], circle.yaw_rate[keep],
                             circle.speed[keep])
    assert g.checks['linear_range_covered'] is False
