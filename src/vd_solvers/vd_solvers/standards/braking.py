# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Straight-line braking: stopping distance and mean fully developed deceleration.

On a run's time series of speed and travelled distance from the brake application
(simulated or measured, SI):

* **Stopping distance**: the distance travelled from the brake application to standstill
  (speed below STANDSTILL), the reaction distance excluded.
* **Mean fully developed deceleration** (UN Regulation No. 13-H, Annex 3, 1.1.1; the same
  definition in ISO 21994): d_m = (v_b^2 - v_e^2) / (2 (s_e - s_b)) with v_b = 0.8 v_0 and
  v_e = 0.1 v_0, s_b and s_e the distances travelled at those speeds (the regulation
  writes it in km/h and m with 25.92 = 2 x 3.6^2; here SI). It leaves out the build-up of
  the deceleration at the start and the last tenth of the speed.
* **Mean deceleration** over the whole stop, v_0^2 / (2 s).

Each speed is passed at the first instant after the brake application the speed falls to
it (linear between samples); the distances are those travelled at these instants.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

STANDSTILL = 0.01  # m/s
MFDD_FROM, MFDD_TO = 0.8, 0.1  # of the initial speed


@dataclass(frozen=True)
class Stop:
    """The measures of one stop (SI)."""

    initial_speed: float  # m/s at the brake application
    stopping_distance: float  # m
    stopping_time: float  # s
    mfdd: float  # m/s^2, mean fully developed deceleration
    mean_deceleration: float  # m/s^2 over the whole stop


def grade_stop(t, speed, distance, brake_time: float) -> Stop:
    """Measure the stop that starts at ``brake_time`` (s) in a run (t, speed, distance)."""
    t, v, s = (np.asarray(a, dtype=float) for a in (t, speed, distance))
    if not (t.shape == v.shape == s.shape) or t.ndim != 1 or t.size < 3:
        raise ValueError('t, speed and distance must be series of one length (at least 3)')
    if not np.all(np.diff(t) > 0.0):
        raise ValueError('the time must increase')
    if not t[0] <= brake_time < t[-1]:
        raise ValueError(f'the brake application ({brake_time} s) lies outside the run')
    v0 = float(np.interp(brake_time, t, v))
    s0 = float(np.interp(brake_time, t, s))
    if not v0 > STANDSTILL:
        raise ValueError('the vehicle is not moving at the brake application')
    stopped = np.flatnonzero((t >= brake_time) & (v <= STANDSTILL))
    if stopped.size == 0:
        raise ValueError(f'the vehicle does not come to a stop (speed {v[-1]:.3g} m/s at '
                         f'the end of the run)')
    t_stop = _first_below(t, v, STANDSTILL, brake_time)
    s_stop = float(np.interp(t_stop, t, s))
    vb, ve = MFDD_FROM * v0, MFDD_TO * v0
    s_b = float(np.interp(_first_below(t, v, vb, brake_time), t, s))
    s_e = float(np.interp(_first_below(t, v, ve, brake_time), t, s))
    stopping = s_stop - s0
    return Stop(v0, stopping, t_stop - brake_time,
                (vb * vb - ve * ve) / (2.0 * (s_e - s_b)), v0 * v0 / (2.0 * stopping))


def _first_below(t: np.ndarray, v: np.ndarray, level: float, start: float) -> float:
    """Return the first instant after ``start`` the speed falls to ``level`` (interpolated)."""
    k = int(np.flatnonzero((t >= start) & (v <= level))[0])
    if t[k - 1] < start or v[k - 1] <= v[k]:
        return float(t[k])
    return float(t[k - 1] + (t[k] - t[k - 1]) * (v[k - 1] - level) / (v[k - 1] - v[k]))


__all__ = ['STANDSTILL', 'MFDD_FROM', 'MFDD_TO', 'Stop', 'grade_stop']
