# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
``vd grade FILE|BAG...``: measured and simulated runs graded by their standard.

Every result is graded by the ROS-free cores of ``vd_solvers.standards`` from its
channels, whether it is a log (read and checked as ``vd import`` does: :mod:`.importer`)
or a simulation in a bag -- the same processing for both:

* ``sine_with_dwell`` (FMVSS 126 / UN R140 / GTR 8, :mod:`~vd_solvers.standards.fmvss126`):
  each measured log is one run; the measured runs of the set form one procedure graded
  against A from the slowly-increasing-steer logs of the same set (``--sis``, or results
  of event ``slowly_increasing_steer`` among the inputs), or A given (``--a-reference``);
  without A, responsiveness is not graded and the procedure is not passed. A simulated
  procedure is re-graded run by run from its series, against its own A; a simulated single
  run (a replay of a log) is graded as a log is, its model's runs forming a procedure.
* ``slowly_increasing_steer`` (S7.6): A of each run, with its validity.
* ``step_steer`` (ISO 7401, :mod:`~vd_solvers.standards.iso7401`) and
  ``constant_radius_turn`` (ISO 4138, :mod:`~vd_solvers.standards.iso4138`): metrics,
  gradients and the validity checks of each run.

A measured run is graded on the gap-free stretch of the log that holds its manoeuvre; a
gap inside the manoeuvre is refused with where it is.
"""
from __future__ import annotations

from collections.abc import Mapping, Sequence
import dataclasses
from dataclasses import dataclass, field
import math
from pathlib import Path

import numpy as np

from vd_events.errors import InputError
from vd_events.measured.align import series_runs
from vd_events.measured.checks import segments
from vd_events.measured.columns import ColumnMap, load_map
from vd_events.measured.compare import load_outcomes
from vd_events.measured.importer import ImportOptions, read_measurement, to_outcome
from vd_solvers.constants import DEG
from vd_solvers.results import EventOutcome
from vd_solvers.standards import fmvss126, iso4138, iso7401
from vd_solvers.standards.fmvss126 import ProcessingError

GRADED = ('sine_with_dwell', 'slowly_increasing_steer', 'step_steer', 'constant_radius_turn')
STANDARDS = {'sine_with_dwell': 'FMVSS 126 / UN R140 sine with dwell',
             'slowly_increasing_steer': 'FMVSS 126 S7.6 slowly increasing steer',
             'step_steer': 'ISO 7401:2011 step input',
             'constant_radius_turn': 'ISO 4138:2021 constant radius'}
MEASURED = ('test',)


@dataclass(frozen=True)
class GradeOptions:
    """What ``vd grade`` is told besides the inputs."""

    a_reference: float | None = None  # rad (--a-reference)
    gvwr: float | None = None  # kg
    steering_ratio: float | None = None
    wheelbase: float | None = None  # m


@dataclass
class RunGrade:
    """One run graded: its verdict, metrics (SI), checks and the instants to draw."""

    source: str
    outcome: EventOutcome
    standard: str
    verdict: str  # PASS, FAIL, INVALID (pass/fail standards); VALID, INVALID (metrics)
    metrics: dict[str, tuple[float | None, str]]
    checks: list[str]
    notes: list[str] = field(default_factory=list)
    marks: dict[str, float] = field(default_factory=dict)  # s: BOS, COS, t50, ...
    swd: fmvss126.SwdGrade | None = None
    sis: fmvss126.SisGrade | None = None
    name: str = ''  # a label of its own (a run of a simulated series)

    @property
    def event(self) -> str:
        return self.outcome.event

    @property
    def label(self) -> str:
        if self.name:
            return self.name
        o = self.outcome
        if o.model in MEASURED:
            logged = next((n[len('source: '):] for n in o.notes if n.startswith('source: ')),
                          self.source)
            return f'{Path(logged).name} (log)'
        return f'{o.configuration} ({o.model}{", " + o.fidelity if o.fidelity else ""})'

    def to_json(self) -> dict:
        return {'source': self.source, 'label': self.label, 'event': self.event,
                'model': self.outcome.model, 'configuration': self.outcome.configuration,
                'standard': self.standard, 'verdict': self.verdict,
                'metrics': {k: {'value': _num(v), 'unit': u} for k, (v, u) in
                            self.metrics.items()},
                'checks': self.checks, 'notes': self.notes,
                'marks': {k: _num(v) for k, v in self.marks.items()}}


@dataclass
class Procedure:
    """A sine-with-dwell procedure: its runs graded together (49 CFR 571.126 S5.2)."""

    label: str
    grade: fmvss126.ProcedureGrade
    runs: list[RunGrade]
    a_source: str
    notes: list[str]

    @property
    def verdict(self) -> str:
        g = self.grade
        if not g.valid:
            return 'INVALID'
        if g.a_reference is None:
            return 'INCOMPLETE'
        return 'PASS' if g.passed else 'FAIL'

    @property
    def deciding(self) -> str:
        """Which run and criterion decided, with the value and the limit."""
        g = self.grade
        if g.deciding_sis_run is not None:
            return (f'slowly-increasing-steer run {g.deciding_sis_run + 1}: '
                    f'{g.deciding_criterion} ('
                    + '; '.join(g.sis[g.deciding_sis_run].describe_invalid()) + ')')
        if g.deciding_run is None:
            return f'{g.deciding_criterion}: graded on no run'
        run = g.runs[g.deciding_run]
        label = self.runs[g.deciding_run].label
        if g.deciding_criterion in ('entry_speed', 'steering_profile'):
            return (f'run {g.deciding_run + 1} ({label}): {g.deciding_criterion} ('
                    + '; '.join(run.describe_invalid()) + ')')
        c = next(c for c in g.criteria if c.name == g.deciding_criterion)
        if c.name == 'lateral_displacement':
            value, limit = f'{c.deciding_value:.2f} m', f'>= {c.limit:.2f} m'
        else:
            value, limit = f'{100 * c.deciding_value:.1f} %', f'<= {100 * c.limit:.0f} %'
        return f'run {g.deciding_run + 1} ({label}): {c.name} {value} (limit {limit})'

    def to_json(self) -> dict:
        g = self.grade
        return {'label': self.label, 'standard': STANDARDS['sine_with_dwell'],
                'verdict': self.verdict, 'valid': g.valid, 'passed': g.passed,
                'a_reference': _num(g.a_reference), 'a_source': self.a_source,
                'deciding_run': None if g.deciding_run is None else g.deciding_run + 1,
                'deciding_criterion': g.deciding_criterion, 'deciding': self.deciding,
                'criteria': [{'name': c.name, 'limit': c.limit, 'passed': c.passed,
                              'runs': c.runs, 'deciding_run': None if c.deciding_run is None
                              else c.deciding_run + 1, 'deciding_value': _num(c.deciding_value)}
                             for c in g.criteria],
                'runs': [r.label for r in self.runs], 'notes': self.notes}


@dataclass
class GradeResult:
    runs: list[RunGrade]
    procedures: list[Procedure]

    def to_json(self) -> dict:
        return {'runs': [r.to_json() for r in self.runs],
                'procedures': [p.to_json() for p in self.procedures]}


def _num(value: float | None) -> float | None:
    return None if value is None or not math.isfinite(value) else float(value)


def load_inputs(paths: Sequence[Path], map_path: Path | None,
                options: ImportOptions) -> list[tuple[str, EventOutcome]]:
    """Every result of the bags and every log file (read and checked), with its source."""
    cmap: ColumnMap | None = load_map(map_path) if map_path is not None else None
    out = []
    for path in paths:
        path = Path(path)
        if path.is_dir():
            if not (path / 'metadata.yaml').is_file():
                raise InputError(path, 'a folder that is not a finished bag (no metadata.yaml)')
            outcomes = load_outcomes(path)
            if not outcomes:
                raise InputError(path, 'no results in the bag')
            out += [(str(path), o) for o in outcomes]
            continue
        measured, kind = read_measurement(path, cmap, options)
        if kind != 'vehicle':
            raise InputError(path, 'a K&C rig measurement has no standard to be graded by')
        out.append((str(path), to_outcome(path, measured, kind, cmap, options.event)))
    return out


def _values(o: EventOutcome, name: str) -> np.ndarray | None:
    ch = o.channels.get(name)
    return None if ch is None else np.asarray(ch.values, dtype=float)


def _need(source: str, o: EventOutcome, *names: str) -> list[np.ndarray]:
    missing = [n for n in names if n not in o.channels]
    if missing:
        raise InputError(source, f"{o.event}: no {', '.join(missing)} to grade by "
                         f'{STANDARDS[o.event]}')
    return [np.asarray(o.channels[n].values, dtype=float) for n in names]


def _stretch(source: str, o: EventOutcome, find) -> tuple[slice, object]:
    """Return the gap-free stretch of a log where ``find(t, slice)`` succeeds, and its answer."""
    t = np.asarray(o.channels['time'].values, dtype=float)
    parts = segments(t)
    problems = []
    for s in parts:
        if s.stop - s.start < 30:
            continue
        try:
            return s, find(t, s)
        except ProcessingError as err:
            problems.append(f'{err} (t = {t[s][0]:.2f}..{t[s][-1]:.2f} s)')
    gaps = '; the log has gaps at ' + ', '.join(
        f't = {t[s.start - 1]:.2f} s ({t[s.start] - t[s.start - 1]:.2f} s)'
        for s in parts[1:]) if len(parts) > 1 else ''
    raise InputError(source, f'{o.event}: ' + ('; '.join(problems) or 'no stretch of 30 '
                     'samples without a gap') + gaps)


def grade_swd_run(source: str, o: EventOutcome, a_reference: float | None,
                  gvwr: float | None, commanded: float | None = None) -> RunGrade:
    """One sine-with-dwell run of a log or a simulation's series."""
    t, steer, r, ay = _need(source, o, 'time', 'steering_wheel_angle', 'yaw_rate',
                            'lateral_acceleration')
    roll, speed = _values(o, 'roll'), _values(o, 'speed')

    def find(t_: np.ndarray, s: slice) -> fmvss126.SwdGrade:
        return fmvss126.grade_run(
            t_[s], steer[s], r[s], ay[s], a_reference=a_reference,
            roll=None if roll is None else roll[s], speed=None if speed is None else speed[s],
            gvwr=gvwr or 2000.0, commanded_amplitude=commanded)

    _, g = _stretch(source, o, find)
    assert isinstance(g, fmvss126.SwdGrade)
    return _swd_grade(source, o, g)


