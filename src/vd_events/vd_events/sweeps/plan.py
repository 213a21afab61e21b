# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Sweep and optimisation plans: factors, a design, the runs of each point, responses.

A plan (``vd sweep PLAN.yaml``, ``vd optimize PLAN.yaml``; docs/sweeps.md)::

    name: front_geometry
    master: ../studies/sedan.yaml       # optional, relative to the plan; default: the sample
    configuration: baseline              # the configuration every point starts from
    design: full_factorial               # full_factorial | latin_hypercube | sobol
    samples: 16                          # latin_hypercube and sobol: number of points
    seed: 1                              # latin_hypercube and sobol (default 0)
    factors:
      lca_z:
        key: front_hardpoints.points.lca_outer.z   # any override key path
        unit: mm
        range: [165, 185]                # or: values: [165, 175, 185]
        levels: 3                        # full_factorial with a range
    runs:
      - {event: parallel_wheel_travel, axle: front, parameters: [steps=41]}
    responses:
      bump_steer:
        metric: bump_steer
        event: parallel_wheel_travel
        axle: front
        unit: deg/m
        target: 0 deg/m +- 1 deg/m        # optional: vd optimize reaches it
    pareto: {bump_steer: minimize, camber_gain: maximize}   # optional, two responses

Everything is checked here, before any run: unknown keys, factor keys that the base
configuration does not have, units of the wrong dimension, empty ranges, designs
that cannot take the levels or samples asked for. Factor values are kept in the
plan's units; the overrides sent to the solvers carry them with their unit.
"""
from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
import itertools
import math
from pathlib import Path
import re
from typing import Any, cast

import numpy as np
from scipy.stats import qmc

from vd_data_server.errors import DataError
from vd_data_server.model import Configuration, Value
from vd_data_server.paths import default_master
from vd_data_server.study import load_study
from vd_data_server.units import SI_UNITS, parse_unit, si_factor, ureg
from vd_data_server.yamlio import load_file
from vd_solvers.families import event_model

DESIGNS = ('full_factorial', 'latin_hypercube', 'sobol')
PLAN_KEYS = ('name', 'description', 'master', 'configuration', 'design', 'samples', 'seed',
             'factors', 'runs', 'responses', 'pareto', 'optimize')
FACTOR_KEYS = ('key', 'unit', 'range', 'values', 'levels', 'start')
RUN_KEYS = ('event', 'model', 'axle', 'fidelity', 'parameters')
RESPONSE_KEYS = ('metric', 'event', 'model', 'axle', 'unit', 'target', 'minimum', 'maximum')
OPTIMIZE_KEYS = ('method', 'max_evaluations', 'configuration', 'write_master')
SENSES = ('minimize', 'maximize')
METHODS = ('least_squares', 'slsqp', 'nelder_mead')
#: most levels of one factor in a full factorial design
MAX_LEVELS = 21
#: most design points of one plan (runs per point multiply it)
MAX_POINTS = 4096
#: most evaluations of one optimisation (each is one design point's runs)
MAX_EVALUATIONS = MAX_POINTS
#: fewest points of a sampled design (a regression needs more points than factors)
MIN_SAMPLES = 2
_NAME = re.compile(r'^[A-Za-z][A-Za-z0-9_]*$')
_PLAIN = re.compile(r'^[A-Za-z0-9][A-Za-z0-9_.-]*$')
_TARGET = re.compile(r'^(?P<value>[^±]+?)\s*(?:(?:\+-|±|\+/-)\s*(?P<tol>.+))?$')


@dataclass(frozen=True)
class Factor:
    """One factor: an override key path, its unit and its range or levels (plan units)."""

    name: str
    key: str
    unit: str
    low: float
    high: float
    values: tuple[float, ...] = ()  # explicit levels; () = the continuous range
    levels: int = 0  # full factorial over the range: this many equally spaced levels
    start: float | None = None  # optimisation start; None = the base configuration's value
    base: float = math.nan  # the base configuration's value, in ``unit``

    def override(self, value: float) -> str:
        """``GROUP.KEY=VALUE UNIT``, the override of one point."""
        return f'{self.key}={format_number(value)}{" " + self.unit if self.unit else ""}'

    def level_values(self) -> tuple[float, ...]:
        if self.values:
            return self.values
        return tuple(float(v) for v in np.linspace(self.low, self.high, self.levels))


@dataclass(frozen=True)
class RunSpec:
    """One run every design point makes (event on a model, axle, fidelity, parameters)."""

    event: str
    model: str
    axle: str = ''
    #: "" = the configuration's flexible switch (``results.run_fidelity``)
    fidelity: str = ''
    parameters: tuple[str, ...] = ()

    @property
    def label(self) -> str:
        return f"{self.event}{'/' + self.axle if self.axle else ''} ({self.model})"


@dataclass(frozen=True)
class Target:
    value: float  # response unit
    tolerance: float  # response unit, >= 0


@dataclass(frozen=True)
class Response:
    """A metric of one of the runs, reported in ``unit`` (converted with pint)."""

    name: str
    metric: str
    run: RunSpec
    unit: str
    target: Target | None = None
    minimum: float | None = None  # constraints for vd optimize, response unit
    maximum: float | None = None


@dataclass(frozen=True)
class OptimizeSpec:
    method: str = 'least_squares'
    max_evaluations: int = 60
    configuration: str = ''  # name of the configuration written; '' = <base>_<plan name>
    write_master: Path | None = None  # master file written; None = the plan's master
    #: write_master was named on the command line (vd optimize --write-master): it may lie
    #: anywhere; one from the plan file must lie under the study's data root
    named_by_user: bool = False


@dataclass(frozen=True)
class SweepPlan:
    path: Path
    name: str
    master: Path
    configuration: str
    design: str
    samples: int
    seed: int
    factors: tuple[Factor, ...]
    runs: tuple[RunSpec, ...]
    responses: tuple[Response, ...]
    pareto: tuple[tuple[str, str], ...] = ()
    optimize: OptimizeSpec | None = None
    description: str = ''


def format_number(value: float) -> str:
    """Write a float exactly enough to read back the same value (12 digits)."""
    return format(float(value), '.12g')


def convert(value: float, unit: str, to: str) -> float:
    """
    ``value`` in ``unit`` expressed in ``to``: pint, with angles told apart.

    pint counts the radian as dimensionless; vd does not convert ``deg/m`` to
    ``1/m``. ``''`` and ``'-'`` are dimensionless. ValueError on a mismatch.
    """
    src, dst = _unit(unit), _unit(to)
    if _radians(src) != _radians(dst):
        raise ValueError(f"unit '{unit or '-'}' cannot be converted to '{to or '-'}'")
    try:
        return float(ureg().Quantity(value, src).to(dst).magnitude)
    except Exception as err:  # noqa: BLE001 - pint's DimensionalityError and kin
        raise ValueError(f"unit '{unit or '-'}' cannot be converted to '{to or '-'}'") from err


def _unit(text: str):
    return ureg().dimensionless if text in ('', '-') else parse_unit(text)


def _radians(unit) -> int:
    return cast(int, dict(ureg().Quantity(1.0, unit).to_root_units().unit_items()).get(
        'radian', 0))


def read_quantity(text: Any, unit: str, *, file: str, key: str) -> float:
    """Read a plan number: bare (in ``unit``) or ``"171 mm"`` (converted to ``unit``)."""
    if isinstance(text, bool) or not isinstance(text, (int, float, str)):
        raise DataError(f'expected a number, found {text!r}', file=file, key=key)
    if isinstance(text, (int, float)):
        number = float(text)
    else:
        parts = re.match(r'^\s*([+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)\s*(.*?)\s*$', text)
        if not parts:
            raise DataError(f'expected a number with a unit, found {text!r}', file=file,
                            key=key)
        number = float(parts.group(1))
        if parts.group(2):
            try:
                number = convert(number, parts.group(2), unit)
            except ValueError as err:
                raise DataError(f'{err} (the unit of this value)', file=file, key=key) from None
    if not math.isfinite(number):
        raise DataError(f'value must be finite, found {text!r}', file=file, key=key)
    return number


def load_plan(path: Path, study=None, *, optimize: bool = False) -> SweepPlan:
    """
    Read and check a plan against its master file's configuration.

    ``study`` (the loaded master file) may be passed to save loading it again.
    ``optimize``: a plan for ``vd optimize``, which needs no design (its factors
    are ranges; a ``design`` given is checked all the same). DataError naming the
    plan file and key on any problem.
    """
    file = str(path)
    raw = load_file(path, display=file)
    if not isinstance(raw, Mapping):
        raise DataError("expected a mapping with 'name', 'factors', 'runs' and 'responses'",
                        file=file)
    _known(raw, PLAN_KEYS, file, '')
    name = raw.get('name')
    if not isinstance(name, str) or not _PLAIN.match(name):
        raise DataError("missing or invalid plan name (letters, digits, '_', '-', '.')",
                        file=file, key='name')
    master = default_master()
    if raw.get('master') is not None:
        if not isinstance(raw['master'], str) or not raw['master']:
            raise DataError(f"expected a file path, found {raw['master']!r}", file=file,
                            key='master')
        master = Path(raw['master'])
        master = master if master.is_absolute() else path.parent / master
    study = study if study is not None else load_study(master)
    base_name = raw.get('configuration', study.configuration_names[0])
    if base_name not in study.configurations:
        raise DataError(f"configuration {base_name!r} does not exist in {master} (available: "
                        f"{', '.join(study.configuration_names)})", file=file,
                        key='configuration')
    base = study.configurations[base_name]
    design = raw.get('design', '' if optimize else 'full_factorial')
    if design != '' and design not in DESIGNS:
        raise DataError(f"unknown design {design!r} (designs: {', '.join(DESIGNS)})",
                        file=file, key='design')
    factors = parse_factors(raw.get('factors'), base, design, file)
    samples, seed = _samples(raw, design, factors, file)
    runs = _runs(raw.get('runs'), file)
    responses = _responses(raw.get('responses'), runs, file)
    pareto = _pareto(raw.get('pareto'), responses, file)
    optimize_spec = _optimize(raw.get('optimize'), path, file)
    plan = SweepPlan(path=path, name=name, master=master, configuration=base_name,
                     design=design, samples=samples, seed=seed, factors=factors, runs=runs,
                     responses=responses, pareto=pareto, optimize=optimize_spec,
                     description=str(raw.get('description', '')))
    n = len(points(plan)) if design == 'full_factorial' else samples
    if design and n > MAX_POINTS:
        raise DataError(f'the design has {n} points, more than the limit of {MAX_POINTS}',
                        file=file, key='factors' if design == 'full_factorial' else 'samples')
    return plan


def _known(raw: Mapping, keys: Sequence[str], file: str, where: str) -> None:
    for key in raw:
        if key not in keys:
            raise DataError(f"unknown key (expected one of: {', '.join(keys)})", file=file,
                            key=f'{where}{key}')


def _mapping(value: Any, file: str, key: str, what: str) -> Mapping:
    if not isinstance(value, Mapping) or not value:
        raise DataError(f'expected a non-empty mapping of {what}', file=file, key=key)
    return value


def base_value(config: Configuration, key: str, *, file: str, where: str) -> tuple[float, str]:
    """
    Return the base configuration's value of key ``GROUP.KEY`` in SI, and its quantity.

    Hard-point coordinates (``...points.NAME.z``) are lengths.
    """
    group_name, _, inner = key.partition('.')
    if group_name not in config.groups or not inner:
        raise DataError(f"unknown group {group_name!r} in key {key!r} (groups of "
                        f"'{config.name}': {', '.join(config.groups)}); write GROUP.KEY",
                        file=file, key=where)
    group = config.groups[group_name]
    coord = None
    given = inner
    if inner not in group.values and inner[-2:] in ('.x', '.y', '.z'):
        inner, coord = inner[:-2], 'xyz'.index(inner[-1])
    value: Value | None = group.values.get(inner)
    if value is None:
        raise DataError(f"key {given!r} does not exist in group '{group_name}' ({group.file}); "
                        f"keys: {', '.join(sorted(group.values))}", file=file, key=where)
    if coord is not None:
        if value.type != 'point':
            raise DataError(f"'{inner}' is a {value.type}, not a point", file=file, key=where)
        return float(cast(tuple[float, ...], value.si)[coord]), 'length'
    if value.type != 'scalar':
        raise DataError(f"'{inner}' is a {value.type}: a factor must be a number (a scalar or "
                        "one coordinate '.x', '.y', '.z' of a point)", file=file, key=where)
    quantity = next((q for q, u in SI_UNITS.items() if u == value.unit), None)
    if quantity is None:
        raise DataError(f'values in {value.unit} cannot be overridden', file=file, key=where)
    return float(value.si), quantity  # type: ignore[arg-type]


def parse_factors(raw: Any, base: Configuration, design: str, file: str,
                  section: str = 'factors') -> tuple[Factor, ...]:
    """Read a plan's factors (``section``: factors, or the parameters of vd identify)."""
    out = []
    keys_seen: set[str] = set()
    for name, spec in _mapping(raw, file, section, section).items():
        where = f'{section}.{name}'
        if not _NAME.match(str(name)):
            raise DataError('factor names are letters, digits and _ (a letter first)',
                            file=file, key=where)
        if not isinstance(spec, Mapping):
            raise DataError("expected a mapping with 'key' and 'range' or 'values'", file=file,
                            key=where)
        _known(spec, FACTOR_KEYS, file, f'{where}.')
        key = spec.get('key')
        if not isinstance(key, str) or not key:
            raise DataError('expected an override key path GROUP.KEY', file=file,
                            key=f'{where}.key')
        if key in keys_seen:
            raise DataError(f'key {key!r} is already a factor', file=file, key=f'{where}.key')
        keys_seen.add(key)
        si, quantity = base_value(base, key, file=file, where=f'{where}.key')
        unit = spec.get('unit', '')
        if not isinstance(unit, str):
            raise DataError(f'expected a unit, found {unit!r}', file=file, key=f'{where}.unit')
        if not unit and quantity != 'dimensionless':
            raise DataError(f"{key} is {'an' if quantity[0] in 'aeiou' else 'a'} "
                            f"{quantity.replace('_', ' ')}: give the factor's unit (e.g. "
                            f"'{SI_UNITS[quantity]}')", file=file, key=f'{where}.unit')
        try:
            factor_si = si_factor(unit, quantity)
        except ValueError as err:
            raise DataError(f'{err}, as {key} is', file=file, key=f'{where}.unit') from None
        out.append(_levels(spec, name, key, unit, si / factor_si, design, file, where))
    return tuple(out)


