# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
``vd identify PLAN.yaml``: a configuration's parameters fitted to measured logs.

A plan (docs/testdata.md)::

    name: sedan_lateral
    master: ../studies/sedan.yaml      # optional, relative to the plan; default: the sample
    configuration: baseline            # the base configuration
    model: bicycle                     # bicycle | two_track | vehicle
    logs: [logs/run1, {path: run2.vbo, map: vbox.map.yaml}]  # imported bags (vd import), or
    map: logs/logger.map.yaml          #   log files read and checked as vd import reads them
                                       #   (with their own column map or the plan's)
    validate: [logs/run3]              # optional: predicted, not fitted (cross-validation)
    method: iso22140                   # optional: the correlation of the prediction
    parameters:                        # any override key, with its range (the bounds)
      front_cornering: {key: front_tire.tir.SCALING_COEFFICIENTS.LKY, range: [0.6, 1.4]}
      yaw_inertia: {key: mass.sprung_inertia.izz, unit: kg*m^2, range: [2000, 3500]}
    channels:                          # compared channels, weight and scale (optional)
      yaw_rate: {weight: 1.0, scale: 1 deg/s}
      lateral_acceleration: {weight: 1.0}
    output: {configuration: baseline_identified, write_master: out/identified.yaml}

The parameters take the sweep factors' form (:func:`vd_events.sweeps.plan.parse_factors`:
``key``, ``unit``, ``range``, ``start``). Every log's inputs (steering-wheel angle and
speed) drive the model; the residuals are ``weight * (model - log) / scale`` of every
channel at every logged sample (``scale`` by default the channel's standard deviation
over the logs, so channels of different units weigh alike). A gap in a log is replayed
with the inputs linear across it; the SETTLE s after it, where the model's state still
carries that guess, are left out of the residuals. Models:

* ``bicycle``: the open-loop replay of :mod:`vd_solvers.analytical.replay` (yaw rate,
  lateral acceleration, sideslip). The K&C-derived axle properties and the steering ratio
  are those of the base configuration, computed once: parameters of the suspension need
  the ``vehicle`` model.
* ``two_track``: the two-track steady state (:mod:`vd_solvers.analytical.two_track`) at
  each logged point's lateral acceleration on the radius it drives (speed / yaw rate):
  steering-wheel angle (road-wheel angle times the steering ratio) and roll. A model of
  steady-state logs: points below MIN_LATERAL are left out.
* ``vehicle``: the full-vehicle replay (:mod:`vd_solvers.vehicle.replay`); allowed, slow
  (the K&C maps are rebuilt for every new parameter set).

The fit is ``scipy.optimize.least_squares`` (trust-region reflective, the parameters
scaled to [0, 1] over their ranges, bounds kept). At the solution the Jacobian J is
taken by central differences of FD_STEP of each range; the covariance of the fitted
values is ``sigma^2 (J^T J)^-1`` with sigma^2 = (sum of squared residuals) / (n - p)
(Gauss-Newton, e.g. Seber and Wild, Nonlinear Regression, 2003, sec. 2.1), their
standard errors its diagonal's roots, their correlations the covariance normalised.
Identifiability: the singular values of J with unit-norm columns give the numerical rank
(above RANK_TOLERANCE of the largest) and the condition number; a pair of parameters
whose correlation exceeds PAIR_CORRELATION in magnitude is flagged: the logs determine a
combination of the two, not each.

