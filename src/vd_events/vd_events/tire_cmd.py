# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
``vd tire FILE``: a .tir file's key data and characteristic curves, before it is used.

The file is read and checked as a run reads it (bad input: ``file: key: line N: message``,
exit 2); the key data of :func:`vd_solvers.tire.sheet.characteristics` are printed in
display units, and one PNG holds Fx(kappa), Fy(alpha) and Mz(alpha) swept over load,
inflation pressure and camber (:func:`vd_solvers.tire.sheet.sweeps`).
"""
from __future__ import annotations

import argparse
from collections.abc import Callable
import json
import math
from pathlib import Path

#: display unit and factor from SI per SI unit of the sheet
DISPLAY = {'m': ('mm', 1e3), 'N': ('N', 1.0), 'Pa': ('bar', 1e-5), 'N/m': ('N/mm', 1e-3),
           'N/rad': ('N/deg', math.pi / 180.0), 'rad': ('deg', 180.0 / math.pi), '': ('', 1.0)}


def add_subcommands(sub: argparse._SubParsersAction,
                    handlers: dict[str, Callable[[argparse.Namespace], int]]) -> None:
    tire = sub.add_parser('tire', help="a .tir file's key data and its Fx, Fy, Mz curves")
    tire.add_argument('file', help='TeimOrbit .tir property file (PAC2002, MF 5.2, 6.1, 6.2)')
    tire.add_argument('--out', default='out', help='folder of the PNG (default: out)')
    tire.add_argument('--side', choices=('LEFT', 'RIGHT'), help='evaluate the tire mounted '
                      'on this side (default: as measured, TYRESIDE)')
    tire.add_argument('--pressure', help='inflation pressure with its unit, e.g. "2.4 bar" '
                      "(default: the file's INFLPRES / IP)")
    tire.add_argument('--aligning-normalisation', choices=('mf-tyre', 'book'),
                      default='mf-tyre', help='load the trail and the Fx arm of Mz are '
                      'normalised by: FNOMIN (mf-tyre) or FNOMIN LFZO (book)')
    tire.add_argument('--json', action='store_true')
    handlers['tire'] = cmd_tire


def cmd_tire(args: argparse.Namespace) -> int:
    import dataclasses

    from vd_data_server.tir import read_tir
    from vd_solvers.tire.magic_formula import MagicFormula
    from vd_solvers.tire.sheet import characteristics, sweeps

    props = dataclasses.replace(read_tir(args.file),
                                aligning_normalisation=args.aligning_normalisation)
    mf = MagicFormula(props, side=args.side, pressure=_pressure(args.pressure, args.file))
    rows, warnings = characteristics(mf)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    png = out / f'{Path(args.file).stem}_curves.png'
    _plot(sweeps(mf), png, f'{Path(args.file).name} ({props.file_format})')
    if args.json:
        print(json.dumps({'file': args.file, 'format': props.file_format,
                          'data': [{'name': r.name, 'value': r.value, 'unit': r.unit}
                                   for r in rows],
                          'warnings': warnings, 'plot': str(png)}, indent=2))
        return 0
    print(f'{args.file}')
    width = max(len(r.name) for r in rows)
    for row in rows:
        print(f'  {row.name:<{width}}  {_shown(row.value, row.unit)}')
    for warning in warnings:
        print(f'warning: {warning}')
    print(f'curves: {png}')
    return 0


def _pressure(text: str | None, file: str) -> float | None:
    """Return the --pressure value in Pa (a pressure with its unit, as in master files)."""
    if text is None:
        return None
    from vd_data_server.units import parse_quantity, si_factor

    number, unit = parse_quantity(text, 'pressure', file=file, key='--pressure')
    return number * si_factor(unit, 'pressure')


def _shown(value: float | str, unit: str) -> str:
    if isinstance(value, str):
        return value
    if math.isnan(value):
        return '-'
    shown, factor = DISPLAY.get(unit, (unit, 1.0))
    return f'{value * factor:.4g} {shown}'.rstrip()


def _plot(swept, path: Path, title: str) -> None:
    import matplotlib

    matplotlib.use('Agg')
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(len(swept), 3, figsize=(13.0, 3.4 * len(swept)), dpi=100,
                             squeeze=False)
    for row, sweep in zip(axes, swept):
        for curve in sweep.curves:
            row[0].plot(curve.kappa, curve.fx / 1e3, label=curve.label)
            row[1].plot(curve.alpha * 180.0 / math.pi, curve.fy / 1e3, label=curve.label)
            row[2].plot(curve.alpha * 180.0 / math.pi, curve.mz, label=curve.label)
        for ax, (x, y) in zip(row, (('slip ratio kappa (-)', 'Fx (kN)'),
                                    ('slip angle alpha (deg)', 'Fy (kN)'),
                                    ('slip angle alpha (deg)', 'Mz (N m)'))):
            ax.set_xlabel(x)
            ax.set_ylabel(y)
            ax.grid(True, alpha=0.3)
            ax.legend(fontsize='small', title=sweep.title, title_fontsize='small')
    fig.suptitle(f'{title}: pure slip, TYDEX W axes (file convention)', fontsize='medium')
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)