def _levels(spec: Mapping, name: str, key: str, unit: str, base: float, design: str,
            file: str, where: str) -> Factor:
    has_range, has_values = 'range' in spec, 'values' in spec
    if has_range == has_values:
        raise DataError('give exactly one of: range, values', file=file, key=where)
    start = (read_quantity(spec['start'], unit, file=file, key=f'{where}.start')
             if 'start' in spec else None)
    if has_values:
        raw = spec['values']
        if not isinstance(raw, list) or not raw:
            raise DataError('empty list of values', file=file, key=f'{where}.values')
        values = tuple(read_quantity(v, unit, file=file, key=f'{where}.values[{i}]')
                       for i, v in enumerate(raw))
        if len(set(values)) != len(values):
            raise DataError('the values repeat a level', file=file, key=f'{where}.values')
        if len(values) < 2:
            raise DataError('a factor needs at least 2 levels', file=file, key=f'{where}.values')
        if design and design != 'full_factorial':
            raise DataError(f"design '{design}' samples continuous ranges: give this factor a "
                            "range, not levels", file=file, key=f'{where}.values')
        if 'levels' in spec:
            raise DataError("'levels' goes with a range; these values are the levels",
                            file=file, key=f'{where}.levels')
        if len(values) > MAX_LEVELS:
            raise DataError(f'{len(values)} levels, more than the limit of {MAX_LEVELS} of a '
                            'full factorial design', file=file, key=f'{where}.values')
        return Factor(name, key, unit, min(values), max(values), values, 0, start, base)
    raw = spec['range']
    if not isinstance(raw, list) or len(raw) != 2:
        raise DataError('expected [low, high]', file=file, key=f'{where}.range')
    low, high = (read_quantity(v, unit, file=file, key=f'{where}.range[{i}]')
                 for i, v in enumerate(raw))
    if not low < high:
        raise DataError(f'empty range [{format_number(low)}, {format_number(high)}] (low must be '
                        'below high)', file=file, key=f'{where}.range')
    if start is not None and not low <= start <= high:
        raise DataError(f'start {format_number(start)} is outside the range', file=file,
                        key=f'{where}.start')
    levels = 0
    if design == 'full_factorial':
        raw_levels = spec.get('levels')
        if isinstance(raw_levels, bool) or not isinstance(raw_levels, int):
            raise DataError('a full factorial design needs the number of levels of a range '
                            '(an integer, at least 2)', file=file, key=f'{where}.levels')
        levels = raw_levels
        if levels < 2:
            raise DataError(f'{levels} levels: at least 2', file=file, key=f'{where}.levels')
        if levels > MAX_LEVELS:
            raise DataError(f'{levels} levels, more than the limit of {MAX_LEVELS} of a full '
                            'factorial design', file=file, key=f'{where}.levels')
    elif design and 'levels' in spec:
        raise DataError(f"design '{design}' takes 'samples' for the whole plan, not levels per "
                        'factor', file=file, key=f'{where}.levels')
    return Factor(name, key, unit, low, high, (), levels, start, base)