Logs that fail the import checks of ``vd import`` (:mod:`.importer`: glitches, signs,
units...) are refused, every one named. The result is written as a new configuration of
a master file (the base configuration's copy with the fitted values as overrides, the
plan's and the logs' SHA-256 in its description) through
:func:`vd_data_server.masteredit.edit_master` (validated, atomic); an existing
configuration is never overwritten.
"""
from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
import hashlib
import math
import os
from pathlib import Path
import time
from typing import Any

import numpy as np
from scipy import optimize as so

from vd_data_server.errors import DataError
from vd_data_server.master import with_overrides
from vd_data_server.masteredit import Edit, edit_master, load_document, write_master
from vd_data_server.model import Configuration
from vd_data_server.paths import default_master
from vd_data_server.study import load_study
from vd_data_server.yamlio import load_file
from vd_events.errors import InputError
from vd_events.measured.checks import segments
from vd_events.measured.compare import INPUTS_NOTE, REPLAY_NOTE
from vd_events.measured.correlate import Correlation, correlate, load_bands
from vd_events.measured.grade import load_inputs
from vd_events.measured.importer import ImportOptions
from vd_events.measured.replay import UNITS, replay_outcomes
from vd_events.sweeps.plan import Factor, format_number, parse_factors, read_quantity
from vd_solvers.analytical import two_track
from vd_solvers.analytical.from_config import static_wheel_loads, vehicle_params
from vd_solvers.analytical.kc_link import try_kc_inputs
from vd_solvers.analytical.replay import replay_bicycle
from vd_solvers.errors import SolverError
from vd_solvers.results import Channel, EventOutcome
from vd_solvers.vehicle.maps import suspension_maps

MODELS = ('bicycle', 'two_track', 'vehicle')
#: what each model takes from a log (not compared)
INPUTS = {'bicycle': ('steering_wheel_angle', 'speed'),
          'two_track': ('speed', 'yaw_rate', 'lateral_acceleration'),
          'vehicle': ('steering_wheel_angle', 'speed')}
#: the channels each model predicts
PREDICTS = {'bicycle': ('yaw_rate', 'lateral_acceleration', 'sideslip'),
            'two_track': ('steering_wheel_angle', 'roll'),
            'vehicle': ('yaw_rate', 'lateral_acceleration', 'sideslip', 'roll')}
PLAN_KEYS = ('name', 'description', 'master', 'configuration', 'model', 'logs', 'map',
             'validate', 'method', 'force', 'parameters', 'channels', 'output', 'max_evaluations')
CHANNEL_KEYS = ('weight', 'scale')
OUTPUT_KEYS = ('configuration', 'write_master')
#: the Jacobian's central-difference step, as a fraction of each parameter's range
FD_STEP = 1e-3
#: singular values below this fraction of the largest count as zero (numerical rank)
RANK_TOLERANCE = 1e-8
#: parameters correlated beyond this are reported as not identifiable apart
PAIR_CORRELATION = 0.95
#: s after a gap left out of the residuals of a dynamic model: its state across the gap
#: (the inputs interpolated over it) is a guess that has decayed after this time (the
#: yaw mode's time constant is 0.1-0.3 s in the linear range)
SETTLE = 1.0
#: two-track points: least |lateral acceleration| (m/s^2) and yaw rate (rad/s) of a point
MIN_LATERAL = 0.5
MIN_YAW_RATE = 0.01
#: two-track points kept per log (evenly spread): the steady state is solved per point
MAX_POINTS = 200
MAX_EVALUATIONS = 100


@dataclass(frozen=True)
class ChannelWeight:
    channel: str
    weight: float
    scale: float | None  # SI; None: the channel's standard deviation over the logs


@dataclass(frozen=True)
class IdentifyPlan:
    path: Path
    name: str
    master: Path
    configuration: str
    model: str
    logs: tuple[tuple[Path, Path | None], ...]  # (log, its column map)
    validate: tuple[tuple[Path, Path | None], ...]
    method: str | None
    force: bool
    parameters: tuple[Factor, ...]
    channels: tuple[ChannelWeight, ...]
    output_configuration: str
    write_master: Path
    max_evaluations: int = MAX_EVALUATIONS
    description: str = ''


def _paths(raw: Any, plan: Path, key: str, map_path: Path | None, *, required: bool
           ) -> tuple[tuple[Path, Path | None], ...]:
    """Each log (a path, or ``{path, map}``) with its column map, relative to the plan."""
    if raw is None and not required:
        return ()
    if not isinstance(raw, list) or not raw:
        raise DataError('expected a list of log files or bags', file=str(plan), key=key)
    out = []
    for i, item in enumerate(raw):
        own = map_path
        if isinstance(item, Mapping) and set(item) <= {'path', 'map'} and 'path' in item:
            own = _relative(plan, item['map']) if item.get('map') else map_path
            item = item['path']
        if not isinstance(item, str) or not item:
            raise DataError('expected a log file or bag path, or {path, map}', file=str(plan),
                            key=f'{key}[{i}]')
        out.append((_relative(plan, item), own))
    return tuple(out)


def _relative(plan: Path, text: Any) -> Path:
    path = Path(str(text))
    return path if path.is_absolute() else plan.parent / path


def load_identify_plan(path: Path, study=None) -> IdentifyPlan:
    """Read and check a plan (module doc); DataError naming the plan file and key."""
    file = str(path)
    raw = load_file(path, display=file)
    if not isinstance(raw, Mapping):
        raise DataError("expected a mapping with 'name', 'logs', 'parameters'", file=file)
    for key in raw:
        if key not in PLAN_KEYS:
            raise DataError(f"unknown key (expected one of: {', '.join(PLAN_KEYS)})",
                            file=file, key=str(key))
    name = raw.get('name')
    if not isinstance(name, str) or not name.replace('_', '').replace('-', '').isalnum():
        raise DataError("missing or invalid plan name (letters, digits, '_', '-')", file=file,
                        key='name')
    master = default_master()
    if raw.get('master') is not None:
        master = Path(str(raw['master']))
        master = master if master.is_absolute() else path.parent / master
    study = study if study is not None else load_study(master)
    base = raw.get('configuration', study.configuration_names[0])
    if base not in study.configurations:
        raise DataError(f"configuration {base!r} does not exist in {master} (available: "
                        f"{', '.join(study.configuration_names)})", file=file,
                        key='configuration')
    model = raw.get('model', 'bicycle')
    if model not in MODELS:
        raise DataError(f"unknown model {model!r} (models: {', '.join(MODELS)})", file=file,
                        key='model')
    parameters = parse_factors(raw.get('parameters'), study.configurations[base], '', file,
                               section='parameters')
    for f in parameters:
        if f.values:
            raise DataError('a parameter is fitted over a range, not levels', file=file,
                            key=f'parameters.{f.name}')
    channels = _channels(raw.get('channels'), model, file)
    method = raw.get('method')
    if method is not None and method not in ('iso19364', 'iso19365', 'iso22140'):
        raise DataError(f'unknown method {method!r} (iso19364, iso19365, iso22140)', file=file,
                        key='method')
    output = raw.get('output') or {}
    if not isinstance(output, Mapping):
        raise DataError('expected a mapping with configuration and write_master', file=file,
                        key='output')
    for key in output:
        if key not in OUTPUT_KEYS:
            raise DataError(f"unknown key (expected one of: {', '.join(OUTPUT_KEYS)})",
                            file=file, key=f'output.{key}')
    target = Path(str(output['write_master'])) if output.get('write_master') else master
    target = target if target.is_absolute() else path.parent / target
    budget = raw.get('max_evaluations', MAX_EVALUATIONS)
    if not isinstance(budget, int) or isinstance(budget, bool) or budget < 2:
        raise DataError(f'expected an integer >= 2, found {budget!r}', file=file,
                        key='max_evaluations')
    map_path = _relative(path, raw['map']) if raw.get('map') is not None else None
    return IdentifyPlan(
        path=path, name=name, master=master, configuration=base, model=model,
        logs=_paths(raw.get('logs'), path, 'logs', map_path, required=True),
        validate=_paths(raw.get('validate'), path, 'validate', map_path, required=False),
        method=method, force=bool(raw.get('force', False)),
        parameters=parameters, channels=channels,
        output_configuration=str(output.get('configuration') or f'{base}_{name}'),
        write_master=target, max_evaluations=budget,
        description=str(raw.get('description', '')))


def _channels(raw: Any, model: str, file: str) -> tuple[ChannelWeight, ...]:
    if raw is None:
        return tuple(ChannelWeight(c, 1.0, None) for c in PREDICTS[model])
    if not isinstance(raw, Mapping) or not raw:
        raise DataError('expected channel: {weight, scale}', file=file, key='channels')
    out = []
    for channel, spec in raw.items():
        where = f'channels.{channel}'
        if channel not in PREDICTS[model]:
            raise DataError(f"model {model} predicts {', '.join(PREDICTS[model])}", file=file,
                            key=where)
        spec = spec or {}
        if not isinstance(spec, Mapping):
            raise DataError('expected {weight, scale}', file=file, key=where)
        for key in spec:
            if key not in CHANNEL_KEYS:
                raise DataError(f"unknown key (expected one of: {', '.join(CHANNEL_KEYS)})",
                                file=file, key=f'{where}.{key}')
        weight = read_quantity(spec.get('weight', 1.0), '', file=file, key=f'{where}.weight')
        if not weight > 0.0:
            raise DataError('a weight is positive', file=file, key=f'{where}.weight')
        scale = None
        if 'scale' in spec:
            scale = read_quantity(spec['scale'], UNITS[channel], file=file,
                                  key=f'{where}.scale')
            if not scale > 0.0:
                raise DataError('a scale is positive', file=file, key=f'{where}.scale')
        out.append(ChannelWeight(str(channel), weight, scale))
    return tuple(out)


def sha256(path: Path) -> str:
    """Return the SHA-256 of a file, or of every file of a folder (a bag) in name order."""
    digest = hashlib.sha256()
    files = sorted(p for p in path.rglob('*') if p.is_file()) if path.is_dir() else [path]
    for p in files:
        digest.update(p.name.encode('utf-8'))
        digest.update(p.read_bytes())
    return digest.hexdigest()


def load_logs(paths: Sequence[tuple[Path, Path | None]], where: str | Path
              ) -> list[tuple[Path, EventOutcome]]:
    """
    Every vehicle log of ``paths``, read and checked as ``vd import`` does.

    A log that fails the checks (or a bag without a vehicle log) is refused; the error
    names every such log, not only the first.
    """
    out: list[tuple[Path, EventOutcome]] = []
    refused = []
    for path, map_path in paths:
        try:
            found = [o for _, o in load_inputs([path], map_path, ImportOptions())
                     if o.model == 'test']
            if not found:
                raise InputError(path, 'no vehicle log (model test) in it')
        except DataError as err:
            refused.append(str(err))
            continue
        out += [(path, o) for o in found]
    if refused:
        raise InputError(where, f'{len(refused)} log(s) failed the import checks '
                         'and are not used: ' + ' | '.join(refused))
    return out


class Predictor:
    """One model of one base configuration: what every evaluation shares (module doc)."""

    def __init__(self, base: Configuration, model: str) -> None:
        self.base = base
        self.model = model
        self.kc: Any = None
        self.ratio = math.nan
        self.ratio_source = ''
        if model in ('bicycle', 'two_track'):
            kc = try_kc_inputs(base, static_wheel_loads(base))
            self.kc = None if isinstance(kc, str) else kc
            maps = suspension_maps(base)
            self.ratio = maps.steering_ratio
            self.ratio_source = maps.provenance['steering']

    def configuration(self, overrides: Mapping[str, str]) -> Configuration:
        try:
            return with_overrides(self.base, overrides, source='vd identify')
        except DataError as err:
            raise InputError('parameters', str(err)) from None

    def params(self, config: Configuration):
        if self.kc is None:
            return vehicle_params(config)
        return vehicle_params(config, self.kc.suspension, self.kc.compliance)

    def predict(self, config: Configuration, log: EventOutcome) -> dict[str, np.ndarray]:
        """Return the model's channels at the log's samples (SI; NaN where it has none)."""
        ch = {k: np.asarray(c.values, dtype=float) for k, c in log.channels.items()}
        try:
            if self.model == 'bicycle':
                return replay_bicycle(self.params(config), self.ratio, ch['time'],
                                      ch['steering_wheel_angle'], ch['speed'])
            if self.model == 'two_track':
                return self._steady(config, ch)
            (run,) = replay_outcomes(config, log, ['vehicle'])
            return {k: np.asarray(c.values, dtype=float) for k, c in run.channels.items()}
        except SolverError as err:
            raise InputError(log.configuration, f'{self.model}: {err}') from None

    def _steady(self, config: Configuration, ch: Mapping[str, np.ndarray]
                ) -> dict[str, np.ndarray]:
        p = self.params(config)
        ay, r, u = ch['lateral_acceleration'], ch['yaw_rate'], ch['speed']
        use = np.flatnonzero((np.abs(ay) >= MIN_LATERAL) & (np.abs(r) >= MIN_YAW_RATE)
                             & (ay * r > 0.0))
        if use.size > MAX_POINTS:
            use = use[np.linspace(0, use.size - 1, MAX_POINTS).round().astype(int)]
        swa = np.full(ay.size, np.nan)
        roll = np.full(ay.size, np.nan)
        for i in use:
            point = two_track.steady_state(p, float(ay[i]), float(u[i] / r[i]))
            swa[i] = point.steer_angle * self.ratio
            roll[i] = point.roll_angle
        return {'steering_wheel_angle': swa, 'roll': roll}


@dataclass
class Residuals:
    """The weighted residual vector of a parameter set over a set of logs."""

    predictor: Predictor
    logs: Sequence[EventOutcome]
    channels: Sequence[ChannelWeight]
    parameters: Sequence[Factor]
    scales: dict[str, float] = field(default_factory=dict)
    evaluations: int = 0
    used: list[np.ndarray] = field(default_factory=list)  # per log: samples compared

    def __post_init__(self) -> None:
        dynamic = self.predictor.model != 'two_track'
        for o in self.logs:
            t = np.asarray(o.channels['time'].values, dtype=float)
            keep = np.ones(t.size, dtype=bool)
            for s in segments(t)[1:] if dynamic else ():
                keep &= ~((t >= t[s.start]) & (t < t[s.start] + SETTLE))
            self.used.append(keep)
        for c in self.channels:
            missing = [_label(o) for o in self.logs if c.channel not in o.channels]
            if missing:
                raise InputError(missing[0], f"no '{c.channel}' channel to fit (channels: "
                                 'in the plan)')
            if c.scale is not None:
                self.scales[c.channel] = c.scale
                continue
            values = np.concatenate([np.asarray(o.channels[c.channel].values, dtype=float)
                                     for o in self.logs])
            spread = float(np.std(values))
            if not spread > 0.0:
                raise InputError(_label(self.logs[0]), f"'{c.channel}' does not vary in the "
                                 'logs: give its scale')
            self.scales[c.channel] = spread

    def overrides(self, x: np.ndarray) -> dict[str, str]:
        return {f.key: f'{format_number(v)} {f.unit}'.strip()
                for f, v in zip(self.parameters, x)}

    def per_channel(self, x: np.ndarray) -> list[dict[str, np.ndarray]]:
        """(model - log) per log and channel, SI, at the samples the model predicts."""
        self.evaluations += 1
        config = self.predictor.configuration(self.overrides(x))
        out = []
        for log, keep in zip(self.logs, self.used):
            sim = self.predictor.predict(config, log)
            out.append({c.channel: np.where(keep, sim[c.channel] - np.asarray(
                log.channels[c.channel].values, dtype=float), np.nan)
                for c in self.channels})
        return out

    def __call__(self, x: np.ndarray) -> np.ndarray:
        parts = []
        for per_log in self.per_channel(x):
            for c in self.channels:
                d = per_log[c.channel]
                parts.append(c.weight * d[np.isfinite(d)] / self.scales[c.channel])
        return np.concatenate(parts)


@dataclass
class Identification:
    """What ``vd identify`` found (module doc); values in the parameters' plan units."""

    plan: IdentifyPlan
    start: np.ndarray
    fitted: np.ndarray
    standard_errors: np.ndarray  # nan where the covariance is singular
    correlation: np.ndarray
    singular_values: np.ndarray
    rank: int
    condition: float
    pairs: list[tuple[str, str, float]]  # parameters not identifiable apart, correlation
    sigma: float  # residual standard deviation of the weighted residuals
    points: int
    cost_start: float
    cost_fitted: float
    #: set (identification, validation) -> per log: channel -> RMS (before, after), SI
    rms: dict[str, list[dict[str, tuple[float, float]]]]
    evaluations: int
    seconds: float  # the fit: least squares and the Jacobian at the solution
    message: str
    logs: list[tuple[Path, EventOutcome]]
    validation: list[tuple[Path, EventOutcome]] = field(default_factory=list)
    correlations: dict[str, Correlation] = field(default_factory=dict)
    master: Path | None = None
    configuration: str = ''
    notes: list[str] = field(default_factory=list)

    @property
    def identifiable(self) -> bool:
        return self.rank == len(self.fitted) and not self.pairs

    def to_json(self) -> dict:
        names = [f.name for f in self.plan.parameters]
        return {
            'plan': str(self.plan.path), 'model': self.plan.model,
            'base_configuration': self.plan.configuration,
            'configuration': self.configuration, 'master': str(self.master or ''),
            'parameters': [{'name': f.name, 'key': f.key, 'unit': f.unit, 'start': float(s),
                            'fitted': float(v), 'standard_error': _num(e),
                            'bounds': [f.low, f.high]}
                           for f, s, v, e in zip(self.plan.parameters, self.start, self.fitted,
                                                 self.standard_errors)],
            'correlation': {'names': names, 'matrix': [[_num(v) for v in row]
                                                       for row in self.correlation]},
            'identifiability': {'rank': self.rank, 'parameters': len(names),
                                'condition': _num(self.condition),
                                'singular_values': [float(v) for v in self.singular_values],
                                'unidentifiable_pairs': [
                                    {'parameters': [a, b], 'correlation': c}
                                    for a, b, c in self.pairs],
                                'identifiable': self.identifiable},
            'residual_sigma': self.sigma, 'points': self.points,
            'cost': {'start': self.cost_start, 'fitted': self.cost_fitted},
            'rms': {k: [{ch: {'before': b, 'after': a} for ch, (b, a) in per.items()}
                        for per in v] for k, v in self.rms.items()},
            'logs': [{'path': str(p), 'sha256': o.data_hash} for p, o in self.logs],
            'validation_logs': [{'path': str(p), 'sha256': o.data_hash}
                                for p, o in self.validation],
            'correlations': {k: c.to_json() for k, c in self.correlations.items()},
            'evaluations': self.evaluations, 'seconds': self.seconds, 'message': self.message,
            'notes': self.notes}


