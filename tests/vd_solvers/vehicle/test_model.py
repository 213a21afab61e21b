# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""The full-vehicle multibody model: maps from K&C, kinematics, conservation, statics, errors."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import numpy.testing as npt
import pinocchio as pin
import pytest

from vd_data_server.study import load_study
from vd_solvers.constants import STANDARD_GRAVITY as G
from vd_solvers.errors import SolverError
from vd_solvers.kc.cache import kc_result
from vd_solvers.kc.metrics import derived_metrics
from vd_solvers.vehicle.drivers import OpenLoopSteering, SpeedController
from vd_solvers.vehicle.maps import KC_STEPS
from vd_solvers.vehicle.model import Options, VehicleModel, WheelState
from vd_solvers.vehicle.simulation import simulate
from vd_solvers.vehicle_data import static_wheel_loads

STUDIES = Path(__file__).resolve().parents[3] / 'src' / 'vd_data_server' / 'data' / 'studies'


@pytest.fixture(scope='module')
def sedan():
    return load_study(STUDIES / 'sedan.yaml').configurations['baseline']


@pytest.fixture(scope='module')
def model(sedan):
    return VehicleModel(sedan)


def test_maps_are_the_kc_results_of_the_same_configuration(sedan, model):
    """
    Check that the maps are the K&C results of the same configuration.

    At design (z = 0) the wheel-force map is the K&C pad load less the unsprung weight,
    toe and camber are the K&C ones, and every map names its K&C event and data hash.
    """
    par = kc_result(sedan, 'front', 'parallel_wheel_travel', steps=KC_STEPS)
    at = int(np.argmin(np.abs(par.channels['wheel_travel'][:, 0])))
    z = np.zeros(4)
    z[0] = par.channels['wheel_travel'][at, 0]
    values = model.maps.travel(z)
    m_u = sedan.group('mass').scalar('unsprung_mass_front')
    # resampled on a uniform grid of the same spacing: linear interpolation between nodes
    # of a smooth curve, 1e-5 relative at most here
    npt.assert_allclose(values[0, 0], par.channels['pad_force'][at, 0] - m_u * G, rtol=1e-5)
    npt.assert_allclose(values[1, 0], par.channels['toe'][at, 0], atol=1e-6)
    npt.assert_allclose(values[2, 0], par.channels['camber'][at, 0], atol=1e-6)
    for key in ('wheel_force', 'toe', 'camber', 'anti_roll_bar', 'compliance_steer_lateral',
                'jacking_longitudinal', 'steering'):
        assert sedan.data_hash in model.maps.provenance[key], key


def test_anti_roll_bar_forces_are_zero_in_parallel_travel_and_give_the_kc_bar_stiffness(sedan,
                                                                                    model):
    """
    Check the anti-roll-bar map against the K&C bar roll stiffness.

    No bar force when both wheels travel alike; in roll, the bar forces' roll moment over
    the roll angle is the K&C bar roll stiffness (with bar minus without), within 2 %
    (the K&C metric is a slope fitted over +-10 mm, this a secant over +-5 mm).
    """
    npt.assert_allclose(model.maps.arb(np.array([0.03, 0.03, -0.02, -0.02])), 0.0, atol=1e-6)
    par = kc_result(sedan, 'front', 'parallel_wheel_travel', steps=KC_STEPS)
    track = float(par.channels['track'][int(np.argmin(np.abs(par.channels['pad_travel'][:, 0])))])
    z = np.array([-0.005, 0.005, 0.0, 0.0])
    bar = model.maps.arb(z)
    assert bar[1] > 0.0 > bar[0]  # the bar pushes the bump-side (right) wheel down
    moment = 0.5 * track * (bar[1] - bar[0])
    phi = math.atan((z[1] - z[0]) / track)
    results = {e: kc_result(sedan, 'front', e, steps=KC_STEPS) for e in
               ('opposite_wheel_travel', 'opposite_wheel_travel_no_bar')}
    k_bar = derived_metrics(results, 2.8e5)['roll_stiffness_bar'][0]  # N*m/rad
    npt.assert_allclose(moment / phi, k_bar, rtol=0.02)


