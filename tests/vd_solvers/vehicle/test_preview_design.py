# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""The optimal preview driver: its gains and its closed loop on a single track written here."""
from __future__ import annotations

import math

import numpy as np
import numpy.testing as npt
import pytest
from scipy.linalg import expm

from vd_data_server.paths import default_master
from vd_data_server.study import load_study
from vd_solvers.analytical.bicycle import effective_cornering_stiffness
from vd_solvers.analytical.from_config import vehicle_params
from vd_solvers.errors import SolverError
from vd_solvers.vehicle.drivers import Observation, OptimalPreviewDriver
from vd_solvers.vehicle.preview_design import preview_gains

RATIO, LAG, SAMPLE, HORIZON = 16.0, 0.15, 0.02, 1.5


@pytest.fixture(scope='module')
def params():
    return vehicle_params(load_study(default_master()).configurations['baseline'])


def _gains(p, speed, error_scale=0.02, steer_scale=0.1):
    return preview_gains(p, speed, p.cog_to_rear_axle, LAG, SAMPLE, HORIZON, error_scale,
                         steer_scale)


def _single_track(p):
    """Return (v, r)' of the linear single track, written out here (Milliken ch. 5)."""
    cf, cr = effective_cornering_stiffness(p)
    m, izz, a, b = p.mass, p.yaw_inertia, p.cog_to_front_axle, p.cog_to_rear_axle

    def rates(v, r, delta, u):
        alpha_f = delta - (v + a * r) / u
        alpha_r = (b * r - v) / u
        fyf, fyr = cf * alpha_f, cr * alpha_r
        return (fyf + fyr) / m - u * r, (a * fyf - b * fyr) / izz
    return rates


@pytest.fixture(scope='module', params=['sedan.yaml', 'hmmwv.yaml'])
def both_cars(request):
    study = load_study(default_master().parent / request.param)
    return vehicle_params(study.configurations['baseline'])


@pytest.mark.parametrize('kmh', [20.0, 40.0, 60.0, 80.0, 100.0])
def test_the_feedback_makes_the_sampled_path_plant_stable(both_cars, kmh):
    # the plant of lateral offset, heading error, v, r and lagged road-wheel angle, built
    # here from the equations of motion and sampled with the command held; the driver's
    # feedback must put every closed-loop eigenvalue inside the unit circle
    u = kmh / 3.6
    cf, cr = effective_cornering_stiffness(both_cars)
    m, izz = both_cars.mass, both_cars.yaw_inertia
    a, b = both_cars.cog_to_front_axle, both_cars.cog_to_rear_axle
    cont = np.array([
        [0.0, u, 1.0, -b, 0.0],
        [0.0, 0.0, 0.0, 1.0, 0.0],
        [0.0, 0.0, -(cf + cr) / (m * u), (b * cr - a * cf) / (m * u) - u, cf / m],
        [0.0, 0.0, (b * cr - a * cf) / (izz * u), -(a * a * cf + b * b * cr) / (izz * u),
         a * cf / izz],
        [0.0, 0.0, 0.0, 0.0, -1.0 / LAG]])
    steer = np.array([0.0, 0.0, 0.0, 0.0, 1.0 / LAG])
    block = np.zeros((6, 6))
    block[:5, :5], block[:5, 5] = cont, steer
    held = expm(block * SAMPLE)
    g = _gains(both_cars, u)
    npt.assert_allclose(g.plant, held[:5, :5], rtol=1e-9, atol=1e-12)
    npt.assert_allclose(g.steer, held[:5, 5], rtol=1e-9, atol=1e-12)
    closed = held[:5, :5] - np.outer(held[:5, 5], g.feedback)
    assert np.max(np.abs(np.linalg.eigvals(closed))) < 1.0
    # open loop it is not asymptotically stable (free integrators: position and heading)
    assert np.max(np.abs(np.linalg.eigvals(held[:5, :5]))) == pytest.approx(1.0, abs=1e-9)


def test_impossible_settings_are_refused_with_a_message(params):
    with pytest.raises(SolverError, match='needs a positive speed'):
        preview_gains(params, 0.0, 1.5, LAG, SAMPLE, HORIZON, 0.02, 0.1)
    with pytest.raises(SolverError, match=r'horizon \(0.01 s\) of at least one sample'):
        preview_gains(params, 10.0, 1.5, LAG, SAMPLE, 0.01, 0.02, 0.1)


