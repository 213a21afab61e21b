# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""vd subcommands beyond ``vd data``: run, study, report, launch, bench."""
from __future__ import annotations

import argparse
from collections.abc import Callable
import json
from pathlib import Path
import sys

from vd_data_server.errors import DataError
from vd_events.bags.bag import BagError
from vd_events.orchestration.runner import RunError, RunOutcome, RunRequest
from vd_events.reports.display import HEADLINE_NAMES, display

HANDLERS: dict[str, Callable[[argparse.Namespace], int]] = {}


def add_subcommands(sub: argparse._SubParsersAction) -> None:
    run = sub.add_parser('run', help='run one event on one configuration')
    run.add_argument('event')
    run.add_argument('--config', default=None,
                     help="configuration (default: the first; 'all': every configuration)")
    run.add_argument('--model', default=None, help='bicycle | two_track | kc | vehicle')
    run.add_argument('--fidelity', default='', help="rigid | flexible (K&C; default: the "
                     "configuration's 'flexible' switch in the master file)")
    run.add_argument('--axle', default='', help='front | rear (K&C events)')
    run.add_argument('--set', dest='overrides', action='append', default=[],
                     metavar='KEY=VALUE', help="temporary override, e.g. "
                     "front_alignment.camber='-1 deg'")
    run.add_argument('--param', dest='parameters', action='append', default=[],
                     metavar='NAME=VALUE', help="event parameter, e.g. radius='40 m'")
    run.add_argument('--master', help='master file (default: the bundled sample study)')
    run.add_argument('--bag', help='bag directory to write (must not exist)')
    run.add_argument('--distributed', action='store_true',
                     help='one process per node (DDS on loopback) instead of one process')
    _namespace_arg(run)
    run.add_argument('--json', action='store_true')
    HANDLERS['run'] = cmd_run

    study = sub.add_parser('study', help='many events x configurations x models')
    study.add_argument('plan', help='study plan YAML')
    study.add_argument('--bag', help='folder for the bags (default: out/<plan name>/bags)')
    study.add_argument('--report', help='folder for the report (default: out/<plan name>)')
    study.add_argument('--distributed', action='store_true')
    _namespace_arg(study)
    study.add_argument('--json', action='store_true')
    HANDLERS['study'] = cmd_study

    report = sub.add_parser('report', help='HTML report + PNG plots from bags')
    report.add_argument('bags', nargs='+')
    report.add_argument('--out', default='out/report', help='report folder')
    HANDLERS['report'] = cmd_report

    launch = sub.add_parser('launch', help='start the nodes and keep them running')
    launch.add_argument('--distributed', action='store_true')
    launch.add_argument('--master', help='master file')
    _namespace_arg(launch)
    launch.add_argument('--allow-edits', action='store_true',
                        help='start the data server with allow_edits:=true (set_override)')
    launch.add_argument('--solvers', default='', metavar='FAMILY=N,...', help='solver '
                        'instances per family, e.g. kc=2 (default one of each)')
    launch.add_argument('--lockstep', action='store_true',
                        help='the lock-step vehicle and the example path follower, closed loop')
    launch.add_argument('--config', default='', help='lock-step configuration (default: first)')
    launch.add_argument('--duration', type=float, default=20.0,
                        help='lock-step simulated time, s')
    launch.add_argument('--radius', type=float, default=40.0, help='lock-step circle radius, m')
    launch.add_argument('--speed', type=float, default=12.0, help='lock-step speed, m/s')
    launch.add_argument('--bag', help='lock-step: bag directory to write (must not exist)')
    launch.add_argument('--json', action='store_true')
    HANDLERS['launch'] = cmd_launch

    cap = sub.add_parser('capability', help='rigid vs flexible K&C: which model each '
                         'event and quantity needs (thesis Tables 5.2.1/5.2.2)')
    cap.add_argument('--config', default=None, help='configuration (default: the first)')
    cap.add_argument('--axle', default='', help='front | rear (default: both)')
    cap.add_argument('--master', help='master file (default: the bundled sample study)')
    cap.add_argument('--out', default=None, help='folder for the bag of the runs and tables '
                     '(default: out/capability/<configuration>; must not hold it yet)')
    cap.add_argument('--param', dest='parameters', action='append', default=[],
                     metavar='NAME=VALUE', help='event parameter for every event, e.g. steps=41')
    cap.add_argument('--json', action='store_true')
    HANDLERS['capability'] = cmd_capability

    from vd_events.cli.sweep import add_subcommands as add_sweep_commands

    add_sweep_commands(sub, HANDLERS)

    bench = sub.add_parser('bench', help='the benchmark suite')
    bench.add_argument('--json', action='store_true')
    HANDLERS['bench'] = cmd_bench

    from vd_events.cli.measured import add_subcommands as add_testdata

    add_testdata(sub, HANDLERS)


