# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Whole-vehicle quantities of a configuration that every rung needs.

Mass properties (sprung mass plus four unsprung masses), the design wheel
centres and the static wheel loads, computed from the configuration's
``mass``, ``geometry`` and ``<axle>_hardpoints`` groups. The analytical
models, the K&C rig (its corner load) and the full vehicle (its settled
state) all take them from here, so the rungs agree on them by construction.

Frame: the vd vehicle frame of ISO 8855 (x forward, y left, z up), SI units.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from vd_data_server.model import Configuration
from vd_solvers.constants import STANDARD_GRAVITY

#: axles in the order of :func:`wheel_centres` (each left, then right)
AXLES = ('front', 'rear')


@dataclass(frozen=True)
class MassProperties:
    """Whole-vehicle mass properties: sprung mass plus four unsprung masses."""

    mass: float  # kg
    cog_x: float  # m, vehicle frame (negative: behind the front axle)
    cog_height: float  # m
    yaw_inertia: float  # kg*m^2 about the vehicle COG
    unsprung_front: float  # kg, both front corners
    unsprung_rear: float  # kg, both rear corners
    unsprung_height_front: float  # m, wheel-centre height
    unsprung_height_rear: float  # m
    front_axle_x: float  # m, front wheel-centre x (0 when the data follow the vd frame)

    @property
    def cog_to_front_axle(self) -> float:
        """Return a, m: from the front axle back to the COG."""
        return self.front_axle_x - self.cog_x


def wheel_centres(config: Configuration) -> np.ndarray:
    """
    Return the design wheel centres FL, FR, RL, RR (4, 3), m.

    From the left-side ``points.wheel_centre`` of each axle's hard points,
    mirrored for the right wheel.
    """
    centres = []
    for axle in AXLES:
        x, y, z = config.group(f'{axle}_hardpoints').point('points.wheel_centre')
        centres += [(x, abs(y), z), (x, -abs(y), z)]
    return np.array(centres, dtype=float)


def mass_properties(config: Configuration) -> MassProperties:
    """
    Return the mass properties: the sprung mass and the unsprung masses at the wheel centres.

    Combined with the parallel-axis theorem for the yaw inertia.
    """
    mass = config.group('mass')
    m_s = mass.scalar('sprung_mass')
    x_s, y_s, z_s = mass.point('sprung_cog')
    m_uf = 2.0 * mass.scalar('unsprung_mass_front')
    m_ur = 2.0 * mass.scalar('unsprung_mass_rear')
    centres = wheel_centres(config)
    x_uf, y_uf, z_uf = (float(v) for v in centres[0])
    x_ur, y_ur, z_ur = (float(v) for v in centres[2])
    m = m_s + m_uf + m_ur
    # unsprung masses at the wheel centres (left and right: their mean y is zero)
    x_g = (m_s * x_s + m_uf * x_uf + m_ur * x_ur) / m
    y_g = m_s * y_s / m
    z_g = (m_s * z_s + m_uf * z_uf + m_ur * z_ur) / m
    izz = (mass.scalar('sprung_inertia.izz') + m_s * ((x_s - x_g) ** 2 + (y_s - y_g) ** 2)
           + m_uf * ((x_uf - x_g) ** 2 + y_uf ** 2 + y_g ** 2)
           + m_ur * ((x_ur - x_g) ** 2 + y_ur ** 2 + y_g ** 2))
    return MassProperties(m, x_g, z_g, izz, m_uf, m_ur, z_uf, z_ur, x_uf)


def static_wheel_loads(config: Configuration) -> tuple[float, float]:
    """Return the static vertical load of one front and one rear wheel, N."""
    mp = mass_properties(config)
    wheelbase = config.group('geometry').scalar('wheelbase')
    a = mp.cog_to_front_axle
    weight = mp.mass * STANDARD_GRAVITY
    return weight * (wheelbase - a) / wheelbase / 2.0, weight * a / wheelbase / 2.0
