# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""``vd grade FILE|BAG...``: measured and simulated runs graded by their standard."""
from __future__ import annotations

import argparse
import dataclasses
import json
import math
from pathlib import Path

from vd_events.cli.measured import import_options
from vd_events.errors import InputError
from vd_events.measured.grade import GradeOptions, GradeResult, grade, load_inputs, shown_metric
from vd_events.reports.grade import write_grade_page
from vd_solvers.constants import DEG


def grade_options(args: argparse.Namespace) -> GradeOptions:
    """Return the grading options, each checked (InputError names the option)."""
    for name, value in (('--a-reference', args.a_reference), ('--gvwr', args.gvwr),
                        ('--steering-ratio', args.steering_ratio),
                        ('--wheelbase', args.wheelbase)):
        if value is not None and not (math.isfinite(value) and value > 0.0):
            raise InputError(name, f'must be a positive number, found {value!r}')
    if args.a_reference is not None and args.a_reference > 300.0:
        raise InputError('--a-reference', f'{args.a_reference:g} deg: A is the angle at 0.3 g, '
                         'below the 300 deg cap of the series')
    return GradeOptions(a_reference=None if args.a_reference is None
                        else round(args.a_reference, 1) * DEG,
                        gvwr=args.gvwr, steering_ratio=args.steering_ratio,
                        wheelbase=args.wheelbase)


def cmd_grade(args: argparse.Namespace) -> int:
    options = import_options(args)
    graded = grade_options(args)
    map_path = Path(args.map) if args.map else None
    inputs = load_inputs([Path(p) for p in args.inputs], map_path, options)
    sis = load_inputs([Path(p) for p in args.sis], map_path,
                      dataclasses.replace(options, event='slowly_increasing_steer'))
    result = grade(inputs, sis, graded)
    page = write_grade_page(result, Path(args.out))
    if args.json:
        print(json.dumps({'report': str(page), **result.to_json()}))
    else:
        print_grades(result)
        print(f'report: {page}')
    return 0


def print_grades(result: GradeResult) -> None:
    for run in result.runs:
        print(f'{run.label}: {run.standard}: {run.verdict}')
        for name, (value, unit) in run.metrics.items():
            if value is not None and math.isfinite(value):
                print(f'  {name:34s} {shown_metric(value, unit)}')
        for line in run.checks:
            print(f'  check: {line}')
        for line in run.notes:
            print(f'  {line}')
    for proc in result.procedures:
        g = proc.grade
        a = '-' if g.a_reference is None else f'{g.a_reference / DEG:.1f} deg'
        print(f'{proc.label}: FMVSS 126 / UN R140 procedure: {proc.verdict}; A = {a} '
              f'({proc.a_source})')
        print(f'  deciding: {proc.deciding}')
        for c in g.criteria:
            print(f"  criterion {c.name}: {'pass' if c.passed else 'FAIL'} over {c.runs} "
                  'valid run(s)')
        for line in proc.notes:
            print(f'  {line}')


__all__ = ['cmd_grade', 'grade_options', 'print_grades']
