# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The road contact of the compiled force evaluation: grids, enveloping cams, friction.

References: the bilinear interpolant's exactness on planes; the tandem cams' closed forms
(a cam on a sharp step, the mean and difference of two points on a long sine); the Magic
Formula's peak force D + S_V, which the friction factor scales; translation invariance of
the whole force evaluation under a uniformly raised road.
"""
from __future__ import annotations

import math

import numpy as np
import numpy.testing as npt
import pytest

from vd_data_server.paths import default_master
from vd_data_server.study import load_study
from vd_solvers.road.arrays import FLAT, flat, road_grid
from vd_solvers.road.surface import TrackProfile
from vd_solvers.vehicle.forces import CAM_POINTS, cam_height, grid_value, road_contact, wheel_tires
from vd_solvers.vehicle.model import VehicleModel


@pytest.fixture(scope='module')
def baseline():
    return load_study(default_master()).configurations['baseline']


def test_bilinear_grid_is_exact_on_a_plane_and_held_beyond_the_border():
    xs, ys = np.arange(5) * 0.5 - 1.0, np.arange(4) * 0.25
    plane = 0.3 + 0.2 * xs[:, None] - 0.7 * ys[None, :]
    for x, y in ((0.1, 0.3), (-0.77, 0.01), (0.999, 0.74)):
        assert grid_value(plane, -1.0, 0.0, 0.5, 0.25, x, y) == pytest.approx(
            0.3 + 0.2 * x - 0.7 * y, abs=1e-14)
    # beyond the border: the border value
    assert grid_value(plane, -1.0, 0.0, 0.5, 0.25, 7.0, -3.0) == pytest.approx(
        0.3 + 0.2 * 1.0, abs=1e-14)


def test_flat_road_gives_exactly_zero_height_and_slope_and_unit_friction():
    cam = np.array([[0.35] * 4, [0.35] * 4, [1.8] * 4, [0.12] * 4])
    rng = np.random.default_rng(1)
    x, y = rng.normal(0.0, 50.0, 4), rng.normal(0.0, 5.0, 4)
    heading = rng.uniform(-math.pi, math.pi, 4)
    ground, slope, mu = road_contact(FLAT.height, FLAT.friction, FLAT.axes, cam, x, y,
                                     np.cos(heading), np.sin(heading))
    assert np.all(ground == 0.0) and np.all(slope == 0.0) and np.all(mu == 1.0)


def _drop(s, a, b, c):
    return b * (1.0 - (1.0 - (abs(s) / a) ** c) ** (1.0 / c))


def test_a_cam_climbs_a_sharp_step_along_its_contour():
    # a step of 20 mm at x = 0 (over 0.1 mm); the cam of half-length a rests on the step's
    # edge while its centre is within a of it: lowest point at H - drop(distance)
    a, b, c, step = 0.35, 0.3, 1.8, 0.05
    dx = 1e-4
    xs = np.arange(-1.0, 1.0 + dx / 2, dx)
    table = np.column_stack([np.where(xs > 0.0, step, 0.0)] * 2)
    axes = np.array([-1.0, -1.0, dx, 2.0])
    for k in (2, 5, 9, 14, 23):
        # the cam's samples land just beyond the step edge at this centre
        centre = -a * k / CAM_POINTS + 2 * dx
        h = cam_height(table, axes, centre, 0.0, 1.0, 0.0, a, b, c)
        assert h == pytest.approx(max(0.0, step - _drop(a * k / CAM_POINTS, a, b, c)),
                                  abs=1e-9)
        if k == 5:
            assert 0.0 < h < step
    assert cam_height(table, axes, -a - 0.01, 0.0, 1.0, 0.0, a, b, c) == 0.0
    assert cam_height(table, axes, 0.01, 0.0, 1.0, 0.0, a, b, c) == pytest.approx(step)


def test_tandem_cams_on_a_long_sine_filter_it_as_two_points():
    # on a wave much longer than the cams, each cam touches under its centre, so the
    # effective height is A cos(pi l / L) sin(k x) and the slope A k sinc cos(k x)
    amp, wave, spacing = 0.01, 5.0, 0.12
    k = 2.0 * math.pi / wave
    xs = np.arange(0.0, 20.0, 0.01)
    surface = TrackProfile(xs, amp * np.sin(k * xs), amp * np.sin(k * xs), 1.6)
    road = road_grid(surface, 0.0, 20.0, -0.8, 0.8, 0.01, 1.6)
    cam = np.array([[0.35] * 4, [0.35] * 4, [1.8] * 4, [spacing] * 4])
    x = np.array([5.3, 7.1, 9.9, 12.45])
    ground, slope, _ = road_contact(road.height, road.friction, road.axes, cam, x,
                                    np.zeros(4), np.ones(4), np.zeros(4))
    half = math.pi * spacing / wave
    npt.assert_allclose(ground, amp * math.cos(half) * np.sin(k * x), atol=2e-3 * amp)
    npt.assert_allclose(slope, amp * k * math.sin(half) / half * np.cos(k * x),
                        atol=3e-3 * amp * k)


def test_friction_factor_scales_the_peak_lateral_force(baseline):
    model = VehicleModel(baseline)
    a = model.arrays
    alpha = np.linspace(0.0, 0.4, 801)
    peaks = {}
    for mu in (1.0, 0.6, 0.3):
        fy = np.array([wheel_tires(a.tire_front, a.tire_rear, np.full(4, 4000.0), np.zeros(4),
                                   np.full(4, s), np.zeros(4), np.full(4, 20.0), np.ones(4),
                                   np.full(4, mu))[1] for s in alpha])
        peaks[mu] = np.abs(fy).max(axis=0)
    # the peak is D + S_V, both proportional to LMUY
    npt.assert_allclose(peaks[0.6], 0.6 * peaks[1.0], rtol=2e-4)
    npt.assert_allclose(peaks[0.3], 0.3 * peaks[1.0], rtol=2e-4)


def test_split_friction_per_wheel_equals_each_wheel_alone(baseline):
    model = VehicleModel(baseline)
    a = model.arrays
    fz, kappa = np.array([3800.0, 4100.0, 3500.0, 3300.0]), np.array([0.02, -0.05, 0.1, 0.0])
    alpha, gamma = np.array([0.03, 0.05, -0.02, 0.08]), np.array([0.01, -0.02, 0.0, 0.01])
    vx = np.full(4, 25.0)
    mu = np.array([1.0, 0.3, 0.7, 0.5])
    split = wheel_tires(a.tire_front, a.tire_rear, fz, kappa, alpha, gamma, vx, model.mirror, mu)
    for w in range(4):
        alone = wheel_tires(a.tire_front, a.tire_rear, fz, kappa, alpha, gamma, vx,
                            model.mirror, np.full(4, mu[w]))
        npt.assert_allclose(split[:, w], alone[:, w], rtol=1e-12, atol=1e-9)
    road = flat(0.3, 1.0)  # right of y = 0: 0.3, left: 1
    _, _, mu_road = road_contact(road.height, road.friction, road.axes, model.cam,
                                 np.zeros(4), np.array([0.8, -0.8, 0.8, -0.8]), np.ones(4),
                                 np.zeros(4))
    npt.assert_array_equal(mu_road, [1.0, 0.3, 1.0, 0.3])


def test_forces_are_unchanged_on_a_uniformly_raised_road(baseline):
    flat_model = VehicleModel(baseline)
    raised = road_grid(TrackProfile(np.array([-50.0, 50.0]), np.full(2, 0.25), np.full(2, 0.25),
                                    1.6), -50.0, 50.0, -5.0, 5.0, 2.5, 2.5)
    raised_model = VehicleModel(baseline, maps=flat_model.maps, road=raised)
    q, v = flat_model.initial_state(25.0, 0.2)
    v[8] += 0.3  # some travel speed
    q_up = q.copy()
    q_up[2] += 0.25
    slip = np.array([[0.01, -0.02, 0.0, 0.03], [0.02, 0.01, -0.01, 0.0]])
    for args in ((slip, None), (slip, None)):
        tau, wheel, update = flat_model.forces(q, v, 0.3, np.zeros(4), *args, 0.005)
        tau_up, wheel_up, update_up = raised_model.forces(q_up, v, 0.3, np.zeros(4), *args,
                                                          0.005)
        npt.assert_allclose(tau_up, tau, rtol=1e-9, atol=1e-6)
        npt.assert_allclose(np.array(wheel_up), np.array(wheel), rtol=1e-9, atol=1e-9)
        npt.assert_allclose(np.array(update_up), np.array(update), rtol=1e-9, atol=1e-12)
