# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The full vehicle with its brakes, driveline and aerodynamics, and the longitudinal events.

References outside the code: the coast-down under drag alone, m_e dv/dt = -k v^2 with
k = rho C_d A / 2 and m_e the mass plus the wheels' spin inertia over R_e^2, has
v(t) = v0 / (1 + k v0 t / m_e); a stop whose deceleration ramps linearly to a in T_r and
is then held travels v0^2 / (2 a) + v0 T_r / 2 - a T_r^2 / 24; the aerodynamic wrench is
written out here from C_d, C_l, A and rho; an open differential splits its torque
equally, a limited-slip one by at most its locking torque; the turn metrics of an exact
circle are 1 (ratios) and 0 (deviations).
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from vd_data_server.master import with_overrides
from vd_data_server.study import load_study
from vd_solvers.chassis.from_config import chassis_systems
from vd_solvers.errors import SolverError
from vd_solvers.vehicle.drivers import Observation, OpenLoopSteering
from vd_solvers.vehicle.events import run_vehicle_event
from vd_solvers.vehicle.forces import vehicle_forces
from vd_solvers.vehicle.longitudinal_events import (
    EVALUATION_TIME,
    PedalRamp,
    pressure_for_deceleration,
    turn_response,
)
from vd_solvers.vehicle.model import VehicleModel
from vd_solvers.vehicle.simulation import simulate

STUDIES = Path(__file__).resolve().parents[3] / 'src' / 'vd_data_server' / 'data' / 'studies'


@pytest.fixture(scope='module')
def sedan():
    return load_study(STUDIES / 'sedan_longitudinal.yaml').configurations


def _low_mu(config, mu: float):
    """Put the configuration on a low-friction road: the tires' friction scaled (LMUX, LMUY)."""
    return with_overrides(config, {f'{axle}_tire.tir.SCALING_COEFFICIENTS.{k}': mu
                                   for axle in ('front', 'rear') for k in ('LMUX', 'LMUY')})


def test_the_chassis_systems_come_from_the_data(sedan) -> None:
    chassis = chassis_systems(sedan['abs'])
    assert chassis.brakes is not None and chassis.driveline is not None
    # T = 2 mu p A r of the front caliper at 80 bar, by hand
    assert chassis.brakes.front.torque(80e5) == pytest.approx(
        2 * 0.40 * 80e5 * math.pi * 0.057**2 / 4 * 0.125, rel=1e-12)
    # above the 40 bar knee the rear pressure rises at half the rate: 40 + 0.5 x 40 bar
    assert chassis.brakes.rear_pressure(80e5) == pytest.approx(60e5)
    assert chassis.anti_lock is not None
    assert chassis_systems(sedan['no_abs']).anti_lock is None
    assert chassis.driveline.front_share == 1.0  # FWD
    assert chassis.driveline.front.kind == 'limited_slip'
    assert chassis_systems(sedan['open_differential']).driveline.front.kind == 'open'
    assert chassis.shift_speed == pytest.approx(4500 * math.pi / 30)


@pytest.mark.parametrize('pressure', [20e5, 40e5, 90e5])
def test_the_pressure_for_a_brake_torque_inverts_the_torques(sedan, pressure) -> None:
    brakes = chassis_systems(sedan['abs']).brakes
    front, rear = brakes.torques(pressure)
    assert brakes.pressure_for_torque(2 * (front + rear)) == pytest.approx(pressure, rel=1e-12)


def test_the_aerodynamic_wrench_on_the_body(sedan) -> None:
    """The drag and lift added to the generalised forces, written out from the data."""
    model = VehicleModel(sedan['abs'])
    q, v = model.initial_state(40.0)
    still, _, _ = model.forces(q, v, 0.0, np.zeros(4), np.zeros((2, 4)), None, 0.005)
    aero = model.config.group('aero')
    rho, area = aero.scalar('air_density'), aero.scalar('frontal_area')
    drag = -0.5 * rho * aero.scalar('drag_coefficient') * area * 40.0**2
    lift_f = 0.5 * rho * aero.scalar('lift_coefficient_front') * area * 40.0**2
    lift_r = 0.5 * rho * aero.scalar('lift_coefficient_rear') * area * 40.0**2
    x_f, x_r = model.wheel_centres[0, 0], model.wheel_centres[2, 0]
    z = model.config.group('mass').point('sprung_cog')[2]
    arrays = model.arrays._replace(aero=np.zeros_like(model.arrays.aero))
    bare = vehicle_forces(q, v, 0.0, np.zeros(4), np.zeros((2, 4)), np.zeros((4, 4)), False,
                          0.005, arrays, model.vx_floor, model.total_mass, True, True)[0]
    diff = still - bare
    assert diff[0] == pytest.approx(drag, rel=1e-12)
    assert diff[2] == pytest.approx(lift_f + lift_r, rel=1e-12)
    assert diff[4] == pytest.approx(z * drag - x_f * lift_f - x_r * lift_r, rel=1e-12)
    assert np.all(diff[[1, 3, 5]] == 0.0) and np.all(diff[6:] == 0.0)


