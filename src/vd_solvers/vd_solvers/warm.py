# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Build the compiled-code cache at setup: ``python -m vd_solvers.warm`` (``make setup`` runs it).

Every compiled function of the full-vehicle step, of the brakes, anti-lock brakes and
driveline (as their classes and the actuation of a step call them) and of the Magic
Formula's public methods is called once with the argument types a run passes (contiguous
float vectors, floats, bools), with the bundled sample tires, so numba writes its cache
(:mod:`vd_solvers.compiled`) and the first ``vd run`` after setup loads machine code instead
of compiling it. No K&C solve is needed: the suspension maps are stand-ins of the right
shapes, the tires are real; the K&C
solver's compiled parts are called through one evaluation of the sample axle's tangent.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from vd_data_server.paths import default_master
from vd_data_server.study import load_study
from vd_data_server.tire_group import tire_properties
from vd_solvers import compiled
from vd_solvers.chassis.antilock import controller_step
from vd_solvers.chassis.brakes import master_pressure_for_torque, rear_line_pressure
from vd_solvers.chassis.driveline import (
    available_torque,
    choose_gear,
    drive_torques,
    driven_speed,
    engine_speed,
    engine_torque,
    inertia_torque,
    split,
)
from vd_solvers.kc.from_config import build_kc_model
from vd_solvers.kc.system import LoadCase
from vd_solvers.tire.magic_formula import MagicFormula, relaxation_at
from vd_solvers.vehicle import adaptive, dynamics
from vd_solvers.vehicle.drivers import (
    ACTUATION_STATE,
    ActuationArrays,
    actuate,
    speed_law,
    wheel_torques,
)
from vd_solvers.vehicle.forces import (
    AERO_ROWS,
    COMPLIANCE_ROWS,
    CONSTANT_ROWS,
    VehicleArrays,
    vehicle_forces,
    wheel_radii,
    wheel_tires,
)
from vd_solvers.vehicle.maps import GRID_POINTS, TRAVEL_ROWS, grid_lookup, half_difference


def _tire(mf: MagicFormula) -> None:
    fz = np.array([1000.0, 4000.0, 8000.0])
    slip = np.array([-0.1, 0.0, 0.1])
    mf.fy(fz, slip, slip)
    mf.fx(fz, slip, slip)
    mf.cornering_stiffness(fz, slip)
    mf.slip_stiffness(fz)
    mf.peak_lateral_friction(fz, slip)
    mf.lateral_curvature(fz, slip, slip)
    mf.steady_state(fz, slip, slip, slip, fz)
    mf.pneumatic_trail(fz, slip)
    mf.relaxation_lengths(fz, slip)
    if mf.vertical_stiffness > 0.0:
        mf.radii(fz)
        mf.loaded_radius(fz)
        mf.deflection(fz, slip)
        mf.vertical_force(slip, slip, slip, slip, slip)


