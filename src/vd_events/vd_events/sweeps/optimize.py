# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
``vd optimize``: change factors within their bounds until responses meet their targets.

The factors are scaled to [0, 1] over their ranges; every evaluation is a design
point whose runs go through the same evaluator, cache and ``runs.jsonl`` as a
sweep (sweep.evaluate), so a point evaluated twice is computed once. Methods
(scipy.optimize):

- ``least_squares`` (default): trust-region reflective on the residuals
  (response - target) / tolerance, bounds kept; the Jacobian by forward
  differences of 1 % of each range, its points evaluated as one batch (in
  parallel over the solver instances);
- ``slsqp``: the sum of squared residuals, response ``minimum``/``maximum`` as
  inequality constraints;
- ``nelder_mead``: derivative-free, bounds kept, constraints as penalties.

Every evaluation is recorded (``history.csv``). The best point that meets every
target and constraint (else the one with the smallest objective) is written as a
new configuration of a master file (the base configuration plus the factor values
as overrides), which the feedback shows as MODIFIED.
"""
from __future__ import annotations

from collections.abc import Callable, Sequence
import csv
from dataclasses import dataclass, field
import io
import math
import os
from pathlib import Path

import numpy as np
from ruamel.yaml import YAML
from scipy import optimize as so

from vd_data_server.errors import DataError
from vd_data_server.files import locked
from vd_data_server.master import inside
from vd_data_server.masteredit import ConflictError, Fingerprint, fingerprint
from vd_data_server.study import load_study
from vd_events.sweeps.plan import SweepPlan, format_number
from vd_events.sweeps.sweep import Evaluator, evaluate, load_records, requests_for, response_values

#: forward-difference step of the Jacobian, as a fraction of each factor's range
FD_STEP = 0.01


@dataclass
class Evaluation:
    x: tuple[float, ...]  # factor values, plan units
    responses: tuple[float, ...]  # response units (nan: failed)
    objective: float
    met: bool
    error: str = ''


@dataclass
class OptimizeResult:
    best: Evaluation
    history: list[Evaluation] = field(default_factory=list)
    message: str = ''
    configuration: str = ''
    master: Path | None = None


def residuals(plan: SweepPlan, y: Sequence[float]) -> np.ndarray:
    """(response - target) / scale for targets; violations / scale for minimum/maximum."""
    out = []
    for r, v in zip(plan.responses, y):
        if r.target is not None:
            scale = r.target.tolerance or abs(r.target.value) or 1.0
            out.append((v - r.target.value) / scale)
        for bound, sign in ((r.minimum, -1.0), (r.maximum, 1.0)):
            if bound is not None:
                scale = abs(bound) or 1.0
                out.append(max(0.0, sign * (v - bound)) / scale)
    return np.array(out, dtype=float)


def meets(plan: SweepPlan, y: Sequence[float]) -> bool:
    """Every target within its tolerance and every minimum/maximum respected."""
    for r, v in zip(plan.responses, y):
        if not math.isfinite(v):
            return False
        if r.target is not None and abs(v - r.target.value) > r.target.tolerance:
            return False
        if (r.minimum is not None and v < r.minimum) or (r.maximum is not None
                                                         and v > r.maximum):
            return False
    return True


def check_plan(plan: SweepPlan, study, out: Path | None = None) -> str:
    """Refuse a plan that cannot be optimised; return the new configuration's name."""
    file = str(plan.path)
    if not any(r.target is not None for r in plan.responses):
        raise DataError('vd optimize needs at least one response with a target (e.g. '
                        "target: '0 deg/m +- 1 deg/m')", file=file, key='responses')
    for f in plan.factors:
        if f.values:
            raise DataError('vd optimize varies factors over a range, not levels', file=file,
                            key=f'factors.{f.name}.values')
    spec = plan.optimize
    name = (spec.configuration if spec and spec.configuration
            else f'{plan.configuration}_{plan.name}'.replace('.', '_'))
    target = output_master(plan, out)
    root = study.master.data_root
    if spec and spec.write_master is not None and not spec.named_by_user \
            and not inside(root, target):
        raise DataError(f"{target} is outside the study's data root {root}: a plan writes "
                        'master files only under it (name the file on the command line to '
                        'write elsewhere: vd optimize --write-master PATH)', file=file,
                        key='optimize.write_master')
    if name in study.configurations_in(target):
        raise DataError(f'configuration {name!r} already exists in {target} (choose another '
                        'name: optimize.configuration)', file=file, key='optimize.configuration')
    # the bounds of every factor, each with the others at the start, are points that run
    for j, f in enumerate(plan.factors):
        for bound in (f.low, f.high):
            x = [g.start if g.start is not None else min(max(g.base, g.low), g.high)
                 for g in plan.factors]
            x[j] = bound
            requests_for(plan, study, [tuple(x)])
    return name


