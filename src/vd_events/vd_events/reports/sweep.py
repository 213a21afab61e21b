# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The files of a sweep: table (CSV, Parquet), sensitivity, main effects, Pareto front, HTML.

Every file is written atomically (``vd_data_server.files``), so a reader never sees a
half-written one. The CSV is complete on its own; the Parquet copy (same columns,
units in the column metadata) is written when pyarrow is installed.
"""
from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

import numpy as np

from vd_data_server.files import atomic_path, atomic_write
from vd_events.reports.figures import plt, save
from vd_events.reports.html import Cell, Section, Table, images, write_page
from vd_events.sweeps.sweep import (
    SweepResult,
    columns,
    first_order_indices,
    main_effects,
    pareto_front,
    src,
    table_csv,
)


def sensitivity(result: SweepResult) -> dict[str, Any]:
    """SRC and R^2 per response; first-order Sobol indices for a full factorial."""
    plan = result.plan
    x = np.array(result.points, dtype=float)
    out: dict[str, Any] = {}
    for k, response in enumerate(plan.responses):
        y = result.responses[:, k]
        coef, r2 = src(x, y)
        entry: dict[str, Any] = {'src': dict(zip([f.name for f in plan.factors],
                                                 map(_num, coef))), 'r2': _num(r2)}
        if plan.design == 'full_factorial':
            s1 = first_order_indices(x, y, [f.level_values() for f in plan.factors])
            entry['first_order'] = dict(zip([f.name for f in plan.factors], map(_num, s1)))
        out[response.name] = entry
    return out


def _num(v: float) -> float | None:
    return float(v) if math.isfinite(v) else None


def write_outputs(result: SweepResult, out: Path) -> dict[str, str]:
    """Write the table, its Parquet copy, the summary, the plots and the page of a sweep."""
    out.mkdir(parents=True, exist_ok=True)
    files: dict[str, str] = {}
    files['csv'] = str(atomic_write(out / 'table.csv', table_csv(result)))
    parquet = _write_parquet(result, out / 'table.parquet')
    if parquet:
        files['parquet'] = parquet
    sens = sensitivity(result)
    fronts = _fronts(result)
    plots = _plots(result, out, fronts)
    summary = {'plan': str(result.plan.path), 'design': result.plan.design,
               'points': len(result.points), 'computed': result.computed,
               'cached': result.cached, 'failed': sum(1 for e in result.errors if e),
               'sensitivity': sens,
               'pareto': {'responses': [n for n, _ in result.plan.pareto],
                          'points': [int(i) for i in fronts]} if result.plan.pareto else None}
    files['summary'] = str(atomic_write(out / 'summary.json', json.dumps(summary, indent=2)))
    files['report'] = str(_page(result, sens, fronts, plots, out / 'sweep.html'))
    return files


def _write_parquet(result: SweepResult, path: Path) -> str | None:
    try:
        import pyarrow as pa
        import pyarrow.parquet as pq
    except ImportError:  # optional: the CSV is complete on its own
        return None
    plan = result.plan
    fields = [pa.field('point', pa.int64())]
    arrays = [pa.array(range(len(result.points)), pa.int64())]
    for j, f in enumerate(plan.factors):
        fields.append(pa.field(f.name, pa.float64(), metadata={'unit': f.unit, 'kind': 'factor',
                                                               'key': f.key}))
        arrays.append(pa.array([p[j] for p in result.points], pa.float64()))
    for k, r in enumerate(plan.responses):
        fields.append(pa.field(r.name, pa.float64(), metadata={
            'unit': r.unit, 'kind': 'response', 'metric': r.metric, 'run': r.run.label}))
        arrays.append(pa.array([None if math.isnan(v) else float(v)
                                for v in result.responses[:, k]], pa.float64()))
    fields.append(pa.field('error', pa.string()))
    arrays.append(pa.array(result.errors, pa.string()))
    table = pa.Table.from_arrays(arrays, schema=pa.schema(fields, metadata={
        'vd.plan': str(plan.path), 'vd.design': plan.design,
        'vd.columns': json.dumps(columns(plan))}))
    with atomic_path(path) as tmp:
        pq.write_table(table, tmp)
    return str(path)


def _fronts(result: SweepResult) -> np.ndarray:
    plan = result.plan
    if not plan.pareto:
        return np.array([], dtype=int)
    names = [r.name for r in plan.responses]
    (a, sa), (b, sb) = plan.pareto
    return pareto_front(result.responses[:, names.index(a)], result.responses[:, names.index(b)],
                        (sa, sb))


def _plots(result: SweepResult, out: Path, fronts: np.ndarray) -> list[str]:
    plan = result.plan
    x = np.array(result.points, dtype=float)
    files = []
    nf, nr = len(plan.factors), len(plan.responses)
    fig, axes = plt.subplots(nr, nf, figsize=(3.2 * nf, 2.6 * nr), squeeze=False)
    for k, r in enumerate(plan.responses):
        for j, f in enumerate(plan.factors):
            ax = axes[k][j]
            y = result.responses[:, k]
            ax.plot(x[:, j], y, '.', color='0.6', ms=4)
            if plan.design == 'full_factorial':
                lv, means = main_effects(x[:, j], y, f.level_values())
                ax.plot(lv, means, 'o-', color='C0')
            ax.set_xlabel(f"{f.name}{f' [{f.unit}]' if f.unit else ''}")
            if j == 0:
                ax.set_ylabel(f"{r.name}{f' [{r.unit}]' if r.unit else ''}")
            if r.target is not None:
                ax.axhline(r.target.value, color='C3', lw=0.8)
    fig.suptitle(f'{plan.name}: main effects' if plan.design == 'full_factorial'
                 else f'{plan.name}: responses over each factor')
    save(fig, out / 'main_effects.png', dpi=90)
    files.append('main_effects.png')
    if plan.pareto:
        names = [r.name for r in plan.responses]
        (a, sa), (b, sb) = plan.pareto
        ya, yb = result.responses[:, names.index(a)], result.responses[:, names.index(b)]
        ra, rb = plan.responses[names.index(a)], plan.responses[names.index(b)]
        fig, ax = plt.subplots(figsize=(5, 4))
        ax.plot(ya, yb, '.', color='0.6', label='points')
        ax.plot(ya[fronts], yb[fronts], 'o-', color='C3', label='Pareto front')
        ax.set_xlabel(f'{a} [{ra.unit}] ({sa})')
        ax.set_ylabel(f'{b} [{rb.unit}] ({sb})')
        ax.legend()
        save(fig, out / 'pareto.png', dpi=90)
        files.append('pareto.png')
    return files


def _page(result: SweepResult, sens: dict, fronts: np.ndarray, plots: list[str],
          path: Path) -> Path:
    plan = result.plan
    factors = [f.name for f in plan.factors]
    full = plan.design == 'full_factorial'
    sens_rows = [[name, *(entry['src'][f] for f in factors), entry['r2'],
                  *((entry['first_order'][f] for f in factors) if 'first_order' in entry
                    else ())] for name, entry in sens.items()]
    failed = sum(1 for e in result.errors if e)
    body = [Section('Sensitivity', paragraphs=[
        'Standardised regression coefficients (SRC) of each response on the factors, R² of '
        'the linear fit' + ('; first-order Sobol indices S1 of the full factorial (ANOVA)'
                            if full else '') + '.'],
        tables=[Table(['response', *(f'SRC {f}' for f in factors), 'R²',
                       *((f'S1 {f}' for f in factors) if full else ())], sens_rows)],
        images=images(plots))]
    if plan.pareto:
        body.append(Section('Pareto front', paragraphs=[
            'points ' + ', '.join(str(int(i)) for i in fronts)]))
    rows = [[i, *(float(v) for v in p), *(float(v) for v in result.responses[i]),
             result.errors[i]] for i, p in enumerate(result.points)]
    body.append(Section('Table', tables=[Table(columns(plan), rows)]))
    intro = [plan.description] if plan.description else []
    intro.append(f'master {plan.master}, configuration {plan.configuration}, design '
                 f'{plan.design}, {len(result.points)} points x {len(plan.runs)} runs; '
                 f'{result.computed} runs computed, {result.cached} taken from earlier '
                 f'results; {failed} points failed. Table: table.csv')
    body.insert(0, Section(tables=[Table(['table'], [[Cell('table.csv', href='table.csv')]])]))
    return write_page(path, f'Sweep {plan.name}', body, intro=intro)


__all__ = ['write_outputs', 'sensitivity']