def _samples(raw: Mapping, design: str, factors: Sequence[Factor], file: str) -> tuple[int, int]:
    seed = raw.get('seed', 0)
    if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
        raise DataError(f'expected a non-negative integer, found {seed!r}', file=file,
                        key='seed')
    if not design:
        return 0, seed
    if design == 'full_factorial':
        if 'samples' in raw:
            raise DataError("a full factorial design has the product of the levels as its "
                            "points; 'samples' is for latin_hypercube and sobol", file=file,
                            key='samples')
        return 0, seed
    samples = raw.get('samples')
    if isinstance(samples, bool) or not isinstance(samples, int):
        raise DataError(f"design '{design}' needs 'samples' (an integer)", file=file,
                        key='samples')
    if samples < MIN_SAMPLES:
        raise DataError(f'{samples} samples: at least {MIN_SAMPLES}', file=file, key='samples')
    if design == 'sobol' and samples & (samples - 1):
        raise DataError(f'{samples} samples: a Sobol sequence is balanced only for a power of '
                        f'2 (e.g. {1 << (samples.bit_length() - 1)} or '
                        f'{1 << samples.bit_length()})', file=file, key='samples')
    if samples > MAX_POINTS:
        raise DataError(f'{samples} samples, more than the limit of {MAX_POINTS}', file=file,
                        key='samples')
    return samples, seed


