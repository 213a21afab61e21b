# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""Whole-vehicle quantities shared by the rungs: mass properties, wheel centres, loads."""
from __future__ import annotations

from numpy.testing import assert_allclose
import pytest

from vd_data_server.study import load_study
from vd_solvers.constants import STANDARD_GRAVITY as G
from vd_solvers.vehicle_data import mass_properties, static_wheel_loads, wheel_centres


@pytest.fixture(scope='module')
def baseline():
    from conftest import SAMPLE_DATA

    return load_study(SAMPLE_DATA / 'studies' / 'sedan.yaml').configurations['baseline']


def test_wheel_centres_mirror_the_left_hard_points(baseline):
    """Sedan hard points: front wheel centre (0, 0.78, 0.329), rear (-2.776, 0.79, 0.332)."""
    assert_allclose(wheel_centres(baseline), [[0.0, 0.78, 0.329], [0.0, -0.78, 0.329],
                                              [-2.776, 0.79, 0.332], [-2.776, -0.79, 0.332]],
                    atol=1e-12)


def test_mass_properties_by_hand(baseline):
    """
    Check the mass properties against a hand calculation.

    sedan/mass/X.yaml: 1550 kg at x = -1.25 m, z = 0.55 m; 2 x 45 kg at the front wheel
    centres (x 0, z 0.329), 2 x 40 kg at the rear (x -2.776, z 0.332).
    """
    mp = mass_properties(baseline)
    m = 1550.0 + 90.0 + 80.0
    assert mp.mass == pytest.approx(m)
    assert mp.cog_x == pytest.approx((1550.0 * -1.25 + 80.0 * -2.776) / m)
    assert mp.cog_height == pytest.approx((1550.0 * 0.55 + 90.0 * 0.329 + 80.0 * 0.332) / m)
    x_g = mp.cog_x
    izz = (2600.0 + 1550.0 * (-1.25 - x_g) ** 2 + 90.0 * (x_g ** 2 + 0.78 ** 2)
           + 80.0 * ((-2.776 - x_g) ** 2 + 0.79 ** 2))
    assert mp.yaw_inertia == pytest.approx(izz)


def test_static_loads_balance_weight_and_pitch_moment(baseline):
    front, rear = static_wheel_loads(baseline)
    mp = mass_properties(baseline)
    assert 2 * (front + rear) == pytest.approx(mp.mass * G)
    # moments about the COG: front axle load x a = rear axle load x b
    a = mp.cog_to_front_axle
    assert 2 * front * a == pytest.approx(2 * rear * (2.776 - a))
