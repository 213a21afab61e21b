# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The sine-with-dwell section of ``vd report``: the thesis' Figs. 4.4.4-4.4.6 and the verdicts.

Figures over the time from BOS (each run aligned on its own beginning of steer, S7.11.6),
runs and configurations overlaid: lateral acceleration (Fig. 4.4.4), roll angle
(Fig. 4.4.5) and yaw rate (Fig. 4.4.6), from the ``series_<signal>_<run>`` channels of a
simulated ``sine_with_dwell`` result (every run of the procedure at 50 Hz). Shown per
configuration: the left-first runs at the amplitude nearest 5A and at the largest
amplitude of the series (colour per configuration, line style per amplitude). Measured
logs of the manoeuvre (``vd import``, event ``sine_with_dwell``) are drawn beside them
(black, markers) and graded by the same processing (:mod:`vd_events.measured.grade`;
A from the slowly-increasing-steer logs of the same bags, else responsiveness is not
graded). The table lists every run with its yaw-rate ratios, lateral displacement and
verdict, and each configuration's (and the measured runs') verdict with the deciding run
(49 CFR 571.126 S5.2).
"""
from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
import math
from pathlib import Path

import numpy as np

from vd_events.errors import InputError
from vd_events.measured.align import reference_time
from vd_events.measured.grade import Procedure, RunGrade, grade
from vd_events.reports.figures import new_figure, save_figure
from vd_events.reports.html import Cell, Section, Table, images
from vd_events.reports.runs import TO_DEG, TO_G
from vd_solvers.standards.fmvss126 import ProcessingError

FIGURES = (('series_lateral_acceleration', 'lateral acceleration [m/s²]', 1.0, '4.4.4'),
           ('series_roll', 'roll angle [deg]', TO_DEG, '4.4.5'),
           ('series_yaw_rate', 'yaw rate [deg/s]', TO_DEG, '4.4.6'))
STYLES = ('-', '--')
COLOURS = ('tab:blue', 'tab:orange', 'tab:green', 'tab:red', 'tab:purple', 'tab:brown')
MEASURED_STYLE = {'color': 'black', 'marker': '.', 'markersize': 2, 'linewidth': 0.6}


def _picked(run) -> list[int]:
    """Run indices plotted: left first, nearest 5A and the largest amplitude."""
    ch = run.channels
    amp, direction = ch.get('run_amplitude'), ch.get('run_direction')
    a_ref = run.metrics['a_reference'].value if 'a_reference' in run.metrics else math.nan
    if amp is None or direction is None or not math.isfinite(a_ref):
        return []
    left = [k for k in range(len(amp)) if direction[k] > 0] or list(range(len(amp)))
    near = min(left, key=lambda k: abs(amp[k] - 5.0 * a_ref))
    last = max(left, key=lambda k: amp[k])
    return sorted({near, last})


def _bos(time, steering) -> float | None:
    try:
        return reference_time('sine_with_dwell', time, steering)
    except ProcessingError:
        return None


def measured_grades(runs: Sequence, sis: Sequence = ()) -> tuple[list[RunGrade],
                                                                 Procedure | None, list[str]]:
    """Grade the measured sine-with-dwell logs of a group as one procedure (module doc)."""
    logs = [(str(r.bag), r.outcome) for r in runs if r.model == 'test']
    if not logs:
        return [], None, []
    try:
        result = grade(logs, [(str(r.bag), r.outcome) for r in sis])
    except InputError as err:
        return [], None, [f'measured runs not graded: {err}']
    procedure = result.procedures[0] if result.procedures else None
    return [g for g in result.runs if g.event == 'sine_with_dwell'], procedure, []


@dataclass(frozen=True)
class Curve:
    """One line of a figure: over the time from BOS, in the figure's unit."""

    label: str
    x: np.ndarray
    y: np.ndarray
    style: dict


def figure_curves(runs: Sequence, logs: Sequence[RunGrade]) -> list[list[Curve]]:
    """Return the curves of each of FIGURES: the picked simulated runs, then every log."""
    out = []
    for channel, _, scale, _ in FIGURES:
        curves = []
        for c, run in enumerate(r for r in runs if 'series_time' in r.channels):
            ch = run.channels
            for s, k in enumerate(_picked(run)):
                t = ch['series_time']
                bos = _bos(t, ch[f'series_steering_wheel_angle_{k + 1:02d}'])
                if bos is None:
                    continue
                curves.append(Curve(
                    f"{run.label}, {ch['run_amplitude'][k] * TO_DEG:.0f} deg", t - bos,
                    ch[f'{channel}_{k + 1:02d}'] * scale,
                    {'color': COLOURS[c % len(COLOURS)], 'linestyle': STYLES[s % len(STYLES)]}))
        signal = channel.removeprefix('series_')
        for g in logs:
            ch = g.outcome.channels
            if signal in ch and g.swd is not None:
                curves.append(Curve(f'{g.label}, {g.swd.amplitude * TO_DEG:.0f} deg',
                                    ch['time'].values - g.swd.bos, ch[signal].values * scale,
                                    dict(MEASURED_STYLE)))
        out.append(curves)
    return out


