# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Full-vehicle events: the thesis' trends (4.4.1), ladder consistency, bad input.

The constant radius turns of the trend test start at 4 m/s^2 with a looser steady-state
tolerance (the limit, not gradients, is compared there); the ladder checks use a turn over
the linear range only.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from vd_data_server.errors import DataError
from vd_data_server.study import load_study
from vd_solvers.analytical import two_track
from vd_solvers.analytical.from_config import vehicle_params
from vd_solvers.analytical.kc_link import kc_inputs
from vd_solvers.errors import SolverError
from vd_solvers.vehicle.events import run_vehicle_event
from vd_solvers.vehicle_data import mass_properties, static_wheel_loads

STUDIES = Path(__file__).resolve().parents[3] / 'src' / 'vd_data_server' / 'data' / 'studies'
TO_THE_LIMIT = ['start_lateral_acceleration=4 m/s^2', 'steady_tolerance=0.01',
                'limit_resolution=0.2 m/s^2']
LINEAR_ONLY = ['start_lateral_acceleration=1 m/s^2', 'max_lateral_acceleration=3 m/s^2']


@pytest.fixture(scope='module')
def sedan():
    return load_study(STUDIES / 'sedan.yaml').configurations


@pytest.fixture(scope='module')
def turns(sedan):
    return {name: run_vehicle_event(sedan[name], 'constant_radius_turn', TO_THE_LIMIT)
            for name in ('baseline', 'stiff_rear')}


@pytest.fixture(scope='module')
def linear_turn(sedan):
    return run_vehicle_event(sedan['baseline'], 'constant_radius_turn', LINEAR_ONLY)


@pytest.fixture(scope='module')
def step(sedan):
    return run_vehicle_event(sedan['baseline'], 'step_steer')


def _m(outcome, name):
    return outcome.metrics[name].value


def _steady_points(outcome) -> dict[str, np.ndarray]:
    """Means of every channel over each steady point's averaging window."""
    flag = outcome.channels['steady_window'].values > 0.5
    idx = np.flatnonzero(flag)
    windows = np.split(idx, np.flatnonzero(np.diff(idx) > 1) + 1)
    return {k: np.array([c.values[w].mean() for w in windows])
            for k, c in outcome.channels.items()}


def test_stiffer_rear_roll_stiffness_gives_the_thesis_trends(turns):
    """
    Check: stiffer rear roll stiffness gives the thesis trends.

    Thesis 4.4.1 (Figs. 4.4.1-4.4.3): more rear roll stiffness reaches a higher lateral
    acceleration, with less body roll and a slower rise of the steering angle: at every
    steady level both turns share, less roll and less steering-wheel angle.
    """
    base, stiff = turns['baseline'], turns['stiff_rear']
    assert _m(stiff, 'max_lateral_acceleration') > _m(base, 'max_lateral_acceleration') + 0.2
    pb, ps = _steady_points(base), _steady_points(stiff)
    # the levels both turns held (the last ones differ where each bisected its limit)
    pairs = [(i, int(np.argmin(np.abs(ps['lateral_acceleration'] - a))))
             for i, a in enumerate(pb['lateral_acceleration'])]
    pairs = [(i, j) for i, j in pairs
             if abs(ps['lateral_acceleration'][j] / pb['lateral_acceleration'][i] - 1.0) < 0.01]
    assert len(pairs) >= 4
    for i, j in pairs:
        assert ps['roll'][j] < 0.9 * pb['roll'][i]
        assert ps['steering_wheel_angle'][j] < pb['steering_wheel_angle'][i]


def _axle_forces(outcome, config):
    """
    Check: axle forces.

    Effective lateral force of each axle, N: the axle's yaw moment about the CoG over its
    lever arm (a for the front, -b for the rear), from the wheels' forces in body axes
    (steer angles), the track offsets of their longitudinal forces and their aligning
    moments. The yaw moment is what the single-track model's axle force stands for.
    """
    ch = {k: c.values for k, c in outcome.channels.items()}
    mp = mass_properties(config)
    out = []
    for axle in ('front', 'rear'):
        x, y, _ = config.group(f'{axle}_hardpoints').point('points.wheel_centre')
        moment = 0.0
        for side, sign in (('left', 1.0), ('right', -1.0)):
            w = f'{axle}_{side}'
            delta = ch[f'wheel_steer_{w}']
            fx, fy = ch[f'tire_force_x_{w}'], ch[f'tire_force_y_{w}']
            f_long = fx * np.cos(delta) - fy * np.sin(delta)
            f_lat = fx * np.sin(delta) + fy * np.cos(delta)
            moment = moment + (x - mp.cog_x) * f_lat - sign * abs(y) * f_long \
                + ch[f'aligning_moment_{w}']
        out.append(moment / (x - mp.cog_x))
    return out