def _swd_grade(source: str, o: EventOutcome, g: fmvss126.SwdGrade) -> RunGrade:
    metrics: dict[str, tuple[float | None, str]] = {
        'amplitude': (g.amplitude, 'rad'), 'peak_yaw_rate': (g.peak_yaw_rate, 'rad/s'),
        'yaw_rate_ratio_1_00': (g.yaw_rate_ratio_1_00, '-'),
        'yaw_rate_ratio_1_75': (g.yaw_rate_ratio_1_75, '-'),
        'lateral_displacement': (g.lateral_displacement, 'm'),
        'peak_lateral_acceleration': (g.peak_lateral_acceleration, 'm/s^2'),
        'entry_speed': (g.entry_speed, 'm/s'), 'half_period': (g.half_period, 's'),
        'steer_duration': (g.steer_duration, 's')}
    word = {True: 'ok', False: 'FAILED'}
    checks = [f'entry speed {g.entry_speed * 3.6:.1f} km/h at BOS (80 +/- 2 km/h, S7.9): '
              f'{word[g.speed_valid]}' if g.entry_speed is not None else
              'entry speed: no speed signal, not checked',
              f'steering profile: half-period {g.half_period:.3f} s, start to COS '
              f'{g.steer_duration:.3f} s (0.714 s and 1.929 s within '
              f'{100 * fmvss126.PROFILE_TOLERANCE:g} %, S7.9.1): {word[g.profile_valid]}']
    verdict = 'INVALID' if not g.valid else ('PASS' if g.passed else 'FAIL')
    notes = [f"first steer to the {'left' if g.direction > 0 else 'right'}",
             f'stability r(COS+1.00) {100 * g.yaw_rate_ratio_1_00:.1f} % (<= 35 %): '
             f'{word[g.stable_1_00]}; r(COS+1.75) {100 * g.yaw_rate_ratio_1_75:.1f} % '
             f'(<= 20 %): {word[g.stable_1_75]}',
             f'responsiveness Y(BOS+1.07) {g.lateral_displacement:.2f} m (>= '
             f'{g.displacement_limit:.2f} m): '
             + (word[bool(g.responsive)] if g.responsiveness_applies else
                'not graded (below 5A, or A not known)')]
    return RunGrade(source=source, outcome=o, standard=STANDARDS['sine_with_dwell'],
                    verdict=verdict, metrics=metrics, checks=checks, notes=notes,
                    marks={'BOS': g.bos, 'COS': g.cos, 'COS + 1.0 s': g.cos + 1.0,
                           'COS + 1.75 s': g.cos + 1.75}, swd=g)


