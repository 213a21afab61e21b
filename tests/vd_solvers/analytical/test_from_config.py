# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""Analytical parameters derived from a configuration: sources and frames."""
from __future__ import annotations

from dataclasses import replace

import pytest

from vd_data_server.model import GroupData
from vd_data_server.study import load_study
from vd_solvers.analytical.from_config import vehicle_params
from vd_solvers.vehicle_data import static_wheel_loads


@pytest.fixture(scope='module')
def baseline():
    from conftest import SAMPLE_DATA

    return load_study(SAMPLE_DATA / 'studies' / 'sedan.yaml').configurations['baseline']


def _shift_x(group: GroupData, dx: float) -> GroupData:
    values = {}
    for key, value in group.values.items():
        if value.type == 'point':
            x, y, z = value.si
            value = replace(value, si=(x + dx, y, z))
        values[key] = value
    return replace(group, values=values)


def test_moving_the_whole_car_in_x_changes_nothing(baseline):
    """
    Check that the vehicle frame's origin is a convention.

    Shifting every point and the COG by the same dx must give the same analytical
    parameters.
    """
    groups = dict(baseline.groups)
    for name in ('front_hardpoints', 'rear_hardpoints', 'mass'):
        groups[name] = _shift_x(groups[name], 0.4)
    moved = replace(baseline, groups=groups)
    p0, p1 = vehicle_params(baseline), vehicle_params(moved)
    assert p1.cog_to_front_axle == pytest.approx(p0.cog_to_front_axle, abs=1e-12)
    assert p1.yaw_inertia == pytest.approx(p0.yaw_inertia, rel=1e-12)
    assert static_wheel_loads(moved) == pytest.approx(static_wheel_loads(baseline))


def test_every_parameter_names_its_source(baseline):
    p = vehicle_params(baseline)
    for name in ('mass', 'cog_to_front_axle', 'cog_height', 'yaw_inertia', 'tire_front',
                 'tire_rear', 'roll_stiffness_front', 'roll_stiffness_rear',
                 'roll_centre_height_front', 'roll_centre_height_rear'):
        assert p.sources[name], name
    assert p.sources['roll_stiffness_front'] == ('design target sedan/targets/X.yaml '
                                                 '(variant X)')
    assert p.sources['tire_front'].startswith('tires/Sedan_Pac02Tire.tir Magic Formula fitted')

