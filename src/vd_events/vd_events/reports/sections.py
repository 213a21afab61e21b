# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The sections the report pages share, as data (``reports.html.Section``).

The configuration overview with the master file's feedback (the thesis' overview tab,
§2.3), an event's metric table with its understeer budgets, the K&C metric table, the
rigid-vs-flexible capability tables (thesis Tables 5.2.1/5.2.2), pass/fail criteria
and provenance. ``report.py`` and ``study.py`` compose their pages from these.
"""
from __future__ import annotations

from collections.abc import Sequence
import os
from pathlib import Path
from typing import Any

from vd_events.bags.bag import custom_data
from vd_events.reports.display import HEADLINE_NAMES, display
from vd_events.reports.html import Cell, Section, Table
from vd_events.reports.runs import Run, shown, shown_unit
from vd_events.studies.capability import QUANTITIES
from vd_events.studies.capability import Table as CapabilityTable
from vd_solvers.analytical.budget import TERMS as BUDGET_TERMS

#: K&C metrics of the K&C table, in this order, where a run has them
KC_TABLE = ('bump_steer', 'camber_gain', 'wheel_rate', 'ride_rate', 'track_change',
            'roll_centre_height_kinematic', 'roll_stiffness', 'roll_steer', 'roll_camber',
            'lateral_compliance_steer', 'lateral_compliance_camber', 'lateral_stiffness',
            'longitudinal_compliance', 'anti_dive', 'anti_squat',
            'aligning_torque_compliance_steer', 'steering_ratio', 'ackermann')


def verdict_cell(text: str, good: bool | None) -> Cell:
    """Return a verdict cell coloured as the thesis' tables: green good, red not, grey unknown."""
    return Cell(text, cls='na' if good is None else 'ok' if good else 'bad')


def overview(status: Any) -> Section:
    """Return the configuration x input group overview of a DataStatus (UNCHANGED/MODIFIED...)."""
    section = Section('Configuration overview', paragraphs=[
        'Green: the data fed to the models is the shared data file unchanged; red: the master '
        'file modifies it (hover for the values). Last column: whether all configurations use '
        'the same data.'])
    if status is None:
        section.paragraphs.append('No data status recorded.')
        return section
    configs = list(status.configurations)
    cells = {(s.configuration, s.group): s for s in status.status}
    rows = []
    for group in status.groups:
        row: list[Any] = [Cell(group, header=True)]
        consistency = 'SAME'
        for c in configs:
            s = cells.get((c, group))
            if s is None or not s.variant:
                row.append(Cell('–', cls='unused'))
                continue
            modified = s.state == s.MODIFIED
            consistency = 'DIFFERS' if s.consistency == s.DIFFERS else 'SAME'
            row.append(Cell(f"{s.variant} {'MODIFIED' if modified else 'UNCHANGED'}",
                            cls='mod' if modified else 'unch',
                            title='; '.join(f'{k.key}: {k.data_value} → {k.master_value} '
                                            f'{k.unit}' for k in s.modified_keys)))
        row.append(Cell(consistency, cls=consistency.lower()))
        rows.append(row)
    section.paragraphs.append(f'Master file: {status.master_file}')
    section.tables.append(Table(['input group', *configs, 'all configurations'], rows))
    modified = [[s.configuration, s.group, k.key, k.data_value, Cell(k.master_value, cls='mod'),
                 k.unit] for s in status.status for k in s.modified_keys]
    if modified:
        section.tables.append(Table(['configuration', 'group', 'key', 'data file', 'master',
                                     'unit'], modified, caption='Modified values'))
    return section


def metric_table(runs: Sequence[Run]) -> Table:
    """Every metric of ``runs`` in its display unit, the headline metrics first."""
    names = [m for m in HEADLINE_NAMES if any(m in r.metrics for r in runs)]
    names += sorted({m for r in runs for m in r.metrics} - set(names))
    head = ['run', *(Cell(n, small=shown_unit(runs, n)) for n in names)]
    rows = [[r.label, *(shown(r, n) if n in r.metrics else '' for n in names)] for r in runs]
    return Table(head, rows)


def budget(run: Run) -> Section | None:
    """Return the understeer-gradient budget of a run (Gillespie ch. 6): term, value, source."""
    names = [f'understeer_budget_{t}' for t in BUDGET_TERMS]
    if not all(n in run.metrics for n in names):
        return None
    rows: list[list[Any]] = [[t.replace('_', ' '), f'{shown(run, n):.3f}',
                              Cell(run.metrics[n].source, small='')]
                             for t, n in zip(BUDGET_TERMS, names)]
    if 'understeer_budget_total' in run.metrics:
        rows.append([Cell('total', header=True),
                     Cell(f"{shown(run, 'understeer_budget_total'):.3f}", header=True), ''])
    return Section(f'Understeer budget — {run.label}', level=3, tables=[
        Table(['term', shown_unit([run], names[0]), 'source'], rows, cls='budget')])


