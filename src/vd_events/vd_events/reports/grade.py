# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The page of ``vd grade``: every run graded by its standard, a section per run.

``grade.html``: the verdicts first (runs and sine-with-dwell procedures), then per
procedure its criteria and deciding run, and per run a figure of its steering and
responses over time with the instants the standard defines (BOS, COS, COS + 1 s,
COS + 1.75 s; t50 and the steady window of a step), its metrics in display units, the
validity checks and the notes. The grading is :mod:`vd_events.measured.grade`.
"""
from __future__ import annotations

from collections.abc import Sequence
import dataclasses
import math
from pathlib import Path

from vd_events.errors import InputError
from vd_events.measured.grade import (
    GradeOptions,
    GradeResult,
    Procedure,
    RunGrade,
    grade_circle_run,
    grade_step_run,
    shown_metric,
)
from vd_events.reports.figures import new_figure, save_figure
from vd_events.reports.html import Image, Section, Table, write_page
from vd_events.reports.runs import Run
from vd_events.reports.sections import verdict_cell
from vd_solvers.constants import DEG
from vd_solvers.results import Metric

#: verdict -> colour of its cell (True green, False red, None grey)
GOOD = {'PASS': True, 'VALID': True, 'FAIL': False, 'INVALID': False, 'INCOMPLETE': None}
#: what each run's figure draws: channel, label, scale to the label's unit
TRACES = (('steering_wheel_angle', 'steering-wheel angle [deg] / 10', 0.1 / DEG),
          ('yaw_rate', 'yaw rate [deg/s]', 1.0 / DEG),
          ('lateral_acceleration', 'lateral acceleration [m/s²]', 1.0))


def _figure(run: RunGrade, out: Path, name: str) -> str:
    ch = run.outcome.channels
    fig, ax = new_figure()
    t = ch['time'].values
    for channel, label, scale in TRACES:
        if channel in ch:
            ax.plot(t, ch[channel].values * scale, label=label, linewidth=1.0)
    for k, (mark, when) in enumerate(run.marks.items()):
        ax.axvline(when, color='0.4', linestyle=(':', '--')[k % 2], linewidth=0.8)
        ax.annotate(mark, (when, 1.0), xycoords=('data', 'axes fraction'), fontsize=7,
                    rotation=90, va='top', ha='right')
    save_figure(fig, ax, out / name, 'time [s]', 'signal', f'{run.label}: {run.standard}',
                legend='x-small')
    return name


def run_section(run: RunGrade, image: str | None) -> Section:
    """One run: its figure, metrics, checks and notes."""
    rows = [[name, shown_metric(value, unit)] for name, (value, unit) in run.metrics.items()
            if value is not None]
    return Section(f'{run.label} — {run.standard}: {run.verdict}', level=3,
                   images=[Image(image, image)] if image else [],
                   tables=[Table(['metric', 'value'], rows)],
                   notes=[*(f'check: {c}' for c in run.checks), *run.notes,
                          f'source: {run.source}'])


def procedure_section(proc: Procedure) -> Section:
    """Return a procedure's section: A, the criteria, the deciding run, the runs."""
    g = proc.grade
    a = '–' if g.a_reference is None else f'{g.a_reference / DEG:.1f} deg'
    criteria = [[c.name, c.runs, '–' if c.deciding_run is None else c.deciding_run + 1,
                 f'{c.deciding_value:.2f} m' if c.name == 'lateral_displacement'
                 else f'{100 * c.deciding_value:.1f} %',
                 f'>= {c.limit:.2f} m' if c.name == 'lateral_displacement'
                 else f'<= {100 * c.limit:.0f} %',
                 verdict_cell('pass' if c.passed else 'FAIL', c.passed)] for c in g.criteria]
    runs = [[k + 1, r.label, f'{r.swd.amplitude / DEG:.1f}' if r.swd else '–',
             f'{r.swd.entry_speed * 3.6:.1f}' if r.swd and r.swd.entry_speed else '–',
             verdict_cell(r.verdict, GOOD.get(r.verdict))] for k, r in enumerate(proc.runs)]
    return Section(f'{proc.label} — FMVSS 126 / UN R140 sine with dwell: {proc.verdict}',
                   paragraphs=[f'A = {a} ({proc.a_source}). Deciding: {proc.deciding}.'],
                   tables=[Table(['criterion', 'valid runs graded', 'deciding run', 'value',
                                  'limit', 'verdict'], criteria),
                           Table(['#', 'run', 'amplitude [deg]', 'entry speed [km/h]',
                                  'result'], runs)],
                   notes=proc.notes)


def with_grades(runs: Sequence[Run]) -> list[Run]:
    """
    Return the runs, the measured step steers and constant radius turns graded.

    Their ISO 7401 / ISO 4138 metrics join the log's, under the names the simulations
    give the same metrics, so the event's table shows them side by side; a log that cannot
    be graded says why in its notes.
    """
    out = []
    for run in runs:
        if run.model != 'test' or run.event not in ('step_steer', 'constant_radius_turn'):
            out.append(run)
            continue
        source = str(run.bag)
        try:
            graded = (grade_step_run(source, run.outcome) if run.event == 'step_steer' else
                      grade_circle_run(source, run.outcome, GradeOptions()))
        except InputError as err:
            outcome = dataclasses.replace(run.outcome, notes=(
                *run.outcome.notes, f'not graded: {err}'))
            out.append(dataclasses.replace(run, outcome=outcome))
            continue
        metrics = dict(run.outcome.metrics)
        metrics.update({name: Metric(value, unit, graded.standard)
                        for name, (value, unit) in graded.metrics.items()
                        if value is not None and math.isfinite(value)})
        metrics['valid'] = Metric(1.0 if graded.verdict == 'VALID' else 0.0, '-',
                                  graded.standard)
        outcome = dataclasses.replace(run.outcome, metrics=metrics, notes=(
            *run.outcome.notes, *(f'{graded.standard}: {c}' for c in graded.checks)))
        out.append(dataclasses.replace(run, outcome=outcome))
    return out


def write_grade_page(result: GradeResult, out: Path) -> Path:
    """Write ``out/grade.html`` and its figures; return the page."""
    out.mkdir(parents=True, exist_ok=True)
    summary = Section(tables=[Table(['run', 'standard', 'verdict'], [
        [r.label, r.standard, verdict_cell(r.verdict, GOOD.get(r.verdict))]
        for r in result.runs] + [
        [p.label, 'FMVSS 126 / UN R140 procedure', verdict_cell(p.verdict,
                                                                GOOD.get(p.verdict))]
        for p in result.procedures])])
    sections = [summary, *(procedure_section(p) for p in result.procedures)]
    runs = Section('Runs')
    for k, run in enumerate(result.runs):
        image = _figure(run, out, f'grade_{k}.png') if 'time' in run.outcome.channels else None
        runs.subsections.append(run_section(run, image))
    sections.append(runs)
    return write_page(out / 'grade.html', 'vd grade', sections,
                      intro=[f'{len(result.runs)} run(s) graded by their standard; '
                             f'{len(result.procedures)} sine-with-dwell procedure(s).'])


__all__ = ['write_grade_page', 'run_section', 'procedure_section', 'with_grades']
