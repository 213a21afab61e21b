# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The automatic study report: one self-contained HTML file from the bags alone.

``build_study_report(bags, out)`` writes ``out/study.html`` (``vd study`` writes the
static ``report.html`` with its PNGs beside it, :func:`vd_events.reports.report.build_report`):

1. the configuration overview with the master file's feedback (UNCHANGED/MODIFIED,
   SAME/DIFFERS);
2. every event with the configurations overlaid, as interactive plots (zoom, hover,
   click a legend entry to hide a curve) of the same channel pairs as the static report,
   and its metric table and understeer budgets;
3. the K&C metric table of every K&C run (axle, fidelity, configuration) side by side;
4. the rigid-vs-flexible capability tables (thesis Tables 5.2.1/5.2.2);
5. the full-vehicle pass/fail metrics (any metric named ``*passed*``: 1 pass, 0 fail);
6. simulation vs test: every measured result (``vd import``, models ``rig``/``test``)
   against each simulation of its event and axle in the same bags (:mod:`.testdata.compare`);
7. provenance: per bag, its metadata (data hash, variants, modified keys, model,
   software version, source files and their hashes for measurements).

The interactive plots use plotly (plotly.js inlined once, so the file opens offline and
can be sent as it is); the comparison PNGs are embedded as data URIs.
"""
from __future__ import annotations

import base64
from collections.abc import Sequence
import html
import math
import os
from pathlib import Path

import numpy as np

from vd_events.bags.bag import BagError, custom_data

#: K&C metrics of the K&C table, in this order, where a run has them
KC_TABLE = ('bump_steer', 'camber_gain', 'wheel_rate', 'ride_rate', 'track_change',
            'roll_centre_height_kinematic', 'roll_stiffness', 'roll_steer', 'roll_camber',
            'lateral_compliance_steer', 'lateral_compliance_camber', 'lateral_stiffness',
            'longitudinal_compliance', 'anti_dive', 'anti_squat',
            'aligning_torque_compliance_steer', 'steering_ratio', 'ackermann')


def _figure_html(xa, ya, runs) -> str:
    """One interactive overlay (plotly) of ``ya`` over ``xa`` for ``runs``."""
    import plotly.graph_objects as go

    fig = go.Figure()
    for run in runs:
        x, y = run.channels[xa.channel], run.channels[ya.channel]
        if ya.relative:
            y = y - y[int(np.argmin(np.abs(x)))]
        measured = run.model in ('rig', 'test')
        fig.add_trace(go.Scatter(x=x * xa.scale, y=y * ya.scale, name=run.label,
                                 mode='markers' if measured else 'lines',
                                 marker={'size': 4}))
    fig.update_layout(xaxis_title=xa.label, yaxis_title=ya.label, height=380,
                      margin={'l': 60, 'r': 10, 't': 30, 'b': 50},
                      title={'text': f'{ya.channel} vs {xa.channel}', 'font': {'size': 13}},
                      legend={'font': {'size': 10}})
    return fig.to_html(full_html=False, include_plotlyjs=False)


def _plotly_js() -> str:
    from plotly.offline import get_plotlyjs

    return get_plotlyjs()


def _vehicle_test_plots():
    """Return the channel pairs of a vehicle log and its replays (event vehicle_test)."""
    from vd_events.reports.report import DEG, Axis

    time = Axis('time', 'time [s]')
    return tuple((time, Axis(c, label, scale)) for c, label, scale in (
        ('yaw_rate', 'yaw rate [deg/s]', DEG),
        ('lateral_acceleration', 'lateral acceleration [m/s²]', 1.0),
        ('sideslip', 'sideslip angle [deg]', DEG), ('roll', 'roll angle [deg]', DEG),
        ('steering_wheel_angle', 'steering-wheel angle [deg]', DEG),
        ('speed', 'speed [km/h]', 3.6)))


def _event_sections(runs) -> list[str]:
    from vd_events.reports.report import (
        KC_PLOTS,
        PLOTS,
        VEHICLE_PLOTS,
        _family,
        _generic_plots,
        _section,
    )

    groups: dict[tuple[str, str, str], list] = {}
    for run in runs:
        groups.setdefault((run.event, run.axle, _family(run.model)), []).append(run)
    out = []
    for (event, axle, family), members in groups.items():
        table = {'kc': KC_PLOTS, 'vehicle': VEHICLE_PLOTS}.get(family, PLOTS)
        plots = table.get(event, _vehicle_test_plots() if event == 'vehicle_test'
                          else _generic_plots(members[0]))
        figures = []
        for xa, ya in plots:
            usable = [r for r in members if xa.channel in r.channels and ya.channel in r.channels]
            if usable:
                figures.append(f"<div class='fig'>{_figure_html(xa, ya, usable)}</div>")
        section = _section(event, axle, family, members, [])
        head, _, rest = section.partition('</h2>')
        out.append(f"{head}</h2><div class='figs'>{''.join(figures)}</div>{rest}")
    return out


def _kc_table(runs) -> str:
    kc = [r for r in runs if r.model == 'kc']
    names = [m for m in KC_TABLE if any(m in r.metrics for r in kc)]
    if not kc or not names:
        return ''
    units = {m: next(r.metrics[m].unit for r in kc if m in r.metrics) for m in names}
    head = ''.join(f'<th>{html.escape(m)}<br><small>{html.escape(units[m])}</small></th>'
                   for m in names)
    rows = ''.join(
        f'<tr><td>{html.escape(r.configuration)}</td><td>{html.escape(r.axle)}</td>'
        f'<td>{html.escape(r.event)}</td><td>{html.escape(r.fidelity)}</td>' + ''.join(
            f"<td>{_fmt(r.metrics[m].value) if m in r.metrics else ''}</td>" for m in names)
        + '</tr>' for r in sorted(kc, key=lambda r: (r.axle, r.event, r.configuration)))
    return ('<h2>K&amp;C metrics</h2><div class="scroll"><table><tr><th>configuration</th>'
            f'<th>axle</th><th>event</th><th>fidelity</th>{head}</tr>{rows}</table></div>')


def _fmt(value: float) -> str:
    return '–' if not math.isfinite(value) else f'{value:.4g}'


def _pass_fail(runs) -> str:
    rows = []
    for r in runs:
        for name, metric in r.metrics.items():
            value = metric.value
            if 'passed' in name:
                verdict = 'PASS' if value >= 0.5 else 'FAIL'
                colour = '#c9e7c0' if verdict == 'PASS' else '#f4c7c3'
                rows.append(f'<tr><td>{html.escape(r.label)}</td><td>{html.escape(r.event)}</td>'
                            f'<td>{html.escape(name)}</td><td style="background:{colour}">'
                            f'{verdict}</td></tr>')
    if not rows:
        return ''
    return ('<h2>Pass / fail</h2><table><tr><th>run</th><th>event</th><th>criterion</th>'
            f"<th>verdict</th></tr>{''.join(rows)}</table>")


def _embed_images(section: str, out: Path) -> str:
    """Replace ``<img src="name.png">`` of files in ``out`` by data URIs (one file)."""
    import re

    def inline(match) -> str:
        path = out / html.unescape(match.group(1))
        if not path.is_file():
            return match.group(0)
        data = base64.b64encode(path.read_bytes()).decode('ascii')
        return f'<img src="data:image/png;base64,{data}"'

    return re.sub(r'<img src="([^"]+\.png)"', inline, section)


def _comparisons(bags: Sequence[Path], out: Path) -> tuple[list[str], list[str]]:
    from vd_events.measured.columns import InputError
    from vd_events.measured.compare import compare, load_outcomes, pair, sections

    outcomes = [o for bag in bags for o in load_outcomes(bag)]
    tests = [o for o in outcomes if o.model in ('rig', 'test')]
    sims = [o for o in outcomes if o.model not in ('rig', 'test')]
    comparisons, problems = [], []
    for sim, test in pair(sims, tests):
        try:
            comparisons.append(compare(sim, test))
        except InputError as err:
            problems.append(str(err))
    return [_embed_images(s, out) for s in sections(comparisons, out, 'study_compare')], problems


def _provenance(bags: Sequence[Path], out: Path) -> str:
    rows = []
    for bag in bags:
        meta = custom_data(bag)
        items = ''.join(f'<li><b>{html.escape(k)}</b>: {html.escape(v[:400])}</li>'
                        for k, v in sorted(meta.items()) if k != 'vd.column_map')
        rows.append(f'<tr><td>{html.escape(os.path.relpath(bag, out))}</td>'
                    f'<td><ul class="notes">{items}</ul></td></tr>')
    return ("<h2>Provenance</h2><p>Per bag, what produced it (the bag's metadata).</p>"
            f"<table><tr><th>bag</th><th>metadata</th></tr>{''.join(rows)}</table>")


CSS_EXTRA = """
.figs{display:flex;flex-wrap:wrap}.fig{width:49%;min-width:420px}
.plots img{max-width:48%}
"""


def build_study_report(bags: Sequence[Path], out: Path) -> Path:
    """Write ``out/study.html`` (module doc); return its path."""
    from vd_events.reports.report import (
        CSS,
        _capability_section,
        _overview,
        load_capability,
        load_runs,
    )
    from vd_solvers import __version__

    bags = [Path(b) for b in bags]
    for bag in bags:
        if not (bag / 'metadata.yaml').is_file():
            raise BagError(f'{bag}: not a finished rosbag2 bag (no metadata.yaml)')
    out.mkdir(parents=True, exist_ok=True)
    runs, status = load_runs(bags)
    tables = load_capability(bags)
    compare_sections, problems = _comparisons(bags, out)
    body = [
        f'<h1>vd study report</h1><p>{len(runs)} results from {len(bags)} bag(s); vd '
        f'{html.escape(__version__)}. Plots: drag to zoom, double-click to reset, hover for '
        'values, click a legend entry to hide its curve.</p>',
        '<h2>Configuration overview</h2>', _overview(status),
        *_event_sections(runs), _kc_table(runs),
        *(_capability_section(t) for t in tables), _pass_fail(runs),
    ]
    if compare_sections or problems:
        body.append('<h2>Simulation vs test</h2>')
        body += compare_sections
        body += [f'<p class="notes">not compared: {html.escape(p)}</p>' for p in problems]
    body.append(_provenance(bags, out))
    page = (f'<!DOCTYPE html><html><head><meta charset="utf-8"><title>vd study report</title>'
            f'<style>{CSS}{CSS_EXTRA}</style><script>{_plotly_js()}</script></head><body>'
            f"{''.join(body)}</body></html>")
    path = out / 'study.html'
    tmp = out / '.study.html.partial'
    tmp.write_text(page, encoding='utf-8')
    os.replace(tmp, path)
    return path


__all__ = ['build_study_report']