def _namespace_arg(parser: argparse.ArgumentParser) -> None:
    parser.add_argument('--namespace', default=None, metavar='NS',
                        help='ROS namespace of the nodes (default: /vd): /car2 gives '
                        '/car2/configuration, /car2/kc/run_event, ...')


def _namespace(args: argparse.Namespace) -> str:
    from vd_data_server.ros.names import DEFAULT_NAMESPACE, check_namespace

    return check_namespace(args.namespace) if args.namespace is not None else DEFAULT_NAMESPACE


def _study(master: str | None):
    from vd_data_server.paths import default_master
    from vd_data_server.study import load_study

    path = Path(master) if master else default_master()
    return path, load_study(path)


class _ProgressBar:
    """
    A rich progress bar on the terminal (stderr) for the runs' action feedback.

    One task per run; a context manager, so the bar is closed however the runs end.
    """

    def __init__(self) -> None:
        from rich.console import Console
        from rich.progress import BarColumn, Progress, TaskProgressColumn, TextColumn

        self.progress = Progress(TextColumn('{task.description}'), BarColumn(),
                                 TaskProgressColumn(), TextColumn('{task.fields[stage]}'),
                                 console=Console(stderr=True), transient=False)
        self.tasks: dict[RunRequest, object] = {}

    def __call__(self, request: RunRequest, fraction: float, stage: str) -> None:
        if request not in self.tasks:
            self.tasks[request] = self.progress.add_task(
                f'{request.configuration} / {request.event} / {request.model}', total=1.0,
                stage=stage)
        self.progress.update(self.tasks[request], completed=fraction, stage=stage)

    def __enter__(self):
        self.progress.start()
        return self

    def __exit__(self, *exc) -> None:
        self.progress.stop()


def _progress_printer(enabled: bool):
    """Return a progress bar for the terminal, or None (not a terminal, --json)."""
    return _ProgressBar() if enabled else None


def _with_progress(progress, work):
    """Run ``work()`` with the progress bar (if any) shown."""
    if progress is None:
        return work()
    with progress:
        return work()


