# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
A mid-size passenger car for the analytical models.

Numbers and why they are sane:

* 1500 kg, wheelbase 2.7 m, 58/42 front/rear static weight, COG 0.55 m,
  tracks 1.55 m: a front-engined compact/mid-size saloon.
* Roll stiffness 60/40 kN*m/rad front/rear with roll centres 0.05/0.10 m:
  roll gradient ~4.1 deg/g, mid-range for passenger cars (3-7 deg/g).
* Unsprung 80/70 kg per axle at the wheel-centre height 0.31 m.
* I_zz = 2500 kg*m^2, about 0.94 m a b (yaw radius of gyration near the
  geometric mean of a and b, typical of saloons).
* Tire: C_a = 18/rad * Fz at 4 kN, i.e. 72 kN/rad (0.31/deg); the load
  sensitivity c1 = 5e-5/N puts the C_a(Fz) maximum at 12 kN, far above the
  wheel loads, so C_a stays increasing and concave; mu falls by 0.02 per kN
  (mu1 = 2e-5/N); C = 1.3 and E = -0.5 peak near 8.8 deg of slip.
"""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace

import pytest

from vd_solvers.analytical.params import VehicleParams
from vd_solvers.tire.simple import SimpleTire

TIRE = SimpleTire(
    mu0=1.0,
    mu1=2e-5,
    fz0=4000.0,
    c0=18.0,
    c1=5e-5,
    shape=1.3,
    curvature=-0.5,
    source='test fixture: generic 205/55 R16 passenger tire',
)

WHEELBASE = 2.7

CarFactory = Callable[..., VehicleParams]


def build_car(front_share: float = 0.58, **overrides: object) -> VehicleParams:
    """Build the fixture car with ``front_share`` of its weight on the front axle."""
    car = VehicleParams(
        mass=1500.0,
        wheelbase=WHEELBASE,
        cog_to_front_axle=(1.0 - front_share) * WHEELBASE,
        track_front=1.55,
        track_rear=1.55,
        cog_height=0.55,
        roll_centre_height_front=0.05,
        roll_centre_height_rear=0.10,
        roll_stiffness_front=60000.0,
        roll_stiffness_rear=40000.0,
        yaw_inertia=2500.0,
        tire_front=TIRE,
        tire_rear=TIRE,
        unsprung_mass_front=80.0,
        unsprung_mass_rear=70.0,
        unsprung_cog_height_front=0.31,
        unsprung_cog_height_rear=0.31,
        sources={'mass': 'test fixture', 'tire_front': TIRE.source, 'tire_rear': TIRE.source},
    )
    return replace(car, **overrides)


@pytest.fixture
def make_car() -> CarFactory:
    return build_car


@pytest.fixture
def passenger_car() -> VehicleParams:
    return build_car()


@pytest.fixture
def oversteering_car() -> VehicleParams:
    """Return the same car, 40/60 rear-heavy: the load-sensitive tires make it oversteer."""
    return build_car(front_share=0.40, roll_stiffness_front=45000.0, roll_stiffness_rear=55000.0)
