# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""The display-unit table: SI values shown in the customary units, from any unit string."""
from __future__ import annotations

import math

import pytest

from vd_events.reports.display import HEADLINE_NAMES, display, summary

G = 9.80665  # m/s^2, standard gravity (CGPM 1901)
DEG = 180.0 / math.pi


@pytest.mark.parametrize('value, unit, name, expected', [
    (4.92e-4, 'rad/(m/s^2)', 'understeer_gradient', (4.92e-4 * DEG * G, 'deg/g')),
    (26.8, 'm/s', 'characteristic_speed', (26.8 * 3.6, 'km/h')),
    (8.76, 'm/s^2', 'max_lateral_acceleration', (8.76 / G, 'g')),
    (-0.122, 'rad/m', 'bump_steer', (-0.122 * DEG, 'deg/m')),
    (1.2e-6, 'rad/N', 'lateral_compliance_steer', (1.2e-6 * DEG * 1e3, 'deg/kN')),
    (84800.0, 'N*m/rad', 'roll_stiffness', (84800.0 / DEG, 'N*m/deg')),
    (29700.0, 'N/m', 'wheel_rate', (29.7, 'N/mm')),
    (0.07, 'm', 'roll_centre_height_kinematic', (70.0, 'mm')),
    (0.012, 'm', 'scrub_radius', (12.0, 'mm')),
    (0.5, 'rad/s', 'yaw_rate', (0.5 * DEG, 'deg/s')),
    (1.9, 'm', 'cog_to_front_axle', (1.9, 'm')),
    (12.4, '%', 'yaw_rate_overshoot', (12.4, '%')),
    (15.8, '-', 'steering_ratio', (15.8, '-')),
])
def test_si_values_are_shown_in_their_display_units(value, unit, name, expected):
    shown, label = display(value, unit, name)
    assert label == expected[1]
    assert shown == pytest.approx(expected[0], rel=1e-12)


@pytest.mark.parametrize('value, unit, name, expected', [
    (-7.0, 'deg/m', 'bump_steer', (-7.0, 'deg/m')),
    (0.069, 'deg/kN', 'lateral_compliance_steer', (0.069, 'deg/kN')),
    (1480.0, 'N*m/deg', 'roll_stiffness', (1480.0, 'N*m/deg')),
    (12.0, 'mm', 'scrub_radius', (12.0, 'mm')),
    (2.2, 'deg/g', 'understeer_gradient', (2.2, 'deg/g')),
    (96.0, 'km/h', 'characteristic_speed', (96.0, 'km/h')),
    (29.7, 'N/mm', 'wheel_rate', (29.7, 'N/mm')),
])
def test_values_in_other_units_of_the_same_quantity_are_shown_alike(value, unit, name, expected):
    shown, label = display(value, unit, name)
    assert (pytest.approx(shown, rel=1e-12), label) == expected


def test_g_in_a_unit_is_standard_gravity_not_the_gram():
    assert display(1.0, 'deg/g', 'x') == (pytest.approx(1.0), 'deg/g')
    assert display(1.0, 'rad/(m/s^2)', 'x')[0] == pytest.approx(DEG * G, rel=1e-12)


def test_non_finite_values_pass_through():
    value, unit = display(float('nan'), 'rad/m', 'bump_steer')
    assert math.isnan(value) and unit == 'deg/m'


def test_the_demo_summary_says_each_headline_metric_in_its_display_unit():
    metrics = {'understeer_gradient': {'value': 2.196 / DEG / G, 'unit': 'rad/(m/s^2)'},
               'characteristic_speed': {'value': 96.0 / 3.6, 'unit': 'm/s'},
               'natural_frequency': {'value': 1.26, 'unit': 'Hz'},
               'mass': {'value': 1500.0, 'unit': 'kg'}}
    assert summary(metrics) == 'K_us 2.196 deg/g, v_char 96 km/h, f_n 1.26 Hz'


def test_headline_names_are_si_metric_names():
    assert not [n for n in HEADLINE_NAMES if n.endswith(('_deg_per_g', '_kmh', '_g'))]
