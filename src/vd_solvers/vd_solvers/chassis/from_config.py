# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The chassis systems of a configuration: its ``brakes``, ``driveline`` and ``aero`` groups.

Each group is optional; a configuration without one gets ``None`` for it and the full
vehicle keeps its fixed torque shares (:func:`vd_solvers.vehicle.drivers.wheel_torques`)
and no aerodynamic force. The groups' keys are documented in docs/data-format.md.
"""
from __future__ import annotations

from dataclasses import dataclass
import math

import numpy as np

from vd_data_server.model import Configuration, GroupData
from vd_solvers.errors import SolverError

from .aero import Aero
from .antilock import AntiLock
from .brakes import BrakeSystem, Caliper
from .driveline import Differential, Driveline, Engine

#: front share of the drive torque of each layout but AWD (whose share is data)
LAYOUT_SHARE = {'FWD': 1.0, 'RWD': 0.0}


@dataclass(frozen=True)
class Chassis:
    """The brakes (with their anti-lock option), driveline and aerodynamics of a vehicle."""

    brakes: BrakeSystem | None = None
    anti_lock: AntiLock | None = None  # None: no anti-lock brakes
    driveline: Driveline | None = None
    shift_speed: float = math.inf  # rad/s engine speed of a full-throttle upshift
    aero: Aero | None = None


def _caliper(group: GroupData, axle: str) -> Caliper:
    return Caliper(piston_diameter=group.scalar(f'{axle}.piston_diameter'),
                   pistons=int(round(group.scalar(f'{axle}.pistons'))),
                   pad_friction=group.scalar(f'{axle}.pad_friction'),
                   effective_radius=group.scalar(f'{axle}.effective_radius'))


def _differential(group: GroupData, axle: str) -> Differential:
    base = f'{axle}_differential'
    if not group.has(f'{base}.type'):
        return Differential()
    return Differential(kind=group.text(f'{base}.type'),
                        locking_torque=group.scalar(f'{base}.locking_torque'),
                        lock_damping=group.scalar(f'{base}.lock_damping'))


def chassis_systems(config: Configuration) -> Chassis:
    """Build the :class:`Chassis` of ``config`` (a SolverError names the group's file)."""
    brakes = anti_lock = driveline = aero = None
    shift = math.inf
    groups = config.groups
    try:
        if 'brakes' in groups:
            g = groups['brakes']
            brakes = BrakeSystem(
                front=_caliper(g, 'front'), rear=_caliper(g, 'rear'),
                knee_pressure=g.get_scalar('knee_pressure') or math.inf,
                knee_slope=g.scalar('knee_slope'),
                master_diameter=g.scalar('master_cylinder_diameter'),
                pedal_ratio=g.scalar('pedal_ratio'), booster_gain=g.scalar('booster_gain'))
            if g.has('anti_lock') and g.text('anti_lock') == 'all_wheels':
                anti_lock = AntiLock(dump_slip=g.scalar('abs_dump_slip'),
                                     build_slip=g.scalar('abs_build_slip'))
        if 'driveline' in groups:
            g = groups['driveline']
            speeds, torques = g.curve('engine_torque')
            layout = g.text('layout')
            share = LAYOUT_SHARE[layout] if layout in LAYOUT_SHARE else g.scalar('front_share')
            driveline = Driveline(
                engine=Engine(np.array(speeds), np.array(torques)),
                gears=tuple(float(r) for r in g.curve('gears')[1]),
                final_drive=g.scalar('final_drive'), efficiency=g.scalar('efficiency'),
                front_share=share, front=_differential(g, 'front'),
                rear=_differential(g, 'rear'), inertia=g.scalar('inertia'))
            shift = g.get_scalar('shift_speed') or float(speeds[-1])
        if 'aero' in groups:
            g = groups['aero']
            area = g.scalar('frontal_area')
            aero = Aero(drag_area=g.scalar('drag_coefficient') * area, frontal_area=area,
                        lift_front=g.scalar('lift_coefficient_front'),
                        lift_rear=g.scalar('lift_coefficient_rear'),
                        density=g.scalar('air_density'))
    except (ValueError, KeyError) as err:
        raise SolverError(f"configuration '{config.name}': {err}") from err
    return Chassis(brakes, anti_lock, driveline, shift, aero)


__all__ = ['Chassis', 'chassis_systems', 'LAYOUT_SHARE']
