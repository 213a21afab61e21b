# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Build the analytical models' parameters from a resolved configuration.

What the data describes in more detail than the simple models need is
derived here, and every value says where it came from (``VehicleParams.sources``):

* mass, COG and yaw inertia: the sprung mass (mass group) plus four unsprung
  masses at the wheel centres (hard points), combined with the parallel-axis
  theorem (``vd_solvers/vehicle_data.py``, shared by every rung);
* tracks and wheelbase: geometry group; unsprung COG height: wheel-centre height;
* per-axle tire (thesis eqs. 6-9): fitted to the .tir Magic Formula over
  FIT_RANGE times the static wheel load of that axle (``tire/fit.py``); the tire's
  vertical stiffness (.tir VERTICAL_STIFFNESS) for the axles' roll on their tires;
  the wheels' spin inertia over their rolling radius for their gyroscopic roll moment
  (SPIN_INERTIA_FACTOR m_corner R0^2, the full vehicle's);
* roll stiffness and roll-centre heights: the design targets of the targets
  group, unless K&C results of the same configuration are passed in
  (``suspension``), which then win and are labelled as such;
* per-axle compliance steer, roll steer and camber (``compliance``, from the
  K&C results, see ``kc_link.py``); without them the axles are rigid and
  every compliance term of the understeer budget says "bare tire".
"""
from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from vd_data_server.model import Configuration
from vd_data_server.tire_group import tire_properties
from vd_solvers.analytical.budget import BARE_TIRE
from vd_solvers.analytical.cornering import CorneringVehicle
from vd_solvers.analytical.kc_link import AxleSuspension
from vd_solvers.analytical.params import SPIN_INERTIA_FACTOR, AxleCompliance, VehicleParams
from vd_solvers.kc.steering_map import steering_map
from vd_solvers.tire.fit import fit_simple_tire
from vd_solvers.tire.magic_formula import MagicFormula
from vd_solvers.tire.simple import SimpleTire
from vd_solvers.vehicle_data import mass_properties, static_wheel_loads

#: load range of the simple-tire fit, as fractions of the static wheel load
FIT_RANGE = (0.2, 1.8)


def vehicle_params(config: Configuration,
                   suspension: Mapping[str, AxleSuspension] | None = None,
                   compliance: Mapping[str, AxleCompliance] | None = None) -> VehicleParams:
    mass = config.group('mass')
    geo = config.group('geometry')
    targets = config.group('targets')
    wheelbase = geo.scalar('wheelbase')
    mp = mass_properties(config)
    m, z_g, izz = mp.mass, mp.cog_height, mp.yaw_inertia
    m_uf, m_ur, z_uf, z_ur = (mp.unsprung_front, mp.unsprung_rear, mp.unsprung_height_front,
                              mp.unsprung_height_rear)
    t_f, t_r = geo.scalar('track_front'), geo.scalar('track_rear')
    a = mp.cog_to_front_axle
    fz_front, fz_rear = static_wheel_loads(config)
    tire_front, src_tf = _fit(config, 'front_tire', fz_front)
    tire_rear, src_tr = _fit(config, 'rear_tire', fz_rear)
    mf_f, mf_r = (MagicFormula(tire_properties(config.group(g)))
                  for g in ('front_tire', 'rear_tire'))
    c_zf, c_zr = mf_f.vertical_stiffness, mf_r.vertical_stiffness
    gyro = [SPIN_INERTIA_FACTOR * mass.scalar(f'unsprung_mass_{axle}') * mf.unloaded_radius**2
            / float(mf.radii(fz)[1])
            for axle, mf, fz in (('front', mf_f, fz_front), ('rear', mf_r, fz_rear))]
    mass_src = f'{mass.file} (sprung) + unsprung masses at the wheel centres'
    sources = {
        'mass': mass_src, 'cog_to_front_axle': mass_src, 'cog_height': mass_src,
        'yaw_inertia': f'{mass.file} sprung_inertia.izz + parallel-axis unsprung terms',
        'wheelbase': geo.file, 'track_front': geo.file, 'track_rear': geo.file,
        'tire_front': src_tf, 'tire_rear': src_tr,
        'tire_vertical_stiffness_front': (f"{config.group('front_tire').text('file')} "
                                          'VERTICAL_STIFFNESS'),
        'tire_vertical_stiffness_rear': (f"{config.group('rear_tire').text('file')} "
                                         'VERTICAL_STIFFNESS'),
        'wheel_gyroscopic_front': (f'{SPIN_INERTIA_FACTOR} unsprung_mass_front R0^2 over the '
                                   'effective rolling radius (the data have no wheel inertia)'),
        'wheel_gyroscopic_rear': (f'{SPIN_INERTIA_FACTOR} unsprung_mass_rear R0^2 over the '
                                  'effective rolling radius (the data have no wheel inertia)'),
        'unsprung_mass_front': mass.file, 'unsprung_mass_rear': mass.file,
        'unsprung_cog_height_front': 'front_hardpoints wheel_centre z',
        'unsprung_cog_height_rear': 'rear_hardpoints wheel_centre z',
    }
    roll: dict[str, float] = {}
    for axle in ('front', 'rear'):
        kc = (suspension or {}).get(axle)
        if kc is not None:
            roll[f'roll_stiffness_{axle}'] = kc.roll_stiffness
            roll[f'roll_centre_height_{axle}'] = kc.roll_centre_height
            sources[f'roll_stiffness_{axle}'] = kc.source
            sources[f'roll_centre_height_{axle}'] = kc.source
        else:
            for key in (f'roll_stiffness_{axle}', f'roll_centre_height_{axle}'):
                roll[key] = targets.scalar(key)
                sources[key] = f'design target {targets.values[key].source}'
    comp: dict[str, AxleCompliance] = {}
    for axle in ('front', 'rear'):
        given = (compliance or {}).get(axle)
        comp[f'compliance_{axle}'] = given if given is not None else AxleCompliance()
        sources[f'compliance_{axle}'] = (
            '; '.join(dict.fromkeys(given.sources.values())) if given is not None and given.sources
            else BARE_TIRE)
    return VehicleParams(
        mass=m, wheelbase=wheelbase, cog_to_front_axle=a, track_front=t_f, track_rear=t_r,
        cog_height=z_g, yaw_inertia=izz, tire_front=tire_front, tire_rear=tire_rear,
        unsprung_mass_front=m_uf, unsprung_mass_rear=m_ur,
        unsprung_cog_height_front=z_uf, unsprung_cog_height_rear=z_ur, sources=sources,
        roll_stiffness_front=roll['roll_stiffness_front'],
        roll_stiffness_rear=roll['roll_stiffness_rear'],
        roll_centre_height_front=roll['roll_centre_height_front'],
        roll_centre_height_rear=roll['roll_centre_height_rear'],
        compliance_front=comp['compliance_front'], compliance_rear=comp['compliance_rear'],
        tire_vertical_stiffness_front=c_zf, tire_vertical_stiffness_rear=c_zr,
        wheel_gyroscopic_front=gyro[0], wheel_gyroscopic_rear=gyro[1])


def _fit(config: Configuration, group: str, fz_static: float) -> tuple[SimpleTire, str]:
    props = tire_properties(config.group(group))
    low, high = FIT_RANGE[0] * fz_static, FIT_RANGE[1] * fz_static
    tire = fit_simple_tire(MagicFormula(props), (low, high))
    return tire, (f"{config.group(group).text('file')} Magic Formula fitted over "
                  f"{low:.0f}..{high:.0f} N")


def cornering_vehicle(config: Configuration, p: VehicleParams,
                      drive_front: float = 0.5) -> CorneringVehicle:
    """
    Return the wheel-by-wheel steady-state model of ``config`` (:mod:`.cornering`).

    ``p`` from :func:`vehicle_params` (with the K&C results); the Magic Formula of each
    axle's .tir, the alignment groups' toe and camber, the K&C steering map.
    """
    tires = tuple(MagicFormula(tire_properties(config.group(f'{axle}_tire')))
                  for axle in ('front', 'rear'))
    toe, camber = [], []
    for axle in ('front', 'rear'):
        align = config.group(f'{axle}_alignment')
        toe += [align.scalar('toe')] * 2
        camber += [align.scalar('camber')] * 2
    return CorneringVehicle(params=p, tires=(tires[0], tires[1]), toe=np.array(toe),
                            camber=np.array(camber), steering=steering_map(config),
                            drive_front=drive_front)