def _vehicle(front: np.ndarray, rear: np.ndarray) -> None:
    grid = np.linspace(-0.1, 0.1, GRID_POINTS)
    ones, zeros = np.ones(4), np.zeros(4)
    travel = np.broadcast_to(grid, (len(TRAVEL_ROWS), 4, GRID_POINTS)).copy()
    curve = np.array([-1.0, 0.0, 1.0])
    wheel = np.ones((len(CONSTANT_ROWS), 4))
    arrays = VehicleArrays(
        centres=np.array([[0.0, 0.8, 0.3], [0.0, -0.8, 0.3], [-2.8, 0.8, 0.3],
                          [-2.8, -0.8, 0.3]]),
        wheel=wheel, tire_front=front, tire_rear=rear, travel0=zeros - 0.1,
        travel_step=ones * (grid[1] - grid[0]), travel_table=travel, arb0=zeros - 0.1,
        arb_step=ones * (grid[1] - grid[0]), arb_table=travel[:1].copy(), roll0=zeros - 0.1,
        roll_step=ones * (grid[1] - grid[0]), roll_table=travel[:2].copy(),
        compliance=np.zeros((len(COMPLIANCE_ROWS), 4)), damper_front_x=curve,
        damper_front_y=curve, damper_rear_x=curve, damper_rear_y=curve, steer_swa=curve,
        steer_left=curve * 0.1, steer_right=curve * 0.1, aero=np.zeros(len(AERO_ROWS)),
        road_axes=np.array([0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 1.0, 1.0]),
        road_height=np.zeros((2, 2)), road_friction=np.array([[1.0, 0.5], [1.0, 0.5]]),
        cam=np.array([[0.3] * 4, [0.3] * 4, [1.8] * 4, [0.1] * 4]))
    q = np.zeros(15)
    q[6] = 1.0
    v = np.zeros(14)
    v[0] = 20.0
    for previous in (False, True):
        vehicle_forces(q, v, 0.1, zeros.copy(), np.zeros((2, 4)), np.zeros((4, 4)), previous,
                       0.005, arrays, 1.0, 1500.0, True, True)
    _dynamics(q, v, arrays)
    fz = np.full(4, 4000.0)
    wheel_radii(front, rear, fz)
    wheel_tires(front, rear, fz, zeros.copy(), zeros.copy(), zeros.copy(), fz, ones.copy(),
                ones.copy())
    relaxation_at(front, fz[:2], zeros[:2])
    z = zeros.copy()
    grid_lookup(travel, arrays.travel0, arrays.travel_step, z)
    half_difference(z)


def _dynamics(q: np.ndarray, v: np.ndarray, arrays: VehicleArrays) -> None:
    """Compile the step and loop of :mod:`vd_solvers.vehicle.dynamics` on a stand-in tree."""
    mb = dynamics.MultibodyArrays(body=np.diag([1000.0, 1000.0, 1000.0, 500.0, 2000.0, 2000.0]),
                                  offsets=arrays.centres.copy(), carrier_mass=np.full(4, 40.0),
                                  wheel_inertia=np.full((4, 2), 1.0),
                                  gravity=np.array([0.0, 0.0, -9.81]))
    zeros, ones = np.zeros(4), np.ones(4)
    dynamics.vehicle_step(q, v, 0.1, zeros.copy(), np.zeros((2, 4)), np.zeros((4, 4)), False,
                          0.005, arrays, 1.0, 1500.0, True, True, mb)
    dynamics.cosim_step(q.copy(), v.copy(), np.zeros((2, 4)), np.zeros((4, 4)), False,
                        np.zeros((9, 4)), np.zeros(dynamics.ROW_SIZE + 2), 0.1, 1.0, 0.0, 0.5,
                        0.65, 0.005, 0.005, arrays, 1.0, 1500.0, True, True, mb, np.zeros(3))
    dynamics.observation(q, v)
    dynamics.record_row(q, v, 0.0, 0.0, np.zeros((9, 4)), np.zeros(3), 0.0)
    wheel_torques(1.0, 0.5, 0.65, zeros.copy())
    speed_law(1.0, 1.0, 1.0, 0.0, 1.0, 1.0, 1.0, 1.0, 0.005)
    systems = _chassis()
    none = np.zeros(0)
    for actuation in (systems, ActuationArrays(*([none] * 6 + [np.zeros(3)] * 2))):
        for pedals in (False, True):
            actuate(pedals, -1.0, 0.5, 1e6, ones.copy(), zeros.copy(), 20.0, 0.005, 0.5, 0.65,
                    actuation, np.zeros(ACTUATION_STATE))
    swa = np.zeros(3)
    flags = np.zeros(3, dtype=bool)
    for gains in (np.zeros(0), np.ones(4)):
        dynamics.run_open_loop(q, v, np.zeros((2, 4)), np.zeros((4, 4)), False, 0, 2, 2, 1,
                               0.005, swa, flags, swa, swa, swa, swa, gains, 0.0, 0.5, 0.65,
                               systems, np.zeros(ACTUATION_STATE), zeros.copy(), arrays, 1.0,
                               1500.0, True, True, mb, np.zeros(3), np.empty((3, 16)),
                               np.empty((3, 9, 4)), np.empty((3, dynamics.ACTUATION_SIZE)))
        adaptive.run_adaptive(q, v, np.zeros((2, 4)), np.zeros((4, 4)), False, 0.0, 0.005,
                              0.01, 0.01, 0, np.array([0.005]), 1e-4, 2.5e-4, 0.02, 0.005,
                              swa, swa, gains, 0.0, 0.5, 0.65, arrays, 1.0, 1500.0, True,
                              True, mb, np.zeros(3), np.empty((8, 16)), np.empty((8, 9, 4)))


