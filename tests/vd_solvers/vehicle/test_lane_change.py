# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""The ISO 3888-2 lane change: driving line, coasting run, cone check (vehicle.lane_change)."""
from __future__ import annotations

import math

import numpy as np
import pytest

from vd_data_server.paths import default_master
from vd_data_server.study import load_study
from vd_solvers.errors import SolverError
from vd_solvers.standards import iso3888
from vd_solvers.vehicle.lane_change import (
    APPROACH,
    LANE_CHANGE_PARAMS,
    LIMIT_PARAMS,
    driving_line,
    run_lane_change,
    run_lane_change_limit,
    vehicle_rectangle,
)
from vd_solvers.vehicle.model import VehicleModel


@pytest.fixture(scope='module')
def base_model():
    return VehicleModel(load_study(default_master()).configurations['baseline'])


def _lanes(width):
    """ISO 3888-2:2011 Table 1 for a vehicle ``width`` m wide, written out: (x0, x1, lo, hi)."""
    w1, w3, w5 = 1.1 * width + 0.25, width + 1.0, max(1.3 * width + 0.25, 3.0)
    near3 = 0.5 * w1 + 1.0
    return [(0.0, 12.0, -0.5 * w1, 0.5 * w1), (25.5, 36.5, near3, near3 + w3),
            (49.0, 61.0, -0.5 * w1, -0.5 * w1 + w5)]


def _corner_points(x, y, heading, length, width, front, step=0.05):
    """Points along the rectangle's outline at every pose, rotated here (not iso3888)."""
    along = np.arange(front - length, front + 1e-9, step)
    local = np.concatenate([np.column_stack([along, np.full_like(along, s * 0.5 * width)])
                            for s in (1.0, -1.0)])
    c, s = np.cos(heading)[:, None], np.sin(heading)[:, None]
    return x[:, None] + c * local[:, 0] - s * local[:, 1], \
        y[:, None] + s * local[:, 0] + c * local[:, 1]


def test_the_driving_line_keeps_the_rectangle_inside_the_lanes():
    length, width, front, margin = 4.6, 1.8, 3.4, 0.05
    x, y = driving_line(iso3888.course(width), length, width, front, margin)
    px, py = _corner_points(x, y, np.arctan(np.gradient(y, x)), length, width, front)
    # the clearance is imposed at the grid's poses, linearised in the heading: what is
    # guaranteed is the rectangle inside every lane, the line's purpose
    for x0, x1, lo, hi in _lanes(width):
        inside = (px >= x0) & (px <= x1)
        assert np.any(inside)
        assert np.min(py[inside] - lo) > 0.0 and np.min(hi - py[inside]) > 0.0
    # it starts straight on the approach centre line and ends straight after the course
    np.testing.assert_allclose(y[:3], 0.0, atol=1e-9)
    assert np.ptp(y[x >= 61.0 + length + 15.0]) < 1e-6


def test_the_driving_line_bends_less_than_the_lane_centres_half_cosines():
    # the least peak curvature through the lanes is below that of the obvious line: the
    # centre lines of sections 1, 3, 5 joined by half-cosines over sections 2 and 4
    width = 1.8
    x, y = driving_line(iso3888.course(width), 4.6, width, 3.4, 0.0)
    kappa = np.gradient(np.gradient(y, x), x) / (1.0 + np.gradient(y, x) ** 2) ** 1.5
    lanes = _lanes(width)
    shift = 0.5 * (lanes[1][2] + lanes[1][3])  # centre of section 3 from centre of section 1
    cosine = 0.5 * shift * (math.pi / 13.5) ** 2  # peak of A/2 (1 - cos(pi x / l))
    assert np.max(np.abs(kappa)) < cosine


def test_an_impossible_clearance_is_refused_with_a_message():
    with pytest.raises(SolverError, match='leave no driving line with 0.3 m clearance'):
        driving_line(iso3888.course(1.8), 4.6, 1.8, 3.4, 0.3)


def _run(model, speed):
    values = {k: p.default for k, p in LANE_CHANGE_PARAMS.items()}
    values['speed'] = speed
    kept = {}

    def channels_of(m, trace):
        kept.update(trace.channels())
        return {}

    metrics, _, notes = run_lane_change(model, values, None, channels_of)
    return metrics, notes, kept


