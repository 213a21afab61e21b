# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
What the import checks in a vehicle log: sample interval, gaps, glitches, signs, noise.

Pure functions on the SI channels of a log (``time`` in s from the first sample) and the
file line of each sample; :mod:`.importer` runs them and says what they found.

* **Sample interval**: the logger's own interval is the median time step (a VBOX at
  100 Hz steps 0.01 s; gaps do not change the median); the sample rate is its inverse.
* **Gaps**: a step longer than GAP_FACTOR intervals; reported with where (time and line)
  and how long.
* **Glitches**: per channel kind (:data:`LIMITS`), a sample outside the range, or a run
  of at most MAX_GLITCH_RUN samples that leaves its neighbours faster than the rate
  limit and comes back (a jump out and a jump back of opposite signs, the samples on
  both sides agreeing within the rate limit). Repair (only when asked): linear in time
  between the good samples on both sides.
* **Signs** (ISO 8855: yaw rate and lateral acceleration positive to the left): the yaw
  rate against the heading rate from the GPS heading, and the lateral acceleration
  divided by the speed (a_y = v r in a steady turn); the lateral acceleration and the
  steering-wheel angle against the heading rate; the roll angle against the lateral
  acceleration (a car rolls out of the turn: positive roll, left side up, in a left
  turn). The agreement is the uncentred correlation sum(x r) / sqrt(sum(x^2) sum(r^2))
  over the samples in a turn (|heading rate| above TURN_RATE, speed above MIN_SPEED): +1
  for the same sign throughout, -1 for the opposite (unlike Pearson's, it does not vanish
  in a steady turn where both are constant); |agreement| below SIGN_CORRELATION decides
  nothing.
* **Noise**: the difference-based estimate 1.4826 MAD(diff x) / sqrt(2) (the standard
  deviation of white noise on a signal that changes little from one sample to the next).
"""
from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
import math
from pathlib import Path

import numpy as np

from vd_events.errors import InputError
from vd_events.measured.columns import KC_SWEEP
from vd_solvers.constants import DEG
from vd_solvers.constants import STANDARD_GRAVITY as G

GAP_FACTOR = 1.5
MAX_GLITCH_RUN = 3
#: channel -> (largest plausible |value|, largest plausible |rate of change| per s), SI
LIMITS: Mapping[str, tuple[float, float]] = {
    'steering_wheel_angle': (1080.0 * DEG, 3000.0 * DEG),
    'yaw_rate': (300.0 * DEG, 5000.0 * DEG),
    'lateral_acceleration': (3.0 * G, 300.0),
    'longitudinal_acceleration': (3.0 * G, 300.0),
    'speed': (100.0, 50.0),
    'roll': (30.0 * DEG, 500.0 * DEG),
    'pitch': (30.0 * DEG, 500.0 * DEG),
    'sideslip': (180.0 * DEG, 5000.0 * DEG),
}
#: how values are shown in messages: SI unit -> (unit, factor)
SHOWN: Mapping[str, tuple[str, float]] = {
    'rad': ('deg', 1.0 / DEG), 'rad/s': ('deg/s', 1.0 / DEG), 'm/s': ('km/h', 3.6),
    'm/s^2': ('m/s^2', 1.0)}
#: SI unit -> largest plausible |value| of a K&C rig channel (catches 1e308 and mm read as m)
RIG_LIMITS: Mapping[str, float] = {'m': 2.0, 'rad': math.pi, 'N': 1e6, 'N*m': 1e6}
#: fewest steps of a K&C rig sweep (a gradient needs points on both sides of design)
MIN_RIG_STEPS = 5
TURN_RATE = 2.0 * DEG  # rad/s of heading rate: the car is turning
MIN_SPEED = 5.0  # m/s: the GPS heading means something
SIGN_CORRELATION = 0.5
MIN_TURN_SAMPLES = 20


def shown(value: float, unit: str, digits: int = 5) -> str:
    """Return a value in its display unit: '27899 deg', '327.67 deg/s'."""
    name, factor = SHOWN.get(unit, (unit, 1.0))
    return f'{value * factor:.{digits}g} {name}'.strip()


def sample_interval(t: np.ndarray) -> float:
    """Return the logger's interval: the median time step, s."""
    return float(np.median(np.diff(t)))


@dataclass(frozen=True)
class Gap:
    start: float  # s, the last sample before the gap
    end: float  # s, the first sample after it
    index: int  # the first sample after the gap
    line: int | None  # its file line

    @property
    def length(self) -> float:
        return self.end - self.start

    def describe(self) -> str:
        where = f' (line {self.line})' if self.line is not None else ''
        return (f'gap: {self.length:.2f} s without samples from t = {self.start:.2f} s to '
                f'{self.end:.2f} s{where}')