def sine_with_dwell_section(runs: Sequence, out: Path, family: str,
                            sis: Sequence = ()) -> Section:
    """Write the figures into ``out``; return the section (``sis``: measured SIS logs)."""
    logs, procedure, problems = measured_grades(runs, sis)
    names = []
    for (channel, label, _, fig_no), curves in zip(FIGURES, figure_curves(runs, logs)):
        fig, ax = new_figure()
        for curve in curves:
            ax.plot(curve.x, curve.y, label=curve.label, **curve.style)
        ax.set_xlim(-1.5, 4.5)
        name = f'sine_with_dwell_{family}_{channel}.png'
        save_figure(fig, ax, out / name, 'time from BOS [s]', label,
                    f'sine with dwell (Fig. {fig_no}): {label.split(" [")[0]}', legend='x-small')
        names.append(name)
    verdicts = _verdicts(runs, procedure)
    subsections = [s for s in (_run_table(r) for r in runs) if s is not None]
    if logs:
        subsections.append(_log_table(logs))
    return Section(f'sine_with_dwell ({family}) — FMVSS 126 / UN R140 / GTR 8',
                   images=images(names), tables=[verdicts], subsections=subsections,
                   notes=[*problems, *(procedure.notes if procedure else [])])


def _criterion(procedure: Procedure, name: str) -> Cell:
    c = next(c for c in procedure.grade.criteria if c.name == name)
    if not c.runs:
        return Cell('–', cls='na')
    return Cell('pass', cls='ok') if c.passed else Cell('FAIL', cls='bad')


def _log_table(logs: Sequence[RunGrade]) -> Section:
    rows = []
    for k, g in enumerate(logs):
        s = g.swd
        assert s is not None
        rows.append([k + 1, g.label, f'{s.amplitude * TO_DEG:.1f}',
                     'left' if s.direction > 0 else 'right',
                     '–' if s.entry_speed is None else f'{s.entry_speed * 3.6:.1f}',
                     f'{s.peak_yaw_rate * TO_DEG:.1f}', f'{100 * s.yaw_rate_ratio_1_00:.1f}',
                     f'{100 * s.yaw_rate_ratio_1_75:.1f}', f'{s.lateral_displacement:.2f}',
                     f'{s.peak_lateral_acceleration * TO_G:.3f}',
                     Cell(g.verdict, cls={'PASS': 'ok', 'FAIL': 'bad', 'INVALID': 'bad'}.get(
                         g.verdict, 'na'))])
    return Section('Runs — measured logs', level=3, tables=[Table(
        ['#', 'log', 'amplitude [deg]', 'first', 'entry speed [km/h]', 'peak yaw rate [deg/s]',
         'r(COS+1.0) [%]', 'r(COS+1.75) [%]', 'Y(BOS+1.07) [m]', 'a_y,max [g]', 'result'],
        rows)])


def _flag(value: float) -> Cell:
    if not math.isfinite(value):
        return Cell('–', cls='na')
    return Cell('pass', cls='ok') if value > 0.5 else Cell('FAIL', cls='bad')


def _verdicts(runs: Sequence, procedure: Procedure | None = None) -> Table:
    rows: list[list] = []
    for r in runs:
        m = {k: v.value for k, v in r.metrics.items()}
        if 'passed' not in m:
            continue
        rows.append([r.label, f"{m.get('a_reference', math.nan) * TO_DEG:.1f}",
                     int(m.get('runs', 0)),
                     _flag(m.get('lateral_stability_1_00_passed', math.nan)),
                     _flag(m.get('lateral_stability_1_75_passed', math.nan)),
                     _flag(m.get('responsiveness_passed', math.nan)), _flag(m['passed']),
                     r.notes[0] if r.notes else ''])
    if procedure is not None:
        a_ref = procedure.grade.a_reference
        rows.append(['measured runs', '–' if a_ref is None else f'{a_ref * TO_DEG:.1f}',
                     len(procedure.runs),
                     *(_criterion(procedure, name) for name in (
                         'yaw_rate_ratio_1_00', 'yaw_rate_ratio_1_75', 'lateral_displacement')),
                     Cell(procedure.verdict, cls={'PASS': 'ok', 'FAIL': 'bad',
                                                  'INVALID': 'bad'}.get(procedure.verdict, 'na')),
                     procedure.deciding])
    return Table(['configuration', 'A [deg]', 'runs', 'r(COS+1.0) ≤ 35 %',
                  'r(COS+1.75) ≤ 20 %', 'Y(BOS+1.07)', 'overall', 'deciding run'], rows)


#: the per-run table a simulated procedure carries (vd_solvers/vehicle/sine_with_dwell.py)
RUN_TABLE = ('run_amplitude', 'run_direction', 'run_peak_yaw_rate', 'run_yaw_rate_ratio_1_00',
             'run_yaw_rate_ratio_1_75', 'run_lateral_displacement',
             'run_peak_lateral_acceleration', 'run_peak_roll', 'run_passed')


def _run_table(run) -> Section | None:
    ch = run.channels
    if not all(name in ch for name in RUN_TABLE):
        return None
    rows = []
    for k in range(len(ch['run_amplitude'])):
        rows.append([
            k + 1, f"{ch['run_amplitude'][k] * TO_DEG:.1f}",
            'left' if ch['run_direction'][k] > 0 else 'right',
            f"{ch['run_peak_yaw_rate'][k] * TO_DEG:.1f}",
            f"{100 * ch['run_yaw_rate_ratio_1_00'][k]:.1f}",
            f"{100 * ch['run_yaw_rate_ratio_1_75'][k]:.1f}",
            f"{ch['run_lateral_displacement'][k]:.2f}",
            f"{ch['run_peak_lateral_acceleration'][k] * TO_G:.3f}",
            f"{ch['run_peak_roll'][k] * TO_DEG:.2f}", _flag(float(ch['run_passed'][k]))])
    return Section(f'Runs — {run.label}', level=3, tables=[Table(
        ['#', 'amplitude [deg]', 'first', 'peak yaw rate [deg/s]', 'r(COS+1.0) [%]',
         'r(COS+1.75) [%]', 'Y(BOS+1.07) [m]', 'a_y,max [g]', 'roll,max [deg]', 'result'],
        rows)])


__all__ = ['sine_with_dwell_section', 'figure_curves', 'measured_grades', 'Curve']
