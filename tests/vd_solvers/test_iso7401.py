# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
ISO 7401 step input on the known response of a linear single-track model.

The steady yaw rate of the linear model is closed form (u / (L + K u^2) per road-wheel
angle); response and peak times come from its 1 kHz truth (tests/vbox_logs.py), which the
grader never sees: it gets the 100 Hz samples only.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

import vbox_logs as vb
from vd_solvers.standards import iso7401
from vd_solvers.standards.fmvss126 import ProcessingError

DEG = math.pi / 180.0


def _first(t: np.ndarray, x: np.ndarray, level: float) -> float:
    i = int(np.argmax(x >= level))
    return float(np.interp(level, x[i - 1:i + 1], t[i - 1:i + 1]))


@pytest.fixture(scope='module')
def step() -> vb.Truth:
    return vb.step_truth(angle=40.0 * DEG, kmh=100.0, ramp_time=0.1, start=2.0)


def test_metrics_of_the_linear_model_step(step) -> None:
    g = iso7401.grade_step(step.time, step.steering_wheel_angle, step.yaw_rate,
                           step.lateral_acceleration, speed=step.speed,
                           sideslip=step.sideslip, roll=step.roll)
    c, u = vb.CAR, 100.0 / 3.6
    wheelbase = c['a'] + c['b']
    gain = u / (wheelbase + vb.understeer_gradient() * u ** 2) / c['ratio']
    assert g.step == pytest.approx(40.0 * DEG, rel=1e-3)
    assert g.t50 == pytest.approx(2.05, abs=0.005)  # the ramp's midpoint
    assert g.rise_time == pytest.approx(0.08, abs=0.01) and g.valid
    assert g.yaw_rate.gain == pytest.approx(gain, rel=0.005)
    assert g.lateral_acceleration.gain == pytest.approx(gain * u, rel=0.005)
    fine = step.fine
    for response, name in ((g.yaw_rate, 'yaw_rate'), (g.lateral_acceleration,
                                                      'lateral_acceleration')):
        y = fine[name]
        steady = float(np.mean(y[fine['time'] >= 7.0]))
        t90 = _first(fine['time'], y, 0.9 * steady) - 2.05
        peak = int(np.argmax(y))
        assert response.response_time == pytest.approx(t90, abs=0.01)
        assert response.peak_response_time == pytest.approx(fine['time'][peak] - 2.05,
                                                            abs=0.02)
        assert response.overshoot == pytest.approx(100.0 * (y[peak] / steady - 1.0), abs=0.5)
    assert g.speed == pytest.approx(u)
    assert g.roll_gain == pytest.approx(c['roll_gradient'] * gain * u, rel=0.01)


def test_a_slow_steering_ramp_is_not_a_step(step) -> None:
    slow = vb.step_truth(angle=40.0 * DEG, ramp_time=0.3)
    g = iso7401.grade_step(slow.time, slow.steering_wheel_angle, slow.yaw_rate,
                           slow.lateral_acceleration)
    assert g.rise_time == pytest.approx(0.24, abs=0.01)
    assert g.checks == {'rise_time': False, 'steering_held': True, 'steady_state': True,
                        'straight_before': True}
    assert not g.valid
    assert g.describe_checks()[0] == (f'rise time 10-90 % {g.rise_time:.3f} s (<= 0.15 s, '
                                      'ISO 7401): FAILED')


def test_a_step_released_too_early_is_refused(step) -> None:
    t = step.time
    swa = np.where(t < 2.6, step.steering_wheel_angle, 0.0)
    with pytest.raises(ProcessingError, match='the steady state needs 1 s'):
        iso7401.grade_step(t, swa, step.yaw_rate, step.lateral_acceleration)
