# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Study plans: events x configurations x models, run as one batch into bags and a report.

Plan file::

    name: demo
    master: path/to/master.yaml     # optional, relative to the plan; default: bundled sample
    runs:
      - event: handling_diagram
        models: [bicycle, two_track]
        configurations: all          # or a list of names
        parameters: [radius=100 m]   # optional event parameters
        overrides: []                # optional GROUP.KEY=VALUE for these runs
        axle: front                  # optional (K&C events)
        fidelity: flexible           # optional (K&C and vehicle: rigid or flexible;
                                     # default: the configuration's flexible switch)
    measurements: [path/to/bag]      # optional: bags of vd import, relative to the plan;
                                     # the study report compares them with the runs
"""
from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from vd_data_server import schema
from vd_data_server.errors import DataError
from vd_data_server.paths import default_master
from vd_data_server.ros.names import DEFAULT_NAMESPACE
from vd_data_server.shape import Collector, check
from vd_data_server.study import Study, load_study
from vd_data_server.yamlio import load_file
from vd_events.errors import BagError, RunError
from vd_events.orchestration.inprocess import run_inprocess
from vd_events.orchestration.requests import RunRequest, validate
from vd_solvers.results import run_fidelity

#: a study plan, in the specs of the data files (``vd_data_server.schema``)
PLAN = schema.Section({
    'name': schema.Name('plan name', refusal="invalid plan name (letters, digits, '_', '-', "
                        "'.'), found {value!r}"),
    'master': schema.Text('master file, relative to the plan (default: the bundled sample)',
                          required=False),
    'runs': schema.ListOf(schema.Section({
        'event': schema.Text('event name'),
        'models': schema.ListOf(schema.Text('model'), 'models (default: two_track)'),
        'configurations': schema.ListOf(schema.Text('configuration'),
                                        'configurations (default: all)', what='names',
                                        alternative='all'),
        'parameters': schema.ListOf(schema.Text('NAME=VALUE'), 'event parameters'),
        'overrides': schema.ListOf(schema.Text('GROUP.KEY=VALUE'), 'overrides of these runs'),
        'axle': schema.Text('axle of a K&C event: front or rear', required=False),
        'fidelity': schema.Text("K&C fidelity: rigid or flexible (default: the "
                                "configuration's flexible switch)", required=False),
    }), 'the runs', what='runs', required=True, non_empty=True),
    'measurements': schema.ListOf(schema.Text('bag path'),
                                  'bags of vd import, relative to the plan', what='bag paths'),
})


@dataclass(frozen=True)
class Plan:
    path: Path
    name: str
    master: Path
    runs: tuple[Mapping[str, Any], ...]
    measurements: tuple[Path, ...] = ()


def load_plan(path: Path) -> Plan:
    """Read and check a study plan (``PLAN``); every problem is reported."""
    raw = load_file(path, display=str(path))
    file = str(path)
    if not isinstance(raw, Mapping):
        raise DataError("expected a mapping with 'name' and 'runs'", file=file)
    col = Collector(file)
    check(PLAN, raw, '', col)
    col.raise_if_any()
    master = Path(raw['master']) if raw.get('master') else default_master()
    if raw.get('master') and not master.is_absolute():
        master = path.parent / master
    return Plan(path, raw['name'], master, tuple(raw['runs']), _measurements(raw, path))


def _measurements(raw: Mapping[str, Any], path: Path) -> tuple[Path, ...]:
    """Return the plan's ``measurements``: finished bags (vd import), relative to it."""
    given = raw.get('measurements') or []
    if not isinstance(given, list) or not all(isinstance(g, str) for g in given):
        raise DataError(f'expected a list of bag paths, found {given!r}', file=str(path),
                        key='measurements')
    bags = tuple(Path(g) if Path(g).is_absolute() else path.parent / g for g in given)
    for i, bag in enumerate(bags):
        if not (bag / 'metadata.yaml').is_file():
            raise DataError(f'{bag}: not a finished bag (vd import writes one)', file=str(path),
                            key=f'measurements[{i}]')
    return bags


def expand(plan: Plan, study: Study, bags: Path) -> list[RunRequest]:
    """
    Return the runs of ``plan``: one per model and configuration of each entry.

    A run without ``fidelity`` gets the configuration's (``results.run_fidelity``);
    the bag of a flexible run ends in ``_flexible``.
    """
    requests = []
    for run in plan.runs:
        configs = _get(run, 'configurations', 'all')
        configs = study.configuration_names if configs == 'all' else list(configs)
        axle = str(_get(run, 'axle', ''))
        asked = str(_get(run, 'fidelity', ''))
        overrides = tuple(str(o) for o in _get(run, 'overrides', []))
        parameters = tuple(str(p) for p in _get(run, 'parameters', []))
        for model in _get(run, 'models', ['two_track']):
            for config in configs:
                fidelity = run_fidelity(str(model), study.configurations.get(str(config)),
                                        asked)
                bag = bags / f"{run['event']}{'_' + axle if axle else ''}_{model}_{config}"
                if fidelity != 'rigid':
                    bag = bag.with_name(f'{bag.name}_{fidelity}')
                requests.append(RunRequest(
                    event=str(run['event']), configuration=str(config), model=str(model),
                    axle=axle, fidelity=fidelity, overrides=overrides, parameters=parameters,
                    bag=bag))
    return requests


def _get(run: Mapping[str, Any], key: str, default: Any) -> Any:
    """Return the value of ``key`` of a run; a key left blank is as if it were not there."""
    value = run.get(key)
    return default if value is None else value


def run_plan(plan: Plan, bags: Path, out: Path, *, distributed: bool = False,
             progress: Callable | None = None, namespace: str | None = None,
             on_done: Callable | None = None) -> dict[str, Any]:
    """
    Validate every run, then run them all; return the summary (``vd study --json``).

    ``on_done(RunOutcome)`` hears each run as soon as it is complete. ``finished``: the
    bags of the runs that finished and the plan's measurements, the input of the
    reports (``vd_events.reports.report.build_pages``).
    """
    study = load_study(plan.master)
    requests = expand(plan, study, bags)
    seen = set()
    checked = []
    for request in requests:
        try:
            checked.append(validate(study, request))
        except (RunError, BagError) as err:
            raise DataError(f'{request.label}: {err}', file=str(plan.path)) from None
        if request.bag in seen:
            raise DataError(f'two runs write the same bag {request.bag}', file=str(plan.path))
        seen.add(request.bag)
    requests = checked
    ns = namespace or DEFAULT_NAMESPACE
    if distributed:
        from vd_events.orchestration.runner import run_distributed

        results = run_distributed(plan.master, requests, progress, namespace=ns,
                                  on_done=on_done)
    else:
        results = run_inprocess(plan.master, requests, progress, namespace=ns,
                                study=study, on_done=on_done)
    done = [r for r in results if r.error is None]
    errors = [r.error for r in results if r.error is not None]
    return {
        'plan': str(plan.path), 'master': str(plan.master),
        'finished': [str(b) for b in [*(r.bag for r in done if r.bag), *plan.measurements]]
        if done else [],
        'bags': str(bags), 'errors': errors,
        'runs': [{'event': r.request.event, 'configuration': r.request.configuration,
                  'model': r.request.model, 'axle': r.request.axle,
                  'bag': str(r.bag) if r.bag else None,
                  'error': r.error,
                  'metrics': {k: {'value': m.value, 'unit': m.unit}
                              for k, m in (r.outcome.metrics.items() if r.outcome else [])}}
                 for r in results],
    }