def _texts(value: Any, file: str, key: str) -> tuple[str, ...]:
    if not isinstance(value, list) or not all(isinstance(v, str) for v in value):
        raise DataError(f'expected a list of texts, found {value!r}', file=file, key=key)
    return tuple(value)


def _runs(raw: Any, file: str) -> tuple[RunSpec, ...]:

    if not isinstance(raw, list) or not raw:
        raise DataError('expected a non-empty list of runs', file=file, key='runs')
    out = []
    for i, run in enumerate(raw):
        where = f'runs[{i}]'
        if not isinstance(run, Mapping) or not isinstance(run.get('event'), str):
            raise DataError("each run needs at least 'event'", file=file, key=where)
        _known(run, RUN_KEYS, file, f'{where}.')
        for key in ('model', 'axle', 'fidelity'):
            if key in run and not isinstance(run[key], str):
                raise DataError(f'expected a text, found {run[key]!r}', file=file,
                                key=f'{where}.{key}')
        spec = RunSpec(event=run['event'], model=run.get('model') or event_model(run['event']),
                       axle=run.get('axle', ''), fidelity=run.get('fidelity', ''),
                       parameters=_texts(run.get('parameters', []), file, f'{where}.parameters'))
        if spec in out:
            raise DataError(f'the run {spec.label} is already in the plan', file=file, key=where)
        out.append(spec)
    return tuple(out)


