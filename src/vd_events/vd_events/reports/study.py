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
   against each simulation of its event and axle in the same bags
   (:mod:`vd_events.measured.compare`, drawn by :mod:`.compare`);
7. provenance: per bag, its metadata (data hash, variants, modified keys, model,
   software version, source files and their hashes for measurements).

The interactive plots use plotly (plotly.js inlined once, so the file opens offline and
can be sent as it is); the comparison PNGs are embedded as data URIs.
"""
from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import markupsafe
import plotly.graph_objects as go
from plotly.offline import get_plotlyjs

from vd_events.errors import InputError
from vd_events.measured.compare import compare, load_outcomes, pair
from vd_events.reports import sections
from vd_events.reports.compare import comparison_sections
from vd_events.reports.figures import data_uri
from vd_events.reports.grade import with_grades
from vd_events.reports.html import Image, Section, write_page
from vd_events.reports.runs import (
    Axis,
    Run,
    check_bags,
    curve,
    groups,
    load_capability,
    load_runs,
    plots_for,
)
from vd_events.reports.sine_with_dwell import sine_with_dwell_section
from vd_solvers import __version__

#: the models of measured results (drawn as markers, compared with the simulations)
MEASURED = ('rig', 'test')


def _figure(xa: Axis, ya: Axis, runs: Sequence[Run]) -> markupsafe.Markup:
    """One interactive overlay (plotly) of ``ya`` over ``xa`` for ``runs``."""
    fig = go.Figure()
    for run in runs:
        x, y = curve(run, xa, ya)
        fig.add_trace(go.Scatter(x=x, y=y, name=run.label,
                                 mode='markers' if run.model in MEASURED else 'lines',
                                 marker={'size': 4}))
    fig.update_layout(xaxis_title=xa.label, yaxis_title=ya.label, height=380,
                      margin={'l': 60, 'r': 10, 't': 30, 'b': 50},
                      title={'text': f'{ya.channel} vs {xa.channel}', 'font': {'size': 13}},
                      legend={'font': {'size': 10}})
    return markupsafe.Markup(fig.to_html(full_html=False, include_plotlyjs=False))


def _event_sections(runs: Sequence[Run], folder: Path) -> list[Section]:
    out = []
    for (event, axle, family), members in groups(runs).items():
        if event == 'sine_with_dwell':
            sis = [r for r in runs if r.event == 'slowly_increasing_steer' and r.model == 'test']
            section = sine_with_dwell_section(members, folder, family, sis)
            section.images = [Image(data_uri(folder / i.src), i.alt) for i in section.images]
            out.append(section)
            continue
        section = sections.event_section(event, axle, family, members)
        section.figures = [_figure(xa, ya, usable)
                           for xa, ya, usable in plots_for(event, family, members)]
        out.append(section)
    return out


def _comparisons(bags: Sequence[Path], out: Path) -> Section | None:
    outcomes = [o for bag in bags for o in load_outcomes(bag)]
    tests = [o for o in outcomes if o.model in MEASURED]
    sims = [o for o in outcomes if o.model not in MEASURED]
    comparisons, problems = [], []
    for sim, test in pair(sims, tests):
        try:
            comparisons.append(compare(sim, test))
        except InputError as err:
            problems.append(str(err))
    if not comparisons and not problems:
        return None
    return Section('Simulation vs test',
                   subsections=comparison_sections(comparisons, out, 'study_compare',
                                                   embed=True),
                   notes=[f'not compared: {p}' for p in problems])


def build_study_report(bags: Sequence[Path], out: Path) -> Path:
    """Write ``out/study.html`` (module doc); return its path."""
    bags = [Path(b) for b in bags]
    check_bags(bags)
    out.mkdir(parents=True, exist_ok=True)
    runs, status = load_runs(bags)
    runs = with_grades(runs)
    body = [sections.overview(status), *_event_sections(runs, out), sections.kc_table(runs),
            *(sections.capability(t) for t in load_capability(bags)),
            sections.pass_fail(runs), _comparisons(bags, out),
            sections.bag_provenance(bags, out)]
    return write_page(out / 'study.html', 'vd study report',
                      [s for s in body if s is not None], script=get_plotlyjs(), intro=[
                          f'{len(runs)} results from {len(bags)} bag(s); vd {__version__}. '
                          'Plots: drag to zoom, double-click to reset, hover for values, '
                          'click a legend entry to hide its curve.'])


__all__ = ['build_study_report']