def _effective_slips(outcome, config):
    """
    Check: effective slips.

    Single-track slip angles with every steer effect in the axle characteristic:
    alpha_f = delta_sw / i_s - beta - a r / v, alpha_r = -beta + b r / v (at the CoG).
    """
    ch = {k: c.values for k, c in outcome.channels.items()}
    mp = mass_properties(config)
    a = mp.cog_to_front_axle
    b = config.group('geometry').scalar('wheelbase') - a
    ratio = _m(outcome, 'steering_ratio')
    r, v, beta = ch['yaw_rate'], ch['speed'], ch['sideslip']
    return (ch['steering_wheel_angle'] / ratio - beta - a * r / v, -beta + b * r / v, mp, a, b)


def test_understeer_gradient_agrees_with_the_bicycle_model_of_the_same_axles(sedan,
                                                                             linear_turn):
    """
    Check: understeer gradient agrees with the bicycle model of the same axles.

    Ladder: feed the bicycle model (thesis eq. 2, K = m/L (b/C_f - a/C_r)) the effective
    axle cornering stiffnesses of the full vehicle's own linear range (axle force over the
    single-track slip angle, every steer effect included, from the steady points of the
    linear range). Its K must equal the full vehicle's K_us within 2 %: the axle forces
    carry the tires' aligning moments and the longitudinal forces' yaw moments, so what
    remains is the steady points' spread about their line.
    """
    config = sedan['baseline']
    turn = linear_turn
    steady = turn.channels['steady_window'].values > 0.5
    alpha_f, alpha_r, mp, a, b = _effective_slips(turn, config)
    f_front, f_rear = _axle_forces(turn, config)
    c_f = np.polyfit(alpha_f[steady], f_front[steady], 1)[0]
    c_r = np.polyfit(alpha_r[steady], f_rear[steady], 1)[0]
    wheelbase = a + b
    k_bicycle = mp.mass / wheelbase * (b / c_f - a / c_r)
    assert k_bicycle == pytest.approx(_m(turn, 'understeer_gradient'), rel=0.02)


def test_yaw_rate_gain_agrees_with_the_bicycle_model_of_the_same_axles(sedan, step):
    """
    Check: yaw rate gain agrees with the bicycle model of the same axles.

    Ladder: the steady yaw-rate gain of the step steer against the bicycle model's
    r / delta = (v / L) / (1 + K v^2 / L), with K from the effective axle stiffnesses of the
    same steady state (secants). Within 3 %: as above, without the speed ramp.
    """
    config = sedan['baseline']
    alpha_f, alpha_r, mp, a, b = _effective_slips(step, config)
    f_front, f_rear = _axle_forces(step, config)
    t = step.channels['time'].values
    steady = t >= t[-1] - 1.0
    c_f = f_front[steady].mean() / alpha_f[steady].mean()
    c_r = f_rear[steady].mean() / alpha_r[steady].mean()
    wheelbase = a + b
    k = mp.mass / wheelbase * (b / c_f - a / c_r)
    v = _m(step, 'speed')
    gain = (v / wheelbase) / (1.0 + k * v**2 / wheelbase)
    vehicle = _m(step, 'yaw_rate_gain') * _m(step, 'steering_ratio')
    assert vehicle == pytest.approx(gain, rel=0.03)


def test_maximum_lateral_acceleration_is_near_the_two_track_model(sedan, turns):
    """
    Check: maximum lateral acceleration is near the two track model.

    Ladder: the two-track model with the same K&C roll stiffness and roll centres reaches
    its steady-state limit within 10 % of the full vehicle's (which loses the radius when
    the front axle saturates; the two-track has no compliance, camber or jacking).
    """
    config = sedan['baseline']
    suspension = kc_inputs(config, static_wheel_loads(config)).suspension
    limit = two_track.handling_diagram(vehicle_params(config, suspension), 40.0, 41).limit
    assert _m(turns['baseline'], 'max_lateral_acceleration') == pytest.approx(
        limit.lateral_acceleration, rel=0.10)


def test_step_steer_metrics_are_consistent_with_its_channels(step):
    """t90 and peak times are read from the recorded yaw rate after the 50 % steer instant."""
    t = step.channels['time'].values
    r = step.channels['yaw_rate'].values
    r_ss = _m(step, 'steady_yaw_rate')
    t50 = 1.0 + 0.5 * 0.1
    t90 = t50 + _m(step, 'yaw_rate_response_time_90')
    assert np.all(r[t < t90 - 1e-9] < 0.9 * r_ss)
    assert r[np.argmin(np.abs(t - t90))] >= 0.9 * r_ss
    peak = r.max()
    assert _m(step, 'yaw_rate_overshoot') == pytest.approx(100.0 * (peak / r_ss - 1.0))
    assert _m(step, 'steady_lateral_acceleration') == pytest.approx(4.0, rel=0.02)


