# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
FMVSS 126 / UN R140 / GTR 8 sine-with-dwell processing and grading.

On any time series -- a simulation or a measured vehicle log.

Implemented as the rule states it (49 CFR 571.126 S5.2, S7.6, S7.9, S7.11; GTR 8):

* **Filtering**: 12-pole phaseless Butterworth low-pass -- a 6-pole Butterworth run
  forward and backward (``scipy.signal.sosfiltfilt``): steering-wheel angle at 10 Hz,
  yaw rate and lateral acceleration at 6 Hz.
* **Steering-wheel rate** (S7.11.4): the derivative of the filtered steering-wheel angle,
  smoothed by a 0.1 s running average.
* **Zeroing** (S7.11.5): each filtered signal minus its mean over the 1.0 s before the
  instant the steering-wheel rate first exceeds 75 deg/s and stays above it for 200 ms.
* **BOS** (beginning of steer): the first instant the zeroed steering-wheel angle reaches
  5 deg in the direction of the first steer. **COS** (completion of steer): the instant the
  steering wheel returns to zero after the dwell (the last zero crossing of the steer).
* **Peak yaw rate**: the first local peak of yaw rate after the steering-wheel angle
  changes sign (between its first and second peaks) -- not the window maximum. A yaw
  rate that turns against the first steer (a sign convention other than ISO 8855's) is
  refused, not graded on the wrong lobe.
* **Lateral stability** (S5.2.1, S5.2.2): yaw rate at COS + 1.0 s <= 35 % and at
  COS + 1.75 s <= 20 % of the peak yaw rate "during the same test run". "Shall not
  exceed" is <=. The rule's text bounds these criteria by no amplitude, so every run of
  the series is graded (STABILITY_FROM = 0 x A).
* **Responsiveness** (S5.2.3): lateral displacement of the CoG, the double integral of
  the (filtered, zeroed) lateral acceleration from BOS, at BOS + 1.07 s >= 1.83 m for a
  GVWR <= 3 500 kg (>= 1.52 m above), for runs with an amplitude of 5A or more.
* **A** (S7.6, S7.6.1): steering-wheel angle at 0.3 g from the slowly-increasing-steer
  runs (80 +/- 2 km/h, steering-wheel rate 13.5 deg/s), by linear regression of
  steering-wheel angle on lateral acceleration over 0.1..0.375 g per run, each run's A to
  the nearest 0.1 deg, the absolute values averaged and rounded to 0.1 deg. A measured
  SIS run (:func:`grade_sis`) is filtered and zeroed as a sine-with-dwell run and checked:
  speed within 80 +/- 2 km/h over the regression window, steering-wheel rate within
  SIS_RATE_TOLERANCE of 13.5 deg/s (the rule states no tolerance; this is vd's).
  **Amplitude series** (S7.9): 1.5A, then steps of 0.5A up to the greater of 6.5A and
  270 deg, no run beyond 300 deg.
* **Validity of a run**: entry speed (S7.9: coasting from 80 +/- 2 km/h; with a speed
  signal the speed at BOS is checked) and the steering profile (S7.9.1: 0.7 Hz sine with
  a 500 ms dwell): the steer's first half-period (its start, extrapolated back from BOS
  along the sine, to the reversal) and its length (start to COS) within
  PROFILE_TOLERANCE of 1/(2 x 0.7 Hz) and 1/0.7 Hz + 0.5 s (vd's tolerance; a hand-driven
  steer with extra lobes fails it). An invalid run is never graded as passed.
* **Procedure** (:func:`grade_procedure`): valid when every run (and every SIS run that
  gave A) is valid; the criteria are graded on the valid runs; the vehicle passes when
  the procedure is valid, A is known and every graded run meets every criterion that
  applies to it.
  The deciding run and criterion: the first invalid run and its reason
  (``entry_speed``, ``steering_profile``; ``sis_speed``, ``sis_steering_rate`` for an SIS
  run), else the first failing run (series order, lowest amplitude first), or, when all
  pass, the run with the least margin to its limit.

Signals in SI (rad, rad/s, m/s^2, s); signs ISO 8855 (left positive). Results carry SI.
"""
from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
import math

import numpy as np
import scipy.signal

from vd_solvers.constants import DEG
from vd_solvers.constants import STANDARD_GRAVITY as G

STEER_CUTOFF = 10.0  # Hz
RESPONSE_CUTOFF = 6.0  # Hz
BUTTERWORTH_POLES = 6  # per pass; forward and backward make the rule's 12 poles
ZERO_RATE = 75.0 * DEG  # rad/s
ZERO_HOLD = 0.2  # s the rate must stay above ZERO_RATE
ZERO_WINDOW = 1.0  # s
BOS_ANGLE = 5.0 * DEG  # rad
YAW_TIMES = (1.0, 1.75)  # s after COS
YAW_LIMITS = (0.35, 0.20)
DISPLACEMENT_TIME = 1.07  # s after BOS
DISPLACEMENT_LIMIT = {'light': 1.83, 'heavy': 1.52}  # m, GVWR <= / > 3 500 kg
HEAVY_GVWR = 3500.0  # kg
RESPONSIVENESS_FROM = 5.0  # x A (S5.2.3: commanded amplitudes of 5A and greater)
STABILITY_FROM = 0.0  # x A (S5.2.1, S5.2.2: every run)
ENTRY_SPEED, ENTRY_TOLERANCE = 80.0 / 3.6, 2.0 / 3.6  # m/s (S7.6, S7.9)
RATE_WINDOW = 0.1  # s, running average of the steering-wheel rate (S7.11.4)
FREQUENCY, DWELL = 0.7, 0.5  # Hz, s (S7.9.1)
#: relative tolerance of the steer's half-period and length (vd's; the rule gives none)
PROFILE_TOLERANCE = 0.05
SIS_RATE = 13.5 * DEG  # rad/s (S7.6)
#: relative tolerance of the SIS steering-wheel rate (vd's; the rule gives none)
SIS_RATE_TOLERANCE = 0.05
#: s, length of an SIS run's zeroing window, ending SIS_ZERO_GAP before the ramp starts
SIS_ZERO_WINDOW, SIS_ZERO_GAP = 1.0, 0.25
SIS_RANGE = (0.1 * G, 0.375 * G)  # m/s^2, regression window of the SIS runs
SIS_TARGET = 0.3 * G
SERIES_START, SERIES_STEP, SERIES_TOP = 1.5, 0.5, 6.5  # x A
SERIES_MIN_LAST, SERIES_CAP = 270.0 * DEG, 300.0 * DEG  # rad


class ProcessingError(ValueError):
    """The signals do not hold what the procedure needs (names the quantity)."""


def lowpass(t: np.ndarray, x: np.ndarray, cutoff: float) -> np.ndarray:
    """12-pole phaseless Butterworth low-pass of ``x`` sampled at times ``t`` (uniform)."""
    t, x = np.asarray(t, dtype=float), np.asarray(x, dtype=float)
    if t.size < 30 or t.shape != x.shape:
        raise ProcessingError('need at least 30 samples of equal-length time and signal')
    check_uniform(t)
    fs = 1.0 / float(np.mean(np.diff(t)))
    if not cutoff < 0.5 * fs:
        raise ProcessingError(f'sample rate {fs:.1f} Hz is too low for a {cutoff:g} Hz filter')
    sos = scipy.signal.butter(BUTTERWORTH_POLES, cutoff, fs=fs, output='sos')
    return scipy.signal.sosfiltfilt(sos, x)


def check_uniform(t: np.ndarray) -> None:
    """Refuse a time axis that is not strictly increasing with one step, saying where."""
    dt = np.diff(t)
    bad = np.flatnonzero(dt <= 0.0)
    if bad.size:
        i = int(bad[0])
        raise ProcessingError(f'time does not increase at t = {t[i + 1]:.3f} s (sample '
                              f'{i + 2}: {t[i]:.3f} s, then {t[i + 1]:.3f} s)')
    step = float(np.median(dt))
    bad = np.flatnonzero(np.abs(dt - step) > 1e-6 * step + 1e-12)
    if bad.size:
        i = int(bad[0])
        raise ProcessingError(f'time step not uniform: {dt[i]:.4g} s from t = {t[i]:.3f} s to '
                              f'{t[i + 1]:.3f} s where the step is {step:.4g} s (a gap in the '
                              f'record; {bad.size} such step(s))')


def steering_rate(t: np.ndarray, steering: np.ndarray) -> np.ndarray:
    """
    Return the steering-wheel rate (S7.11.4), rad/s.

    The derivative of the filtered steering-wheel angle, smoothed by a running average
    over RATE_WINDOW (0.1 s, centred).
    """
    rate = np.gradient(steering, t)
    n = max(1, int(round(RATE_WINDOW / float(np.mean(np.diff(t))))))
    if n < 2:
        return rate
    kernel = np.ones(n) / n
    padded = np.pad(rate, (n // 2, n - 1 - n // 2), mode='edge')
    return np.convolve(padded, kernel, mode='valid')


def zeroing_end(t: np.ndarray, steering: np.ndarray) -> float:
    """
    Find the end of the zeroing window (S7.11.5).

    The instant the steering-wheel rate (:func:`steering_rate`) first exceeds 75 deg/s
    and stays above it for at least 200 ms.
    """
    above = np.abs(steering_rate(t, steering)) > ZERO_RATE
    starts = np.flatnonzero(above & ~np.r_[False, above[:-1]])
    for i in starts:
        j = i
        while j + 1 < t.size and above[j + 1]:
            j += 1
        if t[j] - t[i] >= ZERO_HOLD:
            return float(t[i])
    raise ProcessingError('the steering-wheel rate never exceeds 75 deg/s for 200 ms')


def _zeroed(t: np.ndarray, x: np.ndarray, end: float) -> np.ndarray:
    window = (t >= end - ZERO_WINDOW) & (t < end)
    if not np.any(window):
        raise ProcessingError('no samples in the 1 s zeroing window before the steer')
    return x - x[window].mean()


def _crossing(t: np.ndarray, x: np.ndarray, i: int) -> float:
    """Time where x crosses zero between samples i and i + 1 (linear)."""
    return float(t[i] - x[i] * (t[i + 1] - t[i]) / (x[i + 1] - x[i]))


@dataclass(frozen=True)
class SwdGrade:
    """One sine-with-dwell run, processed and graded (SI; ratios as fractions)."""

    amplitude: float  # rad, steering-wheel, |first peak|
    direction: int  # +1 first steer to the left, -1 to the right
    bos: float  # s
    cos: float  # s
    peak_yaw_rate: float  # rad/s, signed (first local peak after the steering reversal)
    yaw_rate_ratio_1_00: float
    yaw_rate_ratio_1_75: float
    lateral_displacement: float  # m at BOS + 1.07 s, in the direction of the first steer
    peak_lateral_acceleration: float  # m/s^2, |max|
    peak_roll: float | None  # rad, |max|, when a roll signal is given
    responsiveness_applies: bool
    stable_1_00: bool
    stable_1_75: bool
    responsive: bool | None  # None when the criterion does not apply to this amplitude
    peak_yaw_rate_abs: float = float('nan')  # rad/s, |max| of the filtered yaw rate
    entry_speed: float | None = None  # m/s at BOS, when a speed signal is given
    displacement_limit: float = DISPLACEMENT_LIMIT['light']  # m
    steer_start: float = float('nan')  # s, the sine's start extrapolated back from BOS
    reversal: float = float('nan')  # s, the steer's first zero crossing after BOS
    zeroing_end: float = float('nan')  # s, end of the zeroing window (S7.11.5)

    @property
    def speed_valid(self) -> bool:
        """Entry speed within 80 +/- 2 km/h (True without a speed signal)."""
        return self.entry_speed is None or abs(self.entry_speed - ENTRY_SPEED) <= \
            ENTRY_TOLERANCE * (1.0 + 1e-9)

    @property
    def half_period(self) -> float:
        """Return the time from the steer's start to its reversal, s (0.714 s at 0.7 Hz)."""
        return self.reversal - self.steer_start

    @property
    def steer_duration(self) -> float:
        """Return the time from the steer's start to COS, s (1.929 s at 0.7 Hz + 0.5 s)."""
        return self.cos - self.steer_start

    @property
    def profile_valid(self) -> bool:
        """The steer is the rule's 0.7 Hz sine with a 500 ms dwell (PROFILE_TOLERANCE)."""
        if not (math.isfinite(self.steer_start) and math.isfinite(self.reversal)):
            return True  # graded without the profile (a run built from its results)
        return (abs(self.half_period * 2.0 * FREQUENCY - 1.0) <= PROFILE_TOLERANCE and
                abs(self.steer_duration / (1.0 / FREQUENCY + DWELL) - 1.0) <= PROFILE_TOLERANCE)

    @property
    def invalid_reasons(self) -> tuple[str, ...]:
        """Why the run is not a valid run of the rule ('entry_speed', 'steering_profile')."""
        out = []
        if not self.speed_valid:
            out.append('entry_speed')
        if not self.profile_valid:
            out.append('steering_profile')
        return tuple(out)

    @property
    def valid(self) -> bool:
        return not self.invalid_reasons

    def describe_invalid(self) -> list[str]:
        """Return one sentence per reason the run is invalid, with the measured value."""
        out = []
        if not self.speed_valid:
            assert self.entry_speed is not None
            out.append(f'entry speed {self.entry_speed * 3.6:.1f} km/h at BOS, outside '
                       f'{ENTRY_SPEED * 3.6:.0f} +/- {ENTRY_TOLERANCE * 3.6:.0f} km/h (S7.9)')
        if not self.profile_valid:
            out.append(f'steering profile: half-period {self.half_period:.3f} s (0.7 Hz: '
                       f'{0.5 / FREQUENCY:.3f} s), start to COS {self.steer_duration:.3f} s '
                       f'(with the 0.5 s dwell: {1.0 / FREQUENCY + DWELL:.3f} s); tolerance '
                       f'{100 * PROFILE_TOLERANCE:g} % (S7.9.1)')
        return out

    @property
    def passed(self) -> bool:
        """Valid, and every criterion that applies to the run is met."""
        return (self.valid and self.stable_1_00 and self.stable_1_75
                and self.responsive is not False)


def grade_run(t, steering, yaw_rate, lateral_acceleration, *, a_reference: float | None,
              roll=None, gvwr: float = 2000.0, speed=None,
              commanded_amplitude: float | None = None) -> SwdGrade:
    """
    Process and grade one run (see the module doc). ``a_reference`` is A (rad).

    ``commanded_amplitude`` (rad) decides whether responsiveness applies (S5.2.3: the
    commanded angle); without it the measured first-peak amplitude does. ``speed``
    (m/s, optional) gives the entry speed at BOS. ``a_reference`` None: A is not known
    and responsiveness is not graded (stability is).
    """
    t = np.asarray(t, dtype=float)
    if a_reference is not None and not (math.isfinite(a_reference) and a_reference > 0.0):
        raise ProcessingError(f'A must be a positive angle, got {a_reference!r}')
    if not (math.isfinite(gvwr) and gvwr > 0.0):
        raise ProcessingError(f'GVWR must be a positive mass, got {gvwr!r}')
    signals = [('steering', steering), ('yaw_rate', yaw_rate),
               ('lateral_acceleration', lateral_acceleration)]
    signals += [(name, x) for name, x in (('roll', roll), ('speed', speed)) if x is not None]
    for name, x in signals:
        x = np.asarray(x, dtype=float)
        if x.shape != t.shape:
            raise ProcessingError(f'{name} has {x.size} samples, time has {t.size}')
        if not np.all(np.isfinite(x)):
            raise ProcessingError(f'{name} holds non-finite samples')
    delta = lowpass(t, steering, STEER_CUTOFF)
    r = lowpass(t, yaw_rate, RESPONSE_CUTOFF)
    ay = lowpass(t, lateral_acceleration, RESPONSE_CUTOFF)
    ev = steer_events(t, delta, filtered=True)
    end, bos, cos, direction, amplitude = (ev.zeroing_end, ev.bos, ev.cos, ev.direction,
                                           ev.amplitude)
    delta, r, ay = (_zeroed(t, x, end) for x in (delta, r, ay))
    after = t >= end
    s = direction * delta
    reversal = ev.reversal_index
    _check_signs(t, s, direction * r, direction * ay, bos, reversal)
    # the first local peak of yaw rate (opposite to the first steer) after the reversal
    ry = -direction * r
    peak_i = None
    for k in range(reversal + 1, t.size - 1):
        if ry[k] > 0 and ry[k] >= ry[k - 1] and ry[k] > ry[k + 1]:
            peak_i = k
            break
    if peak_i is None:
        raise ProcessingError('no yaw-rate peak after the steering reversal')
    peak = float(r[peak_i])
    if t[-1] < cos + YAW_TIMES[1]:
        raise ProcessingError(f'the record ends {t[-1] - cos:.2f} s after COS; the rule '
                              f'needs {YAW_TIMES[1]:g} s')
    ratios = [float(np.interp(cos + dt, t, r) / peak) for dt in YAW_TIMES]
    if t[-1] < bos + DISPLACEMENT_TIME:
        raise ProcessingError('the record ends before BOS + 1.07 s')
    window = t >= bos
    tt = np.concatenate(([bos], t[window]))
    aa = np.concatenate(([np.interp(bos, t, ay)], ay[window]))
    vy = np.concatenate(([0.0], np.cumsum(0.5 * (aa[1:] + aa[:-1]) * np.diff(tt))))
    yy = np.concatenate(([0.0], np.cumsum(0.5 * (vy[1:] + vy[:-1]) * np.diff(tt))))
    displacement = direction * float(np.interp(bos + DISPLACEMENT_TIME, tt, yy))
    nominal = amplitude if commanded_amplitude is None else commanded_amplitude
    applies = a_reference is not None and \
        nominal >= RESPONSIVENESS_FROM * a_reference * (1.0 - 1e-3)
    limit = DISPLACEMENT_LIMIT['heavy' if gvwr > HEAVY_GVWR else 'light']
    w = 2.0 * math.pi * FREQUENCY
    start = bos - math.asin(min(1.0, BOS_ANGLE / amplitude)) / w
    return SwdGrade(
        amplitude=amplitude, direction=direction, bos=bos, cos=cos, peak_yaw_rate=peak,
        yaw_rate_ratio_1_00=ratios[0], yaw_rate_ratio_1_75=ratios[1],
        lateral_displacement=displacement,
        peak_lateral_acceleration=float(np.max(np.abs(ay[after]))),
        peak_roll=None if roll is None else float(np.max(np.abs(np.asarray(roll)))),
        responsiveness_applies=applies,
        stable_1_00=ratios[0] <= YAW_LIMITS[0], stable_1_75=ratios[1] <= YAW_LIMITS[1],
        responsive=(displacement >= limit) if applies else None,
        peak_yaw_rate_abs=float(np.max(np.abs(r[after]))),
        entry_speed=None if speed is None else float(np.interp(bos, t, np.asarray(speed, float))),
        displacement_limit=limit, steer_start=start, reversal=ev.reversal, zeroing_end=end)


@dataclass(frozen=True)
class SteerEvents:
    """The instants of a sine-with-dwell steer (S7.11.5-S7.11.7), s."""

    zeroing_end: float
    bos: float
    reversal: float  # the steer's first zero crossing after BOS
    reversal_index: int  # the sample before it
    cos: float
    direction: int  # +1 first steer to the left
    amplitude: float  # rad, |first peak| of the filtered, zeroed angle


def steer_events(t, steering, filtered: bool = False) -> SteerEvents:
    """
    Find zeroing end, BOS, the reversal and COS of a steer (module doc).

    ``steering`` raw (filtered here at 10 Hz) or, with ``filtered``, already filtered.
    """
    t = np.asarray(t, dtype=float)
    delta = np.asarray(steering, dtype=float) if filtered else lowpass(t, steering,
                                                                        STEER_CUTOFF)
    end = zeroing_end(t, delta)
    delta = _zeroed(t, delta, end)
    after = t >= end
    first = int(np.argmax(np.abs(delta) * after >= BOS_ANGLE))
    if not abs(delta[first]) >= BOS_ANGLE:
        raise ProcessingError('the steering-wheel angle never reaches 5 deg')
    direction = 1 if delta[first] > 0 else -1
    i = first
    while i > 0 and direction * delta[i - 1] >= BOS_ANGLE:
        i -= 1
    bos = float(np.interp(BOS_ANGLE, direction * delta[i - 1: i + 1], t[i - 1: i + 1])) if i > 0 \
        else float(t[i])
    s = direction * delta
    crossings = [k for k in range(first, t.size - 1) if (s[k] > 0) != (s[k + 1] > 0)
                 and abs(s[k] - s[k + 1]) > 0]
    if len(crossings) < 2:
        raise ProcessingError('the steer does not reverse and return to zero')
    reversal = crossings[0]
    back = [k for k in crossings[1:] if s[k] < 0 <= s[k + 1]]
    if not back:
        raise ProcessingError('the steering wheel does not return to zero after the dwell')
    return SteerEvents(zeroing_end=end, bos=bos, reversal=_crossing(t, s, reversal),
                       reversal_index=reversal, cos=_crossing(t, s, back[0]),
                       direction=direction,
                       amplitude=float(np.max(np.abs(delta[first: reversal + 1]))))


def _check_signs(t: np.ndarray, steer: np.ndarray, yaw: np.ndarray, ay: np.ndarray,
                 bos: float, reversal: int) -> None:
    """
    Refuse a yaw rate or lateral acceleration that turns against the first steer.

    Over the first steer lobe (BOS to the reversal) a car turns the way it is steered: the
    yaw rate and the lateral acceleration (signed by the first steer) integrate positive.
    A negative integral is a sign convention other than ISO 8855's (positive left), which
    would make the grader pick the wrong lobe.
    """
    lobe = (t >= bos) & (np.arange(t.size) <= reversal)
    if np.count_nonzero(lobe) < 3:
        return
    for name, x in (('yaw rate', yaw), ('lateral acceleration', ay)):
        if np.trapezoid(x[lobe], t[lobe]) < 0.0:
            raise ProcessingError(
                f'the {name} turns against the first steer (BOS to the reversal): its sign '
                'convention is not ISO 8855 (positive to the left, anticlockwise seen from '
                'above); reverse it (vd import --yaw-sign, a column map sign: -1)')


@dataclass(frozen=True)
class SisGrade:
    """One slowly-increasing-steer run (S7.6): its A and the validity of the run."""

    a_value: float  # rad, |steering-wheel angle| at 0.3 g, to the nearest 0.1 deg
    direction: int  # +1 steered to the left, -1 to the right
    steering_rate: float  # rad/s, |slope| of the steering-wheel angle over the regression window
    ramp_start: float  # s, where the fitted ramp leaves the zeroed straight-ahead angle
    speed_range: tuple[float, float] | None  # m/s, min and max over the regression window
    max_lateral_acceleration: float  # m/s^2, |max| of the filtered, zeroed signal

    @property
    def speed_valid(self) -> bool:
        if self.speed_range is None:
            return True
        low, high = self.speed_range
        return (abs(low - ENTRY_SPEED) <= ENTRY_TOLERANCE * (1 + 1e-9) and
                abs(high - ENTRY_SPEED) <= ENTRY_TOLERANCE * (1 + 1e-9))

    @property
    def rate_valid(self) -> bool:
        return abs(self.steering_rate / SIS_RATE - 1.0) <= SIS_RATE_TOLERANCE

    @property
    def invalid_reasons(self) -> tuple[str, ...]:
        return tuple(name for name, ok in (('sis_speed', self.speed_valid),
                                           ('sis_steering_rate', self.rate_valid)) if not ok)

    @property
    def valid(self) -> bool:
        return not self.invalid_reasons

    def describe_invalid(self) -> list[str]:
        out = []
        if not self.speed_valid:
            assert self.speed_range is not None
            out.append(f'speed {self.speed_range[0] * 3.6:.1f}..{self.speed_range[1] * 3.6:.1f}'
                       f' km/h over the regression window, outside '
                       f'{ENTRY_SPEED * 3.6:.0f} +/- {ENTRY_TOLERANCE * 3.6:.0f} km/h (S7.6)')
        if not self.rate_valid:
            out.append(f'steering-wheel rate {self.steering_rate / DEG:.2f} deg/s, not '
                       f'{SIS_RATE / DEG:g} deg/s within {100 * SIS_RATE_TOLERANCE:g} % (S7.6)')
        return out


def _sis_value(steer: np.ndarray, ay: np.ndarray, label: str) -> tuple[float, np.ndarray]:
    """|steering| at 0.3 g by regression over 0.1..0.375 g, and the window (a mask)."""
    steer, ay = np.abs(steer), np.abs(ay)
    window = (ay >= SIS_RANGE[0]) & (ay <= SIS_RANGE[1])
    if np.count_nonzero(window) < 3:
        raise ProcessingError(f'{label}: fewer than 3 samples between 0.1 and 0.375 g '
                              '(the run must reach 0.375 g)')
    slope, intercept = np.polyfit(ay[window], steer[window], 1)
    return float(slope * SIS_TARGET + intercept), window


def grade_sis(t, steering, lateral_acceleration, speed=None) -> SisGrade:
    """
    Process one measured slowly-increasing-steer run (S7.6; module doc).

    Filters as S7.11 (steering 10 Hz, lateral acceleration 6 Hz), zeroes over the
    SIS_ZERO_WINDOW of straight running that ends SIS_ZERO_GAP before the ramp (the
    straight line through the regression window's steering-wheel angle over time,
    extended back to zero), and checks speed and steering-wheel rate.
    """
    t = np.asarray(t, dtype=float)
    for name, x in (('steering', steering), ('lateral_acceleration', lateral_acceleration),
                    ('speed', speed)):
        if x is None:
            continue
        x = np.asarray(x, dtype=float)
        if x.shape != t.shape:
            raise ProcessingError(f'{name} has {x.size} samples, time has {t.size}')
        if not np.all(np.isfinite(x)):
            raise ProcessingError(f'{name} holds non-finite samples')
    delta = lowpass(t, steering, STEER_CUTOFF)
    ay = lowpass(t, lateral_acceleration, RESPONSE_CUTOFF)
    first = t < t[0] + SIS_ZERO_WINDOW
    delta0, ay0 = delta - delta[first].mean(), ay - ay[first].mean()
    _, window = _sis_value(delta0, ay0, 'SIS run')
    rate, offset = np.polyfit(t[window], delta0[window], 1)
    if rate == 0.0:
        raise ProcessingError('SIS run: the steering-wheel angle does not ramp')
    start = float(-offset / rate)
    zero = (t >= start - SIS_ZERO_GAP - SIS_ZERO_WINDOW) & (t < start - SIS_ZERO_GAP)
    if np.count_nonzero(zero) < 3:
        raise ProcessingError(f'SIS run: the record starts {start - t[0]:.2f} s before the '
                              f'ramp; zeroing needs {SIS_ZERO_WINDOW + SIS_ZERO_GAP:g} s of '
                              'straight running')
    delta, ay = delta - delta[zero].mean(), ay - ay[zero].mean()
    value, window = _sis_value(delta, ay, 'SIS run')
    direction = 1 if float(np.mean(delta[window])) > 0 else -1
    rate = float(np.polyfit(t[window], delta[window], 1)[0])
    speed_range = None
    if speed is not None:
        v = np.asarray(speed, dtype=float)[window]
        speed_range = (float(v.min()), float(v.max()))
    return SisGrade(a_value=round(value / DEG, 1) * DEG, direction=direction,
                    steering_rate=abs(rate), ramp_start=start, speed_range=speed_range,
                    max_lateral_acceleration=float(np.max(np.abs(ay))))


def a_from_sis(runs: Sequence[SisGrade]) -> float:
    """Return A (rad, S7.6.1): the runs' A values (each to 0.1 deg) averaged, to 0.1 deg."""
    if not runs:
        raise ProcessingError('no slowly-increasing-steer runs')
    return round(float(np.mean([abs(g.a_value) for g in runs])) / DEG, 1) * DEG


@dataclass(frozen=True)
class CriterionVerdict:
    """One criterion over the graded runs of a procedure."""

    name: str  # 'yaw_rate_ratio_1_00' | 'yaw_rate_ratio_1_75' | 'lateral_displacement'
    limit: float
    passed: bool
    runs: int  # how many runs the criterion was graded on
    deciding_run: int | None  # index into the runs; None when graded on no run
    deciding_value: float


@dataclass(frozen=True)
class ProcedureGrade:
    """Every run of a sine-with-dwell procedure, and the verdicts."""

    a_reference: float | None  # rad; None: A not known (responsiveness not graded)
    runs: tuple[SwdGrade, ...]
    criteria: tuple[CriterionVerdict, ...]
    valid: bool  # every run (and every SIS run given) valid
    passed: bool
    deciding_run: int | None
    deciding_criterion: str
    sis: tuple[SisGrade, ...] = ()
    deciding_sis_run: int | None = None  # the SIS run that decided (an invalid one)


def grade_procedure(runs: Sequence[SwdGrade], a_reference: float | None,
                    sis: Sequence[SisGrade] = ()) -> ProcedureGrade:
    """
    Grade a series of graded runs: per criterion and overall, with the deciding run.

    Runs must be graded against the same A (module doc); ``sis``: the SIS runs that gave A
    (their validity is the procedure's).
    """
    if not runs:
        raise ProcessingError('no sine-with-dwell runs to grade')
    criteria = []
    valid_runs = [k for k, g_ in enumerate(runs) if g_.valid]
    for name, limit_of, value_of, applies, ok in (
            ('yaw_rate_ratio_1_00', lambda g_: YAW_LIMITS[0], lambda g_: g_.yaw_rate_ratio_1_00,
             lambda g_: True, lambda g_: g_.stable_1_00),
            ('yaw_rate_ratio_1_75', lambda g_: YAW_LIMITS[1], lambda g_: g_.yaw_rate_ratio_1_75,
             lambda g_: True, lambda g_: g_.stable_1_75),
            ('lateral_displacement', lambda g_: g_.displacement_limit,
             lambda g_: g_.lateral_displacement, lambda g_: g_.responsiveness_applies,
             lambda g_: bool(g_.responsive))):
        graded = [k for k in valid_runs if applies(runs[k])]
        failing = [k for k in graded if not ok(runs[k])]
        if failing:
            decide = failing[0]
        elif graded:
            # least margin: ratio closest to its limit from below, displacement from above
            sign = -1.0 if name == 'lateral_displacement' else 1.0
            decide = max(graded, key=lambda k: sign * (value_of(runs[k]) - limit_of(runs[k])))
        else:
            decide = None
        criteria.append(CriterionVerdict(
            name=name, limit=limit_of(runs[0]), passed=not failing, runs=len(graded),
            deciding_run=decide,
            deciding_value=float('nan') if decide is None else value_of(runs[decide])))
    bad_sis = [k for k, g_ in enumerate(sis) if not g_.valid]
    bad_runs = [k for k, g_ in enumerate(runs) if not g_.valid]
    valid = not bad_sis and not bad_runs
    # without A responsiveness is graded on no run: the vehicle cannot be said to pass
    passed = valid and a_reference is not None and all(c.passed for c in criteria)
    if bad_sis:
        return ProcedureGrade(a_reference=a_reference, runs=tuple(runs),
                              criteria=tuple(criteria), valid=False, passed=False,
                              deciding_run=None,
                              deciding_criterion=sis[bad_sis[0]].invalid_reasons[0],
                              sis=tuple(sis), deciding_sis_run=bad_sis[0])
    if bad_runs:
        return ProcedureGrade(a_reference=a_reference, runs=tuple(runs),
                              criteria=tuple(criteria), valid=False, passed=False,
                              deciding_run=bad_runs[0],
                              deciding_criterion=runs[bad_runs[0]].invalid_reasons[0],
                              sis=tuple(sis))
    failed = [c for c in criteria if not c.passed]
    if failed:
        def run_of(c: CriterionVerdict) -> int:
            assert c.deciding_run is not None  # a failed criterion failed on a run
            return c.deciding_run
        first = min(failed, key=run_of)
    else:
        def margin(c: CriterionVerdict) -> float:
            if c.deciding_run is None:
                return math.inf
            if c.name == 'lateral_displacement':
                return c.deciding_value / c.limit - 1.0
            return 1.0 - c.deciding_value / c.limit
        first = min(criteria, key=margin)
    return ProcedureGrade(a_reference=a_reference, runs=tuple(runs), criteria=tuple(criteria),
                          valid=valid, passed=passed, deciding_run=first.deciding_run,
                          deciding_criterion=first.name, sis=tuple(sis))


def amplitude_from_sis(runs: Sequence[tuple[np.ndarray, np.ndarray]]) -> float:
    """
    Find A (rad) from slowly-increasing-steer runs.

    Each run is (steering-wheel angle, lateral acceleration), filtered and zeroed: per
    run the steering angle at 0.3 g of the linear regression of |steering| on |lateral
    acceleration| over 0.1..0.375 g, to the nearest 0.1 deg; the absolute values
    averaged and rounded to 0.1 deg (S7.6.1).
    """
    if not runs:
        raise ProcessingError('no slowly-increasing-steer runs')
    values = []
    for k, (steer, ay) in enumerate(runs):
        value, _ = _sis_value(np.asarray(steer, float), np.asarray(ay, float), f'SIS run {k}')
        values.append(round(abs(value) / DEG, 1))
    return round(float(np.mean(values)), 1) * DEG


def amplitude_series(a_reference: float) -> list[float]:
    """
    Return the commanded amplitudes (rad) of the series.

    1.5A, 2A, ... up to the greater of 6.5A and 270 deg, none beyond 300 deg.
    """
    if not (math.isfinite(a_reference) and a_reference > 0.0):
        raise ProcessingError(f'A must be a positive angle, got {a_reference!r}')
    last = min(max(SERIES_TOP * a_reference, SERIES_MIN_LAST), SERIES_CAP)
    out, k = [], SERIES_START
    while k * a_reference <= last * (1.0 + 1e-12):
        out.append(k * a_reference)
        k += SERIES_STEP
    if out[-1] < last * (1.0 - 1e-12) and last > out[-1]:
        out.append(last)
    return out


def sine_with_dwell(t: np.ndarray, amplitude: float, direction: int = 1,
                    start: float = 1.0, frequency: float = 0.7, dwell: float = 0.5) -> np.ndarray:
    """
    Return the steering-wheel angle of the manoeuvre (S7.9.1).

    A 0.7 Hz sine, held for the dwell at its second peak, then the last quarter cycle
    back to zero.
    """
    w = 2.0 * math.pi * frequency
    period = 1.0 / frequency
    tau = np.asarray(t, dtype=float) - start
    out = np.zeros_like(tau)
    a = tau < 0.75 * period
    out[(tau >= 0) & a] = np.sin(w * tau[(tau >= 0) & a])
    d = (tau >= 0.75 * period) & (tau < 0.75 * period + dwell)
    out[d] = -1.0
    e = (tau >= 0.75 * period + dwell) & (tau < period + dwell)
    out[e] = np.sin(w * (tau[e] - dwell))
    return direction * amplitude * out


__all__ = ['ProcessingError', 'SwdGrade', 'SisGrade', 'CriterionVerdict', 'ProcedureGrade',
           'lowpass', 'check_uniform', 'steering_rate', 'zeroing_end', 'grade_run',
           'steer_events', 'SteerEvents',
           'grade_procedure', 'grade_sis', 'a_from_sis', 'amplitude_from_sis',
           'amplitude_series', 'sine_with_dwell', 'DISPLACEMENT_LIMIT', 'YAW_LIMITS',
           'RESPONSIVENESS_FROM', 'STABILITY_FROM', 'ENTRY_SPEED', 'ENTRY_TOLERANCE',
           'SIS_TARGET', 'HEAVY_GVWR', 'FREQUENCY', 'DWELL', 'SIS_RATE']
