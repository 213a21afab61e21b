# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""Track profiles and single obstacles: heights at known points, across the tracks, sides."""
from __future__ import annotations

import math

import numpy as np
import pytest

from vd_solvers.road.obstacles import obstacle_road
from vd_solvers.road.surface import Flat, TrackProfile


def test_flat_road_is_zero_in_the_shape_of_its_points():
    z = Flat().height(np.zeros((2, 3)), 1.0)
    assert z.shape == (2, 3) and not z.any()


def test_track_profile_interpolates_along_and_across():
    road = TrackProfile(np.array([0.0, 10.0]), np.array([0.0, 0.2]), np.array([0.1, 0.1]), 2.0)
    assert road.height(5.0, 1.0) == pytest.approx(0.1)  # left track, halfway
    assert road.height(5.0, -1.0) == pytest.approx(0.1)  # right track
    assert road.height(10.0, 0.0) == pytest.approx(0.15)  # midway across
    assert road.height(10.0, 3.0) == pytest.approx(0.2)  # beyond the left track
    assert road.height(12.0, -3.0) == pytest.approx(0.1)  # after the end: the end height


def test_cosine_bump_height_and_smoothness():
    road = obstacle_road('bump', 0.05, 0.6, start=10.0, road_length=30.0, track_width=1.5)
    x = np.array([9.9, 10.0, 10.15, 10.3, 10.45, 10.6, 10.7])
    expected = [0.0, 0.0, 0.025, 0.05, 0.025, 0.0, 0.0]  # h (1 - cos(2 pi s / l)) / 2
    np.testing.assert_allclose(road.height(x, 0.75), expected, atol=1e-4)
    assert 'bump of height 0.05 m' in road.description


def test_pothole_under_one_track_only():
    road = obstacle_road('pothole', 0.04, 0.5, start=5.0, road_length=20.0, track_width=1.5,
                         side='left')
    assert road.height(5.25, 0.75) == pytest.approx(-0.04, abs=1e-6)
    assert road.height(5.25, -0.75) == pytest.approx(0.0)
    assert road.height(5.25, 0.0) == pytest.approx(-0.02, abs=1e-6)


def test_kerb_ramp_and_step():
    ramp = obstacle_road('kerb', 0.1, 0.2, start=2.0, road_length=10.0, track_width=1.5)
    assert ramp.height(2.1, 0.0) == pytest.approx(0.05)
    assert ramp.height(8.0, 0.0) == pytest.approx(0.1)
    step = obstacle_road('kerb', 0.1, 0.0, start=2.0, road_length=10.0, track_width=1.5,
                         spacing=0.01)
    assert step.height(1.99, 0.0) == pytest.approx(0.0)
    assert step.height(2.0, 0.0) == pytest.approx(0.1)


@pytest.mark.parametrize('kwargs, message', [
    ({'kind': 'ramp'}, "unknown obstacle 'ramp'"),
    ({'side': 'middle'}, "unknown obstacle side 'middle'"),
    ({'height': -0.1}, 'height (depth) must be positive'),
    ({'start': 50.0}, 'must lie on the road'),
    ({'length': 0.0}, 'a bump needs a positive length'),
])
def test_bad_obstacles_are_refused(kwargs, message):
    args = {'kind': 'bump', 'height': 0.05, 'length': 0.5, 'start': 1.0, 'road_length': 10.0,
            'track_width': 1.5}
    args.update(kwargs)
    with pytest.raises(ValueError) as err:
        obstacle_road(**args)
    assert message in str(err.value)


def test_bad_profiles_are_refused():
    with pytest.raises(ValueError, match='increasing'):
        TrackProfile(np.array([0.0, 0.0]), np.zeros(2), np.zeros(2), 1.5)
    with pytest.raises(ValueError, match='finite'):
        TrackProfile(np.array([0.0, 1.0]), np.array([0.0, math.nan]), np.zeros(2), 1.5)
