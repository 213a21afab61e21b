# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
ISO 7401:2011 step input (lateral transient response): metrics and validity of one run.

On any time series -- a simulation or a measured vehicle log -- with the steering-wheel
angle, the yaw rate and the lateral acceleration (SI, ISO 8855 signs):

* **Filtering**: the 12-pole phaseless Butterworth of :mod:`.fmvss126` (steering-wheel
  angle 10 Hz, responses 6 Hz). ISO 7401 leaves the data processing to ISO 15037-1;
  using the FMVSS 126 filters for both transient standards is vd's choice.
* **The step**: the straight-ahead angle is the mean over the PRE_WINDOW before the
  steering wheel first leaves it; the held angle is the median where the filtered angle
  is within 10 % of its largest excursion. t10, t50, t90: the first instants the angle
  passes 10, 50 and 90 % of the step. **t50 is the time origin** of every response time
  (ISO 7401 5.3, the 50 % steering-wheel instant); the rise time t90 - t10 is the
  steering input's speed.
* **Steady state**: the mean over the STEADY_WINDOW that ends where the steering wheel
  leaves the held angle (or the record ends); responses are zeroed by their mean over
  the PRE_WINDOW before the step.
* **Metrics** (yaw rate and lateral acceleration): response time (t50 to the first
  instant the response reaches 90 % of its steady value, interpolated), peak response
  time (t50 to the peak), overshoot (peak / steady - 1, in %), steady-state gain
  (steady value / steering-wheel step); sideslip and roll gains where logged.
* **Validity**: the rise time within RISE_TIME_LIMIT (0.15 s; the ramp bound vd's step
  steer event also states for ISO 7401); the steering wheel held within
  HOLD_TOLERANCE of the step from the instant it reaches the held angle (within a fifth
  of the tolerance) to the end of the steady window; the responses
  steady over that window (the filtered yaw rate within STEADY_TOLERANCE of its steady
  value); straight running before the step (|yaw rate| below STRAIGHT_YAW_RATE over the
  PRE_WINDOW). Tolerances other than the rise time are vd's, stated with the result.