def output_master(plan: SweepPlan, out: Path | None) -> Path:
    if plan.optimize is not None and plan.optimize.write_master is not None:
        return plan.optimize.write_master
    return (out or Path('out') / plan.name) / plan.master.name


def optimize(plan: SweepPlan, study, evaluator: Evaluator, out: Path, *,
             log: Callable[[str], None] | None = None) -> OptimizeResult:
    """Run the optimisation, record its history and write the best configuration."""
    name = check_plan(plan, study, out)
    target = output_master(plan, out)
    # the file as it was when the optimisation started: written only if still so
    read = fingerprint(target) if target.exists() else None
    spec = plan.optimize
    method = spec.method if spec else 'least_squares'
    budget = spec.max_evaluations if spec else 60
    lo = np.array([f.low for f in plan.factors])
    span = np.array([f.high - f.low for f in plan.factors])
    start = np.array([f.start if f.start is not None else min(max(f.base, f.low), f.high)
                      for f in plan.factors])
    # every design point is validated before the first run (an override out of range...)
    requests_for(plan, study, [tuple(start)])
    known = load_records(out)
    history: list[Evaluation] = []
    memo: dict[tuple[float, ...], Evaluation] = {}

    def batch(us: Sequence[np.ndarray]) -> list[Evaluation]:
        xs = [tuple(float(v) for v in lo + np.clip(u, 0.0, 1.0) * span) for u in us]
        new = [x for x in dict.fromkeys(xs) if x not in memo]
        if new:
            if len(history) + len(new) > budget:
                raise _Budget
            reqs = requests_for(plan, study, new)
            records, _ = evaluate([r for row in reqs for r in row], evaluator, out,
                                  known=known)
            known.update(records)
            values, errors = response_values(plan, reqs, records)
            for x, y, err in zip(new, values, errors):
                res = residuals(plan, y)
                obj = float(np.sum(res ** 2)) if np.all(np.isfinite(res)) else math.inf
                ev = Evaluation(x, tuple(float(v) for v in y), obj, meets(plan, y), err)
                memo[x] = ev
                history.append(ev)
                if log is not None:
                    log(f'  {len(history):3d}  {_point(plan, x)}  ->  '
                        + ', '.join(f'{r.name} {v:.4g} {r.unit}'
                                    for r, v in zip(plan.responses, y))
                        + ('  (meets the targets)' if ev.met else ''))
        return [memo[x] for x in xs]

    def fun(u: np.ndarray) -> np.ndarray:
        ev = batch([u])[0]
        res = residuals(plan, ev.responses)
        if not np.all(np.isfinite(res)):
            raise DataError(f'the runs of point {_point(plan, ev.x)} failed: {ev.error}',
                            file=str(plan.path))
        return res

    def jac(u: np.ndarray) -> np.ndarray:
        steps = [np.where(u + FD_STEP <= 1.0, FD_STEP, -FD_STEP)[j] for j in range(len(u))]
        probes = [u.copy() for _ in u]
        for j, p in enumerate(probes):
            p[j] += steps[j]
        evs = batch([u, *probes])
        f0 = residuals(plan, evs[0].responses)
        return np.column_stack([(residuals(plan, e.responses) - f0) / s
                                for e, s in zip(evs[1:], steps)])

    u0 = (start - lo) / span
    message = ''
    try:
        if method == 'least_squares':
            sol = so.least_squares(fun, u0, jac=jac, bounds=(0.0, 1.0), x_scale=1.0,
                                   max_nfev=budget)
        elif method == 'slsqp':
            cons = [{'type': 'ineq', 'fun': lambda u, k=k: _margin(plan, batch([u])[0], k)}
                    for k, r in enumerate(plan.responses)
                    if r.minimum is not None or r.maximum is not None]
            sol = so.minimize(lambda u: float(np.sum(fun(u) ** 2)), u0, method='SLSQP',
                              jac=lambda u: 2.0 * jac(u).T @ fun(u), bounds=[(0, 1)] * len(u0),
                              constraints=cons, options={'maxiter': budget})
        else:
            sol = so.minimize(lambda u: float(np.sum(fun(u) ** 2)), u0, method='Nelder-Mead',
                              bounds=[(0, 1)] * len(u0),
                              options={'maxfev': budget, 'xatol': 1e-4, 'fatol': 1e-8})
        message = str(sol.message)
    except _Budget:
        message = f'stopped at the limit of {budget} evaluations (optimize.max_evaluations)'
    if not history:
        raise DataError('no point was evaluated', file=str(plan.path))
    met = [e for e in history if e.met]
    best = min(met or history, key=lambda e: e.objective)
    result = OptimizeResult(best, history, message, name)
    _write_history(plan, history, out)
    result.master = write_configuration(plan, study, name, best, target, expected=read)
    return result


