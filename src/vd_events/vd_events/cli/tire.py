# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
``vd tire FILE``: a .tir file's key data and characteristic curves, before it is used.

The file is read and checked as a run reads it (bad input: ``file: key: line N: message``,
exit 2); the key data of :func:`vd_solvers.tire.sheet.characteristics` are printed in
display units, and one PNG holds Fx(kappa), Fy(alpha) and Mz(alpha) swept over load,
inflation pressure and camber (:func:`vd_solvers.tire.sheet.sweeps`,
drawn by :func:`vd_events.reports.tire.plot_tire_curves`).
"""
from __future__ import annotations

import argparse
import dataclasses
import json
import math
from pathlib import Path

from vd_data_server.tir import read_tir
from vd_data_server.units import parse_quantity, si_factor
from vd_events.reports.tire import plot_tire_curves
from vd_solvers.constants import DEG
from vd_solvers.tire.magic_formula import MagicFormula
from vd_solvers.tire.sheet import characteristics, sweeps

#: display unit and factor from SI per SI unit of the sheet
DISPLAY = {'m': ('mm', 1e3), 'N': ('N', 1.0), 'Pa': ('bar', 1e-5), 'N/m': ('N/mm', 1e-3),
           'N/rad': ('N/deg', DEG), 'rad': ('deg', 1.0 / DEG), '': ('', 1.0)}


def cmd_tire(args: argparse.Namespace) -> int:
    props = dataclasses.replace(read_tir(args.file),
                                aligning_normalisation=args.aligning_normalisation)
    mf = MagicFormula(props, side=args.side, pressure=_pressure(args.pressure, args.file))
    rows, warnings = characteristics(mf)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    png = out / f'{Path(args.file).stem}_curves.png'
    plot_tire_curves(sweeps(mf), png, f'{Path(args.file).name} ({props.file_format})')
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
    number, unit = parse_quantity(text, 'pressure', file=file, key='--pressure')
    return number * si_factor(unit, 'pressure')


def _shown(value: float | str, unit: str) -> str:
    if isinstance(value, str):
        return value
    if math.isnan(value):
        return '-'
    shown, factor = DISPLAY.get(unit, (unit, 1.0))
    return f'{value * factor:.4g} {shown}'.rstrip()


__all__ = ['cmd_tire']
