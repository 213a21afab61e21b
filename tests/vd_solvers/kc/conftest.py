# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
K&C fixtures built from Project Chrono's vehicle data.

The data (BSD-3, (c) 2016 Project Chrono Development Team) is copied from
/work/shared/reference-data/chrono/ -- not read at test time.

Chrono gives left-side hard points (m) in each suspension's frame, placed at
the vehicle file's "Suspension Location"; the rig frame here has its origin
on the ground under the front axle centre (x forward, y left, z up), so
rig = suspension + location - origin with origin = (front wheel-centre x,
0, front wheel-centre z - loaded radius).

Generic vehicle (generic__vehicle__Vehicle_MacPhersonStruts.json and
..._MultiLinks.json): front axle at [1.25, 0, -0.21], rear at [-1.25, 0,
-0.21]; we pair the MacPherson front (generic__suspension__MacPhersonStrut)
with the multi-link rear (generic__suspension__MultiLink). Chassis
(generic__chassis__Chassis.json): 2086.52 kg, centre of mass at x = 0.056.
Tire (generic__tire__Generic_Pac02Tire.tir): unloaded radius 0.4699 m,
vertical stiffness 1e6 N/m.

Fixture choices where Chrono has no number (stated so they can be judged):

* Spring preload: Chrono's free lengths leave the generic MacPherson spring
  in tension at design (0.306 m free vs 0.340 m installed), so the generic
  axles use the solver's trim: preload such that the design pad load equals
  the corner load.
* Bump stop: 60 mm clearance on the damper length, progressive 0-10 kN over
  30 mm; rebound stop 70 mm, 0-8 kN over 20 mm (typical passenger-car stops).
* Anti-roll bars: Chrono's generic AntirollBarRSD torsional stiffness
  (10000 N*m/rad); the generic vehicles carry no bar, so the bar geometry
  (axis, 0.25 m arms, 0.12 m vertical drop links) is ours.
* Steering: Chrono's RackPinion travel limit (pinion radius 0.1 m x 30 deg =
  52.4 mm); Chrono steers the pinion directly, so the steering-wheel ratio is
  a typical 50 mm of rack per steering-wheel turn (0.00796 m/rad).