def _num(value: float) -> float | None:
    return float(value) if math.isfinite(value) else None


def _label(o: EventOutcome) -> str:
    return next((n[len('source: '):] for n in o.notes if n.startswith('source: ')),
                o.configuration)


def covariance(jac: np.ndarray, residuals: np.ndarray) -> tuple[np.ndarray, float]:
    """sigma^2 (J^T J)^-1 and sigma (module doc); nan-filled when J^T J is singular."""
    n, p = jac.shape
    sigma2 = float(residuals @ residuals) / max(n - p, 1)
    jtj = jac.T @ jac
    try:
        if np.linalg.matrix_rank(jtj) < p:
            raise np.linalg.LinAlgError
        cov = sigma2 * np.linalg.inv(jtj)
    except np.linalg.LinAlgError:
        cov = np.full((p, p), np.nan)
    return cov, math.sqrt(sigma2)


def identifiability(jac: np.ndarray) -> tuple[np.ndarray, int, float]:
    """Singular values of J with unit-norm columns, the numerical rank, the condition."""
    norms = np.linalg.norm(jac, axis=0)
    scaled = jac / np.where(norms > 0.0, norms, 1.0)
    s = np.linalg.svd(scaled, compute_uv=False)
    rank = int(np.count_nonzero(s > RANK_TOLERANCE * s[0])) if s[0] > 0.0 else 0
    condition = float(s[0] / s[-1]) if s[-1] > 0.0 else math.inf
    return s, rank, condition


