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
import html
import math
from pathlib import Path

DEG = 180.0 / math.pi
G = 9.80665
FIGURES = (('series_lateral_acceleration', 'lateral acceleration [m/s²]', 1.0, '4.4.4'),
           ('series_roll', 'roll angle [deg]', DEG, '4.4.5'),
           ('series_yaw_rate', 'yaw rate [deg/s]', DEG, '4.4.6'))
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


def sine_with_dwell_section(runs: Sequence, out: Path, family: str) -> str:
    """Write the figures into ``out``; return the HTML section."""
    import matplotlib.pyplot as plt

    from vd_events.reports.report import save_figure

    usable = [r for r in runs if 'series_time' in r.channels]
    images = []
    for channel, label, scale, fig_no in FIGURES:
        fig, ax = plt.subplots(figsize=(6.4, 4.2), dpi=110)
        for c, run in enumerate(usable):
            ch = run.channels
            for s, k in enumerate(_picked(run)):
                amp = ch['run_amplitude'][k] * DEG
                ax.plot(ch['series_time'], ch[f'{channel}_{k + 1:02d}'] * scale,
                        color=COLOURS[c % len(COLOURS)], linestyle=STYLES[s % len(STYLES)],
                        label=f'{run.label}, {amp:.0f} deg')
        name = f'sine_with_dwell_{family}_{channel}.png'
        save_figure(fig, ax, out / name, 'time [s]', label,
                    f'sine with dwell (Fig. {fig_no}): {label.split(" [")[0]}', legend='x-small')
        images.append(name)
    imgs = ''.join(f'<img src="{html.escape(i)}" alt="{html.escape(i)}">' for i in images)
    return (f"<h2>sine_with_dwell ({html.escape(family)}) — FMVSS 126 / UN R140 / GTR 8</h2>"
            f"<div class='plots'>{imgs}</div>{_verdicts(runs)}"
            + ''.join(_run_table(r) for r in runs))


def _flag(value: float) -> str:
    if not math.isfinite(value):
        return '–'
    return 'pass' if value > 0.5 else '<b>FAIL</b>'


def _verdicts(runs: Sequence) -> str:
    rows = []
    for r in runs:
        m = {k: v.value for k, v in r.metrics.items()}
        if 'passed' not in m:
            continue
        rows.append(
            f"<tr><td>{html.escape(r.label)}</td>"
            f"<td>{m.get('a_reference', math.nan) * DEG:.1f}</td>"
            f"<td>{int(m.get('runs', 0))}</td>"
            f"<td>{_flag(m.get('lateral_stability_1_00_passed', math.nan))}</td>"
            f"<td>{_flag(m.get('lateral_stability_1_75_passed', math.nan))}</td>"
            f"<td>{_flag(m.get('responsiveness_passed', math.nan))}</td>"
            f"<td>{_flag(m['passed'])}</td><td>{html.escape(r.notes[0] if r.notes else '')}"
            '</td></tr>')
    return ("<table><tr><th>configuration</th><th>A [deg]</th><th>runs</th>"
            "<th>r(COS+1.0) ≤ 35 %</th><th>r(COS+1.75) ≤ 20 %</th><th>Y(BOS+1.07)</th>"
            f"<th>overall</th><th>deciding run</th></tr>{''.join(rows)}</table>")


def _run_table(run) -> str:
    ch = run.channels
    if 'run_amplitude' not in ch:
        return ''
    rows = []
    for k in range(len(ch['run_amplitude'])):
        side = 'left' if ch['run_direction'][k] > 0 else 'right'
        rows.append(
            f"<tr><td>{k + 1}</td><td>{ch['run_amplitude'][k] * DEG:.1f}</td><td>{side}</td>"
            f"<td>{ch['run_peak_yaw_rate'][k] * DEG:.1f}</td>"
            f"<td>{100 * ch['run_yaw_rate_ratio_1_00'][k]:.1f}</td>"
            f"<td>{100 * ch['run_yaw_rate_ratio_1_75'][k]:.1f}</td>"
            f"<td>{ch['run_lateral_displacement'][k]:.2f}</td>"
            f"<td>{ch['run_peak_lateral_acceleration'][k] / G:.3f}</td>"
            f"<td>{ch['run_peak_roll'][k] * DEG:.2f}</td>"
            f"<td>{_flag(float(ch['run_passed'][k]))}</td></tr>")
    return (f"<h3>Runs — {html.escape(run.label)}</h3><div class='scroll'><table>"
            '<tr><th>#</th><th>amplitude [deg]</th><th>first</th><th>peak yaw rate [deg/s]</th>'
            '<th>r(COS+1.0) [%]</th><th>r(COS+1.75) [%]</th><th>Y(BOS+1.07) [m]</th>'
            '<th>a_y,max [g]</th><th>roll,max [deg]</th><th>result</th></tr>'
            f"{''.join(rows)}</table></div>")


__all__ = ['sine_with_dwell_section']
