# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""``vd sweep`` and ``vd optimize``: the command-line side (docs/sweeps.md)."""
from __future__ import annotations

import argparse
from contextlib import contextmanager
from dataclasses import replace
import json
from pathlib import Path
import sys

from rich.progress import BarColumn, MofNCompleteColumn, Progress, TimeRemainingColumn

from vd_data_server.study import load_study
from vd_events.errors import Interrupted, RunError
from vd_events.orchestration.dispatch import Dispatcher, SolverGraph, parse_solvers
from vd_events.reports.sweep import write_outputs
from vd_events.sweeps.optimize import check_plan, optimize
from vd_events.sweeps.plan import OptimizeSpec, load_plan, points
from vd_events.sweeps.sweep import requests_for, sweep
from vd_solvers.families import MODEL_FAMILY


def _solvers(text: str | None, attach: bool = False):

    if text is None:
        return 1 if attach else 2
    text = text.strip()
    if text.isdigit():
        if int(text) < 1:
            raise RunError(f'--solvers: expected a positive number, found {text!r}')
        return int(text)
    return parse_solvers(text)


@contextmanager
def _graph(plan, args):
    """Yield an evaluator over the solver instances of the sweep's graph."""
    solvers = _solvers(args.solvers, args.attach)
    families = sorted({MODEL_FAMILY[r.model] for r in plan.runs})
    counts = (dict.fromkeys(families, solvers) if isinstance(solvers, int)
              else {f: solvers.get(f, 1) for f in families})
    quiet = args.json or not sys.stderr.isatty()

    def log(text: str) -> None:
        if not args.json:
            print(text, file=sys.stderr)

    # started at the first runs to compute (a sweep whose runs are all known starts nothing)
    graph = SolverGraph(plan.master, counts, attach=args.attach, log=log)
    dispatchers: list[Dispatcher] = []

    def evaluator(requests, done):
        if not dispatchers:
            dispatchers.append(graph.__enter__())
        try:
            dispatchers[0].run(requests, done)
        except KeyboardInterrupt:
            dispatchers[0].cancel()
            raise Interrupted('interrupted; the finished runs are kept in runs.jsonl '
                              '(a rerun computes only the others)') from None
    try:
        yield evaluator, quiet
    finally:
        if dispatchers:
            graph.__exit__(None, None, None)


def _bar(quiet: bool):
    """Make a rich progress bar on the terminal (runs done / runs to compute)."""
    if quiet:
        return None, None

    progress = Progress('[progress.description]{task.description}', BarColumn(),
                        MofNCompleteColumn(), TimeRemainingColumn(), transient=True)
    task = progress.add_task('runs', total=None)

    def update(done: int, total: int) -> None:
        progress.update(task, completed=done, total=total)
    return progress, update


def cmd_sweep(args: argparse.Namespace) -> int:

    path = Path(args.plan)
    plan = load_plan(path)
    study = load_study(plan.master)
    out = Path(args.out) if args.out else Path('out') / plan.name
    _solvers(args.solvers, args.attach)

    requests_for(plan, study, points(plan))  # every point checked before a process starts
    with _graph(plan, args) as (evaluator, quiet):
        progress, update = _bar(quiet)
        if progress is not None:
            progress.start()
        try:
            result = sweep(plan, study, evaluator, out, progress=update)
        finally:
            if progress is not None:
                progress.stop()
    result.files = write_outputs(result, out)
    failed = sum(1 for e in result.errors if e)
    if args.json:
        print(json.dumps({'points': len(result.points), 'computed': result.computed,
                          'cached': result.cached, 'failed': failed, 'files': result.files,
                          'errors': [e for e in result.errors if e]}, indent=2))
    else:
        print(f'{len(result.points)} points x {len(plan.runs)} runs: {result.computed} runs '
              f'computed, {result.cached} from earlier results, {failed} points failed')
        for e in dict.fromkeys(e for e in result.errors if e):
            print(f'  {e}', file=sys.stderr)
        for kind, file in result.files.items():
            print(f'{kind + ":":9s}{file}')
    return 0 if not failed else 1


def cmd_optimize(args: argparse.Namespace) -> int:

    plan = load_plan(Path(args.plan), optimize=True)
    if args.write_master:
        spec = replace(plan.optimize or OptimizeSpec(), write_master=Path(args.write_master),
                       named_by_user=True)
        plan = replace(plan, optimize=spec)
    study = load_study(plan.master)
    _solvers(args.solvers, args.attach)
    out = Path(args.out) if args.out else Path('out') / plan.name
    check_plan(plan, study, out)

    def log(text: str) -> None:
        if not args.json:
            print(text)

    with _graph(plan, args) as (evaluator, _quiet):
        result = optimize(plan, study, evaluator, out, log=log)
    best = result.best
    summary = {'met': best.met, 'configuration': result.configuration,
               'master': str(result.master), 'evaluations': len(result.history),
               'message': result.message,
               'factors': {f.name: {'value': v, 'unit': f.unit}
                           for f, v in zip(plan.factors, best.x)},
               'responses': {r.name: {'value': v, 'unit': r.unit}
                             for r, v in zip(plan.responses, best.responses)},
               'history': str(out / 'history.csv')}
    if args.json:
        print(json.dumps(summary, indent=2))
    else:
        print(f"{'targets met' if best.met else 'targets NOT met'} after "
              f'{len(result.history)} evaluations ({result.message})')
        print(f'configuration {result.configuration!r} written to {result.master}')
        print(f"history: {summary['history']}")
    return 0 if best.met else 1
