# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""``vd identify PLAN.yaml``: a configuration's parameters fitted to measured logs."""
from __future__ import annotations

import argparse
import dataclasses
import json
from pathlib import Path

from vd_events.measured.identify import (
    Identification,
    identify,
    load_identify_plan,
    write_identified,
)
from vd_events.reports.identify import write_identify_page


def cmd_identify(args: argparse.Namespace) -> int:
    plan = load_identify_plan(Path(args.plan))
    if args.write_master:
        plan = dataclasses.replace(plan, write_master=Path(args.write_master))
    result = identify(plan, log=None if args.json else print)
    if not args.dry_run:
        write_identified(result)
    page = write_identify_page(result, Path(args.out) / plan.name)
    if args.json:
        print(json.dumps({'report': str(page), **result.to_json()}))
    else:
        print_identification(result)
        print(f'report: {page}')
    return 0


def print_identification(result: Identification) -> None:
    plan = result.plan
    print(f'{plan.name}: model {plan.model}, base {plan.configuration}, {len(result.logs)} '
          f'log(s), {result.points} residuals; {result.evaluations} evaluations, '
          f'{result.seconds:.1f} s ({result.message})')
    for f, s, v, e in zip(plan.parameters, result.start, result.fitted,
                          result.standard_errors):
        print(f'  {f.name:24s} {s:.5g} -> {v:.5g} +- {e:.2g} {f.unit}'.rstrip())
    print(f'  rank {result.rank} of {len(result.fitted)}, condition {result.condition:.3g}'
          + ''.join(f'; NOT IDENTIFIABLE APART: {a} and {b} (correlation {c:+.3f})'
                    for a, b, c in result.pairs))
    for which, per_log in result.rms.items():
        for k, channels in enumerate(per_log):
            print(f'  {which} log {k + 1}: ' + ', '.join(
                f'{ch} RMS {b:.4g} -> {a:.4g}' for ch, (b, a) in channels.items()) + ' (SI)')
    for key, c in result.correlations.items():
        for m in c.manoeuvres:
            print(f'  {key}: {c.method.title}: {m.label}: {m.verdict_text}')
    for note in result.notes:
        print(f'  {note}')
    if result.master is not None:
        print(f'configuration {result.configuration} written to {result.master}')


__all__ = ['cmd_identify', 'print_identification']
