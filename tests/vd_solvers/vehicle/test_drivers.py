# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""Driver models and the torque split (vd_solvers.vehicle.drivers)."""
from __future__ import annotations

import math

import numpy as np
import numpy.testing as npt
import pytest

from vd_solvers.errors import SolverError
from vd_solvers.vehicle.drivers import (
    DRIVERS,
    CirclePathFollower,
    CoastingSpeed,
    CurvatureController,
    Observation,
    OpenLoopSteering,
    OptimalPreviewDriver,
    PreviewPathFollower,
    ReplaySteering,
    SpeedController,
    wheel_torques,
)


def _obs(t=0.0, x=0.0, y=0.0, yaw=0.0, speed=10.0):
    return Observation(t=t, x=x, y=y, yaw=yaw, speed=speed, course=yaw)


def test_registry_names_every_driver():
    assert DRIVERS == {'open_loop': OpenLoopSteering, 'replay': ReplaySteering,
                       'path_follower': CirclePathFollower, 'curvature': CurvatureController,
                       'preview_path': PreviewPathFollower,
                       'optimal_preview': OptimalPreviewDriver, 'speed': SpeedController}


def test_on_a_steady_circle_the_feed_forward_is_the_ackermann_plus_understeer_angle():
    # the vehicle on a left circle of radius R, tangent to it: no error to compensate,
    # and the road wheels steer L / R + K a_y with a_y = V^2 / R (Gillespie eq. 6-15)
    radius, speed, wheelbase, ratio, k = 60.0, 15.0, 2.8, 16.0, 0.004
    x = np.linspace(-0.9, 0.9, 3601) * radius
    y = radius - np.sqrt(radius**2 - x**2)
    driver = PreviewPathFollower(x, y, wheelbase, ratio, 10.0, understeer_gradient=k,
                                 anticipation=0.0)
    at = 0.3 * radius
    heading = math.atan(at / math.sqrt(radius**2 - at**2))
    obs = Observation(t=0.0, x=at, y=radius - math.sqrt(radius**2 - at**2), yaw=heading,
                      speed=speed, course=heading)
    expected = ratio * (wheelbase / radius + k * speed**2 / radius)
    assert driver.steering_wheel_angle(obs, 0.005) == pytest.approx(expected, rel=1e-3)


def test_a_lateral_offset_asks_for_the_arc_that_closes_it_over_the_preview():
    # a straight path e to the left: the arc from the vehicle's heading through the point
    # e aside at the preview distance d has the curvature 2 e / d^2 (small e)
    offset, speed, wheelbase, ratio, k = 0.05, 12.0, 2.8, 16.0, 0.003
    driver = PreviewPathFollower(np.array([-100.0, 0.0, 100.0]), np.full(3, offset),
                                 wheelbase, ratio, 10.0, understeer_gradient=k,
                                 preview_time=0.5, min_preview=2.0)
    d = 0.5 * speed
    expected = ratio * (wheelbase + k * speed**2) * 2.0 * offset / d**2
    assert driver.steering_wheel_angle(_obs(speed=speed), 0.005) == pytest.approx(expected)
    assert driver.lateral(50.0) == pytest.approx(offset)
    with pytest.raises(SolverError, match='increasing x'):
        PreviewPathFollower(np.array([1.0, 0.0, 2.0]), np.zeros(3), 2.8, 16.0, 10.0)


def test_coasting_speed_holds_the_controller_to_the_gate_and_no_torque_after():
    driver = CoastingSpeed(SpeedController(lambda t: 20.0, 1500.0, 0.3), gate=10.0)
    assert driver.wheel_torque(_obs(x=0.0, speed=19.0), 0.01) > 0.0
    assert driver.released_at is None
    assert driver.wheel_torque(_obs(t=0.5, x=10.0, speed=19.5), 0.01) == 0.0
    assert driver.released_at == 0.5 and driver.speed_at_release == 19.5
    # released for good, even back behind the gate
    assert driver.wheel_torque(_obs(t=0.6, x=9.0, speed=15.0), 0.01) == 0.0


def test_open_loop_table_interpolates_and_holds_its_ends():
    steer = OpenLoopSteering(times=[1.0, 2.0], angles=[0.0, 0.4])
    assert [steer.steering_wheel_angle(_obs(t), 0.01) for t in (0.0, 1.5, 3.0)] == \
        pytest.approx([0.0, 0.2, 0.4])


@pytest.mark.parametrize('times, angles', [([0.0], [0.0]), ([0.0, 0.0], [0.0, 1.0]),
                                           ([0.0, 1.0], [0.0, math.nan]), ([0.0, 1.0], [1.0])])
