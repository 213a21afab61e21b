# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The files of a sweep: table (CSV, Parquet), sensitivity, main effects, Pareto front, HTML.

Every file is written under a temporary name and renamed, so a reader never sees a
half-written one. The CSV is complete on its own; the Parquet copy (same columns,
units in the column metadata) is written when pyarrow is installed.
"""
from __future__ import annotations

import html
import json
import math
import os
from pathlib import Path
from typing import Any

import numpy as np

from vd_events.sweeps.sweep import (
    SweepResult,
    columns,
    first_order_indices,
    main_effects,
    pareto_front,
    src,
    table_csv,
)


def _atomic(path: Path, data: bytes) -> None:
    tmp = path.with_name(f'.{path.name}.tmp')
    tmp.write_bytes(data)
    os.replace(tmp, path)


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
    out.mkdir(parents=True, exist_ok=True)
    files: dict[str, str] = {}
    _atomic(out / 'table.csv', table_csv(result).encode())
    files['csv'] = str(out / 'table.csv')
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
    _atomic(out / 'summary.json', json.dumps(summary, indent=2).encode())
    files['summary'] = str(out / 'summary.json')
    _atomic(out / 'sweep.html', _html(result, sens, fronts, plots).encode())
    files['report'] = str(out / 'sweep.html')
    return files


def _write_parquet(result: SweepResult, path: Path) -> str | None:
    try:
        import pyarrow as pa
        import pyarrow.parquet as pq
    except ImportError:
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
    tmp = path.with_name(f'.{path.name}.tmp')
    pq.write_table(table, tmp)
    os.replace(tmp, path)
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
    import matplotlib

    matplotlib.use('Agg')
    import matplotlib.pyplot as plt

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
    fig.tight_layout()
    _save(fig, out / 'main_effects.png')
    files.append('main_effects.png')
    plt.close(fig)
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
        fig.tight_layout()
        _save(fig, out / 'pareto.png')
        files.append('pareto.png')
        plt.close(fig)
    return files


def _save(fig, path: Path) -> None:
    tmp = path.with_name(f'.{path.stem}.tmp.png')
    fig.savefig(tmp, dpi=90)
    os.replace(tmp, path)


def _fmt(v: Any) -> str:
    if v is None or (isinstance(v, float) and math.isnan(v)):
        return '-'
    return f'{v:.4g}' if isinstance(v, float) else html.escape(str(v))


def _html(result: SweepResult, sens: dict, fronts: np.ndarray, plots: list[str]) -> str:
    plan = result.plan
    cols = columns(plan)
    rows = []
    for i, p in enumerate(result.points):
        cells = [str(i), *(_fmt(float(v)) for v in p), *(_fmt(float(v)) for v in
                                                        result.responses[i]),
                 html.escape(result.errors[i])]
        rows.append('<tr>' + ''.join(f'<td>{c}</td>' for c in cells) + '</tr>')
    sens_rows = []
    for name, entry in sens.items():
        cells = [name, *(_fmt(entry['src'][f.name]) for f in plan.factors), _fmt(entry['r2'])]
        if 'first_order' in entry:
            cells += [_fmt(entry['first_order'][f.name]) for f in plan.factors]
        sens_rows.append('<tr>' + ''.join(f'<td>{c}</td>' for c in cells) + '</tr>')
    s1_head = ''.join(f'<th>S1 {html.escape(f.name)}</th>' for f in plan.factors) \
        if plan.design == 'full_factorial' else ''
    failed = sum(1 for e in result.errors if e)
    parts = [
        f'<!doctype html><html><head><meta charset="utf-8"><title>sweep {html.escape(plan.name)}'
        '</title><style>body{font-family:sans-serif}table{border-collapse:collapse}'
        'td,th{border:1px solid #ccc;padding:2px 6px;text-align:right}</style></head><body>',
        f'<h1>Sweep {html.escape(plan.name)}</h1>',
        f'<p>{html.escape(plan.description)}</p>' if plan.description else '',
        f'<p>master {html.escape(str(plan.master))}, configuration '
        f'<b>{html.escape(plan.configuration)}</b>, design {plan.design}, {len(result.points)} '
        f'points x {len(plan.runs)} runs; {result.computed} runs computed, {result.cached} '
        f'taken from earlier results; {failed} points failed. Table: '
        '<a href="table.csv">table.csv</a></p>',
        '<h2>Sensitivity</h2><p>Standardised regression coefficients (SRC) of each response '
        'on the factors, R&sup2; of the linear fit'
        + ('; first-order Sobol indices S1 of the full factorial (ANOVA)'
           if plan.design == 'full_factorial' else '') + '.</p>',
        '<table><tr><th>response</th>'
        + ''.join(f'<th>SRC {html.escape(f.name)}</th>' for f in plan.factors)
        + f'<th>R&sup2;</th>{s1_head}</tr>' + ''.join(sens_rows) + '</table>',
        *(f'<p><img src="{p}" alt="{p}"></p>' for p in plots),
    ]
    if plan.pareto:
        parts.append('<h2>Pareto front</h2><p>points ' + ', '.join(str(int(i)) for i in fronts)
                     + '</p>')
    parts += ['<h2>Table</h2><table><tr>' + ''.join(f'<th>{html.escape(c)}</th>' for c in cols)
              + '</tr>' + ''.join(rows) + '</table></body></html>']
    return '\n'.join(parts)