def find_gaps(t: np.ndarray, interval: float, lines: Sequence[int] = ()) -> list[Gap]:
    """Every step longer than GAP_FACTOR intervals."""
    steps = np.diff(t)
    return [Gap(start=float(t[i]), end=float(t[i + 1]), index=int(i) + 1,
                line=lines[i + 1] if lines else None)
            for i in map(int, np.flatnonzero(steps > GAP_FACTOR * interval))]


def segments(t: np.ndarray, interval: float | None = None) -> list[slice]:
    """Return the gap-free stretches of ``t`` (slices), in order."""
    if t.size < 2:
        return [slice(0, t.size)]
    cuts = [g.index for g in find_gaps(t, interval or sample_interval(t))]
    bounds = [0, *cuts, t.size]
    return [slice(a, b) for a, b in zip(bounds[:-1], bounds[1:])]


@dataclass(frozen=True)
class Glitch:
    channel: str
    column: str  # the file's name of the channel
    first: int  # first sample of the run
    last: int  # last sample of the run
    time: float  # s of the first sample
    value: float  # SI, the sample farthest from its neighbours
    unit: str  # SI
    reason: str
    line: int | None

    def describe(self, with_line: bool = True) -> str:
        line = f'line {self.line}, ' if with_line and self.line is not None else ''
        samples = '' if self.last == self.first else f' ({self.last - self.first + 1} samples)'
        where = f' ({line}{self.reason})' if line else f' ({self.reason})'
        return (f'{self.channel} {shown(self.value, self.unit)} at t = {self.time:.2f} s'
                f'{samples}{where}')


def find_glitches(channel: str, column: str, t: np.ndarray, x: np.ndarray, unit: str,
                  lines: Sequence[int] = ()) -> list[Glitch]:
    """Find the glitches of one channel (module doc); none for a channel without limits."""
    if channel not in LIMITS or x.size < 3:
        return []
    limit, rate = LIMITS[channel]
    bad = np.zeros(x.size, dtype=bool)
    reason = [''] * x.size
    out_of_range = np.abs(x) > limit
    for k in map(int, np.flatnonzero(out_of_range)):
        bad[k] = True
        reason[k] = f'outside +/-{shown(limit, unit)}'
    dt = np.diff(t)
    jump = np.diff(x)
    fast = np.abs(jump) > rate * dt
    for i in map(int, np.flatnonzero(fast)):
        first = i + 1  # a run starts after the jump out
        if bad[first]:
            continue
        for last in range(first, min(first + MAX_GLITCH_RUN, int(x.size) - 1)):
            back = x[last + 1] - x[last]
            if (abs(back) > rate * (t[last + 1] - t[last]) and back * jump[i] < 0
                    and abs(x[last + 1] - x[i]) <= rate * (t[last + 1] - t[i])):
                bad[first:last + 1] = True
                for k in range(first, last + 1):
                    reason[k] = f'a spike beyond {shown(rate, unit)}/s'
                break
    out = []
    runs = np.flatnonzero(np.diff(np.concatenate(([0], bad.astype(int), [0]))))
    for a, b in zip(runs[::2], runs[1::2]):
        around = x[max(a - 1, 0)] if a > 0 else x[min(b, x.size - 1)]
        k = a + int(np.argmax(np.abs(x[a:b] - around)))
        out.append(Glitch(channel=channel, column=column, first=int(a), last=int(b) - 1,
                          time=float(t[a]), value=float(x[k]), unit=unit, reason=reason[k],
                          line=lines[a] if lines else None))
    return out


def repair(t: np.ndarray, x: np.ndarray, glitches: Sequence[Glitch]) -> np.ndarray:
    """``x`` with every glitch replaced linearly in time between the good samples around it."""
    good = np.ones(x.size, dtype=bool)
    for g in glitches:
        good[g.first:g.last + 1] = False
    if not np.any(good):
        return x.copy()
    y = x.copy()
    y[~good] = np.interp(t[~good], t[good], x[good])
    return y


@dataclass(frozen=True)
class Findings:
    """What the checks of one log found (the importer fills it)."""

    interval: float  # s, the logger's own interval
    gaps: tuple[Gap, ...]
    glitches: tuple[Glitch, ...]  # in the imported window
    repaired: bool  # the glitches were repaired (--repair glitches)
    window: tuple[float, float]  # s of the log imported
    log_rate: float | None = None  # Hz, as the file states it

    @property
    def sample_rate(self) -> float:
        return 1.0 / self.interval


def noise(x: np.ndarray) -> float:
    """Noise standard deviation from successive differences (module doc)."""
    d = np.diff(x)
    return float(1.4826 * np.median(np.abs(d - np.median(d))) / math.sqrt(2.0))