def jacobian(fun: Callable[[np.ndarray], np.ndarray], x: np.ndarray, low: np.ndarray,
             high: np.ndarray) -> np.ndarray:
    """Central differences of FD_STEP of each range (one-sided at a bound), plan units."""
    cols = []
    for j in range(x.size):
        h = FD_STEP * (high[j] - low[j])
        a, b = x.copy(), x.copy()
        a[j] = max(low[j], x[j] - h)
        b[j] = min(high[j], x[j] + h)
        cols.append((fun(b) - fun(a)) / (b[j] - a[j]))
    return np.column_stack(cols)


def _rms(parts: list[dict[str, np.ndarray]]) -> list[dict[str, float]]:
    return [{c: float(np.sqrt(np.nanmean(d ** 2))) for c, d in per.items()} for per in parts]


def identify(plan: IdentifyPlan, study=None, log: Callable[[str], None] | None = None,
             predictor: Predictor | None = None) -> Identification:
    """
    Fit the plan's parameters to its logs; cross-validate; nothing is written here.

    ``predictor``: the plan's model of its base configuration, when the caller has it.
    """
    study = study if study is not None else load_study(plan.master)
    check_output(plan, study)
    logs = load_logs(plan.logs, plan.path)
    validation = load_logs(plan.validate, plan.path) if plan.validate else []
    if predictor is None or predictor.model != plan.model:
        predictor = Predictor(study.configurations[plan.configuration], plan.model)
    started = time.perf_counter()
    fun = Residuals(predictor, [o for _, o in logs], plan.channels, plan.parameters)
    low = np.array([f.low for f in plan.parameters])
    high = np.array([f.high for f in plan.parameters])
    span = high - low
    start = np.array([f.start if f.start is not None else min(max(f.base, f.low), f.high)
                      for f in plan.parameters])

    def scaled(u: np.ndarray) -> np.ndarray:
        res = fun(low + np.clip(u, 0.0, 1.0) * span)
        if log is not None:
            log(f'  {fun.evaluations:3d}  cost {0.5 * float(res @ res):.6g}')
        return res

    r0 = fun(start)
    sol = so.least_squares(scaled, (start - low) / span, bounds=(0.0, 1.0),
                           x_scale=1.0, diff_step=FD_STEP, max_nfev=plan.max_evaluations)
    fitted = low + np.clip(sol.x, 0.0, 1.0) * span
    r1 = fun(fitted)
    jac = jacobian(fun, fitted, low, high)
    evaluations = fun.evaluations
    fit_seconds = time.perf_counter() - started
    cov, sigma = covariance(jac, r1)
    se = np.sqrt(np.diag(cov))
    with np.errstate(invalid='ignore', divide='ignore'):
        corr = cov / np.outer(se, se)
    if not np.all(np.isfinite(corr)):
        # singular: the correlation of the Jacobian's columns says which move together
        norms = np.linalg.norm(jac, axis=0)
        unit = jac / np.where(norms > 0.0, norms, 1.0)
        corr = -(unit.T @ unit)
        np.fill_diagonal(corr, 1.0)
    s, rank, condition = identifiability(jac)
    names = [f.name for f in plan.parameters]
    pairs = [(names[i], names[k], float(corr[i, k])) for i in range(len(names))
             for k in range(i + 1, len(names)) if abs(corr[i, k]) > PAIR_CORRELATION]
    rms = {'identification': [{c: (b, a) for (c, b), a in zip(before.items(), after.values())}
                              for before, after in zip(_rms(fun.per_channel(start)),
                                                       _rms(fun.per_channel(fitted)))]}
    result = Identification(
        plan=plan, start=start, fitted=fitted, standard_errors=se, correlation=corr,
        singular_values=s, rank=rank, condition=condition, pairs=pairs, sigma=sigma,
        points=int(r1.size), cost_start=0.5 * float(r0 @ r0),
        cost_fitted=0.5 * float(r1 @ r1), rms=rms, evaluations=evaluations,
        seconds=fit_seconds, message=str(sol.message), logs=logs,
        validation=validation)
    if validation:
        vfun = Residuals(predictor, [o for _, o in validation], plan.channels, plan.parameters)
        rms['validation'] = [{c: (b, a) for (c, b), a in zip(before.items(), after.values())}
                             for before, after in zip(_rms(vfun.per_channel(start)),
                                                      _rms(vfun.per_channel(fitted)))]
    for which, items in (('identification', logs), ('validation', validation)):
        if not items:
            continue
        tests = [o for _, o in items]
        for when, x in (('before', start), ('after', fitted)):
            sims = predictions(predictor, fun.overrides(x), tests)
            try:
                result.correlations[f'{which} {when}'] = correlate(
                    sims, tests, plan.method or default_method(tests), load_bands(),
                    force=plan.force)
            except InputError as err:
                result.notes.append(f'{which} set {when}: not correlated: {err}')
    return result


