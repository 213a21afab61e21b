# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
from __future__ import annotations

from dataclasses import FrozenInstanceError, replace
import math

import pytest

from vd_solvers.analytical.params import VehicleParams
from vd_solvers.constants import STANDARD_GRAVITY


def test_static_axle_loads_add_up_to_the_weight(passenger_car: VehicleParams) -> None:
    p = passenger_car
    assert p.g == STANDARD_GRAVITY
    assert p.axle_load_front + p.axle_load_rear == pytest.approx(p.mass * p.g, rel=1e-15)
    assert p.axle_load_front / p.weight == pytest.approx(0.58, rel=1e-12)
    assert p.cog_to_rear_axle == pytest.approx(0.58 * p.wheelbase, rel=1e-12)


@pytest.mark.parametrize(
    ('field', 'value'),
    [
        ('mass', 0.0),
        ('mass', -1500.0),
        ('wheelbase', 0.0),
        ('cog_to_front_axle', 0.0),
        ('cog_to_front_axle', 2.7),
        ('track_front', 0.0),
        ('track_rear', -1.5),
        ('cog_height', 0.0),
        ('roll_stiffness_front', -1.0),
        ('roll_stiffness_rear', -1.0),
        ('yaw_inertia', 0.0),
        ('unsprung_mass_front', -10.0),
        ('unsprung_cog_height_rear', -0.3),
        ('g', 0.0),
        ('roll_centre_height_front', math.nan),
        ('cog_height', math.inf),
    ],
)
def test_invalid_values_name_their_field(passenger_car: VehicleParams, field: str,
                                         value: float) -> None:
    with pytest.raises(ValueError, match=field):
        replace(passenger_car, **{field: value})


def test_unsprung_masses_must_leave_a_sprung_body(passenger_car: VehicleParams) -> None:
    with pytest.raises(ValueError, match='unsprung_mass'):
        replace(passenger_car, unsprung_mass_front=800.0, unsprung_mass_rear=700.0)


@pytest.mark.parametrize(
    ('change', 'field'),
    [
        ({'shape': 1.0}, 'tire_front.shape'),
        ({'shape': 2.2}, 'tire_front.shape'),
        ({'curvature': 1.0}, 'tire_front.curvature'),
        ({'fz0': 0.0}, 'tire_front.fz0'),
        ({'c0': -18.0}, 'tire_front'),
        ({'mu0': 0.0}, 'tire_front'),
    ],
)
def test_unusable_tires_are_rejected(passenger_car: VehicleParams, change: dict[str, float],
                                     field: str) -> None:
    with pytest.raises(ValueError, match=field):
        replace(passenger_car, tire_front=replace(passenger_car.tire_front, **change))


def test_sources_must_name_fields_and_are_frozen(passenger_car: VehicleParams) -> None:
    with pytest.raises(ValueError, match='sources'):
        replace(passenger_car, sources={'mass_kg': 'typo'})
    assert passenger_car.sources['mass'] == 'test fixture'
    with pytest.raises(TypeError):
        passenger_car.sources['mass'] = 'changed'  # type: ignore[index]
    with pytest.raises(FrozenInstanceError):
        passenger_car.mass = 1.0  # type: ignore[misc]


def test_sources_do_not_affect_equality(passenger_car: VehicleParams) -> None:
    assert replace(passenger_car, sources={}) == passenger_car
