# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The compiled multibody step against Pinocchio, and the compiled loop against the per-step one.

Pinocchio is the reference of :mod:`vd_solvers.vehicle.dynamics`: its articulated-body
algorithm (``pin.aba``) for the accelerations on random states of both sample vehicles,
``pin.integrate`` for the configuration update, and a step steer integrated here step by
step with ``VehicleModel.forces``, ``pin.aba`` and ``pin.integrate`` (the slip update
written out from the model's equations) for the whole step.
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import numpy.testing as npt
import pinocchio as pin
import pytest

from vd_data_server.study import load_study
from vd_solvers.errors import SolverError
from vd_solvers.vehicle.drivers import OpenLoopSteering, SpeedController, wheel_torques
from vd_solvers.vehicle.dynamics import accelerations, integrate, multibody_arrays
from vd_solvers.vehicle.model import VehicleModel
from vd_solvers.vehicle.simulation import simulate

STUDIES = Path(__file__).resolve().parents[3] / 'src' / 'vd_data_server' / 'data' / 'studies'


@pytest.fixture(scope='module', params=['sedan', 'hmmwv'])
def vehicle(request):
    return VehicleModel(load_study(STUDIES / f'{request.param}.yaml').configurations['baseline'])


@pytest.fixture(scope='module')
def sedan():
    return VehicleModel(load_study(STUDIES / 'sedan.yaml').configurations['baseline'])


def test_the_accelerations_are_pinocchios_aba(vehicle):
    """Random configurations, velocities and forces: the accelerations equal pin.aba (1e-10)."""
    rng = np.random.default_rng(5)
    mb = multibody_arrays(vehicle.model)
    model, data = vehicle.model, vehicle.data
    for _ in range(40):
        q = pin.randomConfiguration(model, -np.ones(model.nq), np.ones(model.nq))
        v = rng.normal(0.0, 3.0, model.nv)
        tau = rng.normal(0.0, 2000.0, model.nv)
        expected = pin.aba(model, data, q, v, tau)
        npt.assert_allclose(accelerations(q, v, tau, mb), expected, rtol=0.0,
                            atol=1e-10 * np.max(np.abs(expected)))


def test_the_update_is_pinocchios_integrate(vehicle):
    """Tangent steps from 1e-9 to 1 (rad, m): the configuration equals pin.integrate."""
    rng = np.random.default_rng(6)
    model = vehicle.model
    for scale in (1e-9, 1e-6, 1e-4, 1e-2, 1.0):
        for _ in range(10):
            q = pin.randomConfiguration(model, -np.ones(model.nq), np.ones(model.nq))
            dq = rng.normal(0.0, scale, model.nv)
            npt.assert_allclose(integrate(q, dq), pin.integrate(model, q, dq), rtol=0.0,
                                atol=1e-13)


def test_the_multibody_data_must_be_the_vehicle_tree():
    model = pin.Model()
    model.addJoint(0, pin.JointModelFreeFlyer(), pin.SE3.Identity(), 'body')
    with pytest.raises(SolverError, match='compiled multibody step needs the tree'):
        multibody_arrays(model)


def _reference_step_steer(vehicle: VehicleModel, swa_of, n_steps: int, h: float):
    """Integrate a step steer with Pinocchio, step by step (module doc); yaw rate per step."""
    q, v = vehicle.initial_state(27.8)
    slip = np.zeros((2, 4))
    previous = None
    out = []
    for step in range(n_steps):
        torques = np.zeros(4)
        tau, wheel, update = vehicle.forces(q, v, swa_of(step * h), torques, slip, previous, h)
        v = v + h * pin.aba(vehicle.model, vehicle.data, q, v, tau)
        q = pin.integrate(vehicle.model, q, h * v)
        spin = v[7::2]
        # kappa' moves with the end-of-step spin towards its steady value (model doc)
        steady = (spin * update.radius - update.vx) / update.denominator
        slip = np.stack([steady + (update.kappa - steady) * update.decay, update.alpha])
        previous = wheel
        rot = pin.Quaternion(q[6], q[3], q[4], q[5]).toRotationMatrix()
        out.append((rot @ v[3:6])[2])
    return np.array(out)


def test_a_step_steer_follows_the_pinocchio_step(sedan):
    """
    Check the compiled step over a 3 s step steer.

    Its yaw rate every step against the same forces stepped with pin.aba and
    pin.integrate: the two differ by rounding only (1e-9 of the peak).
    """
    h = 0.005
    steering = OpenLoopSteering(times=[0.0, 0.5, 0.6, 3.0], angles=[0.0, 0.0, 0.4, 0.4])
    n_steps = 600
    trace = simulate(sedan, steering, None, n_steps * h, event='step_steer',
                     initial_speed=27.8, record_every=1)
    compiled = trace.channels()['yaw_rate'][1:]  # the row of step k is the state before it
    reference = _reference_step_steer(sedan, steering.signal, n_steps, h)
    assert np.max(np.abs(reference)) > 0.1
    npt.assert_allclose(compiled, reference, rtol=0.0, atol=1e-9 * np.max(np.abs(reference)))


def test_wheel_torques_split_drive_and_brake():
    """Drive: front share, halves per side; brake: front share, opposing the spin."""
    npt.assert_allclose(wheel_torques(1000.0, 0.3, 0.6, np.ones(4)), [150, 150, 350, 350])
    spin = np.array([50.0, -50.0, 0.0, 50.0])
    npt.assert_allclose(wheel_torques(-1000.0, 0.3, 0.6, spin),
                        [-300.0, 300.0, 0.0, -200.0 * math.tanh(500.0)])


def _runs(sedan, **kwargs):
    out = []
    for compiled_loop in (True, False):
        _, r_e = sedan.tire_radii(sedan.static_loads())
        steering = OpenLoopSteering(times=[0.0, 0.5, 0.6, 3.0], angles=[0.0, 0.0, 0.4, 0.4])
        speed = SpeedController(lambda t: 27.8 - 0.5 * t, sedan.total_mass, float(r_e.mean()))
        out.append(simulate(sedan, steering, speed, 3.0, event='step_steer',
                            initial_speed=27.8, compiled_loop=compiled_loop, **kwargs))
    return out


def test_the_compiled_loop_gives_the_per_step_trace(sedan):
    """An open-loop step steer with a braking speed controller: the same trace, bit for bit."""
    fast, slow = _runs(sedan, record_every=3)
    assert fast.steps == slow.steps == 600
    a, b = fast.channels(), slow.channels()
    assert a.keys() == b.keys()
    for key in a:
        npt.assert_array_equal(a[key], b[key], err_msg=key)
    assert np.min(a['wheel_torque']) < 0.0  # the brakes worked


def test_the_compiled_loop_stops_where_the_per_step_loop_stops(sedan):
    """A stop condition on the recorded rows and a progress report: the same trace."""
    reports: list[float] = []

    def stop(row):
        return 'turning' if row['yaw_rate'] > 0.1 else ''

    fast, slow = _runs(sedan, record_every=2, stop=stop,
                       progress=lambda f, stage: reports.append(f))
    assert fast.stop_reason == slow.stop_reason == 'turning'
    assert fast.steps == slow.steps
    a, b = fast.channels(), slow.channels()
    for key in a:
        npt.assert_array_equal(a[key], b[key], err_msg=key)
    assert 0.1 < a['yaw_rate'][-1] and a['yaw_rate'][-2] <= 0.1
    assert reports and reports[0] == 0.0
