# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""``vd import`` and ``vd compare`` (ARCHITECTURE §5): measured data and simulation vs test."""
from __future__ import annotations

import argparse
from collections.abc import Callable
import json
from pathlib import Path


def add_subcommands(sub: argparse._SubParsersAction,
                    handlers: dict[str, Callable[[argparse.Namespace], int]]) -> None:
    imp = sub.add_parser('import', help='rig / vehicle-test data (CSV, VBOX .vbo) into a bag')
    imp.add_argument('files', nargs='+', metavar='FILE')
    imp.add_argument('--map', help='column map YAML (docs/testdata.md; needed for tables, '
                     'optional for .vbo)')
    imp.add_argument('--bag', required=True, help='bag directory to write (must not exist)')
    imp.add_argument('--json', action='store_true')
    handlers['import'] = cmd_import

    cmp = sub.add_parser('compare', help='simulation vs test: overlays, error metrics, verdicts')
    cmp.add_argument('sim_bag', metavar='SIM_BAG')
    cmp.add_argument('test_bag', metavar='TEST_BAG')
    cmp.add_argument('--out', default='out/compare', help='report folder')
    cmp.add_argument('--tolerances', help='tolerance YAML (channel: {rms, max, bias, '
                     'gradient}); default: docs/testdata.md')
    cmp.add_argument('--json', action='store_true')
    handlers['compare'] = cmd_compare

    rep = sub.add_parser('replay', help='drive the bicycle and full-vehicle models with the '
                         'steering and speed of a vehicle log and compare (open-loop '
                         'validation)')
    rep.add_argument('test_bag', metavar='TEST_BAG')
    rep.add_argument('--config', default=None, help='configuration (default: the first)')
    rep.add_argument('--master', help='master file (default: the bundled sample study)')
    rep.add_argument('--models', default='bicycle,vehicle', help='bicycle,vehicle')
    rep.add_argument('--bag', help='bag for the replayed runs (must not exist; default: '
                     '<out>/replay)')
    rep.add_argument('--out', default='out/replay', help='report folder')
    rep.add_argument('--json', action='store_true')
    handlers['replay'] = cmd_replay


def cmd_import(args: argparse.Namespace) -> int:
    from vd_events.measured.importer import import_files

    path, outcomes = import_files([Path(f) for f in args.files],
                                  Path(args.map) if args.map else None, Path(args.bag))
    if args.json:
        print(json.dumps({'bag': str(path), 'results': [
            {'event': o.event, 'model': o.model, 'axle': o.axle, 'configuration': o.configuration,
             'source_sha256': o.data_hash, 'channels': sorted(o.channels),
             'samples': o.n_steps} for o in outcomes]}))
    else:
        for o in outcomes:
            print(f'  {o.event:24s} {o.model:5s} {o.axle or "-":6s} {o.n_steps:6d} samples, '
                  f"channels: {', '.join(sorted(o.channels))}")
        print(f'bag: {path}')
    return 0


def cmd_compare(args: argparse.Namespace) -> int:
    from vd_events.measured.compare import compare_bags, load_tolerances, print_comparisons

    tolerances = load_tolerances(Path(args.tolerances) if args.tolerances else None)
    comparisons, page = compare_bags(Path(args.sim_bag), Path(args.test_bag), Path(args.out),
                                     tolerances)
    if args.json:
        print(json.dumps({'report': str(page), 'comparisons': [c.to_json() for c in comparisons]}))
    else:
        print_comparisons(comparisons)
        print(f'report: {page}')
    return 0


def cmd_replay(args: argparse.Namespace) -> int:
    from vd_events.measured.replay import replay_bag

    models = [m.strip() for m in args.models.split(',') if m.strip()]
    out = Path(args.out)
    result = replay_bag(Path(args.test_bag), models, args.config,
                        Path(args.master) if args.master else None,
                        Path(args.bag) if args.bag else out / 'replay', out)
    comparisons = result.pop('_comparisons')
    if args.json:
        print(json.dumps(result))
    else:
        from vd_events.measured.compare import print_comparisons

        print_comparisons(comparisons)
        print(f"bag:    {result['bag']}")
        print(f"report: {result['report']}")
    return 0


__all__ = ['add_subcommands']
