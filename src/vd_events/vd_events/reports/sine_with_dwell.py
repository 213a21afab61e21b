# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The sine-with-dwell section of ``vd report``: the thesis' Figs. 4.4.4-4.4.6 and the verdicts.

Figures over time, runs and configurations overlaid: lateral acceleration (Fig. 4.4.4),
roll angle (Fig. 4.4.5) and yaw rate (Fig. 4.4.6), from the ``series_<signal>_<run>``
channels of a ``sine_with_dwell`` result (every run of the procedure at 50 Hz). Shown per
configuration: the left-first runs at the amplitude nearest 5A and at the largest
amplitude of the series (colour per configuration, line style per amplitude). The table
lists every run with its yaw-rate ratios, lateral displacement and verdict, and each
configuration's verdict with the deciding run (49 CFR 571.126 S5.2).
"""
from __future__ import annotations

from collections.abc import Sequence
import math
from pathlib import Path

from vd_events.reports.figures import new_figure, save_figure
from vd_events.reports.html import Cell, Section, Table, images
from vd_events.reports.runs import TO_DEG, TO_G

FIGURES = (('series_lateral_acceleration', 'lateral acceleration [m/s²]', 1.0, '4.4.4'),
           ('series_roll', 'roll angle [deg]', TO_DEG, '4.4.5'),
           ('series_yaw_rate', 'yaw rate [deg/s]', TO_DEG, '4.4.6'))
STYLES = ('-', '--')
COLOURS = ('tab:blue', 'tab:orange', 'tab:green', 'tab:red', 'tab:purple', 'tab:brown')


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


def sine_with_dwell_section(runs: Sequence, out: Path, family: str) -> Section:
    """Write the figures into ``out``; return the section."""
    usable = [r for r in runs if 'series_time' in r.channels]
    names = []
    for channel, label, scale, fig_no in FIGURES:
        fig, ax = new_figure()
        for c, run in enumerate(usable):
            ch = run.channels
            for s, k in enumerate(_picked(run)):
                amp = ch['run_amplitude'][k] * TO_DEG
                ax.plot(ch['series_time'], ch[f'{channel}_{k + 1:02d}'] * scale,
                        color=COLOURS[c % len(COLOURS)], linestyle=STYLES[s % len(STYLES)],
                        label=f'{run.label}, {amp:.0f} deg')
        name = f'sine_with_dwell_{family}_{channel}.png'
        save_figure(fig, ax, out / name, 'time [s]', label,
                    f'sine with dwell (Fig. {fig_no}): {label.split(" [")[0]}', legend='x-small')
        names.append(name)
    return Section(f'sine_with_dwell ({family}) — FMVSS 126 / UN R140 / GTR 8',
                   images=images(names), tables=[_verdicts(runs)],
                   subsections=[s for s in (_run_table(r) for r in runs) if s is not None])


def _flag(value: float) -> Cell:
    if not math.isfinite(value):
        return Cell('–', cls='na')
    return Cell('pass', cls='ok') if value > 0.5 else Cell('FAIL', cls='bad')


def _verdicts(runs: Sequence) -> Table:
    rows = []
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
    return Table(['configuration', 'A [deg]', 'runs', 'r(COS+1.0) ≤ 35 %',
                  'r(COS+1.75) ≤ 20 %', 'Y(BOS+1.07)', 'overall', 'deciding run'], rows)


def _run_table(run) -> Section | None:
    ch = run.channels
    if 'run_amplitude' not in ch:
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


__all__ = ['sine_with_dwell_section']