def grade_sis_run(source: str, o: EventOutcome) -> RunGrade:
    t, steer, ay = _need(source, o, 'time', 'steering_wheel_angle', 'lateral_acceleration')
    speed = _values(o, 'speed')

    def find(t_: np.ndarray, s: slice) -> fmvss126.SisGrade:
        return fmvss126.grade_sis(t_[s], steer[s], ay[s],
                                  None if speed is None else speed[s])

    _, g = _stretch(source, o, find)
    assert isinstance(g, fmvss126.SisGrade)
    word = {True: 'ok', False: 'FAILED'}
    checks = [f'steering-wheel rate {g.steering_rate / DEG:.2f} deg/s (13.5 deg/s within '
              f'{100 * fmvss126.SIS_RATE_TOLERANCE:g} %): {word[g.rate_valid]}']
    if g.speed_range is not None:
        checks.append(f'speed {g.speed_range[0] * 3.6:.1f}..{g.speed_range[1] * 3.6:.1f} km/h '
                      f'over the regression window (80 +/- 2 km/h): {word[g.speed_valid]}')
    return RunGrade(source=source, outcome=o, standard=STANDARDS['slowly_increasing_steer'],
                    verdict='VALID' if g.valid else 'INVALID',
                    metrics={'a_value': (g.a_value, 'rad'),
                             'steering_rate': (g.steering_rate, 'rad/s'),
                             'max_lateral_acceleration': (g.max_lateral_acceleration,
                                                          'm/s^2')},
                    checks=checks, marks={'ramp start': g.ramp_start}, sis=g,
                    notes=[f"steered to the {'left' if g.direction > 0 else 'right'}"])


