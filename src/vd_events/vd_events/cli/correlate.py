# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""``vd correlate BAG...``: the model against repeated test runs by an ISO validation method."""
from __future__ import annotations

import argparse
import json
from pathlib import Path

from vd_events.errors import InputError
from vd_events.measured.compare import shown
from vd_events.measured.correlate import METHODS, Correlation, correlate, load_bands
from vd_events.measured.grade import load_inputs
from vd_events.measured.importer import ImportOptions
from vd_events.reports.correlate import write_correlate_page
from vd_solvers.results import EventOutcome

#: the method a test event is correlated by when --method is not given
DEFAULT_METHOD = {'constant_radius_turn': 'iso19364', 'sine_with_dwell': 'iso19365',
                  'step_steer': 'iso22140', 'vehicle_test': 'iso22140'}


def method_for(tests: list[EventOutcome], given: str | None) -> str:
    """Return ``--method``, or the one the test runs' events call for."""
    if given is not None:
        return given
    methods = sorted({DEFAULT_METHOD.get(t.event, '') for t in tests})
    if len(methods) != 1 or not methods[0]:
        events = ', '.join(sorted({t.event for t in tests}))
        raise InputError('--method', f'the test runs hold {events}: name the method '
                         f"(--method {'|'.join(METHODS)})")
    return methods[0]


def cmd_correlate(args: argparse.Namespace) -> int:
    bands = load_bands(Path(args.bands) if args.bands else None)
    inputs = load_inputs([Path(p) for p in args.inputs], Path(args.map) if args.map else None,
                         ImportOptions())
    tests = [o for _, o in inputs if o.model == 'test']
    sims = [o for _, o in inputs if o.model not in ('test', 'rig')]
    if not tests:
        raise InputError('BAG', 'no vehicle log among the inputs (vd import writes test bags; '
                         'a .vbo or a CSV log with --map is read as vd import reads it)')
    if not sims:
        raise InputError('BAG', 'no simulation among the inputs (vd run, vd replay and vd '
                         'study write simulation bags)')
    result = correlate(sims, tests, method_for(tests, args.method), bands, force=args.force)
    page = write_correlate_page(result, Path(args.out))
    if args.json:
        print(json.dumps({'report': str(page), **result.to_json()}))
    else:
        print_correlation(result)
        print(f'report: {page}')
    return 0


def print_correlation(result: Correlation) -> None:
    spec = result.method
    print(f'{spec.title}: {result.verdict} (bands: {result.bands.name}, version '
          f'{result.bands.version})')
    for m in result.manoeuvres:
        print(f'  {m.label}: {m.verdict_text}; {len(m.runs)} test run(s), simulation: '
              f"{', '.join(m.simulations)}")
        for c in m.channels:
            print(f'    {c.channel:22s} {c.run:28s} {100 * c.fraction:5.1f} % inside, '
                  f'largest excess {shown(c.excess, c.unit):>12s}  {c.verdict}')


__all__ = ['cmd_correlate', 'method_for', 'print_correlation']
