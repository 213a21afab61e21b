# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
ISO 3888-2 track against the standard's Table 1, and the cone check on constructed runs.

References: ISO 3888-2:2011, 4.1 and Table 1 (sections 12, 13.5, 11, 12.5, 12 m, 61 m in
all; widths 1.1 b + 0.25, b + 1, 1.3 b + 0.25 but at least 3 m; section 3 offset 1 m
beyond section 1; section 5 in line with section 1 on the outer side). The runs are
straight lines and a smooth lane change whose clearances are computed here by hand.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from vd_solvers.standards import iso3888

B, LENGTH, FRONT = 1.8, 4.7, 0.9  # vehicle width, length; reference point behind the front


def test_the_track_of_table_1():
    c = iso3888.course(B)
    assert c.length == pytest.approx(61.0)
    assert c.widths == pytest.approx({1: 1.1 * B + 0.25, 3: B + 1.0, 5: 3.0})
    assert iso3888.course(2.2).widths[5] == pytest.approx(1.3 * 2.2 + 0.25)
    lim = {(b.section, b.side): b for b in c.boundaries}
    w1 = 1.1 * B + 0.25
    assert lim[1, 'left'].y == pytest.approx(w1 / 2)
    assert lim[1, 'right'].y == pytest.approx(-w1 / 2)
    assert lim[3, 'right'].y == pytest.approx(w1 / 2 + 1.0)
    assert lim[3, 'left'].y == pytest.approx(w1 / 2 + 1.0 + B + 1.0)
    assert lim[5, 'right'].y == pytest.approx(-w1 / 2)
    assert (lim[3, 'right'].x0, lim[3, 'right'].x1) == pytest.approx((25.5, 36.5))
    assert (lim[5, 'left'].x0, lim[5, 'left'].x1) == pytest.approx((49.0, 61.0))
    mirrored = {(b.section, b.side): b.y for b in iso3888.course(B, 'right').boundaries}
    assert mirrored[3, 'left'] == pytest.approx(-lim[3, 'right'].y)
    assert mirrored[3, 'right'] == pytest.approx(-lim[3, 'left'].y)


def _run(y_of_x, x_end=75.0, dx=0.05):
    x = np.arange(-10.0, x_end, dx)
    y = y_of_x(x)
    yaw = np.arctan(np.gradient(y, x))
    return x / 20.0, x, y, yaw  # 20 m/s


def test_driving_straight_past_the_avoidance_lane_fails():
    track = iso3888.course(B)
    check = iso3888.check_run(track, *_run(lambda x: 0.0 * x), length=LENGTH, width=B,
                              front=FRONT)
    assert not check.passed
    assert [(s, side) for s, side, _ in check.hits] == [(3, 'right')]
    # the first violation: the front reaches section 3 (x = 25.5 m); t = x / 20 m/s
    assert check.hits[0][2] == pytest.approx((25.5 - FRONT) / 20.0, abs=0.01)
    w1 = 1.1 * B + 0.25
    assert check.margins[1, 'left'] == pytest.approx(w1 / 2 - B / 2, abs=1e-9)


def test_a_smooth_lane_change_on_the_lane_centres_passes():
    track = iso3888.course(B)
    y3, y5 = track.centre(3), track.centre(5)

    def path(x):
        def blend(x, x0, x1):  # 0 -> 1 with zero slope at both ends
            u = np.clip((x - x0) / (x1 - x0), 0.0, 1.0)
            return u * u * (3 - 2 * u)

        # each lane change between the rear leaving one lane and the front entering the next
        rear = LENGTH - FRONT
        return y3 * blend(x, 12.0 + rear, 25.5 - FRONT) + (y5 - y3) * blend(
            x, 36.5 + rear, 49.0 - FRONT)

    check = iso3888.check_run(track, *_run(path), length=LENGTH, width=B, front=FRONT)
    assert check.passed, check.hits
    assert check.covered
    # the yawed car comes closer than on the lane centre, never touching
    for (section, _), margin in check.margins.items():
        assert 0.0 < margin <= (track.widths[section] - B) / 2 + 1e-9


def test_margins_of_a_car_on_the_lane_centres_are_the_half_free_widths():
    # the car moved sideways (no yaw) between the lanes, each move 1 m into a gap, so
    # that the lanes' own clearances are the smallest
    track = iso3888.course(B)
    rear = LENGTH - FRONT
    x = np.arange(-10.0, 75.0, 0.05)
    y = np.where(x < 12.0 + rear + 1.0, 0.0, track.centre(3))
    y = np.where(x < 36.5 + rear + 1.0, y, track.centre(5))
    check = iso3888.check_run(track, x / 20.0, x, y, np.zeros_like(x), length=LENGTH, width=B,
                              front=FRONT)
    assert check.passed
    for (section, _), margin in check.margins.items():
        assert margin == pytest.approx((track.widths[section] - B) / 2, abs=1e-9)


def test_the_yawed_rectangle_is_checked_at_its_corners():
    # a car at rest across the entry lane, its reference point at its middle: its corners
    # reach beyond both limits (+-LENGTH / 2 against +-(1.1 b + 0.25) / 2)
    track = iso3888.course(B)
    t = np.array([0.0, 1.0])
    check = iso3888.check_run(track, t, np.full(2, 6.0), np.zeros(2), np.full(2, math.pi / 2),
                              length=LENGTH, width=B, front=LENGTH / 2)
    assert {(s, side) for s, side, _ in check.hits} == {(1, 'left'), (1, 'right')}
    assert not check.covered and not check.passed


def test_bad_input_is_refused():
    with pytest.raises(ValueError, match='vehicle width must be positive'):
        iso3888.course(0.0)
    with pytest.raises(ValueError, match="'left' or 'right'"):
        iso3888.course(B, 'up')
    with pytest.raises(ValueError, match='one length'):
        iso3888.check_run(iso3888.course(B), [0, 1], [0], [0, 1], [0, 0], length=LENGTH,
                          width=B, front=FRONT)