def test_the_coast_down_follows_the_closed_form(sedan) -> None:
    """
    Free rolling from 40 m/s: the sedan's tire file has no rolling resistance (no QSY).

    The speed at 10 s against v0 / (1 + k v0 t / m_e) within 0.3 %: the tires' small
    longitudinal slip and the pitch are all that the closed form leaves out.
    """
    model = VehicleModel(sedan['abs'])
    v0, duration = 40.0, 10.0
    trace = simulate(model, OpenLoopSteering(lambda t: 0.0), None, duration,
                     event='coast_down', initial_speed=v0)
    ch = trace.channels()
    aero = model.chassis.aero
    k = 0.5 * aero.density * aero.drag_area
    r_e = model.tire_radii(model.static_loads())[1]
    m_e = model.total_mass + float(np.sum(model.spin_inertia / r_e**2))
    closed = v0 / (1.0 + k * v0 * ch['time'] / m_e)
    assert ch['speed'][-1] == pytest.approx(closed[-1], rel=3e-3)
    assert closed[-1] < v0 - 3.0  # the drag slows it by 3.4 m/s: a real test of it


def test_a_held_deceleration_stops_in_the_closed_form_distance(sedan) -> None:
    """
    Straight-line braking at a held 4 m/s^2 (no wheel near its friction limit).

    s = v0^2 / (2 a) + v0 T_r / 2 - a T_r^2 / 24 with the pressure's ramp T_r; the aero
    drag (0.2 m/s^2 at the start, from C_d A) shortens the stop by less than 2 %, so the
    simulated distance lies between 0.97 and 1.0 of the closed form.
    """
    outcome = run_vehicle_event(sedan['no_abs'], 'straight_line_braking',
                                ['deceleration=4 m/s^2', 'speed=25 m/s', 'ramp_time=0.2 s'])
    a, v0, ramp = 4.0, 25.0, 0.2
    closed = v0**2 / (2 * a) + v0 * ramp / 2 - a * ramp**2 / 24
    distance = outcome.metrics['stopping_distance'].value
    assert 0.97 * closed < distance < closed
    assert outcome.metrics['locked_wheels'].value == 0
    assert outcome.metrics['max_pitch'].value > 0.0  # nose down under braking


def test_anti_lock_brakes_stop_shorter_and_keep_the_wheels_turning_on_low_mu(sedan) -> None:
    """On mu 0.3 a 500 N pedal locks every wheel without ABS; with it none locks."""
    results = {name: run_vehicle_event(_low_mu(sedan[name], 0.3), 'straight_line_braking',
                                       ['speed=20 m/s'])
               for name in ('abs', 'no_abs')}
    with_abs, without = (results[n].metrics for n in ('abs', 'no_abs'))
    assert without['locked_wheels'].value == 4
    assert with_abs['locked_wheels'].value == 0
    assert with_abs['stopping_distance'].value < without['stopping_distance'].value
    # a locked tire slides at about the friction limit: d about 0.3 g, ABS near the peak
    assert without['mean_fully_developed_deceleration'].value < 0.32 * 9.81


def test_anti_lock_brakes_keep_the_car_steerable_on_low_mu() -> None:
    """
    The HMMWV braking with 500 N on mu 0.3, the steering wheel turned 90 deg at 0.5 s.

    Its tire file's combined-slip terms take a sliding tire's side force away (the
    sedan's file has none: its side force does not depend on the slip ratio). With ABS
    the wheels keep turning, the front ones (which lock first: the proportioning valve)
    held at the controller's braking slip, and the path bends (over 2 m to the side by
    2.5 s); with the wheels locked the car slides on straight, less than a fifth of that.
    """
    configs = load_study(STUDIES / 'hmmwv_longitudinal.yaml').configurations
    side = {}
    for name in ('abs', 'no_abs'):
        model = VehicleModel(_low_mu(configs[name], 0.3))
        brakes = model.chassis.brakes
        pedals = PedalRamp(0.0, 0.15, (0.0, 0.0), (0.0, brakes.pressure_from_pedal(500.0)))
        steering = OpenLoopSteering(times=[0.0, 0.5, 0.6, 2.5],
                                    angles=[0.0, 0.0, math.radians(90.0), math.radians(90.0)])
        trace = simulate(model, steering, pedals, 2.5, event='braking_in_a_bend',
                         initial_speed=20.0)
        ch = trace.channels()
        kappa = ch['slip_ratio'][-1]
        if name == 'no_abs':
            assert np.max(kappa) < -0.9
        else:
            assert np.min(kappa) > -0.5 and np.max(kappa) < 0.0  # all turn, all braked
            assert np.max(kappa[:2]) < -0.05  # the front at the controller's slip
        side[name] = float(ch['y'][-1])
    assert side['abs'] > 2.0
    assert abs(side['no_abs']) < side['abs'] / 5.0