Signals in SI (rad, rad/s, m/s^2, s). Results carry SI.
"""
from __future__ import annotations

from dataclasses import dataclass
import math

import numpy as np

from vd_solvers.constants import DEG

from .fmvss126 import RESPONSE_CUTOFF, STEER_CUTOFF, ProcessingError, lowpass

PRE_WINDOW = 1.0  # s of straight running before the step (zeroing, straight-ahead angle)
STEADY_WINDOW = 1.0  # s averaged for the steady state (the vehicle step steer event's)
RISE_TIME_LIMIT = 0.15  # s, 10 % to 90 % of the steering-wheel step
HOLD_TOLERANCE = 0.05  # of the step: the steering wheel held after t90
STEADY_TOLERANCE = 0.05  # of the steady yaw rate over the steady window
STRAIGHT_YAW_RATE = 1.0 * DEG  # rad/s, before the step
LEAVE_ANGLE = 2.0 * DEG  # rad: the steering wheel has left straight ahead


@dataclass(frozen=True)
class Response:
    """The transient metrics of one response to the step (SI)."""

    steady: float  # steady-state value
    gain: float  # steady / steering-wheel step
    response_time: float  # s from t50 to 90 % of steady (NaN if never reached)
    peak_response_time: float  # s from t50 to the peak
    peak: float  # peak value (signed like the steady value)
    overshoot: float  # %, peak / steady - 1


@dataclass(frozen=True)
class StepGrade:
    """One ISO 7401 step-input run: the step, the responses and the validity checks."""

    step: float  # rad, steering-wheel angle step (signed)
    t10: float
    t50: float
    t90: float
    steady_window: tuple[float, float]  # s
    yaw_rate: Response
    lateral_acceleration: Response
    speed: float | None  # m/s, mean over the steady window
    speed_at_step: float | None  # m/s at t50
    sideslip_gain: float | None  # rad/rad
    roll_gain: float | None  # rad/rad
    hold_error: float  # max |angle - held| / |step| once reached, to the steady window's end
    steady_error: float  # max |yaw rate - steady| / |steady| over the steady window
    straight_yaw_rate: float  # rad/s, max |yaw rate| over the PRE_WINDOW

    @property
    def rise_time(self) -> float:
        return self.t90 - self.t10

    @property
    def checks(self) -> dict[str, bool]:
        """Each validity check: rise_time, steering_held, steady_state, straight_before."""
        return {'rise_time': self.rise_time <= RISE_TIME_LIMIT * (1 + 1e-9),
                'steering_held': self.hold_error <= HOLD_TOLERANCE,
                'steady_state': self.steady_error <= STEADY_TOLERANCE,
                'straight_before': self.straight_yaw_rate <= STRAIGHT_YAW_RATE}

    @property
    def valid(self) -> bool:
        return all(self.checks.values())

    def describe_checks(self) -> list[str]:
        """One line per check with the measured value and its limit."""
        c = self.checks
        word = {True: 'ok', False: 'FAILED'}
        return [f"rise time 10-90 % {self.rise_time:.3f} s (<= {RISE_TIME_LIMIT:g} s, "
                f"ISO 7401): {word[c['rise_time']]}",
                f"steering wheel held within {100 * self.hold_error:.1f} % of the step "
                f"(<= {100 * HOLD_TOLERANCE:g} %, vd): {word[c['steering_held']]}",
                f"steady yaw rate within {100 * self.steady_error:.1f} % over the last "
                f"{STEADY_WINDOW:g} s (<= {100 * STEADY_TOLERANCE:g} %, vd): "
                f"{word[c['steady_state']]}",
                f"straight before the step: |yaw rate| <= {self.straight_yaw_rate / DEG:.2f} "
                f"deg/s (<= {STRAIGHT_YAW_RATE / DEG:g} deg/s, vd): "
                f"{word[c['straight_before']]}"]


def _first_crossing(t: np.ndarray, x: np.ndarray, level: float, start: int) -> float:
    """First time at or after sample ``start`` where x reaches ``level`` (x rising)."""
    above = np.flatnonzero(x[start:] >= level)
    if not above.size:
        return float('nan')
    i = start + int(above[0])
    if i == 0 or x[i - 1] >= level:
        return float(t[i])
    return float(t[i - 1] + (level - x[i - 1]) * (t[i] - t[i - 1]) / (x[i] - x[i - 1]))


def step_instants(t: np.ndarray, steering: np.ndarray) -> tuple[float, float, float, float,
                                                                 float, float]:
    """
    Find the step of a filtered steering-wheel angle (module doc).

    Returns (straight-ahead angle, held angle, t10, t50, t90, end of hold): the hold ends
    where the angle leaves the held value by more than twice HOLD_TOLERANCE of the step,
    or at the end of the record.
    """
    if t[-1] - t[0] < PRE_WINDOW + STEADY_WINDOW:
        raise ProcessingError(f'the record is {t[-1] - t[0]:.2f} s long; a step steer needs '
                              f'{PRE_WINDOW:g} s before and {STEADY_WINDOW:g} s of steady state')
    first = t < t[0] + PRE_WINDOW
    moved = np.flatnonzero(np.abs(steering - np.mean(steering[first])) > LEAVE_ANGLE)
    if not moved.size:
        raise ProcessingError('the steering-wheel angle never leaves straight ahead by 2 deg')
    leave = int(moved[0])
    pre = (t >= t[leave] - PRE_WINDOW - 0.1) & (t < t[leave] - 0.1)
    if np.count_nonzero(pre) < 3:
        raise ProcessingError(f'the steer starts {t[leave] - t[0]:.2f} s into the record; '
                              f'the step needs {PRE_WINDOW:g} s of straight running before it')
    straight = float(np.mean(steering[pre]))
    excursion = steering - straight
    k_max = int(np.argmax(np.abs(excursion)))
    sign = 1.0 if excursion[k_max] > 0 else -1.0
    s = sign * excursion
    near = s >= 0.9 * s[k_max]
    held = float(np.median(s[near]))
    start = leave
    while start > 0 and s[start - 1] < s[start]:
        start -= 1
    t10, t50, t90 = (_first_crossing(t, s, f * held, start) for f in (0.1, 0.5, 0.9))
    i90 = int(np.searchsorted(t, t90))
    off = np.flatnonzero(np.abs(s[i90:] - held) > 2.0 * HOLD_TOLERANCE * held)
    end = float(t[i90 + int(off[0]) - 1]) if off.size else float(t[-1])
    return straight, straight + sign * held, t10, t50, t90, end


def _response(t: np.ndarray, y: np.ndarray, step: float, t50: float,
              steady: tuple[float, float]) -> Response:
    window = (t >= steady[0]) & (t <= steady[1])
    y_ss = float(np.mean(y[window]))
    if y_ss == 0.0:
        raise ProcessingError('a response has no steady value (zero)')
    sign = 1.0 if y_ss > 0 else -1.0
    i50 = int(np.searchsorted(t, t50))
    t_90 = _first_crossing(t, sign * y, 0.9 * abs(y_ss), i50)
    span = (t >= t50) & (t <= steady[1])
    k = int(np.argmax(np.where(span, sign * y, -np.inf)))
    return Response(steady=y_ss, gain=y_ss / step, response_time=t_90 - t50,
                    peak_response_time=float(t[k] - t50), peak=float(y[k]),
                    overshoot=100.0 * (float(y[k]) / y_ss - 1.0))


def grade_step(t, steering, yaw_rate, lateral_acceleration, *, speed=None, sideslip=None,
               roll=None) -> StepGrade:
    """Process one step-input run (module doc); ProcessingError names what is missing."""
    t = np.asarray(t, dtype=float)
    named = {'steering': steering, 'yaw_rate': yaw_rate,
             'lateral_acceleration': lateral_acceleration, 'speed': speed,
             'sideslip': sideslip, 'roll': roll}
    for name, x in named.items():
        if x is None:
            continue
        x = np.asarray(x, dtype=float)
        if x.shape != t.shape:
            raise ProcessingError(f'{name} has {x.size} samples, time has {t.size}')
        if not np.all(np.isfinite(x)):
            raise ProcessingError(f'{name} holds non-finite samples')
    delta = lowpass(t, steering, STEER_CUTOFF)
    straight, held, t10, t50, t90, end = step_instants(t, delta)
    if not math.isfinite(t90):
        raise ProcessingError('the steering-wheel angle never reaches 90 % of its step')
    step = held - straight
    steady = (end - STEADY_WINDOW, end)
    if steady[0] < t90:
        raise ProcessingError(f'the steering wheel is held {end - t90:.2f} s after t90; the '
                              f'steady state needs {STEADY_WINDOW:g} s')
    pre = (t >= t10 - PRE_WINDOW - 0.1) & (t < t10 - 0.1)
    r = lowpass(t, yaw_rate, RESPONSE_CUTOFF)
    ay = lowpass(t, lateral_acceleration, RESPONSE_CUTOFF)
    straight_r = float(np.max(np.abs(r[pre])))
    r, ay = r - np.mean(r[pre]), ay - np.mean(ay[pre])
    yaw = _response(t, r, step, t50, steady)
    lat = _response(t, ay, step, t50, steady)
    window = (t >= steady[0]) & (t <= steady[1])
    reached = _first_crossing(t, (delta - straight) / step, 1.0 - 0.2 * HOLD_TOLERANCE,
                              int(np.searchsorted(t, t90)))
    hold = (t >= (reached if math.isfinite(reached) else t90)) & (t <= steady[1])
    gains = {}
    for name, x in (('sideslip', sideslip), ('roll', roll)):
        if x is not None:
            x = np.asarray(x, dtype=float)
            gains[name] = float(np.mean(x[window]) - np.mean(x[pre])) / step
    v = None if speed is None else np.asarray(speed, dtype=float)
    return StepGrade(
        step=step, t10=t10, t50=t50, t90=t90, steady_window=steady, yaw_rate=yaw,
        lateral_acceleration=lat,
        speed=None if v is None else float(np.mean(v[window])),
        speed_at_step=None if v is None else float(np.interp(t50, t, v)),
        sideslip_gain=gains.get('sideslip'), roll_gain=gains.get('roll'),
        hold_error=float(np.max(np.abs(delta[hold] - held)) / abs(step)),
        steady_error=float(np.max(np.abs(r[window] - yaw.steady)) / abs(yaw.steady)),
        straight_yaw_rate=straight_r)


__all__ = ['StepGrade', 'Response', 'grade_step', 'step_instants', 'RISE_TIME_LIMIT',
           'STEADY_WINDOW', 'PRE_WINDOW']
