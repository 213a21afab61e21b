# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The page of ``vd identify``: fitted values, their errors and correlations, before/after.

``identify.html``: the parameters (start, fitted, standard error, bounds), the
identifiability (rank, condition, the pairs not identifiable apart) and the correlation
matrix; the RMS error of every channel before and after on the identification and the
validation logs; the ISO correlation verdicts of both sets before and after, with the
band plots of the validation set after the fit. The identification is
:mod:`vd_events.measured.identify`.
"""
from __future__ import annotations

from pathlib import Path

from vd_events.measured.compare import shown
from vd_events.measured.identify import Identification
from vd_events.measured.replay import UNITS
from vd_events.reports.correlate import write_correlate_page
from vd_events.reports.html import Section, Table, write_page
from vd_events.reports.sections import verdict_cell
from vd_events.sweeps.plan import format_number


def _value(value: float, unit: str) -> str:
    return f'{float(value):.5g} {unit}'.strip()


def write_identify_page(result: Identification, out: Path) -> Path:
    """Write ``out/identify.html`` (and the validation's correlate page); return the page."""
    out.mkdir(parents=True, exist_ok=True)
    plan = result.plan
    params = Section('Parameters', tables=[Table(
        ['parameter', 'key', 'start', 'fitted', 'standard error', 'bounds'],
        [[f.name, f.key, _value(s, f.unit), _value(v, f.unit),
          '–' if e != e else _value(e, f.unit),
          f'{format_number(f.low)} .. {format_number(f.high)} {f.unit}'.strip()]
         for f, s, v, e in zip(plan.parameters, result.start, result.fitted,
                               result.standard_errors)])],
        paragraphs=[f'Model {plan.model} of {plan.configuration}; {result.points} residuals, '
                    f'residual sigma {result.sigma:.3g} (in units of the channel scales); '
                    f'cost {result.cost_start:.4g} -> {result.cost_fitted:.4g}; '
                    f'{result.evaluations} model evaluations in {result.seconds:.1f} s '
                    f'({result.message}).'])
    names = [f.name for f in plan.parameters]
    ident = Section('Identifiability', paragraphs=[
        f'Rank {result.rank} of {len(names)}, condition number {result.condition:.3g}; '
        + ('every parameter identifiable.' if result.identifiable else
           'NOT every parameter is identifiable from these logs: '
           + '; '.join(f'{a} and {b} move together (correlation {c:+.3f}): the logs fix a '
                       'combination of the two, not each' for a, b, c in result.pairs)
           + ('.' if result.pairs else '.'))],
        tables=[Table(['', *names], [[n, *(f'{v:+.3f}' for v in row)]
                                     for n, row in zip(names, result.correlation)],
                      caption='correlation of the fitted values')])
    rms_rows = []
    for which, per_log in result.rms.items():
        logs = result.logs if which == 'identification' else result.validation
        for (path, _), channels in zip(logs, per_log):
            for channel, (before, after) in channels.items():
                unit = UNITS.get(channel, '')
                rms_rows.append([which, path.name, channel, shown(before, unit),
                                 shown(after, unit)])
    rms = Section('RMS error, before and after', tables=[Table(
        ['set', 'log', 'channel', 'before', 'after'], rms_rows)])
    verdicts = Section('Correlation (ISO method), before and after', tables=[Table(
        ['set and fit', 'method', 'manoeuvre', 'verdict'],
        [[key, c.method.title, m.label, verdict_cell(m.verdict_text, m.verdict == 'PASS')]
         for key, c in result.correlations.items() for m in c.manoeuvres])],
        notes=result.notes)
    sections = [params, ident, rms, verdicts]
    shown_after = result.correlations.get('validation after') or \
        result.correlations.get('identification after')
    if shown_after is not None:
        page = write_correlate_page(shown_after, out / 'correlation')
        verdicts.paragraphs.append(f'Band plots after the fit: correlation/{page.name}')
    provenance = Section('Provenance', notes=[
        f'plan: {plan.path}', *(f'log: {p} (sha256 {o.data_hash})' for p, o in result.logs),
        *(f'validation log: {p} (sha256 {o.data_hash})' for p, o in result.validation),
        f'written: configuration {result.configuration} in {result.master}'
        if result.master else 'not written'])
    sections.append(provenance)
    return write_page(out / 'identify.html', f'vd identify {plan.name}', sections,
                      intro=[plan.description] if plan.description else [])


__all__ = ['write_identify_page']