def _responses(raw: Any, runs: Sequence[RunSpec], file: str) -> tuple[Response, ...]:
    out = []
    for name, spec in _mapping(raw, file, 'responses', 'responses').items():
        where = f'responses.{name}'
        if not _NAME.match(str(name)):
            raise DataError('response names are letters, digits and _ (a letter first)',
                            file=file, key=where)
        if not isinstance(spec, Mapping):
            raise DataError("expected a mapping with 'metric' and 'event'", file=file,
                            key=where)
        _known(spec, RESPONSE_KEYS, file, f'{where}.')
        metric = spec.get('metric', name)
        if not isinstance(metric, str) or not metric:
            raise DataError('expected a metric name', file=file, key=f'{where}.metric')
        run = _response_run(spec, runs, file, where)
        unit = spec.get('unit', '')
        if not isinstance(unit, str):
            raise DataError(f'expected a unit, found {unit!r}', file=file, key=f'{where}.unit')
        try:
            _unit(unit)
        except ValueError as err:
            raise DataError(str(err), file=file, key=f'{where}.unit') from None
        target = None
        if spec.get('target') is not None:
            target = _target(spec['target'], unit, file, f'{where}.target')
        bounds = {k: read_quantity(spec[k], unit, file=file, key=f'{where}.{k}')
                  for k in ('minimum', 'maximum') if spec.get(k) is not None}
        if len(bounds) == 2 and not bounds['minimum'] < bounds['maximum']:
            raise DataError('empty range: minimum must be below maximum', file=file,
                            key=f'{where}.maximum')
        out.append(Response(str(name), metric, run, unit, target, bounds.get('minimum'),
                            bounds.get('maximum')))
    return tuple(out)


