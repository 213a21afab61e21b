"""Analytical parameters derived from a configuration: sources, mass properties, frames."""
from __future__ import annotations

from dataclasses import replace

import pytest

from vd_data_server.model import GroupData
from vd_data_server.study import load_study
from vd_solvers.analytical.from_config import mass_properties, static_wheel_loads, vehicle_params

G = 9.80665


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


def test_mass_properties_by_hand(baseline):
    """
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


def test_moving_the_whole_car_in_x_changes_nothing(baseline):
    """
    The vehicle frame's origin is a convention: shifting every point and the COG by the
    same dx must give the same analytical parameters.
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

