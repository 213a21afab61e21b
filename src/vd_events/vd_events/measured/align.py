# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Where the manoeuvre is in a log, and a simulation put on the log's time axis by it.

* :func:`manoeuvre_window`: the part of a log that holds the manoeuvre (``vd import
  --window auto``), found by its steering as the standards define it, inside one gap-free
  stretch: a sine with dwell from PRE s before the zeroing instant of FMVSS 126 S7.11.5
  (the steering-wheel rate passes 75 deg/s for 200 ms) to POST_SWD s after it; a step
  steer from PRE s before its 10 % instant to the end of the hold (ISO 7401,
  :func:`vd_solvers.standards.iso7401.step_instants`); a slowly increasing steer from
  PRE_SIS s before the steering wheel leaves straight ahead to its largest angle; a
  constant radius turn over the longest stretch of turning (yaw rate above TURN_RATE at
  speed); any other log from PRE s before the first to PRE s after the last steering of
  more than LEAVE_ANGLE.
* :func:`reference_time`: the instant a comparison aligns on -- BOS for a sine with dwell
  (S7.11.6), the 50 % steering-wheel instant of a step (ISO 7401).
* :func:`aligned`: a simulation of the same manoeuvre shifted onto the log's time axis
  (for a simulated sine-with-dwell procedure, first the run of its series nearest the
  log's amplitude and direction), with notes that state the alignment.
"""
from __future__ import annotations

from collections.abc import Mapping
import dataclasses
from pathlib import Path

import numpy as np

from vd_events.errors import InputError
from vd_events.measured.checks import segments
from vd_solvers.constants import DEG
from vd_solvers.results import Channel, EventOutcome
from vd_solvers.standards import fmvss126, iso7401
from vd_solvers.standards.fmvss126 import ProcessingError

PRE = 2.0  # s kept before the manoeuvre
POST_SWD = 5.0  # s after the zeroing instant: COS + 1.75 s and a margin
PRE_SIS = 2.5  # s: the SIS zeroing window ends 0.25 s before the ramp
LEAVE_ANGLE = 5.0 * DEG
TURN_RATE = 2.0 * DEG  # rad/s
MIN_SPEED = 3.0  # m/s
#: the events aligned on a manoeuvre instant, and what the instant is called
ALIGNED = {'sine_with_dwell': 'BOS (FMVSS 126 S7.11.6)',
           'step_steer': 'the 50 % steering-wheel instant (ISO 7401)'}
#: the channels a sine-with-dwell series keeps per run (series_<name>_<run>)
SERIES = ('steering_wheel_angle', 'yaw_rate', 'lateral_acceleration', 'roll')


def _segments(t: np.ndarray, minimum: int = 30) -> list[slice]:
    return [s for s in segments(t) if s.stop - s.start >= minimum]


def manoeuvre_window(path: Path | str, event: str, t: np.ndarray,
                     channels: Mapping[str, np.ndarray]) -> tuple[float, float, str]:
    """Find the manoeuvre's part of a log (module doc): (start, end, how it was found)."""
    def need(*names: str) -> None:
        missing = [n for n in names if n not in channels]
        if missing:
            raise InputError(path, f"--window auto: a {event} log needs {', '.join(missing)} "
                             'to find its manoeuvre')

    if event == 'constant_radius_turn':
        need('yaw_rate', 'speed')
        best = None
        for s in segments(t):
            turning = (np.abs(channels['yaw_rate'][s]) > TURN_RATE) & \
                (channels['speed'][s] > MIN_SPEED)
            edges = np.flatnonzero(np.diff(np.concatenate(([0], turning.astype(int), [0]))))
            for a, b in zip(edges[::2], edges[1::2]):
                if best is None or b - a > best[1] - best[0]:
                    best = (s.start + a, s.start + b - 1)
        if best is None:
            raise InputError(path, '--window auto: the log never turns (yaw rate above '
                             f'{TURN_RATE / DEG:g} deg/s at speed)')
        return float(t[best[0]]), float(t[best[1]]), 'the longest stretch of turning'
    need('steering_wheel_angle')
    for s in _segments(t):
        ts = t[s]
        try:
            steer = fmvss126.lowpass(ts, channels['steering_wheel_angle'][s],
                                     fmvss126.STEER_CUTOFF)
        except ProcessingError:
            continue
        lo, hi = float(ts[0]), float(ts[-1])
        try:
            if event == 'sine_with_dwell':
                tz = fmvss126.zeroing_end(ts, steer)
                return (max(lo, tz - PRE), min(hi, tz + POST_SWD),
                        f'the sine with dwell: the steering-wheel rate passes 75 deg/s for '
                        f'200 ms at {tz:.2f} s (S7.11.5); {PRE:g} s before to {POST_SWD:g} s '
                        'after')
            if event == 'step_steer':
                _, _, t10, _, _, end = iso7401.step_instants(ts, steer)
                return (max(lo, t10 - PRE), end,
                        f'the steer step: 10 % at {t10:.2f} s, held to {end:.2f} s (ISO 7401)')
        except ProcessingError:
            continue
        moved = np.flatnonzero(np.abs(steer - steer[0]) > LEAVE_ANGLE)
        if not moved.size:
            continue
        if event == 'slowly_increasing_steer':
            top = int(np.argmax(np.abs(steer - steer[0])))
            return (max(lo, float(ts[moved[0]]) - PRE_SIS), float(ts[top]),
                    f'the steering ramp: leaves straight ahead at {ts[moved[0]]:.2f} s, '
                    f'largest angle at {ts[top]:.2f} s')
        if event not in ALIGNED:
            return (max(lo, float(ts[moved[0]]) - PRE), min(hi, float(ts[moved[-1]]) + PRE),
                    f'steering of more than {LEAVE_ANGLE / DEG:g} deg from '
                    f'{ts[moved[0]]:.2f} s to {ts[moved[-1]]:.2f} s')
    raise InputError(path, f'--window auto: no {event.replace("_", " ")} found in the '
                     'steering-wheel angle of any gap-free stretch of the log')


def reference_time(event: str, t: np.ndarray, steering: np.ndarray) -> float:
    """BOS (sine with dwell) or t50 (step steer) of a steer, s; ProcessingError if none."""
    problems = []
    for s in _segments(t):
        try:
            if event == 'sine_with_dwell':
                return fmvss126.steer_events(t[s], steering[s]).bos
            delta = fmvss126.lowpass(t[s], steering[s], fmvss126.STEER_CUTOFF)
            return iso7401.step_instants(t[s], delta)[3]
        except ProcessingError as err:
            problems.append(str(err))
    raise ProcessingError(problems[0] if problems else 'no stretch of 30 samples without a gap')


def series_runs(sim: EventOutcome) -> list[EventOutcome]:
    """Each run of a simulated sine-with-dwell series as an outcome of its own (50 Hz)."""
    ch = sim.channels
    if 'series_time' not in ch or 'run_amplitude' not in ch:
        return []
    out = []
    for k in range(len(ch['run_amplitude'].values)):
        run = {'time': ch['series_time']}
        for name in SERIES:
            key = f'series_{name}_{k + 1:02d}'
            if key in ch:
                run[name] = ch[key]
        out.append(dataclasses.replace(sim, channels=run, notes=(
            *sim.notes, f"run #{k + 1} of the series "
            f"({ch['run_amplitude'].values[k] / DEG:.1f} deg, "
            f"{'left' if ch['run_direction'].values[k] > 0 else 'right'} first)")))
    return out


def aligned(sim: EventOutcome, test: EventOutcome) -> tuple[EventOutcome, list[str]]:
    """``sim`` on the time axis of ``test`` by the manoeuvre (module doc), and the notes."""
    if test.event not in ALIGNED or 'steering_wheel_angle' not in test.channels:
        return sim, []
    notes = []
    t_test = test.channels['time'].values
    swa_test = test.channels['steering_wheel_angle'].values
    try:
        ref_test = reference_time(test.event, t_test, swa_test)
    except ProcessingError as err:
        raise InputError('comparison', f'{test.event}: cannot find {ALIGNED[test.event]} in '
                         f'the log: {err}') from None
    runs = series_runs(sim) if test.event == 'sine_with_dwell' else []
    if runs:
        ev = fmvss126.steer_events(t_test[_segment_of(t_test, ref_test)],
                                   swa_test[_segment_of(t_test, ref_test)])
        amp = sim.channels['run_amplitude'].values
        direction = sim.channels['run_direction'].values
        same = [k for k in range(amp.size) if direction[k] == ev.direction] or \
            list(range(amp.size))
        k = min(same, key=lambda i: abs(amp[i] - ev.amplitude))
        sim = runs[k]
        notes.append(f'simulated run #{k + 1} of the series ({amp[k] / DEG:.1f} deg, '
                     f"{'left' if direction[k] > 0 else 'right'} first), the nearest to the "
                     f"log's {ev.amplitude / DEG:.1f} deg "
                     f"{'left' if ev.direction > 0 else 'right'} first")
    if 'steering_wheel_angle' not in sim.channels:
        raise InputError('comparison', f'{sim.event}: the simulation has no steering-wheel '
                         'angle to align on')
    try:
        ref_sim = reference_time(test.event, sim.channels['time'].values,
                                 sim.channels['steering_wheel_angle'].values)
    except ProcessingError as err:
        raise InputError('comparison', f'{sim.event}: cannot find {ALIGNED[test.event]} in '
                         f'the simulation: {err}') from None
    shift = ref_test - ref_sim
    channels = dict(sim.channels)
    channels['time'] = Channel(sim.channels['time'].unit, sim.channels['time'].values + shift)
    notes.append(f'aligned on {ALIGNED[test.event]}: simulation time {shift:+.3f} s '
                 f'(simulation {ref_sim:.3f} s, log {ref_test:.3f} s)')
    return dataclasses.replace(sim, channels=channels), notes


def _segment_of(t: np.ndarray, when: float) -> slice:
    for s in segments(t):
        if t[s][0] <= when <= t[s][-1]:
            return s
    return slice(0, t.size)


__all__ = ['manoeuvre_window', 'reference_time', 'aligned', 'series_runs', 'ALIGNED']