def grade_step_run(source: str, o: EventOutcome) -> RunGrade:
    t, steer, r, ay = _need(source, o, 'time', 'steering_wheel_angle', 'yaw_rate',
                            'lateral_acceleration')
    extra = {k: _values(o, k) for k in ('speed', 'sideslip', 'roll')}

    def find(t_: np.ndarray, s: slice) -> iso7401.StepGrade:
        return iso7401.grade_step(t_[s], steer[s], r[s], ay[s],
                                  **{k: None if v is None else v[s] for k, v in extra.items()})

    _, g = _stretch(source, o, find)
    assert isinstance(g, iso7401.StepGrade)
    metrics: dict[str, tuple[float | None, str]] = {
        'steering_wheel_angle_step': (g.step, 'rad'), 'rise_time': (g.rise_time, 's'),
        'speed': (g.speed, 'm/s')}
    for name, resp, unit in (('yaw_rate', g.yaw_rate, 'rad/s'),
                             ('lateral_acceleration', g.lateral_acceleration, 'm/s^2')):
        metrics.update({f'steady_{name}': (resp.steady, unit),
                        f'{name}_gain': (resp.gain, f'{unit}/rad'),
                        f'{name}_response_time_90': (resp.response_time, 's'),
                        f'{name}_peak_response_time': (resp.peak_response_time, 's'),
                        f'{name}_overshoot': (resp.overshoot, '%')})
    metrics['sideslip_gain'] = (g.sideslip_gain, 'rad/rad')
    metrics['roll_gain'] = (g.roll_gain, 'rad/rad')
    return RunGrade(source=source, outcome=o, standard=STANDARDS['step_steer'],
                    verdict='VALID' if g.valid else 'INVALID', metrics=metrics,
                    checks=g.describe_checks(),
                    notes=['time origin: t50, the 50 % steering-wheel instant (ISO 7401)'],
                    marks={'t50': g.t50, 'steady from': g.steady_window[0],
                           'steady to': g.steady_window[1]})