def test_unknown_event_parameter_is_a_data_error(sedan):
    with pytest.raises(DataError) as err:
        run_vehicle_event(sedan['baseline'], 'step_steer', ['diameter=3 m'])
    assert str(err.value) == ("event step_steer: unknown parameter 'diameter' (parameters of "
                              "step_steer: speed, lateral_acceleration, ramp_time, duration, "
                              "time_step, step_tolerance, drive_front, brake_front)")


def test_the_step_steer_with_the_fixed_step_has_the_variable_steps_steady_state(sedan, step):
    """step_tolerance=0: the fixed 5 ms step, the default's steady gains (0.5 %), time base."""
    fixed = run_vehicle_event(sedan['baseline'], 'step_steer', ['step_tolerance=0 m/s'])
    assert any('step 5 ms' in note for note in fixed.notes)
    np.testing.assert_array_equal(fixed.channels['time'].values, step.channels['time'].values)
    for key in ('yaw_rate_gain', 'lateral_acceleration_gain', 'sideslip_gain', 'roll_gain'):
        np.testing.assert_allclose(fixed.metrics[key].value, step.metrics[key].value,
                                   rtol=0.005, err_msg=key)


def test_a_step_beyond_the_steering_lock_is_an_error(sedan):
    with pytest.raises(SolverError) as err:
        run_vehicle_event(sedan['baseline'], 'step_steer',
                          ['speed=5 m/s', 'lateral_acceleration=8 m/s^2'])
    message = str(err.value)
    assert message.startswith('step steer to 8 m/s^2 at 5 m/s needs a steering-wheel angle '
                              'beyond the lock (')


def test_flexible_fidelity_drives_on_the_flexible_kc_maps(sedan, step):
    """
    Check: flexible fidelity drives on the flexible kc maps.

    The same configuration on its flexible K&C results: every suspension map says so,
    and the more compliant suspension changes the response.
    """
    flex = run_vehicle_event(sedan['baseline'], 'step_steer', [], fidelity='flexible')
    assert flex.fidelity == 'flexible'
    maps = [n for n in flex.notes if 'data hash' in n]
    assert maps and all('flexible' in n for n in maps if 'K&C' in n)
    assert _m(flex, 'yaw_rate_gain') != pytest.approx(_m(step, 'yaw_rate_gain'), rel=1e-3)


def test_unknown_event_is_an_error(sedan):
    with pytest.raises(SolverError) as err:
        run_vehicle_event(sedan['baseline'], 'double_lane_change')
    assert str(err.value) == ("configuration 'baseline', event 'double_lane_change': the "
                              "full-vehicle model has no event 'double_lane_change' (events: "
                              "constant_radius_turn, step_steer, sine_with_dwell, "
                              "straight_line_braking, brake_in_turn, power_off_in_turn, "
                              "straight_line_acceleration, ride, bump, lane_change, "
                              "lane_change_limit)")


def test_a_flexible_configuration_drives_on_flexible_maps_unless_told_rigid(sedan):
    """
    Check: the vehicle follows the configuration's flexible switch by default.

    ``sport`` switches its components flexible in the master file: its vehicle run
    without a fidelity (and the solver node's goal with an empty one) is the run asked
    with fidelity 'flexible', value for value, and differs from the one asked 'rigid'.
    """
    from types import SimpleNamespace

    from vd_solvers.solve import run_function

    sport = sedan['sport']
    default = run_vehicle_event(sport, 'step_steer')
    goal = run_function('vehicle')(
        sport, SimpleNamespace(event='step_steer', parameters=[], fidelity=''), None)
    flex = run_vehicle_event(sport, 'step_steer', [], fidelity='flexible')
    rigid = run_vehicle_event(sport, 'step_steer', [], fidelity='rigid')
    assert (default.fidelity, goal.fidelity, flex.fidelity, rigid.fidelity) == (
        'flexible', 'flexible', 'flexible', 'rigid')
    for run in (default, goal):
        assert run.metrics.keys() == flex.metrics.keys()
        for name, metric in flex.metrics.items():
            assert run.metrics[name].value == metric.value, name
        np.testing.assert_array_equal(run.channels['yaw_rate'].values,
                                      flex.channels['yaw_rate'].values)
    assert _m(rigid, 'yaw_rate_gain') != pytest.approx(_m(flex, 'yaw_rate_gain'), rel=1e-3)
