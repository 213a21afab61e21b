# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The ``vd`` command-line tool (ARCHITECTURE §5).

Bad input never ends in a traceback: every expected error is printed as
``file: key: message`` lines (or ``{"error": ...}`` with ``--json``) and the
exit code is 2. Nothing is written before the inputs are validated.
"""
from __future__ import annotations

import argparse
from collections.abc import Callable, Sequence
import json
import signal
import sys

from vd_data_server.errors import DataError

from .bag import BagError
from .domain import DomainError
from .runner import Interrupted, RunError

EXIT_OK = 0
EXIT_USAGE = 2
EXIT_INTERRUPTED = 130


class UsageError(Exception):
    """Bad command-line input (unknown event, model, configuration, bag path...)."""


def _master_arg(parser: argparse.ArgumentParser) -> None:
    parser.add_argument('--master', help='master file (default: the bundled sample study)')


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog='vd', description='vd: vehicle-dynamics simulation '
                                     'on one shared vehicle data set')
    sub = parser.add_subparsers(dest='command', required=True)

    data = sub.add_parser('data', help='vehicle data and master files').add_subparsers(
        dest='data_command', required=True)
    status = data.add_parser('status', help='overview: variant, UNCHANGED/MODIFIED, SAME/DIFFERS')
    _master_arg(status)
    status.add_argument('--json', action='store_true')
    show = data.add_parser('show', help='the resolved configuration in SI')
    show.add_argument('config')
    _master_arg(show)
    show.add_argument('--json', action='store_true')
    check = data.add_parser('check', help='validate the master file and every data file')
    _master_arg(check)
    check.add_argument('--json', action='store_true')

    from . import commands

    commands.add_subcommands(sub)
    from . import workbench_cmd

    workbench_cmd.add_subcommands(sub, commands.HANDLERS)
    from . import tire_cmd

    tire_cmd.add_subcommands(sub, commands.HANDLERS)
    return parser


def _load(master: str | None):
    from vd_data_server.paths import default_master
    from vd_data_server.study import load_study

    return load_study(master or default_master())


def cmd_data(args: argparse.Namespace) -> int:
    from vd_data_server.overview import (
        configuration_json,
        console,
        print_configuration,
        print_status,
    )

    study = _load(args.master)
    term = console()
    if args.data_command == 'status':
        if args.json:
            print(json.dumps(study.to_json(), indent=2))
        else:
            print_status(study, term)
    elif args.data_command == 'show':
        if args.config not in study.configurations:
            raise UsageError(f"{study.master.path}: configuration '{args.config}' does not exist "
                             f"(available: {', '.join(study.configuration_names)})")
        config = study.configurations[args.config]
        if args.json:
            print(json.dumps(configuration_json(config), indent=2))
        else:
            print_configuration(config, term)
    else:
        _check_models(study)
        n_files = len({g.file for c in study.configurations.values() for g in c.groups.values()})
        message = (f'{study.master.path}: OK ({len(study.configurations)} configurations, '
                   f'{n_files} data files)')
        if args.json:
            print(json.dumps({'ok': True, 'message': message, 'warnings': list(study.warnings)}
                             if study.warnings else {'ok': True, 'message': message}))
        else:
            for warning in study.warnings:
                print(f'warning: {warning}', file=sys.stderr)
            print(message)
    return EXIT_OK


def _check_models(study) -> None:
    """
    Build what a run builds from the data beyond loading it.

    That is each configuration's tire models (finite forces over the working range), so
    `vd data check` and a run agree.
    """
    from vd_data_server.errors import DataErrors
    from vd_data_server.tire_group import tire_properties
    from vd_solvers.errors import SolverError
    from vd_solvers.tire.magic_formula import MagicFormula

    errors: dict[str, DataError] = {}
    for config in study.configurations.values():
        for group in config.groups.values():
            if group.kind != 'tire':
                continue
            try:
                MagicFormula(tire_properties(group))
            except DataError as err:
                errors.setdefault(str(err), err)
            except SolverError:  # a format the analytical models do not evaluate: not bad data
                continue
    if errors:
        found = list(errors.values())
        raise found[0] if len(found) == 1 else DataErrors(found)


def main(argv: Sequence[str] | None = None) -> int:
    from . import commands, workbench_cmd

    argv = list(sys.argv[1:] if argv is None else argv)
    handlers: dict[str, Callable[[argparse.Namespace], int]] = {'data': cmd_data}
    xlsx = argv[:2] == ['import', 'xlsx']  # beside `vd import FILE... --bag` (test data)
    if xlsx:
        args = workbench_cmd.import_xlsx_parser().parse_args(argv[2:])
    else:
        args = build_parser().parse_args(argv)
    handlers.update(commands.HANDLERS)  # filled in while the parser is built
    if xlsx:
        handlers['import'] = workbench_cmd.cmd_import
    want_json = bool(getattr(args, 'json', False))
    previous = signal.signal(signal.SIGTERM, _terminate)
    try:
        return handlers[args.command](args)
    except Interrupted as err:
        _report_error(str(err), want_json)
        return EXIT_INTERRUPTED
    except (DataError, UsageError, RunError, BagError, DomainError) as err:
        _report_error(str(err), want_json)
        return EXIT_USAGE
    except OSError as err:  # a file or folder the input named cannot be used
        where = f'{err.filename}: ' if err.filename else ''
        _report_error(f'{where}{err.strerror or err}', want_json)
        return EXIT_USAGE
    except KeyboardInterrupt:
        _report_error('interrupted', want_json)
        return EXIT_INTERRUPTED
    finally:
        signal.signal(signal.SIGTERM, previous)


def _terminate(signum, frame) -> None:
    """SIGTERM ends a run like Ctrl-C: its nodes stop, its partial bag is removed."""
    raise KeyboardInterrupt


def _report_error(message: str, want_json: bool) -> None:
    if want_json:
        print(json.dumps({'error': message}))
    else:
        print(message, file=sys.stderr)


if __name__ == '__main__':
    sys.exit(main())
