# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Stopping distance and MFDD against the closed forms of a stop.

A deceleration that rises linearly to a over t_r and then stays: the speed
v = v0 - a t^2 / (2 t_r) during the rise, then v_r - a (t - t_r); the distance
v0 t_r - a t_r^2 / 6 + v_r^2 / (2 a) with v_r = v0 - a t_r / 2. The MFDD (UN R13-H: between
0.8 v0 and 0.1 v0) is a when the rise ends above 0.8 v0.
"""
from __future__ import annotations

import numpy as np
import pytest

from vd_solvers.standards.braking import grade_stop


def stop_run(v0, a, rise, brake_time=1.0, dt=1e-4):
    t = np.arange(0.0, brake_time + rise + v0 / a + 1.0, dt)
    tau = np.clip(t - brake_time, 0.0, None)
    in_rise = tau < rise
    v_rise = v0 - a * tau**2 / (2 * rise)
    s_rise = v0 * tau - a * tau**3 / (6 * rise)
    v_r, s_r = v0 - a * rise / 2, v0 * rise - a * rise**2 / 6
    after = tau - rise
    v_after = np.maximum(v_r - a * after, 0.0)
    t_end = v_r / a
    s_after = s_r + v_r * np.minimum(after, t_end) - a * np.minimum(after, t_end) ** 2 / 2
    v = np.where(in_rise, v_rise, v_after)
    s = v0 * np.minimum(t, brake_time) + np.where(in_rise, s_rise, s_after)
    return t, v, s


@pytest.mark.parametrize('v0, a, rise', [(100 / 3.6, 9.0, 0.2), (80 / 3.6, 6.0, 0.3)])
def test_stop_with_a_deceleration_build_up(v0, a, rise):
    t, v, s = stop_run(v0, a, rise)
    stop = grade_stop(t, v, s, brake_time=1.0)
    v_r = v0 - a * rise / 2
    distance = v0 * rise - a * rise**2 / 6 + v_r**2 / (2 * a)
    assert stop.initial_speed == pytest.approx(v0, rel=1e-9)
    assert stop.stopping_distance == pytest.approx(distance, abs=2e-3)
    assert stop.stopping_time == pytest.approx(rise + v_r / a, abs=2e-3)
    assert stop.mfdd == pytest.approx(a, rel=1e-3)
    assert stop.mean_deceleration == pytest.approx(v0**2 / (2 * distance), rel=1e-3)
    assert stop.mean_deceleration < stop.mfdd  # the build-up costs distance


def test_a_run_that_does_not_stop_is_refused():
    t = np.linspace(0.0, 5.0, 501)
    v = 20.0 - 1.0 * t
    with pytest.raises(ValueError, match='does not come to a stop'):
        grade_stop(t, v, np.cumsum(v) * 0.01, brake_time=0.0)
    with pytest.raises(ValueError, match='outside the run'):
        grade_stop(t, v, np.cumsum(v) * 0.01, brake_time=9.0)