def _chassis() -> ActuationArrays:
    """
    Compile the brake, anti-lock and driveline functions as the chassis classes call them.

    Returns stand-in :class:`.drivers.ActuationArrays` of every system.
    """
    speeds, torques = np.array([100.0, 300.0, 600.0]), np.array([150.0, 200.0, 180.0])
    ratios = np.array([12.0, 7.0, 4.0])
    wheels = np.full(4, 20.0)
    rear_line_pressure(5e6, 4e6, 0.5)
    master_pressure_for_torque(1000.0, 1e-4, 5e-5, 4e6, 0.5)
    controller_step(0.15, 0.08, 1e8, 2e7, 2.0, False, 0.0, 0.005, 5e6, 0.2, 20.0)
    engine_torque(speeds, torques, 200.0, 1.0)
    driven = driven_speed(0.5, wheels)
    choose_gear(ratios, driven, 500.0)
    engine_speed(100.0, 12.0, driven)
    available_torque(speeds, torques, 12.0, 0.9, driven)
    inertia_torque(0.2, 100.0, 12.0, 0.9, driven, 1.0)
    split(1, 100.0, 1000.0, 500.0, 20.0, 19.0)
    differential = np.array([1.0, 100.0, 1000.0])
    drive_torques(speeds, torques, 12.0, 0.9, 0.5, differential, differential, 1.0, wheels,
                  0.0)
    return ActuationArrays(brakes=np.array([1e-4, 5e-5, 4e6, 0.5]),
                           anti_lock=np.array([0.15, 0.08, 1e8, 2e7, 2.0]),
                           engine_speeds=speeds, engine_torques=torques, ratios=ratios,
                           driveline=np.array([0.9, 0.5, 0.2, 500.0]),
                           front_differential=differential,
                           rear_differential=np.array([0.0, 0.0, 1000.0]))


def _kc(config) -> None:
    """Compile the K&C solver's parts: one tangent of the flexible (or rigid) front axle."""
    fidelity = 'flexible' if 'front_flex' in config.groups else 'rigid'
    system = build_kc_model(config, 'front', fidelity, 'warm-up').system
    state = system.design_state()
    system.evaluate(state, LoadCase()).tangent(state.lam)


def clear() -> None:
    """
    Remove the package's cached machine code.

    numba checks the time stamp of the file of the function it loads, not of the files of
    the functions that one calls (the step calls the forces, the forces the Magic Formula):
    a fresh cache cannot hold a caller compiled against an older callee.
    """
    for path in Path(compiled.__file__).resolve().parent.rglob('__pycache__/*.nb[ic]'):
        path.unlink(missing_ok=True)


def main() -> int:
    """Compile and cache (module doc); a no-op with VD_NO_JIT=1."""
    if not compiled.ENABLED:
        return 0
    clear()
    study = load_study(default_master())
    seen: set[bytes] = set()
    pairs = []
    for config in study.configurations.values():
        tires = [MagicFormula(tire_properties(config.group(f'{axle}_tire')))
                 for axle in ('front', 'rear')]
        for tire in tires:
            key = tire.coefficients.tobytes()
            if key not in seen:
                seen.add(key)
                _tire(tire)
        pairs.append(tuple(t.coefficients for t in tires))
    for front, rear in pairs[:1]:
        _vehicle(front, rear)
    _kc(study.configurations[study.configuration_names[0]])
    return 0


if __name__ == '__main__':
    raise SystemExit(main())
