# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Simulation vs test on a page: overlays, the error table and the verdict per comparison.

``vd compare`` and ``vd replay`` write ``compare.html`` with :func:`write_compare_page`;
the study report embeds the same sections (:func:`comparison_sections` with ``embed``).
The comparison itself is :mod:`vd_events.measured.compare`.
"""
from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

from vd_events.measured.columns import unit_factor
from vd_events.measured.compare import DISPLAY, Comparison, gradient_shown, shown
from vd_events.reports.figures import data_uri, new_figure, save_figure
from vd_events.reports.html import Image, Section, Table, write_page
from vd_events.reports.sections import verdict_cell

#: the notes of a measured result that say where it came from
PROVENANCE_NOTES = ('source', 'source_sha256', 'rig', 'logger', 'vehicle', 'date', 'column map')


def plot_comparison(c: Comparison, out: Path, prefix: str) -> list[str]:
    """PNG overlays of simulation and test per compared channel; returns the file names."""
    names = []
    ax_unit = c.test.channels[c.axis].unit
    xname, xscale = DISPLAY.get(ax_unit, (ax_unit, 1.0))
    for i, e in enumerate(c.errors):
        yname, yscale = DISPLAY.get(e.unit, (e.unit, 1.0))
        factor, offset = unit_factor(c.test.channels[e.channel].unit, e.unit)
        fig, ax = new_figure(figsize=(6.4, 4.0), dpi=100)
        ax.plot(c.test.channels[c.axis].values * xscale,
                (c.test.channels[e.channel].values * factor + offset) * yscale,
                '.', markersize=3, label=f'test: {c.test.configuration}')
        ax.plot(c.test_x * xscale, c.sim_x[e.channel] * yscale, '-',
                label=f'sim: {c.sim.configuration} ({c.sim.model})')
        name = f'{prefix}_{i}.png'
        save_figure(fig, ax, out / name, f'{c.axis} [{xname}]', f'{e.channel} [{yname}]',
                    f'{c.test.event}: {e.channel} ({e.verdict})')
        names.append(name)
    return names


def comparison_section(c: Comparison, images: Sequence[Image]) -> Section:
    """One simulation-vs-test section: overlays, the error table, the verdict."""
    rows = []
    for e in c.errors:
        tol = ', '.join(f"{k} {shown(v, e.unit) if k != 'gradient' else f'{100 * v:g} %'}"
                        for k, v in e.tolerance.items())
        failures = f" ({', '.join(e.failures)})" if e.failures else ''
        rows.append([e.channel, e.points, shown(e.rms, e.unit), shown(e.max, e.unit),
                     shown(e.bias, e.unit), shown(e.test_rms, e.unit),
                     gradient_shown(e.gradient_sim, e.gradient_unit),
                     gradient_shown(e.gradient_test, e.gradient_unit), tol,
                     verdict_cell(e.verdict + failures,
                                  {'PASS': True, 'FAIL': False}.get(e.verdict))])
    prov = [n for n in c.test.notes if n.split(':')[0] in PROVENANCE_NOTES]
    return Section(f'Simulation vs test — {c.label}: {c.verdict}', images=list(images),
                   tables=[Table(['channel', 'points', 'RMS error', 'max error',
                                  'bias (sim − test)', 'test RMS', 'gradient sim',
                                  'gradient test', 'tolerance', 'verdict'], rows)],
                   notes=[*c.notes, *prov, f'simulation: data hash {c.sim.data_hash}'])


def comparison_sections(comparisons: Sequence[Comparison], out: Path, prefix: str = 'compare',
                        embed: bool = False) -> list[Section]:
    """
    Return the sections of ``comparisons``; their PNGs go into ``out``.

    ``embed``: the figures as data URIs (a page that is one file).
    """
    out.mkdir(parents=True, exist_ok=True)
    sections = []
    for k, c in enumerate(comparisons):
        names = plot_comparison(c, out, f'{prefix}_{k}')
        images = [Image(data_uri(out / n) if embed else n, n) for n in names]
        sections.append(comparison_section(c, images))
    return sections


def write_compare_page(comparisons: Sequence[Comparison], out: Path,
                       bags: Sequence[Path]) -> Path:
    """Write ``out/compare.html`` (the verdicts first, then each comparison)."""
    summary = Section(tables=[Table(['comparison', 'verdict'], [
        [c.label, verdict_cell(c.verdict, {'PASS': True, 'FAIL': False}.get(c.verdict))]
        for c in comparisons])])
    return write_page(out / 'compare.html', 'Simulation vs test',
                      [summary, *comparison_sections(comparisons, out)],
                      intro=[f"Bags: {', '.join(str(b) for b in bags)}"])


__all__ = ['plot_comparison', 'comparison_section', 'comparison_sections', 'write_compare_page']