def test_open_and_limited_slip_differentials_on_a_split_load(sedan) -> None:
    """
    Full throttle with the sprung centre of gravity 300 mm to the left.

    The open differential gives both front wheels the same torque at every instant; the
    limited-slip one differs by at most its locking torque (100 N*m) and, taking torque
    to the loaded left wheel, reaches 100 km/h sooner.
    """
    load = {'mass.sprung_cog.y': '300 mm'}
    runs = {name: run_vehicle_event(with_overrides(sedan[name], load),
                                    'straight_line_acceleration', [])
            for name in ('abs', 'open_differential')}
    lsd, open_ = runs['abs'], runs['open_differential']
    t_fl = open_.channels['applied_torque_front_left'].values
    t_fr = open_.channels['applied_torque_front_right'].values
    assert np.allclose(t_fl, t_fr, rtol=1e-12, atol=1e-9)
    gap = (lsd.channels['applied_torque_front_left'].values
           - lsd.channels['applied_torque_front_right'].values)
    assert np.max(np.abs(gap)) <= 100.0 + 1e-9
    assert np.max(np.abs(gap)) > 50.0  # the clutch works
    assert lsd.metrics['acceleration_time'].value < open_.metrics['acceleration_time'].value


def test_the_driveline_inertia_adds_its_equivalent_mass() -> None:
    """
    The HMMWV at full throttle with and without its 1.4 kg*m^2 at engine speed.

    At the same speed in the same gear the drive force and the resistances are the same,
    so the accelerations stand as m_e / (m_e + J i^2 eta / r_e^2), with m_e the mass plus
    the wheels' spin inertia over r_e^2 (the equivalent mass of the rotating parts).
    """
    config = load_study(STUDIES / 'hmmwv_longitudinal.yaml').configurations['no_abs']
    runs = {j: run_vehicle_event(with_overrides(config, {'driveline.inertia': f'{j} kg*m^2'}),
                                 'straight_line_acceleration', ['end_speed=20 m/s'])
            for j in (0.0, 1.4)}
    model = VehicleModel(config)
    line = model.chassis.driveline
    r_e = model.tire_radii(model.static_loads())[1]
    m_e = model.total_mass + float(np.sum(model.spin_inertia / r_e**2))
    at = 17.0  # m/s: second gear, away from the shifts
    accel, gears = {}, set()
    for j, run in runs.items():
        ch = {k: c.values for k, c in run.channels.items()}
        k = int(np.argmax(ch['speed'] >= at))
        window = slice(k - 25, k + 25)
        accel[j] = float(np.mean(ch['longitudinal_acceleration'][window]))
        gears.update(ch['gear'][window].tolist())
    assert gears == {2.0}
    i = line.ratio(2)
    expected = m_e / (m_e + 1.4 * i**2 * line.efficiency / float(np.mean(r_e))**2)
    assert accel[1.4] / accel[0.0] == pytest.approx(expected, rel=0.02)
    assert expected < 0.93  # the inertia matters: over 7 % in second gear


def test_the_hmmwv_reaches_60_mph_in_the_published_time() -> None:
    """
    0-60 mph (26.82 m/s) within the published road tests of the HMMWV's civilian version.

    Published (same 4-speed automatic, geared hubs and 37 in tires; power over mass 46.7 to
    48.3 W/kg against this HMMWV's 119.3 kW / 2478.5 kg = 48.1 W/kg): 16.0 s, Hummer H1
    6.5 L turbodiesel 195 hp, 6863 lb (The Auto Channel, 2002 AM Hummer H1 Open-top
    review); 17.3 s, the same engine, 6620 lb (topclassiccars.com, AM General Hummer
    specifications); 18.1 s, the 5.7 L petrol V8 of 190 hp (Car and Driver, June 1995,
    as quoted by MotorBiscuit). The event starts at walking pace; the time from standstill
    to it is added at the launch acceleration (the first 0.5 s mean).
    """
    config = load_study(STUDIES / 'hmmwv_longitudinal.yaml').configurations['no_abs']
    run = run_vehicle_event(config, 'straight_line_acceleration', ['end_speed=26.8224 m/s'])
    ch = {k: c.values for k, c in run.channels.items()}
    launch = float(np.mean(ch['longitudinal_acceleration'][ch['time'] <= 0.5]))
    standing = ch['speed'][0] / launch
    assert 0.0 < standing < 0.5
    t_60 = run.metrics['acceleration_time'].value + standing
    assert 16.0 <= t_60 <= 18.1