def test_the_lane_change_passes_slowly_coasting_from_the_gate(base_model):
    metrics, notes, ch = _run(base_model, 30.0 / 3.6)
    assert metrics['passed'].value == 1.0 and metrics['cones_hit'].value == 0.0, notes
    assert metrics['smallest_margin'].value > 0.0
    assert metrics['entry_speed'].value == pytest.approx(30.0 / 3.6, rel=0.01)
    # coasting: no torque from the entry gate on, and the vehicle slows down
    length, width, front = vehicle_rectangle(base_model)
    after = ch['x'] - APPROACH + front >= 0.0
    assert np.all(ch['wheel_torque'][after] == 0.0) and np.any(ch['wheel_torque'][~after] != 0.0)
    assert metrics['exit_speed'].value < metrics['entry_speed'].value
    # the cone check, recomputed: the rectangle's outline inside every gated lane
    px, py = _corner_points(ch['x'] - APPROACH, ch['y'], ch['yaw'], length, width, front)
    for x0, x1, lo, hi in _lanes(width):
        inside = (px >= x0) & (px <= x1)
        assert np.all(py[inside] > lo) and np.all(py[inside] < hi)


def test_the_sedan_passes_at_60_km_h_as_a_test_driver_does(base_model):
    # a passenger car with a test driver passes ISO 3888-2 at about 60-75 km/h (the
    # moose test's best cars 70-80 km/h, docs/events.md); the planned line asks the
    # sample sedan for about 7.4 m/s^2 there, below its 0.88 g steady-state limit
    metrics, notes, ch = _run(base_model, 60.0 / 3.6)
    assert metrics['passed'].value == 1.0 and metrics['cones_hit'].value == 0.0, notes
    length, width, front = vehicle_rectangle(base_model)
    px, py = _corner_points(ch['x'] - APPROACH, ch['y'], ch['yaw'], length, width, front)
    for x0, x1, lo, hi in _lanes(width):
        inside = (px >= x0) & (px <= x1)
        assert np.all(py[inside] > lo) and np.all(py[inside] < hi)


def test_the_hmmwv_passes_at_30_km_h_well_off_the_steering_lock():
    # the truck's 19.5:1 steering and slow yaw response once drove a path follower into
    # oscillation up to the 720 deg lock at this speed; the preview driver's gains come
    # from the truck's own single track with the steering lag, and the loop stays calm
    study = default_master().parent / 'hmmwv_roads.yaml'
    model = VehicleModel(load_study(study).configurations['dry'])
    metrics, notes, ch = _run(model, 30.0 / 3.6)
    assert metrics['passed'].value == 1.0, notes
    lock = float(min(-model.maps.steer_swa[0], model.maps.steer_swa[-1]))
    assert metrics['peak_steering_wheel_angle'].value < 0.5 * lock
    # the line asks little at this speed: the car follows it without scrubbing speed
    assert metrics['exit_speed'].value > 0.8 * metrics['entry_speed'].value


def test_the_lane_change_hits_cones_at_an_absurd_speed(base_model):
    metrics, notes, ch = _run(base_model, 90.0 / 3.6)
    assert metrics['passed'].value == 0.0 and metrics['cones_hit'].value > 0.0, notes
    length, width, front = vehicle_rectangle(base_model)
    px, py = _corner_points(ch['x'] - APPROACH, ch['y'], ch['yaw'], length, width, front)
    outside = False
    for x0, x1, lo, hi in _lanes(width):
        inside = (px >= x0) & (px <= x1)
        outside |= bool(np.any(py[inside] <= lo) or np.any(py[inside] >= hi))
    assert outside


def test_the_limit_search_needs_a_bracket_of_at_least_its_resolution(base_model):
    values = {k: p.default for k, p in LIMIT_PARAMS.items()}
    values['lowest'] = values['highest'] = 50.0 / 3.6
    with pytest.raises(SolverError) as err:
        run_lane_change_limit(base_model, values, None, lambda m, trace: {})
    assert str(err.value) == ('the highest entry speed (50 km/h) must exceed the lowest '
                              '(50 km/h) by at least 1 km/h')
