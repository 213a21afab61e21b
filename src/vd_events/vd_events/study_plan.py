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
        fidelity: flexible           # optional (K&C: rigid, the default, or flexible)
"""
from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path
import re
from typing import Any

from vd_data_server.errors import DataError
from vd_data_server.paths import default_master
from vd_data_server.study import load_study
from vd_data_server.yamlio import load_file

from .bag import BagError
from .runner import RunError, RunRequest, run_distributed, run_embedded, validate

RUN_KEYS = ('event', 'models', 'configurations', 'parameters', 'overrides', 'axle', 'fidelity')
_NAME = re.compile(r'^[A-Za-z0-9][A-Za-z0-9_.-]*$')


@dataclass(frozen=True)
class Plan:
    path: Path
    name: str
    master: Path
    runs: tuple[Mapping[str, Any], ...]


def load_plan(path: Path) -> Plan:
    raw = load_file(path, display=str(path))
    file = str(path)
    if not isinstance(raw, Mapping):
        raise DataError("expected a mapping with 'name' and 'runs'", file=file)
    for key in raw:
        if key not in ('name', 'master', 'runs'):
            raise DataError('unknown key (expected name, master, runs)', file=file, key=key)
    name = raw.get('name')
    if not isinstance(name, str) or not _NAME.match(name):
        raise DataError("missing or invalid plan name (letters, digits, '_', '-', '.')",
                        file=file, key='name')
    if raw.get('master') and not isinstance(raw['master'], str):
        raise DataError(f"expected a file path, found {raw['master']!r}", file=file,
                        key='master')
    master = Path(raw['master']) if raw.get('master') else default_master()
    if raw.get('master') and not master.is_absolute():
        master = path.parent / master
    runs = raw.get('runs')
    if not isinstance(runs, list) or not runs:
        raise DataError('expected a non-empty list of runs', file=file, key='runs')
    for i, run in enumerate(runs):
        if not isinstance(run, Mapping) or 'event' not in run:
            raise DataError("each run needs at least 'event'", file=file, key=f'runs[{i}]')
        for key in run:
            if key not in RUN_KEYS:
                raise DataError(f"unknown key (expected one of: {', '.join(RUN_KEYS)})",
                                file=file, key=f'runs[{i}].{key}')
        _check_run_types(run, file, f'runs[{i}]')
    return Plan(path, name, master, tuple(runs))


def _check_run_types(run: Mapping[str, Any], file: str, where: str) -> None:
    """
    Check that texts are where texts belong and lists of texts where lists do.

    ``configurations`` may also be ``all``; checked before anything iterates over them.
    """
    for key in ('event', 'axle'):
        if key in run and not isinstance(run[key], str):
            raise DataError(f'expected a text, found {run[key]!r}', file=file,
                            key=f'{where}.{key}')
    for key in ('models', 'configurations', 'parameters', 'overrides'):
        if key not in run or (key == 'configurations' and run[key] == 'all'):
            continue
        value = run[key]
        if not isinstance(value, list) or not all(isinstance(v, str) for v in value):
            expected = "'all' or a list of names" if key == 'configurations' else 'a list of texts'
            raise DataError(f'expected {expected}, found {value!r}', file=file,
                            key=f'{where}.{key}')


def expand(plan: Plan, names: list[str], bags: Path) -> list[RunRequest]:
    requests = []
    for i, run in enumerate(plan.runs):
        configs = run.get('configurations', 'all')
        configs = names if configs == 'all' else list(configs)
        for model in run.get('models', ['two_track']):
            for config in configs:
                axle = str(run.get('axle', ''))
                bag = bags / f"{run['event']}{'_' + axle if axle else ''}_{model}_{config}"
                fidelity = str(run.get('fidelity', 'rigid'))
                if fidelity != 'rigid':
                    bag = bag.with_name(f'{bag.name}_{fidelity}')
                requests.append(RunRequest(
                    event=str(run['event']), configuration=str(config), model=str(model),
                    axle=axle, fidelity=fidelity,
                    overrides=tuple(str(o) for o in run.get('overrides', [])),
                    parameters=tuple(str(p) for p in run.get('parameters', [])), bag=bag))
    return requests


def run_plan(plan: Plan, bags: Path, out: Path, *, distributed: bool = False,
             progress: Callable | None = None, namespace: str | None = None) -> dict[str, Any]:
    """Validate every run, then run them all, then build the report."""
    from .report import build_report

    study = load_study(plan.master)
    requests = expand(plan, study.configuration_names, bags)
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
    runner = run_distributed if distributed else run_embedded
    results = runner(plan.master, requests, progress,
                     **({'namespace': namespace} if namespace else {}))
    done = [r for r in results if r.error is None]
    errors = [r.error for r in results if r.error is not None]
    report = build_report([r.bag for r in done if r.bag], out) if done else None
    return {
        'plan': str(plan.path), 'master': str(plan.master), 'report': str(report),
        'bags': str(bags), 'errors': errors,
        'runs': [{'event': r.request.event, 'configuration': r.request.configuration,
                  'model': r.request.model, 'axle': r.request.axle,
                  'bag': str(r.bag) if r.bag else None,
                  'error': r.error,
                  'metrics': {k: {'value': m.value, 'unit': m.unit}
                              for k, m in (r.outcome.metrics.items() if r.outcome else [])}}
                 for r in results],
    }