def event_section(event: str, axle: str, family: str, runs: Sequence[Run]) -> Section:
    """Return an event's section without its figures: the metric table, budgets and notes."""
    title = f"{event}{' — ' + axle if axle else ''} ({family})"
    return Section(title, tables=[metric_table(runs)],
                   subsections=[b for b in (budget(r) for r in runs) if b is not None],
                   notes=[f'{r.label}: {r.notes[0]}' for r in runs if r.notes])


def kc_table(runs: Sequence[Run]) -> Section | None:
    """Return the K&C metrics of every K&C run side by side (axle, event, fidelity)."""
    kc = [r for r in runs if r.model == 'kc']
    names = [m for m in KC_TABLE if any(m in r.metrics for r in kc)]
    if not kc or not names:
        return None
    head = ['configuration', 'axle', 'event', 'fidelity',
            *(Cell(m, small=shown_unit(kc, m)) for m in names)]
    rows = [[r.configuration, r.axle, r.event, r.fidelity,
             *(shown(r, m) if m in r.metrics else '' for m in names)]
            for r in sorted(kc, key=lambda r: (r.axle, r.event, r.configuration))]
    return Section('K&C metrics', tables=[Table(head, rows)])


def capability_rows(table: CapabilityTable) -> list[list[str]]:
    """Rows (event, then one 'verdict (worst difference unit)' per quantity), as text."""
    rows = []
    for event in dict.fromkeys(c.event for c in table.cells):
        row = [event]
        for quantity in QUANTITIES:
            cell = next(c for c in table.cells if c.event == event and c.quantity == quantity)
            value, unit = display(cell.max_difference, cell.unit, quantity)
            row.append(f'{cell.label} ({value:.3g} {unit})')
        rows.append(row)
    return rows


def capability(table: CapabilityTable) -> Section:
    """Return the table coloured as the thesis' Tables 5.2.1/5.2.2, worst difference per cell."""
    rows = [[row[0], *(verdict_cell(c, not c.startswith('Flexible')) for c in row[1:])]
            for row in capability_rows(table)]
    metric_rows = [[c.event, c.quantity, c.rigid_value, c.flexible_value, c.unit,
                    verdict_cell(c.verdict, c.verdict != 'Flexible')] for c in table.metrics]
    offsets = '; '.join(
        '{} {} {:.3g} {}'.format(c.event, c.quantity,
                                 *display(c.design_offset, c.unit, c.quantity))
        for c in table.cells if c.quantity == 'wheel_load' and abs(c.design_offset) > 0.0)
    return Section(
        f'Analytical capability: {table.configuration}, {table.axle} axle',
        paragraphs=[f"Rigid vs flexible K&C (flexible: {', '.join(table.components)}; data "
                    f'hash {table.data_hash}). Green: the rigid model is good enough; red: the '
                    f"flexible model is needed; worst difference in brackets. "
                    f"{' '.join(table.notes)}"],
        tables=[Table(['event', *QUANTITIES], rows),
                Table(['event', 'metric', 'rigid', 'flexible', 'unit', 'verdict'], metric_rows,
                      caption='Wheel-load offset at design (flexible − rigid: FE vs user-given '
                      f"masses, thesis 5.1): {offsets or 'none'}", level=4)])


def pass_fail(runs: Sequence[Run]) -> Section | None:
    """Return every pass/fail criterion of the runs (metrics ``*passed*``: 1 pass, 0 fail)."""
    rows = [[r.label, r.event, name, verdict_cell('PASS' if m.value >= 0.5 else 'FAIL',
                                                   m.value >= 0.5)]
            for r in runs for name, m in r.metrics.items() if 'passed' in name]
    if not rows:
        return None
    return Section('Pass / fail', tables=[Table(['run', 'event', 'criterion', 'verdict'], rows)])


def run_provenance(runs: Sequence[Run], out: Path) -> Section:
    """Return, per result, its bag, event, configuration, model, data hash and modified values."""
    rows = [[os.path.relpath(r.bag, out), r.event, r.configuration, r.model, r.data_hash,
             '; '.join(r.modified) or '–'] for r in runs]
    return Section('Provenance', tables=[Table(
        ['bag', 'event', 'configuration', 'model', 'data hash', 'modified values'], rows)])


def bag_provenance(bags: Sequence[Path], out: Path) -> Section:
    """Return, per bag, what produced it (the bag's metadata)."""
    rows = []
    for bag in bags:
        meta = custom_data(bag)
        rows.append([os.path.relpath(bag, out), '; '.join(
            f'{k}: {v[:400]}' for k, v in sorted(meta.items()) if k != 'vd.column_map')])
    return Section('Provenance', paragraphs=["Per bag, what produced it (the bag's metadata)."],
                   tables=[Table(['bag', 'metadata'], rows)])


__all__ = ['overview', 'metric_table', 'budget', 'event_section', 'kc_table',
           'capability_rows', 'capability', 'pass_fail', 'run_provenance', 'bag_provenance',
           'verdict_cell', 'KC_TABLE']