def cmd_run(args: argparse.Namespace) -> int:
    import time

    t0 = time.perf_counter()
    from vd_events.orchestration.runner import run_distributed, run_embedded, validate
    from vd_solvers.families import event_model

    namespace = _namespace(args)
    master, study = _study(args.master)
    model = args.model or event_model(args.event)
    every = args.config == 'all'
    names = study.configuration_names if every else [args.config or
                                                     study.configuration_names[0]]
    if every and args.bag:
        raise DataError('--config all writes no single bag; run each configuration with '
                        'its own --bag')
    requests = []
    for config_name in names:
        fidelity = args.fidelity
        if not fidelity:
            config = study.configurations.get(config_name)
            fidelity = 'flexible' if model == 'kc' and config is not None and \
                config.flexible else 'rigid'
        request = RunRequest(event=args.event, configuration=config_name, model=model,
                             fidelity=fidelity, axle=args.axle or '',
                             overrides=tuple(args.overrides),
                             parameters=tuple(args.parameters),
                             bag=Path(args.bag) if args.bag else None)
        try:
            requests.append(validate(study, request))
        except (RunError, BagError) as err:
            raise DataError(str(err)) from None
    progress = _progress_printer(sys.stderr.isatty() and not args.json)
    # where the time goes (vd bench reports it): load + validate, then the runner's phases
    timings = {'load_and_validate': time.perf_counter() - t0}
    if args.distributed:
        results = _with_progress(progress, lambda: run_distributed(
            master, requests, progress, namespace=namespace))
    else:
        results = _with_progress(progress, lambda: run_embedded(
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


def cmd_study(args: argparse.Namespace) -> int:
    from vd_events.studies.plan import load_plan, run_plan

    plan = load_plan(Path(args.plan))
    out = Path(args.report) if args.report else Path('out') / plan.name
    bags = Path(args.bag) if args.bag else out / 'bags'
    namespace = _namespace(args)
    progress = _progress_printer(sys.stderr.isatty() and not args.json)
    summary = _with_progress(progress, lambda: run_plan(
        plan, bags, out, distributed=args.distributed, progress=progress, namespace=namespace))
    if args.json:
        print(json.dumps(summary, indent=2))
    else:
        print(f"report: {summary['report']}")
        print(f"study report (one self-contained file): {summary['study_report']}")
        print(f"bags:   {summary['bags']}")
    return 0 if not summary['errors'] else 1


def cmd_report(args: argparse.Namespace) -> int:
    from vd_events.reports.report import build_report
    from vd_events.reports.study import build_study_report

    path = build_report([Path(b) for b in args.bags], Path(args.out))
    study = build_study_report([Path(b) for b in args.bags], Path(args.out))
    print(f'report: {path}')
    print(f'study report (one self-contained file): {study}')
    return 0


def cmd_launch(args: argparse.Namespace) -> int:
    from vd_events.orchestration.launch import launch

    if args.lockstep:
        return _launch_lockstep(args)
    return launch(Path(args.master) if args.master else None, distributed=args.distributed,
                  namespace=_namespace(args), allow_edits=args.allow_edits,
                  solvers=args.solvers)


def _launch_lockstep(args: argparse.Namespace) -> int:
    from vd_events.orchestration.lockstep import run_lockstep

    for name, low, high in (('duration', 0.01, 3600.0), ('radius', 5.0, 1000.0),
                            ('speed', 0.5, 60.0)):
        value = getattr(args, name)
        if not low <= value <= high:
            raise DataError(f'--{name} {value:g} is outside [{low:g}, {high:g}]')
    if args.distributed:
        raise DataError('--lockstep runs embedded; for separate processes start '
                        'vehicle_solver (mode:=lockstep) and path_follower (docs/ros-api.md)')
    master, study = _study(args.master)
    if args.config and args.config not in study.configurations:
        raise DataError(f"configuration '{args.config}' is not in the study "
                        f"(configurations: {', '.join(study.configuration_names)})")
    out = run_lockstep(configuration=args.config, master=master, duration=args.duration,
                       radius=args.radius, speed=args.speed,
                       bag=Path(args.bag) if args.bag else None)
    if args.json:
        print(json.dumps(out.to_json()))
    else:
        print(f'lock-step {out.status}; {out.steps} steps in {out.wall:.1f} s '
              f'({out.steps_per_second:.0f} steps/s)' + (f'; bag: {out.bag}' if out.bag else ''))
    return 0 if out.status.startswith('finished') else 1


def cmd_bench(args: argparse.Namespace) -> int:
    from vd_events.bench.suite import print_bench, run_bench

    results = run_bench()
    if args.json:
        print(json.dumps(results, indent=2))
    else:
        print_bench(results)
    return 0


def cmd_capability(args: argparse.Namespace) -> int:
    from vd_events.studies.capability import QUANTITIES, format_table, run_study

    master, study = _study(args.master)
    name = args.config or study.configuration_names[0]
    if name not in study.configurations:
        raise DataError(f"configuration '{name}' does not exist (available: "
                        f"{', '.join(study.configuration_names)})", file=str(master))
    if args.axle not in ('', 'front', 'rear'):
        raise DataError(f"--axle must be front or rear, found '{args.axle}'")
    axles = [args.axle] if args.axle else ['front', 'rear']
    steps = [p for p in args.parameters if p.partition('=')[0].strip() == 'steps']
    if len(steps) != len(args.parameters):
        raise DataError("vd capability takes only the parameter 'steps' (every event has it)")
    out = Path(args.out) if args.out else Path('out') / 'capability' / name
    progress = _progress_printer(sys.stderr.isatty() and not args.json)
    tables = _with_progress(progress, lambda: run_study(master, study, name, axles, out,
                                                        args.parameters, progress=progress))
    if args.json:
        print(json.dumps({'configuration': name, 'out': str(out),
                          'tables': [t.to_json() for t in tables]}))
        return 0
    from rich.table import Table as RichTable

    from vd_data_server.overview import console

    term = console()
    for t in tables:
        table = RichTable(title=f"capability - {t.configuration} - {t.axle} axle "
                          f"(flexible: {', '.join(t.components)})", title_justify='left')
        table.add_column('event')
        for q in QUANTITIES:
            table.add_column(q)
        for row in format_table(t):
            table.add_row(*[c if i == 0 else (f'[red]{c}[/red]' if c.startswith('Flexible')
                                              else f'[green]{c}[/green]')
                            for i, c in enumerate(row)])
        term.print(table)
        for note in t.notes:
            term.print(note)
    term.print(f'bag (both runs of every event and the tables): {out}/capability_{name}')
    return 0
