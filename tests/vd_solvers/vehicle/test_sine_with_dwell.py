# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The FMVSS 126 procedure on the full vehicle.

A from the SIS runs, a reduced series
graded with the rule's processing, mirror symmetry, the thesis' 4.4.2 trend, bad input.

The full series for every sample configuration runs in ``make bench`` / the demo; here a
reduced series (A given, 1.5A and 2A, both directions) keeps the suite short.
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from vd_data_server.errors import DataError
from vd_data_server.master import parse_set, with_overrides
from vd_data_server.study import load_study
from vd_solvers.analytical import bicycle
from vd_solvers.analytical.from_config import static_wheel_loads, vehicle_params
from vd_solvers.analytical.kc_link import kc_inputs
from vd_solvers.errors import SolverError
from vd_solvers.standards import fmvss126 as rule
from vd_solvers.vehicle import sine_with_dwell as swd
from vd_solvers.vehicle.adaptive import STEP_TOLERANCE
from vd_solvers.vehicle.events import run_vehicle_event
from vd_solvers.vehicle.model import VehicleModel

STUDIES = Path(__file__).resolve().parents[3] / 'src' / 'vd_data_server' / 'data' / 'studies'
DEG = math.pi / 180.0
A_GIVEN = 28.2  # deg, the sedan baseline's A from its SIS runs (test below)
REDUCED = [f'a_reference={A_GIVEN} deg', f'max_amplitude={2.0 * A_GIVEN + 0.05:.2f} deg']


@pytest.fixture(scope='module')
def sedan():
    return load_study(STUDIES / 'sedan.yaml').configurations


@pytest.fixture(scope='module')
def reduced(sedan):
    return run_vehicle_event(sedan['baseline'], 'sine_with_dwell', REDUCED)


def test_a_from_the_sis_run_is_the_steady_state_steer_at_0_3_g(sedan):
    """
    Find A near the steady-state steer at 0.3 g.

    The slowly increasing steer (13.5 deg/s) is quasi-steady: A is close to the steady
    steering-wheel angle at 0.3 g and 80 km/h of the bicycle model of the same K&C axles,
    i_s (L a / v^2 + K a); the two differ by the full vehicle's nonlinearity at 0.3 g.
    """
    model = VehicleModel(sedan['baseline'])
    steer, ay, trace = swd._sis(model, 1, STEP_TOLERANCE)  # as the event runs it
    a_sis = rule.amplitude_from_sis([(steer, ay)])
    config = sedan['baseline']
    kc = kc_inputs(config, static_wheel_loads(config))
    p = vehicle_params(config, kc.suspension, kc.compliance)
    a_y, v = 0.3 * 9.80665, 80.0 / 3.6
    steady = model.maps.steering_ratio * a_y * (p.wheelbase / v**2
                                                + bicycle.understeer_gradient(p))
    assert a_sis == pytest.approx(steady, rel=0.1)
    assert round(a_sis / DEG, 1) == pytest.approx(A_GIVEN, abs=0.05)
    # the run is held at 80 km/h and ends at 0.5 g
    ch = trace.channels()
    assert np.all(np.abs(ch['speed'] - 80.0 / 3.6) < 2.0 / 3.6)
    assert ch['yaw_rate'][-1] * ch['speed'][-1] >= 0.5 * 9.80665


def test_the_reduced_series_is_graded_in_both_directions(reduced):
    m = {k: v.value for k, v in reduced.metrics.items()}
    assert m['a_reference'] == pytest.approx(A_GIVEN * DEG)
    assert m['runs'] == 4 and m['reduced_series'] == 1.0
    assert reduced.notes[0].startswith('FMVSS 126 sine with dwell: PASS (reduced series: 2 of')
    ch = {k: c.values for k, c in reduced.channels.items()}
    np.testing.assert_allclose(ch['run_direction'], [1, 1, -1, -1])
    np.testing.assert_allclose(ch['run_amplitude'], np.array([1.5, 2.0, 1.5, 2.0]) * A_GIVEN * DEG,
                               rtol=5e-3)
    # both runs coast in from 80 km/h: the entry speed is within the rule's 80 +/- 2 km/h
    assert np.all(np.abs(ch['run_entry_speed'] - 80.0 / 3.6) <= 2.0 / 3.6)
    # responsiveness is not graded below 5A; stability on every run
    assert np.all(np.isnan(ch['run_responsive'])) and np.all(ch['run_stable_1_00'] == 1.0)


