# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""``vd data status|show|check``: the data server's view of a master file, on the terminal."""
from __future__ import annotations

import argparse
import json
import sys

from vd_data_server.errors import DataError, DataErrors
from vd_data_server.overview import (
    configuration_json,
    console,
    print_configuration,
    print_status,
)
from vd_data_server.study import Study
from vd_data_server.tire_group import tire_properties
from vd_events.cli.options import study as load
from vd_events.errors import UsageError
from vd_solvers.errors import SolverError
from vd_solvers.kc.from_config import build_kc_model
from vd_solvers.results import FIDELITIES
from vd_solvers.tire.magic_formula import MagicFormula


def cmd_status(args: argparse.Namespace) -> int:
    _, study = load(args.master)
    if args.json:
        print(json.dumps(study.to_json(), indent=2))
    else:
        print_status(study, console())
    return 0


def cmd_show(args: argparse.Namespace) -> int:
    _, study = load(args.master)
    if args.config not in study.configurations:
        raise UsageError(f"{study.master.path}: configuration '{args.config}' does not exist "
                         f"(available: {', '.join(study.configuration_names)})")
    config = study.configurations[args.config]
    if args.json:
        print(json.dumps(configuration_json(config), indent=2))
    else:
        print_configuration(config, console())
    return 0


def cmd_check(args: argparse.Namespace) -> int:
    _, study = load(args.master)
    check_models(study)
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
    return 0


#: the axles a K&C model is built for
KC_AXLES = ('front', 'rear')


def check_models(study: Study) -> None:
    """
    Build what a run builds from the data beyond loading it.

    That is each configuration's tire models (finite forces over the working range) and
    its K&C models of both axles, rigid and flexible (hard points, flexible components,
    imported stiffness files), with the functions the runs use, so `vd data check` and a
    run agree.
    """
    errors: dict[str, DataError] = {}
    for config in study.configurations.values():
        for axle in KC_AXLES:
            if f'{axle}_hardpoints' not in config.groups:
                continue
            for fidelity in FIDELITIES[::-1]:  # flexible first: it builds every component
                label = f"configuration '{config.name}', axle '{axle}', {fidelity}"
                try:
                    build_kc_model(config, axle, fidelity, label)
                except DataError as err:
                    errors.setdefault(str(err), err)
                except SolverError as err:
                    # one line per problem: the first configuration that meets it names it
                    errors.setdefault(str(err).removeprefix(f'{label}: '), DataError(str(err)))
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


__all__ = ['cmd_status', 'cmd_show', 'cmd_check', 'check_models']
