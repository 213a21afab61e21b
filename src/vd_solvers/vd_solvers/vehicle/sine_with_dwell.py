# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The FMVSS 126 / UN R140 / GTR 8 sine-with-dwell procedure on the full vehicle.

``run_procedure(model, values, progress)`` drives the procedure as the rule writes it
(49 CFR 571.126 S7.6, S7.9) and grades it with :mod:`vd_solvers.standards.fmvss126`, the same
processing that grades a measured log:

1. **Slowly increasing steer** (S7.6): 80 km/h held by the speed controller, the
   steering wheel ramped at 13.5 deg/s from straight running until the lateral
   acceleration reaches SIS_END (about 0.5 g), to the left and to the right. The rule
   asks for three runs per direction; the simulation is deterministic, so repeated
   runs are identical and one per direction gives the same A. **A** is the
   steering-wheel angle at 0.3 g by linear regression, rounded to 0.1 deg.
2. **Sine with dwell** (S7.9): coasting (no wheel torque) from 80 km/h; after
   STEER_START s of straight running (the 1 s zeroing window precedes the steer) a
   0.7 Hz sine with a 500 ms dwell at its second peak, amplitudes 1.5A, 2A, ... to the
   greater of 6.5A and 270 deg (300 deg at most), first to the left, then the series
   again first to the right. Each run is recorded to COS + 1.75 s + RECORD_MARGIN at
   RECORD_RATE and graded (filters, zeroing, BOS/COS, first local yaw-rate peak,
   ratios, lateral displacement) by :func:`vd_solvers.standards.fmvss126.grade_run`.

Every run takes the variable step of :mod:`.adaptive` by default (``step_tolerance``,
0 the fixed step of 5 ms), the rows still at 100 Hz.