def test_left_and_right_first_runs_mirror_each_other(reduced):
    """The sedan is symmetric: the right-first run is the left-first run mirrored."""
    ch = {k: c.values for k, c in reduced.channels.items()}
    for name in ('run_peak_lateral_acceleration', 'run_peak_roll', 'run_peak_yaw_rate_abs',
                 'run_lateral_displacement', 'run_yaw_rate_ratio_1_00'):
        np.testing.assert_allclose(ch[name][:2], ch[name][2:], rtol=1e-3, atol=1e-4,
                                   err_msg=name)
    np.testing.assert_allclose(ch['run_peak_yaw_rate'][:2], -ch['run_peak_yaw_rate'][2:],
                               rtol=1e-3)


def reduced_cog_x() -> float:
    """Return the sprung CoG's x in the body frame (m, negative: behind the front axle)."""
    config = load_study(STUDIES / 'sedan.yaml').configurations['baseline']
    return float(config.group('mass').point('sprung_cog')[0])


def test_the_graded_displacement_is_the_cog_path_the_model_drove(reduced):
    """
    Compare the graded displacement with the CoG path.

    The rule's double integral of the lateral acceleration (in yaw axes, from BOS)
    against the CoG's own lateral offset from the straight entry path: they differ by
    the heading change over 1.07 s (a few per cent at this amplitude), not more.
    """
    ch = {k: c.values for k, c in reduced.channels.items()}
    g = rule.grade_run(ch['time'], ch['steering_wheel_angle'], ch['yaw_rate'],
                       ch['lateral_acceleration'], a_reference=A_GIVEN * DEG)
    decide = int(reduced.metrics['deciding_run'].value) - 1
    assert g.lateral_displacement == pytest.approx(ch['run_lateral_displacement'][decide],
                                                   rel=1e-9)
    cog_x = reduced_cog_x()
    t = ch['time']
    y_cog = ch['y'] + np.sin(ch['yaw']) * cog_x
    at = g.bos + rule.DISPLACEMENT_TIME
    offset = g.direction * (np.interp(at, t, y_cog) - np.interp(g.bos, t, y_cog))
    assert g.lateral_displacement == pytest.approx(offset, rel=0.08)


def test_more_front_roll_stiffness_lowers_lateral_acceleration_roll_and_yaw_rate(sedan,
                                                                                 reduced):
    """
    Check the thesis' 4.4.2 trend (Figs. 4.4.4-4.4.6).

    Stiffer front springs (30 -> 60 N/mm): less roll in every run; lower peak lateral
    acceleration and yaw rate where the load transfer matters, at 2A (0.6 g). At 1.5A
    (0.47 g, nearly linear) the sedan's peaks differ by under 1 % either way. (A thicker
    front bar is not the way here: the sample bar's load steers the front wheels into the
    turn in roll, the K&C opposite-travel roll steer the full vehicle now follows, which
    lifts the yaw rate by as much as its roll stiffness lowers it.)
    """
    stiff = with_overrides(sedan['baseline'], parse_set(['front_spring.rate=60 N/mm']))
    out = run_vehicle_event(stiff, 'sine_with_dwell', REDUCED)
    new = {k: c.values for k, c in out.channels.items()}
    old = {k: c.values for k, c in reduced.channels.items()}
    assert np.all(new['run_peak_roll'] < 0.9 * old['run_peak_roll'])
    at_2a = [1, 3]
    for name in ('run_peak_lateral_acceleration', 'run_peak_yaw_rate_abs'):
        assert np.all(new[name][at_2a] < old[name][at_2a]), name


def test_a_series_cut_below_its_first_amplitude_is_an_error(sedan):
    with pytest.raises(SolverError) as err:
        run_vehicle_event(sedan['baseline'], 'sine_with_dwell',
                          ['max_amplitude=30 deg', 'a_reference=26.7 deg'])
    assert str(err.value) == ("configuration 'baseline', event 'sine_with_dwell': "
                              'max_amplitude 30.0 deg is below the first amplitude of the '
                              'series, 1.5A = 40.1 deg')


@pytest.mark.parametrize('param, message', [
    ('a_reference=400 deg', '400 deg is outside [0, 5.23599] rad'),
    ('gvwr=-5 kg', '-5 kg is outside [0, 20000] kg'),
])
def test_a_parameter_out_of_range_is_a_data_error(sedan, param, message):
    with pytest.raises(DataError) as err:
        run_vehicle_event(sedan['baseline'], 'sine_with_dwell', [param])
    assert message in str(err.value)


def test_unknown_parameter_is_a_data_error(sedan):
    with pytest.raises(DataError) as err:
        run_vehicle_event(sedan['baseline'], 'sine_with_dwell', ['amplitude=3 deg'])
    assert "unknown parameter 'amplitude'" in str(err.value)
    assert 'a_reference, max_amplitude, gvwr, step_tolerance' in str(err.value)