def test_tire_loads_follow_the_wheel_centres_pinocchio_computes(model):
    """
    Check the tire loads against Pinocchio's wheel-centre kinematics.

    The model's own wheel-centre kinematics (used per step for speed) against
    Pinocchio's forward kinematics: the tire load C_z (R0 - h) - c dh/dt at each wheel.
    """
    rng = np.random.default_rng(3)
    q = pin.neutral(model.model)
    q[0:3] = [1.0, -2.0, -0.015]  # every tire on the ground
    q[3:7] = pin.Quaternion(pin.rpy.rpyToMatrix(0.03, -0.02, 0.4)).coeffs()
    q[7::2] = rng.uniform(-0.02, 0.02, 4)
    v = rng.normal(0.0, 0.3, model.model.nv)
    v[0] = 15.0
    _, wheel, _ = model.forces(q, v, 0.0, np.zeros(4), np.zeros((2, 4)), None, 0.001)
    data = model.model.createData()
    pin.forwardKinematics(model.model, data, q, v)
    for w in range(4):
        joint = model.model.getJointId(f"{('front', 'front', 'rear', 'rear')[w]}_"
                                       f"{('left', 'right')[w % 2]}_travel")
        height = data.oMi[joint].translation[2]
        rate = pin.getVelocity(model.model, data, joint, pin.LOCAL_WORLD_ALIGNED).linear[2]
        want = max(model.cz[w] * (model.r0[w] - height) - model.cd[w] * rate, 0.0)
        npt.assert_allclose(wheel.fz[w], want, rtol=1e-10)


def _free_flight_drift(sedan, h: float) -> tuple[float, float]:
    """Relative change of the linear and angular centroidal momentum over 1 s of free flight."""
    free = VehicleModel(sedan, options=Options(road=False, gravity=False))
    q, v = free.initial_state(20.0, yaw_rate=0.5)
    q[7::2] = [0.02, -0.01, 0.015, -0.02]  # springs out of balance: the wheels oscillate
    v[3] = 0.2  # and the body rolls
    h0 = free.momentum(q, v)
    for _ in range(int(round(1.0 / h))):
        tau, _, _ = free.forces(q, v, 0.0, np.zeros(4), np.zeros((2, 4)), None, h)
        tau[7::2] = 0.0  # no tire, no drive: no spin torque
        q, v = free.integrate(q, v, free.acceleration(q, v, tau), h)
    h1 = free.momentum(q, v)
    assert np.abs(q[7::2]).max() > 1e-3  # the suspension did move
    return (float(np.linalg.norm(h1[:3] - h0[:3]) / np.linalg.norm(h0[:3])),
            float(np.linalg.norm(h1[3:] - h0[3:]) / np.linalg.norm(h0[3:])))


def test_free_flight_conserves_momentum_to_the_integration_error(sedan):
    """
    Check that free flight conserves momentum to the integration error.

    No road, no gravity: suspension, dampers and wheel spin are internal forces, so the
    centroidal momentum must stay constant. The semi-implicit Euler step on the body's
    local velocities conserves it only to O(h): the drift must be small and halve with the
    step (a spurious external force would not vanish).
    """
    coarse = _free_flight_drift(sedan, 0.002)
    fine = _free_flight_drift(sedan, 0.001)
    for c, f in zip(coarse, fine):
        assert c < 2e-3
        assert 1.6 < c / f < 2.4  # first order


def test_a_dropped_car_settles_on_the_static_wheel_loads(sedan, model):
    """
    Check that a dropped car settles on the static wheel loads.

    Dropped 20 mm at rest, the car comes to rest with the loads of static_wheel_loads.
    Tolerance 0.2 %: the data's spring preloads hold the rear about 6 mm from design
    height (K&C pad load at design 3970 N vs the 3815 N static load), which pitches the
    body by about 0.002 rad and moves the CoG about 1 mm over the contact points:
    m g 1 mm / L / 2 = 3 N a wheel, 0.1 %. The vertical balance itself is exact.
    """
    front, rear = static_wheel_loads(sedan)
    q, v = model.initial_state(0.0)
    q[2] += 0.02
    slip = np.zeros((2, 4))
    wheel = None
    for _ in range(800):
        tau, wheel, update = model.forces(q, v, 0.0, np.zeros(4), slip, wheel, 0.005)
        q, v = model.integrate(q, v, model.acceleration(q, v, tau), 0.005)
        slip = np.stack([update.kappa_next(v[7::2]), update.alpha])
    tau, wheel, _ = model.forces(q, v, 0.0, np.zeros(4), slip, wheel, 0.005)
    npt.assert_allclose(wheel.fz, [front, front, rear, rear], rtol=2e-3)
    npt.assert_allclose(wheel.fz.sum(), model.total_mass * G, rtol=1e-4)
    assert np.abs(wheel.travel).max() < 8e-3
    # at rest, but for the free rolling (no brakes): the camber thrust of the toed-in
    # wheels has a rearward component, 2 F_gamma sin(toe) per axle, which a steady-state
    # tire model keeps at standstill; the free wheels no longer cancel it, so the car
    # creeps backwards at m/s^2 of (that force) / mass: a few mm/s after 4 s
    npt.assert_allclose(v[1:6], 0.0, atol=1e-4)
    rearward = sum(2.0 * abs(wheel.fy[w]) * math.sin(abs(wheel.steer[w])) for w in (0, 2))
    assert 0.0 < rearward < 2.0  # N
    assert -4.0 * 1.5 * rearward / model.total_mass < v[0] < 0.0