def default_method(tests: Sequence[EventOutcome]) -> str:
    """Return the ISO method of the logs' event (steady state: ISO 19364; else transient)."""
    events = {t.event for t in tests}
    if events == {'constant_radius_turn'}:
        return 'iso19364'
    if events == {'sine_with_dwell'}:
        return 'iso19365'
    return 'iso22140'


def predictions(predictor: Predictor, overrides: Mapping[str, str],
                tests: Sequence[EventOutcome]) -> list[EventOutcome]:
    """Each log's prediction as a replay of it (paired with its own log only)."""
    config = predictor.configuration(overrides)
    out = []
    for test in tests:
        sim = predictor.predict(config, test)
        channels = {k: Channel(UNITS.get(k, test.channels[k].unit if k in test.channels
                                         else ''), np.asarray(v, dtype=float))
                    for k, v in sim.items()}
        channels['time'] = test.channels['time']
        for k in ('steering_wheel_angle', 'speed', 'lateral_acceleration'):
            if k not in channels and k in test.channels:
                channels[k] = test.channels[k]
        inputs = INPUTS[predictor.model]
        out.append(EventOutcome(
            event=test.event, configuration=config.name, model=predictor.model,
            fidelity='rigid', axle=test.axle, data_hash=config.data_hash, metrics={},
            channels=channels, notes=(INPUTS_NOTE + ', '.join(inputs),
                                      REPLAY_NOTE + test.data_hash)))
    return out


