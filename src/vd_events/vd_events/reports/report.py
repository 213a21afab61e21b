# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
``vd report BAG...``: an HTML report with PNG plots from recorded bags.

Per event and model, one plot per channel pair with every configuration
overlaid (like the thesis' Figs. 4.1.1-4.1.2, 4.2.x-4.3.x and, for the full vehicle,
4.4.1-4.4.3), a metrics table, and the configuration overview with the
modified/unchanged feedback. The sections are those of :mod:`.sections`; the page is
``templates/page.html``.
"""
from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

from vd_events.errors import BagError
from vd_events.reports import sections
from vd_events.reports.figures import LINE_STYLES, new_figure, save_figure
from vd_events.reports.grade import with_grades
from vd_events.reports.html import Section, images, write_page
from vd_events.reports.runs import (
    Run,
    check_bags,
    curve,
    groups,
    load_capability,
    load_runs,
    plots_for,
)
from vd_events.reports.sine_with_dwell import sine_with_dwell_section
from vd_events.reports.study import build_study_report


def event_figures(event: str, axle: str, family: str, runs: Sequence[Run],
                  out: Path) -> list[str]:
    """Draw a group's plots (configurations overlaid) into ``out``; return the file names."""
    names = []
    for i, (xa, ya, usable) in enumerate(plots_for(event, family, runs)):
        fig, ax = new_figure()
        for k, run in enumerate(usable):
            x, y = curve(run, xa, ya)
            ax.plot(x, y, label=run.label, linestyle=LINE_STYLES[k % len(LINE_STYLES)],
                    marker='.' if len(x) < 30 else None)
        name = f"{event}{'_' + axle if axle else ''}_{family}_{i}.png"
        save_figure(fig, ax, out / name, xa.label, ya.label,
                    f"{event}{' ' + axle if axle else ''}: {ya.channel} vs {xa.channel}")
        names.append(name)
    return names


def build_report(bags: Sequence[Path], out: Path) -> Path:
    """Write ``out/report.html`` and its PNGs; returns the HTML path."""
    check_bags(bags)
    runs, status = load_runs(bags)
    runs = with_grades(runs)
    tables = load_capability(bags)
    if not runs and not tables:
        raise BagError('no event results in ' + ', '.join(str(b) for b in bags))
    out.mkdir(parents=True, exist_ok=True)
    body: list[Section] = [sections.overview(status)]
    body += [sections.capability(t) for t in tables]
    for (event, axle, family), members in groups(runs).items():
        if event == 'sine_with_dwell':
            sis = [r for r in runs if r.event == 'slowly_increasing_steer' and r.model == 'test']
            body.append(sine_with_dwell_section(members, out, family, sis))
            continue
        section = sections.event_section(event, axle, family, members)
        section.images = images(event_figures(event, axle, family, members, out))
        body.append(section)
    body.append(sections.run_provenance(runs, out))
    return write_page(out / 'report.html', 'vd report', body,
                      intro=[f'{len(runs)} results from {len(bags)} bag(s).'])


def build_pages(bags: Sequence[Path], out: Path) -> dict[str, str]:
    """Write both pages of a study (``report.html``, ``study.html``); return their paths."""
    return {'report': str(build_report(bags, out)),
            'study_report': str(build_study_report(bags, out))}


__all__ = ['build_report', 'build_pages', 'event_figures']