def _response_run(spec: Mapping, runs: Sequence[RunSpec], file: str, where: str) -> RunSpec:
    event = spec.get('event')
    matches = [r for r in runs if r.event == event
               and all(spec.get(k) in (None, getattr(r, k)) for k in ('model', 'axle'))]
    if not matches:
        known = ', '.join(r.label for r in runs)
        raise DataError(f'no run of the plan matches event {event!r}'
                        + ''.join(f', {k} {spec[k]!r}' for k in ('model', 'axle') if k in spec)
                        + f' (runs: {known})', file=file, key=f'{where}.event')
    if len(matches) > 1:
        raise DataError(f"several runs match ({', '.join(r.label for r in matches)}): name "
                        "the axle or model", file=file, key=where)
    return matches[0]


def _target(raw: Any, unit: str, file: str, key: str) -> Target:
    """``0 deg/m +- 1 deg/m`` (or ``±``); a bare number in the response's unit."""
    if isinstance(raw, (int, float)) and not isinstance(raw, bool):
        return Target(float(raw), 0.0)
    match = _TARGET.match(str(raw).strip()) if isinstance(raw, str) else None
    if not match:
        raise DataError(f"expected 'VALUE UNIT +- TOLERANCE UNIT', found {raw!r}", file=file,
                        key=key)
    value = read_quantity(match.group('value'), unit, file=file, key=key)
    tol = (read_quantity(match.group('tol'), unit, file=file, key=key)
           if match.group('tol') else 0.0)
    if tol < 0:
        raise DataError(f'the tolerance must not be negative, found {raw!r}', file=file, key=key)
    return Target(value, tol)