def test_open_loop_table_is_checked(times, angles):
    with pytest.raises(SolverError):
        OpenLoopSteering(times=times, angles=angles)


def test_replay_shifts_the_recorded_signal():
    steer = ReplaySteering([0.0, 1.0], [0.0, 1.0], offset=2.0)
    assert steer.steering_wheel_angle(_obs(2.5), 0.01) == pytest.approx(0.5)


def test_path_follower_on_the_circle_steers_the_ackermann_angle():
    """
    On the circle and tangent to it the preview point lies on it: no correction.

    The steering-wheel angle is i_s L / R (after the lag has settled).
    """
    follower = CirclePathFollower(radius=40.0, wheelbase=2.8, steering_ratio=16.0,
                                  max_angle=10.0)
    phi = 0.3  # somewhere on the circle centred at (0, 40), heading along it
    obs = _obs(x=40.0 * math.sin(phi), y=40.0 - 40.0 * math.cos(phi), yaw=phi)
    for _ in range(200):
        swa = follower.steering_wheel_angle(obs, 0.01)
    assert swa == pytest.approx(16.0 * 2.8 / 40.0, rel=1e-9)


def test_path_follower_steers_back_towards_the_circle_and_respects_the_lock():
    outside = CirclePathFollower(radius=40.0, wheelbase=2.8, steering_ratio=16.0,
                                 max_angle=10.0)
    inside = CirclePathFollower(radius=40.0, wheelbase=2.8, steering_ratio=16.0,
                                max_angle=10.0)
    base = 16.0 * 2.8 / 40.0
    assert outside.steering_wheel_angle(_obs(y=-1.0), 0.01) > base  # outside: more left
    assert inside.steering_wheel_angle(_obs(y=1.0), 0.01) < base
    tight = CirclePathFollower(radius=40.0, wheelbase=2.8, steering_ratio=16.0, max_angle=0.5)
    assert tight.steering_wheel_angle(_obs(y=-20.0), 0.01) == 0.5


def _turning(controller, yaw_rate: float, speed: float, steps: int, first: int = 0,
             h: float = 0.01):
    """Feed the controller observations of a vehicle yawing at ``yaw_rate``."""
    swa = 0.0
    for k in range(first, first + steps):
        swa = controller.steering_wheel_angle(_obs(t=k * h, yaw=yaw_rate * k * h, speed=speed), h)
    return swa


def test_curvature_controller_holds_the_ackermann_angle_on_the_circle():
    """At r / V = 1 / R there is no error: the steering-wheel angle is i_s L / R, and stays."""
    ctrl = CurvatureController(radius=40.0, wheelbase=2.8, steering_ratio=16.0, max_angle=10.0)
    assert _turning(ctrl, 10.0 / 40.0, 10.0, 500) == pytest.approx(16.0 * 2.8 / 40.0,
                                                                   rel=1e-9)


def test_curvature_controller_integrates_the_missing_curvature_and_stops_at_the_lock():
    """
    A vehicle that turns less than the circle asks for more steering, growing in time.

    The integral grows by i_s L (1/R - r/V) per integral time; at the lock it stops
    growing and the controller says so.
    """
    ctrl = CurvatureController(radius=40.0, wheelbase=2.8, steering_ratio=16.0, max_angle=10.0)
    early = _turning(ctrl, 0.9 * 10.0 / 40.0, 10.0, 100)
    later = _turning(ctrl, 0.9 * 10.0 / 40.0, 10.0, 100, first=100)
    assert 16.0 * 2.8 / 40.0 < early < later
    tight = CurvatureController(radius=40.0, wheelbase=2.8, steering_ratio=16.0,
                                max_angle=1.2)
    assert _turning(tight, 0.0, 10.0, 2000) == 1.2
    assert tight.at_lock


def test_speed_controller_feeds_forward_the_reference_slope():
    ctrl = SpeedController(lambda t: 10.0 + 0.5 * t, mass=1000.0, wheel_radius=0.3)
    torque = ctrl.wheel_torque(_obs(t=0.0, speed=10.0), 0.01)
    assert torque == pytest.approx(1000.0 * 0.3 * 0.5, rel=1e-9)  # on the reference: m a R


def test_wheel_torques_split_drive_and_brake():
    npt.assert_allclose(wheel_torques(100.0, 0.3, 0.65, np.full(4, 10.0)), [15, 15, 35, 35])
    brake = wheel_torques(-100.0, 0.3, 0.6, np.array([50.0, 50.0, -50.0, 0.0]))
    npt.assert_allclose(brake, [-30, -30, 20, 0], atol=1e-9)  # opposing the rotation