def _drive(p, driver, speed, duration, x0=0.0, y0=0.0, yaw0=0.0, h=0.002):
    """
    Drive the single track at constant forward speed with ``driver``: RK4, world frame.

    The body origin the driver sees is the CoG; returns time, x, y, yaw, steering wheel.
    """
    rates = _single_track(p)
    state = np.array([x0, y0, yaw0, 0.0, 0.0])  # x, y, yaw, v, r

    def f(s, delta):
        dv, dr = rates(s[3], s[4], delta, speed)
        c, si = math.cos(s[2]), math.sin(s[2])
        return np.array([speed * c - s[3] * si, speed * si + s[3] * c, s[4], dv, dr])

    out = []
    for k in range(int(round(duration / h))):
        t = k * h
        course = state[2] + math.atan2(state[3], speed)
        swa = driver.steering_wheel_angle(
            Observation(t, state[0], state[1], state[2], math.hypot(speed, state[3]), course), h)
        delta = swa / RATIO
        k1 = f(state, delta)
        k2 = f(state + 0.5 * h * k1, delta)
        k3 = f(state + 0.5 * h * k2, delta)
        k4 = f(state + h * k3, delta)
        state = state + h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4)
        out.append((t, state[0], state[1], state[2], swa))
    return np.array(out).T


def _driver(p, x, y, speed):
    return OptimalPreviewDriver(x, y, _gains(p, speed), RATIO, 20.0, LAG,
                                behind=p.cog_to_rear_axle, cog_ahead=0.0)


def test_on_a_circle_the_steering_settles_at_the_steady_state_angle(params):
    # straight, then a left circle of radius R tangent at x = 0; on the circle the driver
    # must end up steering the single track's steady-state angle (L + K V^2) / R through
    # the steering ratio (Gillespie eq. 6-15; K = m / L (b / C_f - a / C_r) written out
    # here) with the rear axle on the line
    radius, speed = 150.0, 25.0
    x = np.arange(-60.0, 0.95 * radius, 0.05)
    y = np.where(x > 0.0, radius - np.sqrt(radius**2 - np.minimum(x, radius) ** 2), 0.0)
    cf, cr = effective_cornering_stiffness(params)
    a, b, wheelbase = params.cog_to_front_axle, params.cog_to_rear_axle, params.wheelbase
    k = params.mass / wheelbase * (b / cf - a / cr)
    expected = RATIO * (wheelbase + k * speed**2) / radius
    t, px, py, yaw, swa = _drive(params, _driver(params, x, y, speed), speed, 7.0,
                                 x0=-40.0 + b)
    late = (t > 5.0) & (px < 0.9 * radius)
    assert np.count_nonzero(late) > 100
    npt.assert_allclose(swa[late], expected, rtol=2e-3)
    rx, ry = px - b * np.cos(yaw), py - b * np.sin(yaw)
    miss = np.hypot(rx[late], ry[late] - radius) - radius
    npt.assert_allclose(miss, 0.0, atol=2e-3)


def test_on_a_straight_line_an_offset_dies_out_and_no_steering_is_left(params):
    speed = 20.0
    x = np.array([-100.0, 0.0, 1000.0])
    t, px, py, yaw, swa = _drive(params, _driver(params, x, np.zeros(3), speed), speed, 8.0,
                                 y0=0.5)
    assert np.max(np.abs(swa)) > 0.0
    late = t > 6.0
    npt.assert_allclose(py[late] - params.cog_to_rear_axle * np.sin(yaw[late]), 0.0, atol=1e-3)
    npt.assert_allclose(swa[late], 0.0, atol=1e-2)
    # on the line from the start, nothing at all
    _, _, py0, _, swa0 = _drive(params, _driver(params, x, np.zeros(3), speed), speed, 1.0)
    assert np.all(swa0 == 0.0) and np.all(py0 == 0.0)


def test_a_mirrored_line_gives_the_mirrored_steering(params):
    # a lane change to the left (half-cosine) and its mirror image to the right
    speed = 16.0
    x = np.arange(-50.0, 150.0, 0.1)
    y = np.where(x < 0.0, 0.0, np.where(x > 30.0, 3.5, 1.75 * (1.0 - np.cos(np.pi * x / 30.0))))
    left = _drive(params, _driver(params, x, y, speed), speed, 6.0)
    right = _drive(params, _driver(params, x, -y, speed), speed, 6.0)
    assert np.max(left[4]) > 0.5  # it does steer
    npt.assert_allclose(right[4], -left[4], atol=1e-9)
    npt.assert_allclose(right[2], -left[2], atol=1e-9)
    npt.assert_allclose(right[1], left[1], atol=1e-9)


def test_the_steering_stops_at_the_lock_and_leaves_it_at_once(params):
    # 5 m to the right of a straight line the command is far beyond the lock: the steering
    # wheel holds the lock; back on the line, the wheels turn back from the lock in the
    # very next step (the lag's state is the wheels' angle, not a wound-up command)
    lock, speed, h = 2.0, 15.0, 0.005
    driver = OptimalPreviewDriver(np.array([-100.0, 0.0, 1000.0]), np.zeros(3),
                                  _gains(params, speed), RATIO, lock, LAG)
    swa = [driver.steering_wheel_angle(Observation(k * h, k * h * speed, -5.0, 0.0, speed,
                                                   0.0), h) for k in range(200)]
    assert max(swa) == pytest.approx(lock) and min(swa) > 0.0
    back = driver.steering_wheel_angle(Observation(1.0, 15.0, 0.0, 0.0, speed, 0.0), h)
    assert back < lock
