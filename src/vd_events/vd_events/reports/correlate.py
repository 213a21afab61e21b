# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The page of ``vd correlate``: the verdict table, then per manoeuvre its band plots.

``correlate.html``: the verdict per manoeuvre and channel (forced verdicts say so), the
band file (name, version, each width with its source), and per manoeuvre and channel a
figure of the simulation, its tolerance band and every test run overlaid, the points
outside the band marked. The correlation is :mod:`vd_events.measured.correlate`.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from vd_events.measured.compare import DISPLAY, shown
from vd_events.measured.correlate import Correlation, Manoeuvre
from vd_events.reports.figures import LINE_STYLES, new_figure, save_figure
from vd_events.reports.html import Image, Section, Table, write_page
from vd_events.reports.sections import verdict_cell

#: the abscissa of each method, as the figure labels it (SI)
ABSCISSA = {'time': 'time [s]', 'lateral_acceleration': 'lateral acceleration [m/s²]'}


def _figure(m: Manoeuvre, channel: str, abscissa: str, out: Path, name: str) -> str:
    bands = [c for c in m.channels if c.channel == channel]
    unit_name = DISPLAY.get(bands[0].unit, (bands[0].unit, 1.0))[0]
    fig, ax = new_figure()
    xlabel = ABSCISSA[abscissa]
    for k, c in enumerate(bands):
        order = np.argsort(c.x, kind='stable')
        x = c.x[order]
        scale = DISPLAY.get(c.unit, (c.unit, 1.0))[1]
        ax.fill_between(x, c.low[order] * scale, c.high[order] * scale, color='0.85',
                        label='band' if k == 0 else None, step=None)
        ax.plot(x, c.sim[order] * scale, color='k', linewidth=1.0,
                label='simulation' if k == 0 else None)
        style = LINE_STYLES[k % len(LINE_STYLES)]
        marker = '.' if abscissa != 'time' else None
        ax.plot(x, c.test[order] * scale, linestyle=style if marker is None else 'none',
                marker=marker, linewidth=1.0, label=f'{c.run} ({100 * c.fraction:.0f} % in)')
        outside = ~c.inside
        if np.any(outside):
            ax.plot(c.x[outside], c.test[outside] * scale, 'x', color='tab:red',
                    markersize=4, label='outside' if k == 0 else None)
    save_figure(fig, ax, out / name, xlabel, f'{channel.replace("_", " ")} [{unit_name}]',
                f'{m.label}: {channel}', legend='x-small')
    return name


def write_correlate_page(result: Correlation, out: Path) -> Path:
    """Write ``out/correlate.html`` and its figures; return the page."""
    out.mkdir(parents=True, exist_ok=True)
    spec = result.method
    channels = list(dict.fromkeys(c.channel for m in result.manoeuvres for c in m.channels))
    rows = []
    for m in result.manoeuvres:
        per = m.channel_verdicts()
        rows.append([m.label, len(m.runs), ', '.join(m.simulations),
                     *(verdict_cell(per[ch], per[ch] == 'PASS') if ch in per else '–'
                       for ch in channels),
                     verdict_cell(m.verdict_text, m.verdict == 'PASS')])
    summary = Section(f'{spec.title}: {result.verdict}', tables=[Table(
        ['manoeuvre', 'test runs', 'simulation', *channels, 'verdict'], rows)])
    band_rows = [[b.channel, shown(b.absolute, b.unit), f'{100 * b.relative:g} %',
                  f'{b.shift:g} {"s" if spec.abscissa == "time" else "m/s²"}', b.source]
                 for b in spec.channels.values()]
    bands = Section(f'Bands: {result.bands.name} (version {result.bands.version})',
                    paragraphs=[f'File: {result.bands.path}. At each point the band is the '
                                'simulation over ± shift, widened by absolute + relative × '
                                'scale (|simulation| on a steady-state abscissa, its peak in '
                                f'a transient window). Every test point must be inside '
                                f'({100 * spec.inside:g} % required); at least '
                                f'{spec.min_runs} test runs per manoeuvre.'],
                    tables=[Table(['channel', 'absolute', 'relative', 'shift', 'source'],
                                  band_rows)],
                    notes=[f'{k.replace("_", " ")}: {v}' for k, v in spec.sources.items()])
    sections = [summary, bands]
    for i, m in enumerate(result.manoeuvres):
        images = []
        for j, channel in enumerate(dict.fromkeys(c.channel for c in m.channels)):
            name = _figure(m, channel, spec.abscissa, out, f'correlate_{i}_{j}.png')
            images.append(Image(name, name))
        table = Table(['channel', 'test run', 'points', 'inside', 'largest excess', 'verdict'],
                      [[c.channel, c.run, c.test.size, f'{100 * c.fraction:.1f} %',
                        shown(c.excess, c.unit), verdict_cell(c.verdict, c.verdict == 'PASS')]
                       for c in m.channels])
        sections.append(Section(f'{m.label}: {m.verdict_text}', images=images, tables=[table],
                                notes=m.notes))
    return write_page(out / 'correlate.html', 'vd correlate', sections,
                      intro=[f'{spec.title}: {len(result.manoeuvres)} manoeuvre(s), the '
                             'simulation with its tolerance band and the test runs '
                             'overlaid.'])


__all__ = ['write_correlate_page']
