# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""``vd import`` and ``vd compare`` (ARCHITECTURE §5): measured data and simulation vs test."""
from __future__ import annotations

import argparse
from collections.abc import Sequence
import json
from pathlib import Path

from vd_events.cli.parsers import XLSX
from vd_events.cli.workbench import import_xlsx
from vd_events.errors import InputError, UsageError
from vd_events.measured.compare import (
    Comparison,
    compare_bags,
    gradient_shown,
    load_tolerances,
    shown,
)
from vd_events.measured.importer import ImportOptions, import_files
from vd_events.measured.replay import replay_bag
from vd_events.reports.compare import write_compare_page


def cmd_import(args: argparse.Namespace) -> int:
    """
    ``vd import FILE... --bag DIR`` (measured data), or ``vd import xlsx WORKBOOK --out MASTER``.

    The two forms share the verb (ARCHITECTURE §5); the first FILE says which it is.
    """
    if args.files[0] == XLSX:
        if len(args.files) != 2 or not args.out or args.bag or args.map or \
                import_options(args) != ImportOptions():
            raise UsageError('vd import xlsx takes one workbook and --out MASTER (no --bag or '
                             '--map): vd import xlsx WORKBOOK --out MASTER')
        return import_xlsx(Path(args.files[1]), Path(args.out))
    if not args.bag or args.out:
        raise UsageError('vd import of measured data takes --bag DIR (and no --out): vd import '
                         'FILE... [--map COLUMNS.yaml] --bag DIR; a master workbook: vd import '
                         'xlsx WORKBOOK --out MASTER')
    options = import_options(args)
    path, outcomes = import_files([Path(f) for f in args.files],
                                  Path(args.map) if args.map else None, Path(args.bag), options)
    if args.json:
        print(json.dumps({'bag': str(path), 'results': [
            {'event': o.event, 'model': o.model, 'axle': o.axle, 'configuration': o.configuration,
             'source_sha256': o.data_hash, 'channels': sorted(o.channels),
             'samples': o.n_steps} for o in outcomes]}))
    else:
        for o in outcomes:
            print(f'  {o.event:24s} {o.model:5s} {o.axle or "-":6s} {o.n_steps:6d} samples, '
                  f"channels: {', '.join(sorted(o.channels))}")
            for note in checked_notes(o.notes):
                print(f'    {note}')
        print(f'bag: {path}')
    return 0


#: the notes of an import that say what the checks found and chose
CHECK_NOTES = ('sample rate', 'gap:', 'glitch', 'window:', 'sign check', 'yaw_rate',
               'lateral_acceleration', 'speed <-', 'roll <-', 'longitudinal_acceleration <-',
               'steering_wheel_angle <-', 'sideslip <-', '[channel units]',
               'no [channel units]')


def checked_notes(notes) -> list[str]:
    """Return the notes of an imported log that a test engineer reads at the terminal."""
    return [n for n in notes if n.startswith(CHECK_NOTES)]


def import_options(args: argparse.Namespace) -> ImportOptions:
    """Return the log-reading options of ``vd import`` and ``vd grade`` (InputError names one)."""
    position = None
    if args.imu_position:
        try:
            values = [float(p) for p in args.imu_position.split(',')]
        except ValueError:
            values = []
        if len(values) != 3:
            raise InputError('--imu-position', f'X,Y,Z in m (three numbers), found '
                             f'{args.imu_position!r}')
        position = (values[0], values[1], values[2])
    return ImportOptions(repair=tuple(args.repair), yaw_sign=args.yaw_sign, start=args.start,
                         end=args.end, window=args.window, imu_position=position,
                         event=args.event)


def cmd_compare(args: argparse.Namespace) -> int:
    tolerances = load_tolerances(Path(args.tolerances) if args.tolerances else None)
    sim_bag, test_bag = Path(args.sim_bag), Path(args.test_bag)
    comparisons = compare_bags(sim_bag, test_bag, tolerances)
    page = write_compare_page(comparisons, Path(args.out), [sim_bag, test_bag])
    if args.json:
        print(json.dumps({'report': str(page), 'comparisons': [c.to_json() for c in comparisons]}))
    else:
        print_comparisons(comparisons)
        print(f'report: {page}')
    return 0


def cmd_replay(args: argparse.Namespace) -> int:
    models = [m.strip() for m in args.models.split(',') if m.strip()]
    out = Path(args.out)
    result = replay_bag(Path(args.test_bag), models, args.config,
                        Path(args.master) if args.master else None,
                        Path(args.bag) if args.bag else out / 'replay')
    comparisons = result.pop('_comparisons')
    result['report'] = str(write_compare_page(comparisons, out, [Path(result['bag']),
                                                                 Path(args.test_bag)]))
    if args.json:
        print(json.dumps(result))
    else:
        print_comparisons(comparisons)
        print(f"bag:    {result['bag']}")
        print(f"report: {result['report']}")
    return 0


def print_comparisons(comparisons: Sequence[Comparison]) -> None:
    for c in comparisons:
        print(f'{c.label}: {c.verdict}')
        for e in c.errors:
            grad = ''
            if e.gradient_error is not None:
                grad = (f', gradient {gradient_shown(e.gradient_sim, e.gradient_unit)} vs '
                        f'{gradient_shown(e.gradient_test, e.gradient_unit)}')
            print(f'  {e.channel:28s} rms {shown(e.rms, e.unit):>14s}  max '
                  f'{shown(e.max, e.unit):>14s}  bias {shown(e.bias, e.unit):>14s}{grad}  '
                  f'{e.verdict}')


__all__ = ['cmd_import', 'cmd_compare', 'cmd_replay', 'import_options', 'checked_notes']