def grade_circle_run(source: str, o: EventOutcome, options: GradeOptions) -> RunGrade:
    t, steer, ay, r, v = _need(source, o, 'time', 'steering_wheel_angle',
                               'lateral_acceleration', 'yaw_rate', 'speed')
    roll, beta = _values(o, 'roll'), _values(o, 'sideslip')
    ratio = options.steering_ratio
    ratio_source = '--steering-ratio'
    if ratio is None and 'steering_ratio' in o.metrics:
        ratio, ratio_source = o.metrics['steering_ratio'].value, "the simulation's"

    def find(t_: np.ndarray, s: slice) -> iso4138.CircleGrade:
        return iso4138.grade_circle(t_[s], steer[s], ay[s], r[s], v[s],
                                    roll=None if roll is None else roll[s],
                                    sideslip=None if beta is None else beta[s],
                                    steering_ratio=ratio, wheelbase=options.wheelbase)

    _, g = _stretch(source, o, find)
    assert isinstance(g, iso4138.CircleGrade)
    notes = [f'understeer gradient: {g.ackermann}' + (f'; steering ratio {ratio:.3f} '
                                                      f'({ratio_source})' if ratio else '')]
    return RunGrade(source=source, outcome=o, standard=STANDARDS['constant_radius_turn'],
                    verdict='VALID' if g.valid else 'INVALID',
                    metrics={'radius': (g.radius, 'm'),
                             'steering_gradient': (g.steering_gradient, 'rad/(m/s^2)'),
                             'understeer_gradient': (g.understeer_gradient, 'rad/(m/s^2)'),
                             'roll_gradient': (g.roll_gradient, 'rad/(m/s^2)'),
                             'sideslip_gradient': (g.sideslip_gradient, 'rad/(m/s^2)'),
                             'max_lateral_acceleration': (g.max_lateral_acceleration,
                                                          'm/s^2')},
                    checks=g.describe_checks(), notes=notes)