class _Budget(Exception):
    """The evaluation budget is spent."""

def _margin(plan: SweepPlan, ev: Evaluation, k: int) -> float:
    r, v = plan.responses[k], ev.responses[k]
    bound = r.minimum if r.minimum is not None else r.maximum
    assert bound is not None  # constraints are built only of responses with a bound
    scale = abs(bound) or 1.0
    low = (v - r.minimum) / scale if r.minimum is not None else math.inf
    high = (r.maximum - v) / scale if r.maximum is not None else math.inf
    return min(low, high)


def _point(plan: SweepPlan, x: Sequence[float]) -> str:
    return ', '.join(f'{f.name} {v:.5g}{" " + f.unit if f.unit else ""}'
                     for f, v in zip(plan.factors, x))


def _write_history(plan: SweepPlan, history: Sequence[Evaluation], out: Path) -> Path:
    stream = io.StringIO()
    writer = csv.writer(stream, lineterminator='\n')
    writer.writerow(['evaluation', *(f'{f.name} [{f.unit}]' if f.unit else f.name
                                     for f in plan.factors),
                     *(f'{r.name} [{r.unit}]' if r.unit else r.name for r in plan.responses),
                     'objective', 'meets_targets', 'error'])
    for i, e in enumerate(history):
        writer.writerow([i, *map(repr, e.x), *('' if math.isnan(v) else repr(v)
                                               for v in e.responses),
                         repr(e.objective), e.met, e.error])
    out.mkdir(parents=True, exist_ok=True)
    path = out / 'history.csv'
    tmp = path.with_name('.history.csv.tmp')
    tmp.write_text(stream.getvalue())
    os.replace(tmp, path)
    return path


def write_configuration(plan: SweepPlan, study, name: str, best: Evaluation,
                        target: Path, *, expected: Fingerprint | None = None) -> Path:
    """
    Write ``name`` (the base configuration plus the best factor values) into ``target``.

    ``target`` is the plan's master file (the configuration is added, comments kept
    by ruamel.yaml's round trip) or a new master file beside it elsewhere (a copy of
    the plan's master with ``study.data_root`` pointing at the same data). Written
    under a temporary name, loaded and checked like any master file, then renamed, with
    ``target`` locked from its reading to its replacement (:func:`files.locked`).
    ``expected``: the fingerprint of ``target`` when the optimisation read it; a file
    changed since raises :class:`ConflictError` and nothing is written.
    """
    if not target.exists():
        return _write_configuration(plan, name, best, target)
    with locked(target):
        if expected is not None and fingerprint(target) != expected:
            raise ConflictError('changed on disk since the optimisation read it: the '
                                f'configuration {name!r} is not written (the history is)',
                                file=str(target))
        return _write_configuration(plan, name, best, target)


def _write_configuration(plan: SweepPlan, name: str, best: Evaluation, target: Path) -> Path:
    yaml = YAML()
    yaml.preserve_quotes = True
    source = target if target.exists() else plan.master
    with source.open() as stream:
        doc = yaml.load(stream)
    configs = doc['configurations']
    if name in configs:
        raise DataError(f'configuration {name!r} already exists', file=str(target),
                        key=f'configurations.{name}')
    if source == plan.master and target.resolve() != plan.master.resolve():
        # the real folder of the master (an installed share may hold links to the sources)
        root = plan.master.resolve().parent / str(doc['study'].get('data_root', '..'))
        target.parent.mkdir(parents=True, exist_ok=True)
        doc['study']['data_root'] = os.path.relpath(root.resolve(), target.parent.resolve())
    base = configs[plan.configuration]
    entry = dict(base or {})
    overrides = dict(entry.get('overrides') or {})
    for f, v in zip(plan.factors, best.x):
        overrides[f.key] = f'{format_number(v)} {f.unit}'.strip()
    entry['description'] = (f'vd optimize {plan.name}: {plan.configuration} with '
                            + ', '.join(f'{f.key} = {format_number(v)} {f.unit}'.strip()
                                        for f, v in zip(plan.factors, best.x))
                            + ('' if best.met else ' (targets not met)'))
    entry['overrides'] = overrides
    configs[name] = entry
    tmp = target.with_name(f'.{target.stem}.tmp{target.suffix}')
    with tmp.open('w') as stream:
        yaml.dump(doc, stream)
    try:
        load_study(tmp)
    except DataError:
        tmp.unlink(missing_ok=True)
        raise
    os.replace(tmp, target)
    return target


__all__ = ['optimize', 'OptimizeResult', 'Evaluation', 'residuals', 'meets',
           'write_configuration', 'check_plan', 'output_master']
