# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
``vd run EVENT``: one event on one configuration (or all).

Solved in this process without a ROS graph (orchestration/inprocess.py), or with
``--distributed`` through the graph, each node its own process (orchestration/runner.py).
"""
from __future__ import annotations

import argparse
import json
from pathlib import Path
import time

from vd_data_server.errors import DataError
from vd_events.cli import options
from vd_events.errors import BagError, RunError
from vd_events.orchestration.requests import RunOutcome, RunRequest, validate
from vd_events.reports.display import HEADLINE_NAMES, display
from vd_solvers.families import event_model


def cmd_run(args: argparse.Namespace) -> int:
    t0 = time.perf_counter()
    namespace = options.namespace(args)
    master, study = options.study(args.master)
    model = args.model or event_model(args.event)
    every = args.config == 'all'
    names = study.configuration_names if every else [args.config or
                                                     study.configuration_names[0]]
    if every and args.bag:
        raise DataError('--config all writes no single bag; run each configuration with '
                        'its own --bag')
    requests = []
    for config_name in names:
        # an empty --fidelity follows the configuration's switch (validate resolves it)
        request = RunRequest(event=args.event, configuration=config_name, model=model,
                             fidelity=args.fidelity, axle=args.axle or '',
                             overrides=tuple(args.overrides),
                             parameters=tuple(args.parameters),
                             bag=Path(args.bag) if args.bag else None)
        try:
            requests.append(validate(study, request))
        except (RunError, BagError) as err:
            raise DataError(str(err)) from None
    progress = options.progress_bar(args)
    # where the time goes (vd bench reports it): load + validate, then the runner's phases
    timings = {'load_and_validate': time.perf_counter() - t0}
    if args.distributed:
        from vd_events.orchestration.runner import run_distributed

        results = options.with_progress(progress, lambda: run_distributed(
            master, requests, progress, namespace=namespace))
    else:
        from vd_events.orchestration.inprocess import run_inprocess

        results = options.with_progress(progress, lambda: run_inprocess(
            master, requests, progress, namespace=namespace, timings=timings, study=study))
    for result in results:
        if result.error:
            raise DataError(result.error)
    outcomes = [r.outcome.to_json(str(r.bag) if r.bag else None) for r in results
                if r.outcome is not None]
    if args.json:
        for out in outcomes:
            out['timings'] = {**timings, 'command': time.perf_counter() - t0}
        print(json.dumps(outcomes if every else outcomes[0]))
    else:
        for result in results:
            _print_outcome(result)
    return 0


def _print_outcome(result: RunOutcome) -> None:
    # imported here: a run with --json prints no table and need not import rich
    from rich.table import Table

    from vd_data_server.overview import console

    outcome = result.outcome
    assert outcome is not None
    table = Table(title=f'{outcome.event} - {outcome.configuration} - {outcome.model}',
                  title_justify='left')
    table.add_column('metric')
    table.add_column('value', justify='right')
    table.add_column('unit')
    names = [m for m in HEADLINE_NAMES if m in outcome.metrics]
    names += [m for m in outcome.metrics if m not in names]
    for name in names:
        metric = outcome.metrics[name]
        value, unit = display(metric.value, metric.unit, name)
        table.add_row(name, f'{value:.5g}', unit)
    term = console()
    term.print(table)
    notes = [*outcome.notes[:1], *(n for n in outcome.notes[1:] if n.startswith('inner '))]
    if outcome.event == 'sine_with_dwell':  # the verdict, A, the series and the run table
        end = next((i for i, n in enumerate(outcome.notes) if n.startswith('integrator step')),
                   len(outcome.notes))
        notes = list(outcome.notes[:end])
    for note in notes:
        term.print(note, highlight=False, markup=False)
    if result.bag:
        term.print(f'bag: {result.bag}')


__all__ = ['cmd_run']