"""
from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import replace

import numpy as np
import pytest

from vd_solvers.kc.model import (
    Bushing,
    Curve,
    SpringSpec,
    StabilizerSpec,
    SteeringSpec,
    StopSpec,
    SuspensionInput,
)

G = 9.80665
TIRE_UNLOADED_RADIUS = 0.4699  # m, generic__tire__Generic_Pac02Tire.tir
TIRE_STIFFNESS = 1e6  # N/m, same file
CHASSIS_MASS = 2086.52  # kg, generic__chassis__Chassis.json
CHASSIS_CG_X = 0.056  # m, vehicle frame, same file

# generic__suspension__MacPhersonStrut.json, suspension frame.
MACPHERSON = {
    'lca_front': [0.220, 0.520, -0.156],
    'lca_rear': [-0.300, 0.507, -0.137],
    'lca_outer': [-0.02165371, 0.94057703, -0.17402826],
    'tierod_inner': [-0.300, 0.520, -0.059],
    'tierod_outer': [-0.2373756, 0.89495045, -0.01605418],
    'strut_top': [-0.115, 0.785, 0.579],  # "Spring" / "Shock" Location Chassis
    'strut_lower': [-0.07402507, 0.8532915, 0.2484536],  # Location Upright
    'wheel_centre': [-0.04000403, 1.09999965, -0.02602507],  # Spindle COM
    # ours: drop link on the upright, bar ahead of the axle
    'arb_link_lower': [-0.030, 0.860, 0.100],
    'arb_link_upper': [-0.030, 0.860, 0.220],
    'arb_pivot': [0.220, 0.450, 0.220],
}
# kg (spindle as wheel)
MACPHERSON_MASSES = {'upright': 20.0, 'lca': 5.091, 'strut': 5.0, 'wheel': 1.103}
MACPHERSON_SPRING_RATE = 369149.0  # N/m

# generic__suspension__MultiLink.json, suspension frame.
MULTILINK = {
    'upper_front': [0.060, 0.547, 0.082],
    'upper_rear': [-0.157, 0.508, 0.062],
    'upper_outer': [0.056, 0.864, 0.151],
    'lateral_inner': [0.036, 0.338, -0.133],
    'lateral_outer': [0.029, 0.842, -0.093],
    'trailing_inner': [0.723, 0.599, -0.072],
    'trailing_outer': [-0.000, 0.864, -0.156],
    'tierod_inner': [-0.257, 0.320, -0.116],
    'tierod_outer': [-0.144, 0.862, -0.056],
    'spring_upper': [0.181, 0.641, 0.110],
    'spring_lower': [0.181, 0.669, -0.164],
    'damper_upper': [0.171, 0.628, 0.315],
    'damper_lower': [0.181, 0.669, -0.162],
    'wheel_centre': [0.000, 0.950, 0.000],
    # ours: drop link on the trailing link, bar ahead of the axle
    'arb_link_lower': [0.250, 0.680, -0.140],
    'arb_link_upper': [0.250, 0.680, -0.020],
    'arb_pivot': [0.500, 0.450, -0.020],
}
# Chrono's universal joint of the trailing link: (chassis axis, link axis).
MULTILINK_TRAILING_CROSS = ([-0.272, 0.962, 0.0], [0.0, 0.0, 1.0])
MULTILINK_MASSES = {
    'upright': 3.201,
    'upper_arm': 4.744,
    'trailing_link': 15.204,
    'lateral_link': 1.910,
    'wheel': 1.103,
}
MULTILINK_SPRING_RATE = 120000.0  # N/m

# generic__suspension__DoubleWishbone.json, suspension frame.
DOUBLE_WISHBONE = {
    'uca_front': [0.160, 0.539, 0.243],
    'uca_rear': [-0.339, 0.587, 0.249],
    'uca_outer': [-0.088, 0.808, 0.243],
    'lca_front': [0.199, 0.479, -0.206],
    'lca_rear': [-0.279, 0.539, -0.200],
    'lca_outer': [-0.040, 0.898, -0.265],
    'tierod_inner': [-0.279, 0.479, -0.026],
    'tierod_outer': [-0.220, 0.898, -0.026],
    'spring_upper': [-0.064, 0.659, 0.094],
    'spring_lower': [-0.040, 0.718, -0.206],
    'damper_upper': [-0.088, 0.599, 0.393],
    'damper_lower': [-0.040, 0.718, -0.206],
    'wheel_centre': [-0.040, 1.100, -0.026],
    # ours: drop link on the lower arm
    'arb_link_lower': [0.050, 0.760, -0.200],
    'arb_link_upper': [0.050, 0.760, -0.080],
    'arb_pivot': [0.300, 0.450, -0.080],
}
DOUBLE_WISHBONE_MASSES = {'upright': 19.450, 'lca': 23.965, 'uca': 5.813, 'wheel': 14.705}
DOUBLE_WISHBONE_SPRING = SpringSpec(rate=369149.0, free_length=0.339)

# hmmwv__suspension__HMMWV_DoubleWishboneFront_bushings.json, suspension frame;
# vehicle hmmwv__vehicle__HMMWV_Vehicle.json: front at [1.688965, 0, 0].
HMMWV_FRONT = {
    'uca_front': [-0.048, 0.446, 0.245],
    'uca_rear': [-0.268, 0.478, 0.196],
    'uca_outer': [-0.053, 0.716, 0.215],
    'lca_front': [0.223, 0.307, 0.000],
    'lca_rear': [-0.223, 0.307, 0.000],
    'lca_outer': [-0.036, 0.787, -0.118],
    'tierod_inner': [-0.250, 0.448, 0.054],
    'tierod_outer': [-0.176, 0.821, -0.016],
    'spring_upper': [0.104, 0.510, 0.197],
    'spring_lower': [0.097, 0.543, -0.047],
    'damper_upper': [0.104, 0.498, 0.323],
    'damper_lower': [0.097, 0.543, -0.047],
    'wheel_centre': [-0.040, 0.910, -0.026],
}
HMMWV_LOCATION = [1.688965, 0.0, 0.0]
HMMWV_MASSES = {
    'upright': 19.450,
    'lca': 23.965,
    'uca': 5.813,
    'wheel': 14.705 + 18.8,
    'tierod': 6.0,
}
# Spring Curve Data (deflection m, force N) and free length.
HMMWV_SPRING_CURVE = Curve(
    np.array([-0.2, -0.18, -0.16, -0.14, -0.12, -0.1, -0.08, -0.06, -0.04, -0.02, 0.0,
              0.02, 0.04, 0.06, 0.08, 0.1, 0.12, 0.14, 0.16, 0.18, 0.2]),
    np.array([-322095.536, -240521.166, -174535.686, -122406.996, -82402.997, -52791.592,
              -31840.681, -17818.165, -8991.945, -3629.923, 0.0, 3629.923, 8991.945,
              17818.165, 31840.681, 52791.592, 82402.997, 122406.996, 174535.686,
              240521.166, 322095.536]),
)
HMMWV_FREE_LENGTH = 0.339
# Bushing Data: linear 7e7 N/m, rotational 1e5 N*m/rad, free ("DOF" 0) about
# the arm's pivot axis -- here the bushing's axial (z) direction.
HMMWV_BUSHING_LINEAR = 7e7
HMMWV_BUSHING_ROTATIONAL = 1e5

GENERIC_FRONT_LOCATION = [1.25, 0.0, -0.21]
GENERIC_REAR_LOCATION = [-1.25, 0.0, -0.21]


def _unsprung(masses: Mapping[str, float], halves: tuple[str, ...]) -> float:
    """Unsprung weight per corner (N): arms and links count half."""
    return G * sum(m * (0.5 if name in halves else 1.0) for name, m in masses.items())


def _generic_loads() -> tuple[float, float, float]:
    """Front and rear corner loads (N) and the wheelbase (m) of the pairing."""
    x_front = GENERIC_FRONT_LOCATION[0] + MACPHERSON['wheel_centre'][0]
    x_rear = GENERIC_REAR_LOCATION[0] + MULTILINK['wheel_centre'][0]
    wheelbase = x_front - x_rear
    front_share = (CHASSIS_CG_X - x_rear) / wheelbase
    sprung = CHASSIS_MASS * G
    front = 0.5 * front_share * sprung + _unsprung(MACPHERSON_MASSES, ('lca', 'strut'))
    rear = 0.5 * (1 - front_share) * sprung + _unsprung(
        MULTILINK_MASSES, ('upper_arm', 'trailing_link', 'lateral_link')
    )
    return front, rear, wheelbase


FRONT_LOAD, REAR_LOAD, GENERIC_WHEELBASE = _generic_loads()
FRONT_RADIUS = TIRE_UNLOADED_RADIUS - FRONT_LOAD / TIRE_STIFFNESS
REAR_RADIUS = TIRE_UNLOADED_RADIUS - REAR_LOAD / TIRE_STIFFNESS
GENERIC_ORIGIN = np.array(
    [
        GENERIC_FRONT_LOCATION[0] + MACPHERSON['wheel_centre'][0],
        0.0,
        GENERIC_FRONT_LOCATION[2] + MACPHERSON['wheel_centre'][2] - FRONT_RADIUS,
    ]
)


def rig_points(
    points: Mapping[str, list[float]], location: list[float], origin: np.ndarray
) -> dict[str, np.ndarray]:
    """Suspension-frame points moved into the rig frame."""
    return {k: np.array(v, dtype=float) + np.array(location) - origin for k, v in points.items()}


BUMP_STOP = StopSpec(
    0.060, Curve(np.array([0.0, 0.01, 0.02, 0.03]), np.array([0.0, 1000.0, 4000.0, 10000.0]))
)
REBOUND_STOP = StopSpec(0.070, Curve(np.array([0.0, 0.01, 0.02]), np.array([0.0, 2000.0, 8000.0])))
ARB = StabilizerSpec(torsional_stiffness=10000.0)  # generic__antirollbar__AntirollBarRSD.json
STEERING = SteeringSpec(rack_ratio=0.05 / (2 * np.pi), rack_travel_limit=0.1 * np.radians(30.0))


def macpherson_front_input(**overrides: object) -> SuspensionInput:
    """Chrono generic MacPherson as the front axle, with rack, bar and stops."""
    inp = SuspensionInput(
        template='macpherson',
        axle='front',
        hardpoints=rig_points(MACPHERSON, GENERIC_FRONT_LOCATION, GENERIC_ORIGIN),
        spring=SpringSpec(rate=MACPHERSON_SPRING_RATE),
        tire_radius=FRONT_RADIUS,
        tire_vertical_stiffness=TIRE_STIFFNESS,
        corner_load=FRONT_LOAD,
        bump_stop=BUMP_STOP,
        rebound_stop=REBOUND_STOP,
        stabilizer=ARB,
        steering=STEERING,
        masses=MACPHERSON_MASSES,
    )
    return replace(inp, **overrides)  # type: ignore[arg-type]


def multilink_rear_input(**overrides: object) -> SuspensionInput:
    """Chrono generic multi-link as the rear axle, with bar and stops."""
    inp = SuspensionInput(
        template='multilink',
        axle='rear',
        hardpoints=rig_points(MULTILINK, GENERIC_REAR_LOCATION, GENERIC_ORIGIN),
        spring=SpringSpec(rate=MULTILINK_SPRING_RATE),
        tire_radius=REAR_RADIUS,
        tire_vertical_stiffness=TIRE_STIFFNESS,
        corner_load=REAR_LOAD,
        bump_stop=BUMP_STOP,
        rebound_stop=REBOUND_STOP,
        stabilizer=ARB,
        masses=MULTILINK_MASSES,
        joint_axes={'trailing_inner': tuple(np.array(v) for v in MULTILINK_TRAILING_CROSS)},
    )
    return replace(inp, **overrides)  # type: ignore[arg-type]


def double_wishbone_input(**overrides: object) -> SuspensionInput:
    """
    Build the Chrono generic double wishbone as a rear axle at the generic rear location.

    Free length from Chrono, no bar.
    """
    inp = SuspensionInput(
        template='double_wishbone',
        axle='rear',
        hardpoints=rig_points(DOUBLE_WISHBONE, GENERIC_REAR_LOCATION, GENERIC_ORIGIN),
        spring=DOUBLE_WISHBONE_SPRING,
        tire_radius=REAR_RADIUS,
        tire_vertical_stiffness=TIRE_STIFFNESS,
        corner_load=REAR_LOAD,
        masses=DOUBLE_WISHBONE_MASSES,
    )
    return replace(inp, **overrides)  # type: ignore[arg-type]


def hmmwv_front_input(with_bushings: bool = True, **overrides: object) -> SuspensionInput:
    """HMMWV front double wishbone with Chrono's arm bushings (or ideal joints)."""
    radius = TIRE_UNLOADED_RADIUS - 6000.0 / TIRE_STIFFNESS  # hmmwv__tire__HMMWV_Pac02Tire.tir
    origin = np.array(
        [
            HMMWV_LOCATION[0] + HMMWV_FRONT['wheel_centre'][0],
            0.0,
            HMMWV_FRONT['wheel_centre'][2] - radius,
        ]
    )
    points = rig_points(HMMWV_FRONT, HMMWV_LOCATION, origin)
    arm_bushings: dict[str, Bushing] = {}
    if with_bushings:
        k, kr = HMMWV_BUSHING_LINEAR, HMMWV_BUSHING_ROTATIONAL
        for arm in ('uca', 'lca'):
            axis = points[f'{arm}_rear'] - points[f'{arm}_front']
            for end in ('front', 'rear'):
                arm_bushings[f'{arm}_{end}'] = Bushing((k, k, k, kr, kr, 0.0), axial=axis)
    inp = SuspensionInput(
        template='double_wishbone',
        axle='front',
        hardpoints=points,
        spring=SpringSpec(curve=HMMWV_SPRING_CURVE, free_length=HMMWV_FREE_LENGTH),
        tire_radius=radius,
        tire_vertical_stiffness=TIRE_STIFFNESS,
        corner_load=6000.0,  # N: 2086.52 kg x 51.8 % front / 2 + 71 kg unsprung, rounded
        bushings=arm_bushings,
        masses=HMMWV_MASSES,
    )
    return replace(inp, **overrides)  # type: ignore[arg-type]


InputFactory = Callable[..., SuspensionInput]


@pytest.fixture(scope='session')
def macpherson_front() -> InputFactory:
    return macpherson_front_input


@pytest.fixture(scope='session')
def multilink_rear() -> InputFactory:
    return multilink_rear_input


@pytest.fixture(scope='session')
def double_wishbone() -> InputFactory:
    return double_wishbone_input


@pytest.fixture(scope='session')
def hmmwv_front() -> InputFactory:
    return hmmwv_front_input


@pytest.fixture(scope='session')
def generic_wheelbase() -> float:
    return GENERIC_WHEELBASE
