"""vd subcommands beyond ``vd data``: run, study, report, launch, bench."""
from __future__ import annotations

import argparse
from collections.abc import Callable
import json
from pathlib import Path
import sys

from vd_data_server.errors import DataError

from .bag import BagError
from .display import HEADLINE_NAMES, display
from .runner import RunError, RunOutcome, RunRequest

HANDLERS: dict[str, Callable[[argparse.Namespace], int]] = {}


def add_subcommands(sub: argparse._SubParsersAction) -> None:
    run = sub.add_parser('run', help='run one event on one configuration')
    run.add_argument('event')
    run.add_argument('--config', default=None, help='configuration (default: the first)')
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
    run.add_argument('--json', action='store_true')
    HANDLERS['run'] = cmd_run

    study = sub.add_parser('study', help='many events x configurations x models')
    study.add_argument('plan', help='study plan YAML')
    study.add_argument('--bag', help='folder for the bags (default: out/<plan name>/bags)')
    study.add_argument('--report', help='folder for the report (default: out/<plan name>)')
    study.add_argument('--distributed', action='store_true')
    study.add_argument('--json', action='store_true')
    HANDLERS['study'] = cmd_study

    report = sub.add_parser('report', help='HTML report + PNG plots from bags')
    report.add_argument('bags', nargs='+')
    report.add_argument('--out', default='out/report', help='report folder')
    HANDLERS['report'] = cmd_report

    launch = sub.add_parser('launch', help='start the nodes and keep them running')
    launch.add_argument('--distributed', action='store_true')
    launch.add_argument('--master', help='master file')
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

    bench = sub.add_parser('bench', help='the benchmark suite')
    bench.add_argument('--json', action='store_true')
    HANDLERS['bench'] = cmd_bench


def _study(master: str | None):
    from vd_data_server.paths import default_master
    from vd_data_server.study import load_study

    path = Path(master) if master else default_master()
    return path, load_study(path)


def _progress_printer(enabled: bool):
    if not enabled:
        return None

    def show(request: RunRequest, fraction: float, stage: str) -> None:
        print(f'\r  {request.configuration} / {request.event} / {request.model}: '
              f'{stage} {100 * fraction:3.0f}%', end='', file=sys.stderr, flush=True)
    return show


def default_model(event: str) -> str:
    """
    Return the model ``vd run EVENT`` uses without --model.

    two_track where it applies, else the first model that runs the event.
    """
    from .runner import MODELS, events_for

    if event in events_for('two_track'):
        return 'two_track'
    return next((m for m in MODELS if event in events_for(m)), 'two_track')


def cmd_run(args: argparse.Namespace) -> int:
    from .runner import run_distributed, run_embedded, validate

    master, study = _study(args.master)
    model = args.model or default_model(args.event)
    config_name = args.config or study.configuration_names[0]
    fidelity = args.fidelity
    if not fidelity:
        config = study.configurations.get(config_name)
        fidelity = 'flexible' if model == 'kc' and config is not None and config.flexible \
            else 'rigid'
    request = RunRequest(event=args.event, configuration=config_name, model=model,
                         fidelity=fidelity, axle=args.axle or '',
                         overrides=tuple(args.overrides), parameters=tuple(args.parameters),
                         bag=Path(args.bag) if args.bag else None)
    try:
        request = validate(study, request)
    except (RunError, BagError) as err:
        raise DataError(str(err)) from None
    runner = run_distributed if args.distributed else run_embedded
    progress = _progress_printer(sys.stderr.isatty() and not args.json)
    (result,) = runner(master, [request], progress)
    if progress:
        print(file=sys.stderr)
    if result.error:
        raise DataError(result.error)
    assert result.outcome is not None
    if args.json:
        print(json.dumps(result.outcome.to_json(str(result.bag) if result.bag else None)))
    else:
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
    for note in [*outcome.notes[:1], *(n for n in outcome.notes[1:] if n.startswith('inner '))]:
        term.print(note)
    if result.bag:
        term.print(f'bag: {result.bag}')


def cmd_study(args: argparse.Namespace) -> int:
    from .study_plan import load_plan, run_plan

    plan = load_plan(Path(args.plan))
    out = Path(args.report) if args.report else Path('out') / plan.name
    bags = Path(args.bag) if args.bag else out / 'bags'
    summary = run_plan(plan, bags, out, distributed=args.distributed,
                       progress=_progress_printer(sys.stderr.isatty() and not args.json))
    if args.json:
        print(json.dumps(summary, indent=2))
    else:
        print(f"report: {summary['report']}")
        print(f"bags:   {summary['bags']}")
    return 0 if not summary['errors'] else 1


def cmd_report(args: argparse.Namespace) -> int:
    from .report import build_report

    path = build_report([Path(b) for b in args.bags], Path(args.out))
    print(f'report: {path}')
    return 0


def cmd_launch(args: argparse.Namespace) -> int:
    from .launch import launch

    return launch(Path(args.master) if args.master else None, distributed=args.distributed)


def cmd_bench(args: argparse.Namespace) -> int:
    from .bench import print_bench, run_bench

    results = run_bench()
    if args.json:
        print(json.dumps(results, indent=2))
    else:
        print_bench(results)
    return 0


def cmd_capability(args: argparse.Namespace) -> int:
    from .capability import QUANTITIES, format_table, run_study

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
    tables = run_study(master, study, name, axles, out, args.parameters, progress=progress)
    if progress:
        print(file=sys.stderr)
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