def test_a_non_finite_state_is_an_error_naming_configuration_event_and_time(model):
    steering = OpenLoopSteering(lambda t: math.nan if t > 0.2 else 0.0)
    with pytest.raises(SolverError) as err:
        simulate(model, steering, None, 1.0, event='step_steer', initial_speed=20.0)
    assert str(err.value) == ("configuration 'baseline', event 'step_steer', t = 0.210 s: "
                              "the state became non-finite")


def test_the_step_converges_with_the_step_size(model):
    """
    Check that the step converges with the step size.

    Steps of 1, 2.5 and 5 ms on a step steer of about 4 m/s^2: the steady state is the
    same, and the peak yaw rate converges at first order (semi-implicit Euler): its error
    against the 1 ms run grows in proportion to h - 1 ms, so the 5 ms error is
    (5 - 1)/(2.5 - 1) = 2.7 times the 2.5 ms error (2.0 .. 3.4 accepted).
    """
    results = {}
    for h in (0.001, 0.0025, 0.005):
        steering = OpenLoopSteering(times=[0.0, 0.2, 0.3, 3.0], angles=[0.0, 0.0, 0.4, 0.4])
        speed = SpeedController(lambda t: 27.8, model.total_mass, 0.33)
        trace = simulate(model, steering, speed, 2.5, event='step_steer', initial_speed=27.8,
                         record_every=int(round(0.01 / h)), h=h)
        results[h] = trace.channels()['yaw_rate']
    fine = results[0.001]
    for h in (0.0025, 0.005):
        npt.assert_allclose(results[h][-1], fine[-1], rtol=1e-3)
    e5, e25 = (abs(results[h].max() - fine.max()) for h in (0.005, 0.0025))
    assert 2.0 < e5 / e25 < 3.4
    assert e5 < 0.02 * fine.max()


@pytest.mark.parametrize('study', ['sedan', 'hmmwv'])
def test_the_initial_state_puts_the_static_loads_on_the_tires(study):
    """
    Check that the initial state puts the static loads on the tires.

    Body height and pitch of the start are those at which the tires carry the static
    wheel loads (the wheel-centre heights of the data need not be the loaded radius).
    """
    config = load_study(STUDIES / f'{study}.yaml').configurations['baseline']
    vehicle = VehicleModel(config)
    q, v = vehicle.initial_state(0.0)
    _, wheel, _ = vehicle.forces(q, v, 0.0, np.zeros(4), np.zeros((2, 4)), None, 0.005)
    front, rear = static_wheel_loads(config)
    npt.assert_allclose(wheel.fz, [front, front, rear, rear], rtol=1e-6)


def _suspension_potential(maps, z: np.ndarray) -> float:
    """
    Return the suspension potential of the wheel-force maps at z.

    Sum over the wheels of the work of the wheel-force map from the grid start to z
    (exact for the piecewise-linear map, with its linear extrapolation).
    """
    total = 0.0
    for w in range(4):
        force = maps.travel_table[0, w]
        step = maps.travel_step[w]
        work = np.concatenate([[0.0], np.cumsum(0.5 * (force[1:] + force[:-1]) * step)])
        u = (z[w] - maps.travel0[w]) / step
        k = int(np.clip(np.floor(u), 0, force.size - 2))
        dz = z[w] - (maps.travel0[w] + k * step)
        slope = (force[k + 1] - force[k]) / step
        total += work[k] + force[k] * dz + 0.5 * slope * dz * dz
    return total