def test_turn_response_of_an_exact_circle_and_of_a_yaw_step() -> None:
    """Synthetic runs with their answers: a circle, then a yaw rate that grows by 10 %."""
    radius, speed, t0 = 80.0, 20.0, 2.0
    t = np.arange(0.0, 4.0, 0.01)
    r = speed / radius
    yaw = r * t
    ch = {'time': t, 'yaw': yaw, 'yaw_rate': np.full_like(t, r), 'speed': np.full_like(t, speed),
          'sideslip': np.zeros_like(t), 'lateral_acceleration': np.full_like(t, speed * r),
          'x': radius * np.sin(yaw), 'y': radius * (1 - np.cos(yaw))}
    m = turn_response(ch, t0)
    assert m['radius_initial'].value == pytest.approx(radius)
    assert m['yaw_rate_ratio'].value == pytest.approx(1.0)
    for name in ('heading_deviation', 'path_deviation', 'yaw_rate_difference'):
        assert m[name].value == pytest.approx(0.0, abs=1e-6), name
    # from t0 the yaw rate is 1.1 r: 0.1 r EVALUATION_TIME of heading gained at t_n
    grown = dict(ch)
    grown['yaw_rate'] = np.where(t >= t0, 1.1 * r, r)
    grown['yaw'] = r * t + np.where(t >= t0, 0.1 * r * (t - t0), 0.0)
    m = turn_response(grown, t0)
    assert m['yaw_rate_ratio'].value == pytest.approx(1.1)
    assert m['heading_deviation'].value == pytest.approx(0.1 * r * EVALUATION_TIME, rel=1e-2)


def test_braking_in_a_turn_and_power_off_keep_the_initial_circle(sedan) -> None:
    """The steady state before t_0 is the aimed circle (ISO 7975 and 9816 start there)."""
    for event, aimed in (('brake_in_turn', 5.0), ('power_off_in_turn', 4.0)):
        m = run_vehicle_event(sedan['abs'], event, []).metrics
        assert m['radius_initial'].value == pytest.approx(100.0, rel=0.03), event
        assert m['lateral_acceleration_initial'].value == pytest.approx(aimed, rel=0.03), event
    braked = run_vehicle_event(sedan['abs'], 'brake_in_turn', ['deceleration=4 m/s^2'])
    assert braked.metrics['mean_longitudinal_deceleration'].value == pytest.approx(4.0, rel=0.1)


def test_a_deceleration_needs_a_pressure_the_brakes_reach(sedan) -> None:
    model = VehicleModel(sedan['abs'])
    p = pressure_for_deceleration(model, 9.81)
    front, rear = model.chassis.brakes.torques(p)
    r_e = float(np.mean(model.tire_radii(model.static_loads())[1]))
    assert 2 * (front + rear) == pytest.approx(model.total_mass * 9.81 * r_e, rel=1e-12)


def test_events_that_need_a_group_name_it() -> None:
    baseline = load_study(STUDIES / 'sedan.yaml').configurations['baseline']
    with pytest.raises(SolverError) as info:
        run_vehicle_event(baseline, 'straight_line_braking', [])
    assert str(info.value) == (
        "configuration 'baseline': event 'straight_line_braking' needs the 'brakes' group "
        '(docs/data-format.md), which it does not pick')
    with pytest.raises(SolverError) as info:
        run_vehicle_event(baseline, 'straight_line_acceleration', [])
    assert "needs the 'driveline' group" in str(info.value)


def test_pedal_ramp_reaches_its_pressure() -> None:
    ramp = PedalRamp(1.0, 0.5, (0.0, 0.0), (0.0, 80e5))
    at = [ramp.wheel_torque(Observation(t, 0, 0, 0, 10, 0), 0.01).pressure
          for t in (0.5, 1.25, 2.0)]
    assert at == pytest.approx([0.0, 40e5, 80e5])