def _pareto(raw: Any, responses: Sequence[Response], file: str) -> tuple[tuple[str, str], ...]:
    if raw is None:
        return ()
    if not isinstance(raw, Mapping) or len(raw) != 2:
        raise DataError('expected two responses, each minimize or maximize', file=file,
                        key='pareto')
    names = {r.name for r in responses}
    for name, sense in raw.items():
        if name not in names:
            raise DataError(f"unknown response (responses: {', '.join(sorted(names))})",
                            file=file, key=f'pareto.{name}')
        if sense not in SENSES:
            raise DataError(f'expected minimize or maximize, found {sense!r}', file=file,
                            key=f'pareto.{name}')
    return tuple((str(k), str(v)) for k, v in raw.items())


def _optimize(raw: Any, path: Path, file: str) -> OptimizeSpec | None:
    if raw is None:
        return None
    if not isinstance(raw, Mapping):
        raise DataError('expected a mapping', file=file, key='optimize')
    _known(raw, OPTIMIZE_KEYS, file, 'optimize.')
    method = raw.get('method', 'least_squares')
    if method not in METHODS:
        raise DataError(f"unknown method {method!r} (methods: {', '.join(METHODS)})",
                        file=file, key='optimize.method')
    evals = raw.get('max_evaluations', 60)
    if isinstance(evals, bool) or not isinstance(evals, int) or not 1 <= evals <= MAX_EVALUATIONS:
        raise DataError(f'expected a whole number 1..{MAX_EVALUATIONS}, found {evals!r}',
                        file=file, key='optimize.max_evaluations')
    name = raw.get('configuration', '')
    if name and (not isinstance(name, str) or not _PLAIN.match(name)):
        raise DataError('a configuration name is letters, digits, _, - and .', file=file,
                        key='optimize.configuration')
    write = raw.get('write_master')
    if write is not None and (not isinstance(write, str) or not write):
        raise DataError(f'expected a file path, found {write!r}', file=file,
                        key='optimize.write_master')
    target = None
    if write:
        target = Path(write) if Path(write).is_absolute() else path.parent / write
    return OptimizeSpec(method, evals, name, target)


def points(plan: SweepPlan) -> list[tuple[float, ...]]:
    """
    Return the design's points, one value per factor (plan units), in run order.

    Full factorial: every combination of the levels (the last factor varies
    fastest). Latin hypercube and Sobol: ``scipy.stats.qmc`` on the unit cube,
    scaled to the ranges; reproducible with ``seed`` (Sobol scrambled).
    """
    if not plan.design:
        raise ValueError(f'{plan.path}: the plan has no design (an optimisation plan)')
    if plan.design == 'full_factorial':
        return [tuple(p) for p in itertools.product(*(f.level_values() for f in plan.factors))]

    d = len(plan.factors)
    if plan.design == 'latin_hypercube':
        unit = qmc.LatinHypercube(d=d, seed=plan.seed).random(plan.samples)
    else:
        unit = qmc.Sobol(d=d, scramble=True, seed=plan.seed).random(plan.samples)
    scaled = qmc.scale(unit, [f.low for f in plan.factors], [f.high for f in plan.factors])
    return [tuple(float(v) for v in row) for row in scaled]


__all__ = ['SweepPlan', 'Factor', 'RunSpec', 'Response', 'Target', 'OptimizeSpec',
           'load_plan', 'points', 'convert', 'format_number', 'parse_factors', 'read_quantity',
           'base_value', 'DESIGNS', 'MAX_LEVELS', 'MAX_POINTS', 'MAX_EVALUATIONS']