def _simulated_procedure(source: str, o: EventOutcome) -> Procedure:
    """Re-grade a simulated procedure run by run from its series, against its own A."""
    if 'a_reference' not in o.metrics:
        raise InputError(source, f'{o.configuration} ({o.model}): a sine_with_dwell result '
                         'without A (a_reference)')
    a_ref = o.metrics['a_reference'].value
    gvwr = o.metrics['gvwr'].value if 'gvwr' in o.metrics else None
    runs = series_runs(o)
    count = len(runs)
    series = fmvss126.amplitude_series(a_ref)[:max(1, count // 2)]
    entry = _values(o, 'run_entry_speed')
    grades = []
    for k, run in enumerate(runs):
        g = grade_swd_run(source, run, a_ref, gvwr, commanded=series[k % len(series)])
        if entry is not None and g.swd is not None and math.isfinite(entry[k]):
            swd = dataclasses.replace(g.swd, entry_speed=float(entry[k]))
            g = _swd_grade(source, run, swd)
        g.name = f'{o.configuration} ({o.model}) run {k + 1}'
        grades.append(g)
    notes = [f"A = {a_ref / DEG:.1f} deg: the simulation's own (its slowly-increasing-steer "
             'runs, S7.6)', "entry speed: the simulation's recorded speed at BOS of each run"]
    return _procedure(f'{o.configuration} ({o.model})', grades, a_ref,
                      "the simulation's slowly-increasing-steer runs", (), notes)


def _procedure(label: str, runs: list[RunGrade], a_ref: float | None, a_source: str,
               sis: Sequence[fmvss126.SisGrade], notes: list[str]) -> Procedure:
    swd = [r.swd for r in runs if r.swd is not None]
    grade = fmvss126.grade_procedure(swd, a_ref, sis)
    return Procedure(label=label, grade=grade, runs=runs, a_source=a_source, notes=notes)


def grade(inputs: Sequence[tuple[str, EventOutcome]],
          sis_inputs: Sequence[tuple[str, EventOutcome]] = (),
          options: GradeOptions | None = None) -> GradeResult:
    """Grade every input by its event's standard (module doc)."""
    options = options or GradeOptions()
    ungradable = [(s, o) for s, o in inputs if o.event not in GRADED]
    if ungradable:
        source, o = ungradable[0]
        raise InputError(source, f"{o.configuration} ({o.model}): event '{o.event}' has no "
                         f"standard to grade by (graded: {', '.join(GRADED)}); a log needs "
                         'its manoeuvre: --event or event: in the column map')
    runs: list[RunGrade] = []
    procedures: list[Procedure] = []
    sis_runs = [grade_sis_run(s, o) for s, o in [*sis_inputs, *inputs]
                if o.event == 'slowly_increasing_steer' and o.model in MEASURED]
    if any(o.event != 'slowly_increasing_steer' for _, o in sis_inputs):
        source, o = next((s, o) for s, o in sis_inputs if o.event != 'slowly_increasing_steer')
        raise InputError(source, f"--sis: event '{o.event}', not slowly_increasing_steer "
                         '(--event slowly_increasing_steer or event: in the column map)')
    runs += sis_runs
    a_ref, a_source = options.a_reference, 'given (--a-reference)'
    if a_ref is None and sis_runs:
        a_ref = fmvss126.a_from_sis([r.sis for r in sis_runs if r.sis is not None])
        a_source = (f'{len(sis_runs)} slowly-increasing-steer run(s) of the set (S7.6.1: each '
                    'to 0.1 deg, averaged, to 0.1 deg)')
    # single runs by who ran them: the logs together, each simulated model (a replay) apart
    single: dict[str, list[RunGrade]] = {}
    for source, o in inputs:
        if o.event == 'sine_with_dwell' and (o.model in MEASURED or not series_runs(o)):
            group = 'measured runs' if o.model in MEASURED else \
                f'{o.configuration} ({o.model}) runs'
            single.setdefault(group, []).append(grade_swd_run(source, o, a_ref, options.gvwr))
        elif o.event == 'sine_with_dwell':
            proc = _simulated_procedure(source, o)
            procedures.append(proc)
            runs += proc.runs
        elif o.event == 'step_steer':
            runs.append(grade_step_run(source, o))
        elif o.event == 'constant_radius_turn':
            runs.append(grade_circle_run(source, o, options))
    for group, members in single.items():
        notes = []
        if a_ref is None:
            a_source = 'not known'
            notes.append('A not known (no slowly-increasing-steer run in the set, no '
                         '--a-reference): responsiveness not graded, the procedure not passed')
        elif sis_runs and len(sis_runs) < 6:
            notes.append(f'S7.6 asks for three slowly-increasing-steer runs each way; A from '
                         f'{len(sis_runs)}')
        if options.gvwr is None:
            notes.append('GVWR not given (--gvwr): the 1.83 m displacement limit of GVWR <= '
                         '3500 kg applies')
        runs += members
        procedures.append(_procedure(group, members, a_ref, a_source,
                                     [r.sis for r in sis_runs if r.sis is not None], notes))
    return GradeResult(runs=runs, procedures=procedures)


def shown_metric(value: float | None, unit: str) -> str:
    """Show a metric in the unit a test engineer reads it in."""
    if value is None or not math.isfinite(value):
        return '-'
    table: Mapping[str, tuple[str, float]] = {
        'rad': ('deg', 1.0 / DEG), 'rad/s': ('deg/s', 1.0 / DEG), 'm/s': ('km/h', 3.6),
        'rad/(m/s^2)': ('deg/(m/s^2)', 1.0 / DEG), 'rad/s/rad': ('1/s', 1.0),
        '-': ('%', 100.0)}
    name, factor = table.get(unit, (unit, 1.0))
    return f'{value * factor:.4g} {name}'.strip()


__all__ = ['GradeOptions', 'RunGrade', 'Procedure', 'GradeResult', 'grade', 'load_inputs',
           'shown_metric', 'GRADED', 'STANDARDS']
