# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The handling events' default variable step against the converged fixed step.

The step steer (ISO 7401) and the sine with dwell (FMVSS 126) take the variable step of
:mod:`vd_solvers.vehicle.adaptive` unless ``step_tolerance=0``. The reference is the same
manoeuvre with the fixed step of 0.5 ms: semi-implicit Euler converges at first order, so
its own error is a tenth of the 5 ms step's (docs/models.md, "Variable step": 0.2 % of
the yaw rate's peak on these cars). Stated bounds, from what the tolerance is chosen for
(the yaw rate and the lateral acceleration within 1 % of their peaks):

* steady values and gains within 0.5 % (the steady state is a fixed point of either step);
* peaks within 1 % (overshoots within 1 percentage point of the steady value);
* response times within one recorded sample (10 ms), and each peak time where the
  reference is within 1 % of its own peak (a flat peak's time is not sharper than that);
* the sine with dwell's graded yaw-rate ratios within 0.01 (1 % of the peak yaw rate),
  the lateral displacement within 1 %, the peak yaw rate within 1 %.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from vd_data_server.study import load_study
from vd_solvers.constants import DEG
from vd_solvers.standards import fmvss126 as rule
from vd_solvers.vehicle import sine_with_dwell as swd
from vd_solvers.vehicle.adaptive import STEP_TOLERANCE
from vd_solvers.vehicle.drivers import OpenLoopSteering
from vd_solvers.vehicle.events import run_vehicle_event
from vd_solvers.vehicle.model import VehicleModel
from vd_solvers.vehicle.simulation import simulate

STUDIES = Path(__file__).resolve().parents[3] / 'src' / 'vd_data_server' / 'data' / 'studies'
#: the converged reference's fixed step, s
FINE = 0.0005
FIXED_FINE = ['step_tolerance=0 m/s', f'time_step={FINE} s']
STEADY = ('steady_yaw_rate', 'steady_lateral_acceleration', 'yaw_rate_gain',
          'lateral_acceleration_gain', 'sideslip_gain', 'roll_gain')
SAMPLE = 0.01  # s, the step steer's recorded period


@pytest.fixture(scope='module', params=['sedan.yaml', 'hmmwv.yaml'])
def config(request):
    configurations = load_study(STUDIES / request.param).configurations
    return configurations[next(iter(configurations))]


@pytest.fixture(scope='module')
def step_steers(config):
    return run_vehicle_event(config, 'step_steer'), run_vehicle_event(config, 'step_steer',
                                                                      FIXED_FINE)


def test_the_step_steer_takes_the_variable_step_by_default(step_steers):
    default, fine = step_steers
    assert any(f'variable step (tolerance {STEP_TOLERANCE:g}' in n for n in default.notes)
    assert any(f'step {FINE * 1e3:g} ms' in n for n in fine.notes)
    np.testing.assert_allclose(default.channels['time'].values, fine.channels['time'].values,
                               atol=1e-12)


def test_the_default_step_steer_metrics_follow_the_converged_step(step_steers):
    """ISO 7401 metrics of the default run against the 0.5 ms run (module doc's bounds)."""
    default, fine = step_steers

    def m(outcome, name):
        return outcome.metrics[name].value

    for name in STEADY:
        np.testing.assert_allclose(m(default, name), m(fine, name), rtol=0.005, err_msg=name)
    t = fine.channels['time'].values
    t50 = 1.0 + 0.5 * 0.1  # the step's 50 % instant: at 1 s, ramp 0.1 s (the defaults)
    for key in ('yaw_rate', 'lateral_acceleration'):
        peak = 1.0 + m(fine, f'{key}_overshoot') / 100.0  # over the steady value
        assert abs(1.0 + m(default, f'{key}_overshoot') / 100.0 - peak) <= 0.01 * peak, key
        assert abs(m(default, f'{key}_response_time_90')
                   - m(fine, f'{key}_response_time_90')) <= SAMPLE + 1e-9, key
        y = fine.channels[key].values
        at = int(np.argmin(np.abs(t - (t50 + m(default, f'{key}_peak_response_time')))))
        assert y[at] >= 0.99 * np.max(y), key


def _sine_run(model: VehicleModel, amplitude: float, h: float, tolerance: float | None):
    """Run a sine with dwell of the procedure (S7.9), steered to the left first."""
    end = swd.STEER_START + 1.0 / swd.FREQUENCY + swd.DWELL
    steering = OpenLoopSteering(
        lambda t: rule.sine_with_dwell(t, amplitude, 1, swd.STEER_START, swd.FREQUENCY,
                                       swd.DWELL), vectorized=True)
    trace = simulate(model, steering, None, end + rule.YAW_TIMES[1] + swd.RECORD_MARGIN,
                     event='sine_with_dwell', initial_speed=swd.SWD_SPEED,
                     record_every=round(0.01 / h), h=h, tolerance=tolerance)
    return trace.channels()


@pytest.mark.parametrize('amplitude', [100.0 * DEG, 270.0 * DEG])
def test_the_default_sine_with_dwell_grades_as_the_converged_step(config, amplitude):
    """FMVSS 126 graded quantities of a run, default step against 0.5 ms (module doc)."""
    model = VehicleModel(config)
    a_reference = amplitude / 6.5  # any A: grading only, no verdict on the series
    grades = []
    for h, tolerance in ((FINE, None), (0.005, STEP_TOLERANCE)):
        ch = _sine_run(model, amplitude, h, tolerance)
        grades.append(rule.grade_run(ch['time'], ch['steering_wheel_angle'], ch['yaw_rate'],
                                     ch['lateral_acceleration'], a_reference=a_reference,
                                     roll=ch['roll'], gvwr=model.total_mass, speed=ch['speed'],
                                     commanded_amplitude=amplitude))
    fine, default = grades
    assert abs(default.yaw_rate_ratio_1_00 - fine.yaw_rate_ratio_1_00) <= 0.01
    assert abs(default.yaw_rate_ratio_1_75 - fine.yaw_rate_ratio_1_75) <= 0.01
    np.testing.assert_allclose(default.lateral_displacement, fine.lateral_displacement,
                               rtol=0.01)
    np.testing.assert_allclose(default.peak_yaw_rate, fine.peak_yaw_rate, rtol=0.01)
    assert default.passed == fine.passed


def test_a_road_with_relief_keeps_the_fixed_step():
    """The ISO 8608 road of hmmwv_roads.yaml: the wheel hop needs the fixed step (notes)."""
    configurations = load_study(STUDIES / 'hmmwv_roads.yaml').configurations
    out = run_vehicle_event(configurations['baseline'], 'step_steer', ['duration=3 s'])
    assert any('step 5 ms' in n for n in out.notes)
    assert not any('variable step' in n for n in out.notes)


def test_brakes_and_a_driveline_keep_the_fixed_step():
    """sedan_longitudinal.yaml's abs: the step steer says it ran the fixed step, and did."""
    config = load_study(STUDIES / 'sedan_longitudinal.yaml').configurations['abs']
    default = run_vehicle_event(config, 'step_steer', ['duration=3 s'])
    fixed = run_vehicle_event(config, 'step_steer', ['duration=3 s', 'step_tolerance=0 m/s'])
    assert any('step 5 ms' in n for n in default.notes)
    assert not any('variable step' in n for n in default.notes)
    for name, channel in fixed.channels.items():
        np.testing.assert_array_equal(default.channels[name].values, channel.values)