def _energy_drift(vehicle, h: float) -> float:
    q, v = vehicle.initial_state(15.0, yaw_rate=0.3)
    q[7::2] = [0.03, -0.02, 0.025, -0.03]
    v[3] = 0.1

    def energy(q, v):
        return vehicle.energy(q, v) + _suspension_potential(vehicle.maps, q[7::2])

    e0 = energy(q, v)
    worst = 0.0
    for _ in range(int(round(0.5 / h))):
        tau, _, _ = vehicle.forces(q, v, 0.0, np.zeros(4), np.zeros((2, 4)), None, h)
        tau[7::2] = 0.0
        q, v = vehicle.integrate(q, v, vehicle.acceleration(q, v, tau), h)
        worst = max(worst, abs(energy(q, v) - e0))
    return worst / e0


def test_free_flight_without_dampers_conserves_energy():
    """
    Check that free flight without dampers conserves energy.

    The HMMWV (no anti-roll bar: its suspension forces derive from the wheel-force
    maps alone) in free flight without dampers, road and gravity: kinetic energy plus
    the maps' potential stays constant but for the symplectic step's bounded O(h) error,
    which halves with the step.
    """
    config = load_study(STUDIES / 'hmmwv.yaml').configurations['baseline']
    vehicle = VehicleModel(config, options=Options(road=False, gravity=False, dampers=False))
    coarse, fine = _energy_drift(vehicle, 0.002), _energy_drift(vehicle, 0.001)
    assert coarse < 1e-3
    assert 1.6 < coarse / fine < 2.4


def test_an_aligning_moment_steers_the_wheels_by_the_kc_aligning_torque_compliance(sedan,
                                                                                   model):
    """
    Check the full vehicle's toe against the K&C aligning-torque compliance.

    An aligning moment M_z on every wheel (previous step's tire state, no forces) turns
    each wheel by the K&C metric ``aligning_torque_compliance_steer`` (d steer / d M_z,
    both wheels averaged, from the ``aligning_torque`` event) times M_z, the number the
    understeer budget uses: 4.44 deg/(kN*m) at the sedan's front, 0.26 at its rear.
    """
    q, v = model.initial_state(20.0)
    zero = np.zeros(4)

    def steer(mz: float) -> np.ndarray:
        previous = WheelState(fz=zero, fx=zero, fy=zero, mz=np.full(4, mz), kappa=zero,
                              alpha=zero, gamma=zero, steer=zero, travel=zero)
        _, wheel, _ = model.forces(q, v, 0.0, zero, np.zeros((2, 4)), previous, 0.005)
        return wheel.steer

    mz = 150.0  # N*m, about the sedan front's at 4 m/s^2
    for axle, wheels in (('front', slice(0, 2)), ('rear', slice(2, 4))):
        results = {e: kc_result(sedan, axle, e) for e in ('aligning_torque',)}
        compliance = derived_metrics(results, 2.8e5)['aligning_torque_compliance_steer'][0]
        npt.assert_allclose(steer(mz)[wheels] - steer(0.0)[wheels], compliance * mz,
                            rtol=1e-6)
        assert compliance > 0.0  # the moment turns the wheel its own way


def test_the_wheels_steer_in_roll_as_the_kc_opposite_wheel_travel_says(sedan, model):
    """
    Check the toe in roll against the K&C roll steer.

    Opposite travel of the front wheels, left in rebound by d and right in bump (roll
    2 d / t, ISO: left side up): the mean steer of the two wheels per rad of roll is the
    K&C metric ``roll_steer`` (opposite_wheel_travel, with the
    bar): +0.0028 rad/rad on the sedan's front, where the parallel-travel bump steer alone
    (-0.122 rad/m a wheel) would give -0.095 rad/rad.
    """
    q, v = model.initial_state(0.0)
    zero = np.zeros(4)

    def mean_steer(d: float) -> float:
        q_d = q.copy()
        q_d[7::2] = [-d, d, 0.0, 0.0]
        _, wheel, _ = model.forces(q_d, v, 0.0, zero, np.zeros((2, 4)), None, 0.005)
        return float(wheel.steer[:2].mean())

    d = 0.002
    results = {e: kc_result(sedan, 'front', e) for e in ('opposite_wheel_travel',)}
    roll_steer = derived_metrics(results, 2.8e5)['roll_steer'][0]
    track = 2.0 * abs(model.wheel_centres[0, 1])
    measured = (mean_steer(d) - mean_steer(-d)) / (2.0 * math.atan(2.0 * d / track))
    npt.assert_allclose(measured, roll_steer, atol=2e-4)
    assert abs(roll_steer) < 0.01