The vehicle model has no electronic stability control: the procedure grades the
passive vehicle (the thesis' §3.4 / §4.4.2 manoeuvre), which is what a chassis set-up
study compares.
"""
from __future__ import annotations

from collections.abc import Callable, Mapping

import numpy as np

from vd_solvers.constants import DEG
from vd_solvers.constants import STANDARD_GRAVITY as G
from vd_solvers.errors import SolverError
from vd_solvers.event_params import Param
from vd_solvers.results import Channel, Metric
from vd_solvers.standards import fmvss126 as rule

from .adaptive import STEP_TOLERANCE_PARAM, event_tolerance
from .drivers import OpenLoopSteering, SpeedController
from .model import STEP, VehicleModel
from .simulation import Trace, simulate

#: SIS: entry speed, steering-wheel rate, lateral acceleration at which a run ends
SIS_SPEED = 80.0 / 3.6  # m/s
SIS_RATE = 13.5 * DEG  # rad/s
SIS_END = 0.5 * G  # m/s^2
SIS_START = 1.0  # s of straight running before the ramp
#: straight running before the sine steer (the rule's 1 s zeroing window fits before it)
STEER_START = 1.5  # s
SWD_SPEED = 80.0 / 3.6  # m/s, entry speed, coasting from here
FREQUENCY, DWELL = 0.7, 0.5  # Hz, s (S7.9.1)
RECORD_MARGIN = 0.5  # s recorded after COS + 1.75 s
RECORD_EVERY = 2  # steps: 100 Hz at the 5 ms step
#: the per-run series kept for the report's time plots, Hz
SERIES_RATE = 50.0

PARAMS: Mapping[str, Param] = {
    'a_reference': Param('angle', 0.0, 'A, the steering-wheel angle at 0.3 g; 0 finds it '
                         'from the slowly-increasing-steer runs (S7.6)', minimum=0.0,
                         maximum=300.0 * DEG),
    'max_amplitude': Param('angle', 300.0 * DEG, 'largest commanded amplitude of the series; '
                           "below the rule's last amplitude the series is reduced and the "
                           'verdict says so', minimum=1.0 * DEG, maximum=300.0 * DEG),
    'gvwr': Param('mass', 0.0, 'gross vehicle weight rating deciding the displacement limit '
                  "(S5.2.3); 0 takes the model's total mass", minimum=0.0, maximum=20000.0),
    'step_tolerance': STEP_TOLERANCE_PARAM,
}


def _sis(model: VehicleModel, direction: int, tolerance: float | None
         ) -> tuple[np.ndarray, np.ndarray, Trace]:
    """One slowly-increasing-steer run; filtered, zeroed steering and lateral acceleration."""
    limit = float(min(-model.maps.steer_swa[0], model.maps.steer_swa[-1]))
    ramp_end = SIS_START + limit / SIS_RATE
    steering = OpenLoopSteering(times=[0.0, SIS_START, ramp_end],
                                angles=[0.0, 0.0, direction * limit])
    _, r_e = model.tire_radii(model.static_loads())
    speed = SpeedController(lambda t: SIS_SPEED, model.total_mass, float(np.mean(r_e)))

    def stop(row: dict[str, float]) -> str:
        return 'done' if row['time'] > SIS_START and abs(_ay_estimate(row)) >= SIS_END else ''

    trace = simulate(model, steering, speed, ramp_end, event='sine_with_dwell',
                     initial_speed=SIS_SPEED, record_every=RECORD_EVERY, stop=stop,
                     tolerance=tolerance)
    ch = trace.channels()
    t = ch['time']
    if trace.stop_reason != 'done':
        raise SolverError(f'slowly increasing steer to the {_side(direction)}: the lateral '
                          f'acceleration stays below {SIS_END / G:.2f} g up to the steering '
                          f'lock ({limit / DEG:.0f} deg)')
    steer = rule.lowpass(t, ch['steering_wheel_angle'], rule.STEER_CUTOFF)
    ay = rule.lowpass(t, ch['lateral_acceleration'], rule.RESPONSE_CUTOFF)
    window = (t >= SIS_START - 1.0) & (t < SIS_START)
    return steer - steer[window].mean(), ay - ay[window].mean(), trace


def _ay_estimate(row: Mapping[str, float]) -> float:
    """Lateral acceleration of a recorded row, steady-turn estimate r * v (m/s^2)."""
    return row['yaw_rate'] * row['speed']


def _side(direction: int) -> str:
    return 'left' if direction > 0 else 'right'


def _sine_run(model: VehicleModel, amplitude: float, direction: int,
              tolerance: float | None) -> Trace:
    end = STEER_START + 1.0 / FREQUENCY + DWELL
    duration = end + rule.YAW_TIMES[1] + RECORD_MARGIN
    steering = OpenLoopSteering(
        lambda t: rule.sine_with_dwell(t, amplitude, direction, STEER_START, FREQUENCY, DWELL),
        vectorized=True)
    return simulate(model, steering, None, duration, event='sine_with_dwell',
                    initial_speed=SWD_SPEED, record_every=RECORD_EVERY, tolerance=tolerance)


def run_procedure(model: VehicleModel, values: Mapping[str, float],
                  progress: Callable[[float, str], None] | None, channels_of) -> tuple:
    """
    Run and grade the procedure (module doc): (metrics, channels, notes).

    ``channels_of(model, trace)`` gives the SI channels of a run (the events' table).
    """
    limit = float(min(-model.maps.steer_swa[0], model.maps.steer_swa[-1]))
    gvwr = values['gvwr'] or model.total_mass
    report = progress or (lambda fraction, stage: None)
    tolerance = event_tolerance(model, values['step_tolerance'])
    notes: list[str] = []
    sis_values: list[float] = []
    if values['a_reference'] > 0.0:
        a_ref = round(values['a_reference'] / DEG, 1) * DEG
        notes.append(f'A = {a_ref / DEG:.1f} deg given (no slowly-increasing-steer runs)')
    else:
        runs = []
        for k, direction in enumerate((1, -1)):
            report(0.05 * k, f'slowly increasing steer, {_side(direction)}')
            steer, ay, _ = _sis(model, direction, tolerance)
            runs.append((steer, ay))
            sis_values.append(rule.amplitude_from_sis([(steer, ay)]))
        a_ref = rule.amplitude_from_sis(runs)
        notes.append(f'A = {a_ref / DEG:.1f} deg from slowly increasing steer at 80 km/h, '
                     f'13.5 deg/s (left {sis_values[0] / DEG:.2f}, right '
                     f'{sis_values[1] / DEG:.2f} deg at 0.3 g)')
    full = rule.amplitude_series(a_ref)
    series = [a for a in full if a <= values['max_amplitude'] * (1.0 + 1e-9)]
    reduced = len(series) < len(full)
    if not series:
        raise SolverError(f"max_amplitude {values['max_amplitude'] / DEG:.1f} deg is below the "
                          f'first amplitude of the series, 1.5A = {full[0] / DEG:.1f} deg')
    if series[-1] > limit:
        raise SolverError(f'the series needs {series[-1] / DEG:.0f} deg of steering-wheel angle, '
                          f'beyond the steering lock of the model ({limit / DEG:.0f} deg)')
    grades: list[rule.SwdGrade] = []
    traces: list[Trace] = []
    order = [(d, a) for d in (1, -1) for a in series]
    for k, (direction, amplitude) in enumerate(order):
        report(0.1 + 0.9 * k / len(order),
               f'sine with dwell {amplitude / DEG:.1f} deg, {_side(direction)} first')
        trace = _sine_run(model, amplitude, direction, tolerance)
        ch = trace.channels()
        try:
            grade = rule.grade_run(ch['time'], ch['steering_wheel_angle'], ch['yaw_rate'],
                                   ch['lateral_acceleration'], a_reference=a_ref,
                                   roll=ch['roll'], gvwr=gvwr, speed=ch['speed'],
                                   commanded_amplitude=amplitude)
        except rule.ProcessingError as err:
            raise SolverError(f'sine with dwell {amplitude / DEG:.1f} deg, {_side(direction)} '
                              f'first: {err}') from err
        grades.append(grade)
        traces.append(trace)
    verdict = rule.grade_procedure(grades, a_ref)
    decide = verdict.deciding_run if verdict.deciding_run is not None else len(grades) - 1
    channels = dict(channels_of(model, traces[decide]))
    channels.update(_table(grades))
    channels.update(_series(traces))
    metrics = _metrics(verdict, a_ref, gvwr, reduced, decide)
    table = _notes(verdict, reduced, series, full, decide, tolerance)
    return metrics, channels, [table[0], *notes, *table[1:]]


def _table(grades) -> dict[str, Channel]:
    """Return the per-run table as channels of one value per run (series order)."""
    def flag(value):
        return float('nan') if value is None else float(bool(value))

    cols = {
        'run_amplitude': ('rad', [g.amplitude for g in grades]),
        'run_direction': ('-', [g.direction for g in grades]),
        'run_entry_speed': ('m/s', [g.entry_speed for g in grades]),
        'run_peak_yaw_rate': ('rad/s', [g.peak_yaw_rate for g in grades]),
        'run_yaw_rate_ratio_1_00': ('-', [g.yaw_rate_ratio_1_00 for g in grades]),
        'run_yaw_rate_ratio_1_75': ('-', [g.yaw_rate_ratio_1_75 for g in grades]),
        'run_lateral_displacement': ('m', [g.lateral_displacement for g in grades]),
        'run_peak_lateral_acceleration': ('m/s^2', [g.peak_lateral_acceleration
                                                    for g in grades]),
        'run_peak_roll': ('rad', [g.peak_roll for g in grades]),
        'run_peak_yaw_rate_abs': ('rad/s', [g.peak_yaw_rate_abs for g in grades]),
        'run_stable_1_00': ('-', [flag(g.stable_1_00) for g in grades]),
        'run_stable_1_75': ('-', [flag(g.stable_1_75) for g in grades]),
        'run_responsive': ('-', [flag(g.responsive) for g in grades]),
        'run_passed': ('-', [flag(g.passed) for g in grades]),
    }
    return {name: Channel(unit, np.array(values, dtype=float))
            for name, (unit, values) in cols.items()}


def _series(traces) -> dict[str, Channel]:
    """
    Return every run's signals over time at SERIES_RATE, one channel per run and signal.

    ``series_time`` (s, from the start of the run; the same for every run) and
    ``series_<signal>_<run>`` with the run's number in series order (01, 02, ...). No
    channel is longer than the deciding run's own time channel (a result's step count).
    """
    out: dict[str, Channel] = {}
    units = {'steering_wheel_angle': 'rad', 'lateral_acceleration': 'm/s^2', 'roll': 'rad',
             'yaw_rate': 'rad/s'}
    for k, trace in enumerate(traces):
        ch = trace.channels()
        every = max(1, int(round(1.0 / (SERIES_RATE * (ch['time'][1] - ch['time'][0])))))
        pick = slice(None, None, every)
        if k == 0:
            out['series_time'] = Channel('s', ch['time'][pick])
        for name, unit in units.items():
            out[f'series_{name}_{k + 1:02d}'] = Channel(unit, ch[name][pick])
    return out


def _metrics(verdict, a_ref: float, gvwr: float, reduced: bool, decide: int) -> dict:
    grades = verdict.runs
    by = {c.name: c for c in verdict.criteria}

    def value(name: str) -> float:
        c = by[name]
        return float('nan') if c.deciding_run is None else c.deciding_value

    rolls = [g.peak_roll for g in grades if g.peak_roll is not None]
    return {
        'a_reference': Metric(a_ref, 'rad', '49 CFR 571.126 S7.6'),
        'runs': Metric(float(len(grades)), '-'),
        'largest_amplitude': Metric(max(g.amplitude for g in grades), 'rad'),
        'passed': Metric(float(verdict.passed), '-', '49 CFR 571.126 S5.2'),
        'valid': Metric(float(verdict.valid), '-', '49 CFR 571.126 S7.9.2'),
        'reduced_series': Metric(float(reduced), '-'),
        'lateral_stability_1_00_passed': Metric(float(by['yaw_rate_ratio_1_00'].passed), '-',
                                                '49 CFR 571.126 S5.2.1'),
        'lateral_stability_1_75_passed': Metric(float(by['yaw_rate_ratio_1_75'].passed), '-',
                                                '49 CFR 571.126 S5.2.2'),
        'responsiveness_passed': Metric(float(by['lateral_displacement'].passed), '-',
                                        '49 CFR 571.126 S5.2.3'),
        'yaw_rate_ratio_1_00_deciding': Metric(value('yaw_rate_ratio_1_00'), '-'),
        'yaw_rate_ratio_1_75_deciding': Metric(value('yaw_rate_ratio_1_75'), '-'),
        'lateral_displacement_deciding': Metric(value('lateral_displacement'), 'm'),
        'lateral_displacement_limit': Metric(by['lateral_displacement'].limit, 'm'),
        'gvwr': Metric(gvwr, 'kg'),
        'deciding_run': Metric(float(decide + 1), '-'),  # number in the series order, from 1
        'peak_lateral_acceleration': Metric(max(g.peak_lateral_acceleration for g in grades),
                                            'm/s^2'),
        'peak_roll': Metric(max(rolls) if rolls else float('nan'), 'rad'),
        'peak_yaw_rate': Metric(max(g.peak_yaw_rate_abs for g in grades), 'rad/s'),
    }


def run_label(grade) -> str:
    """'175.0 deg, left first' for a graded run."""
    return f'{grade.amplitude / DEG:.1f} deg, {_side(grade.direction)} first'


def _notes(verdict, reduced: bool, series, full, decide: int,
           tolerance: float | None) -> list[str]:
    grades = verdict.runs
    crit = {c.name: c for c in verdict.criteria}
    word = 'PASS' if verdict.passed else ('INVALID' if not verdict.valid else 'FAIL')
    if reduced:
        word += f' (reduced series: {len(series)} of {len(full)} amplitudes)'
    g = grades[decide]
    c = crit[verdict.deciding_criterion]
    sign = '>=' if c.name == 'lateral_displacement' else '<='
    unit = ' m' if c.name == 'lateral_displacement' else ''
    value = (f'{c.deciding_value:.2f} m' if unit else f'{100 * c.deciding_value:.1f} %')
    limit = (f'{c.limit:.2f} m' if unit else f'{100 * c.limit:.0f} %')
    out = [f'FMVSS 126 sine with dwell: {word}; deciding run #{decide + 1} '
           f'({run_label(g)}): {c.name} {value} (limit {sign} {limit})',
           'amplitude series (deg): ' + ', '.join(f'{a / DEG:.1f}' for a in series)]
    for name, cv in crit.items():
        state = 'pass' if cv.passed else 'FAIL'
        where = '' if cv.deciding_run is None else f', deciding run #{cv.deciding_run + 1}'
        out.append(f'criterion {name}: {state} over {cv.runs} runs{where}')
    out.append('run  amplitude  first  r_peak    r(COS+1)  r(COS+1.75)  Y(BOS+1.07)  '
               'a_y,max  roll,max  result')
    for k, g in enumerate(grades):
        disp = f'{g.lateral_displacement:6.2f} m' + ('' if g.responsiveness_applies else '*')
        out.append(
            f'{k + 1:3d}  {g.amplitude / DEG:6.1f} deg  {_side(g.direction):5s}  '
            f'{g.peak_yaw_rate / DEG:6.1f} deg/s  {100 * g.yaw_rate_ratio_1_00:6.1f} %  '
            f'{100 * g.yaw_rate_ratio_1_75:6.1f} %  {disp:>10s}  '
            f'{g.peak_lateral_acceleration / G:5.3f} g  '
            f'{(g.peak_roll or 0.0) / DEG:5.2f} deg  {"pass" if g.passed else "FAIL"}')
    out.append('* responsiveness not graded below 5A (S5.2.3); stability graded on every run '
               '(S5.2.1, S5.2.2)')
    out.append('integrator step ' + (f'variable (tolerance {tolerance:g})' if tolerance else
                                     f'{STEP * 1e3:g} ms')
               + f', recorded at {1.0 / (STEP * RECORD_EVERY):g} Hz; coasting, no ESC '
               '(passive vehicle)')
    return out


__all__ = ['PARAMS', 'run_procedure', 'run_label']