def heading_rate(t: np.ndarray, yaw: np.ndarray, interval: float) -> np.ndarray:
    """d(yaw)/dt of the (unwrapped) heading per gap-free segment, smoothed over 0.2 s."""
    out = np.zeros_like(yaw)
    n = max(1, int(round(0.2 / interval)))
    for s in segments(t, interval):
        if s.stop - s.start < 3:
            continue
        rate = np.gradient(yaw[s], t[s])
        if n > 1 and rate.size > n:
            rate = np.convolve(np.pad(rate, (n // 2, n - 1 - n // 2), mode='edge'),
                               np.ones(n) / n, mode='valid')
        out[s] = rate
    return out


@dataclass(frozen=True)
class Agreement:
    """How a channel agrees in sign with a reference over the samples in a turn."""

    correlation: float  # uncentred (module doc), NaN when not enough turning
    samples: int

    @property
    def decided(self) -> bool:
        return self.samples >= MIN_TURN_SAMPLES and abs(self.correlation) >= SIGN_CORRELATION

    @property
    def agrees(self) -> bool:
        return self.decided and self.correlation > 0.0

    @property
    def opposes(self) -> bool:
        return self.decided and self.correlation < 0.0

    def describe(self) -> str:
        if self.samples < MIN_TURN_SAMPLES:
            return f'not enough turning ({self.samples} samples)'
        return f'correlation {self.correlation:+.2f} over {self.samples} samples'


def agreement(x: np.ndarray, reference: np.ndarray, mask: np.ndarray) -> Agreement:
    """Sign agreement of ``x`` with ``reference`` where ``mask`` (module doc)."""
    n = int(np.count_nonzero(mask))
    if n < MIN_TURN_SAMPLES:
        return Agreement(float('nan'), n)
    a, b = x[mask], reference[mask]
    norm = math.sqrt(float(np.sum(a * a)) * float(np.sum(b * b)))
    if norm == 0.0:
        return Agreement(float('nan'), 0)
    return Agreement(float(np.sum(a * b)) / norm, n)


def check_rig(path: Path, channels: Mapping[str, np.ndarray], units: Mapping[str, str],
              lines: Sequence[int], where: Mapping[str, tuple[int, str]], event: str) -> None:
    """
    Refuse a K&C rig measurement the comparison cannot use, naming the row and column.

    ``channels`` SI (``units``), ``lines`` the file line of each step, ``where`` channel ->
    (file column, column name). Every value finite and within :data:`RIG_LIMITS` of its
    unit; at least :data:`MIN_RIG_STEPS` steps; the event's swept channel
    (:data:`columns.KC_SWEEP`) present, changing, and running one way (a loop up and down
    is two sweeps: import them as two files).
    """
    for name, values in channels.items():
        limit = RIG_LIMITS.get(units.get(name, ''), math.inf)
        bad = np.nonzero(~(np.abs(values) <= limit))[0]
        if bad.size:
            i = int(bad[0])
            column, shown_name = where[name]
            what = 'not finite' if not math.isfinite(values[i]) else \
                f'implausible (beyond {limit:g} {units[name]})'
            raise InputError(path, f'{name} {values[i]:.6g} {units[name]} is {what}',
                             line=lines[i], column=column, name=shown_name)
    steps = len(lines)
    if steps < MIN_RIG_STEPS:
        raise InputError(path, f'{steps} steps: a K&C rig measurement needs at least '
                         f'{MIN_RIG_STEPS} (truncated file?)', line=lines[0] if lines else None)
    axis = KC_SWEEP.get(event)
    if axis is None:
        return
    if axis not in channels:
        raise InputError(path, f'no column is mapped to {axis}, the swept channel of {event} '
                         '(the comparison runs along it)')
    x = channels[axis]
    column, shown_name = where[axis]
    if float(np.ptp(x)) == 0.0:
        raise InputError(path, f'{axis} does not change ({x[0]:.6g} {units[axis]} throughout): '
                         'nothing was swept', column=column, name=shown_name)
    step = np.diff(x)
    direction = np.sign(step[np.nonzero(step)[0][0]])
    wrong = np.nonzero(np.sign(step) != direction)[0]
    if wrong.size:
        i = int(wrong[0]) + 1
        raise InputError(path, f'{axis} does not run one way ({x[i - 1]:.6g} {units[axis]}, '
                         f'then {x[i]:.6g} {units[axis]}): import each sweep of a loop as a '
                         'file of its own', line=lines[i], column=column, name=shown_name)


__all__ = ['Gap', 'Glitch', 'Agreement', 'Findings', 'sample_interval', 'find_gaps', 'segments',
           'find_glitches', 'repair', 'noise', 'heading_rate', 'agreement', 'shown', 'LIMITS',
           'GAP_FACTOR', 'TURN_RATE', 'MIN_SPEED', 'check_rig', 'RIG_LIMITS', 'MIN_RIG_STEPS']