def check_output(plan: IdentifyPlan, study) -> None:
    """Refuse a plan whose configuration exists in the master file it would be written to."""
    target = plan.write_master
    if plan.output_configuration in study.configurations_in(target):
        raise DataError(f'configuration {plan.output_configuration!r} already exists in '
                        f'{target} (never overwritten: choose another output.configuration)',
                        file=str(plan.path), key='output.configuration')


def write_identified(result: Identification) -> Path:
    """
    Add the identified configuration to the plan's ``write_master`` (module doc).

    A ``write_master`` that does not exist yet is first a copy of the plan's master file
    with its data root pointing at the same data.
    """
    plan = result.plan
    target = plan.write_master
    if not target.exists():
        text = plan.master.read_text(encoding='utf-8')
        doc = load_document(text, file=str(plan.master))
        root = plan.master.resolve().parent / str(doc['study'].get('data_root', '..'))
        target.parent.mkdir(parents=True, exist_ok=True)
        doc['study']['data_root'] = os.path.relpath(root.resolve(), target.parent.resolve())
        write_master(target, doc)
    values = ', '.join(f'{f.name} = {v:.6g} +- {e:.2g} {f.unit}'.strip()
                       for f, v, e in zip(plan.parameters, result.fitted,
                                          result.standard_errors))
    description = (f'vd identify {plan.name} ({plan.model}): {plan.configuration} with {values}'
                   f' (1 standard error); plan {plan.path.name} sha256 {sha256(plan.path)}; '
                   'logs sha256 ' + ', '.join(o.data_hash for _, o in result.logs))
    edits = [Edit('add', plan.output_configuration, value=description,
                  source=plan.configuration)]
    edits += [Edit('override', plan.output_configuration, key=f.key,
                   value=f'{format_number(v)} {f.unit}'.strip())
              for f, v in zip(plan.parameters, result.fitted)]
    edit_master(target, edits)
    result.master = target
    result.configuration = plan.output_configuration
    return target


def with_fitted(result: Identification) -> dict[str, str]:
    """Return the fitted values as overrides (``GROUP.KEY``: value with unit)."""
    return {f.key: f'{format_number(v)} {f.unit}'.strip()
            for f, v in zip(result.plan.parameters, result.fitted)}


__all__ = ['IdentifyPlan', 'Identification', 'Predictor', 'Residuals', 'identify',
           'load_identify_plan', 'load_logs', 'write_identified', 'covariance',
           'identifiability', 'jacobian', 'with_fitted', 'MODELS', 'PAIR_CORRELATION']
