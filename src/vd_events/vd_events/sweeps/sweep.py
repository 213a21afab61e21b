# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
``vd sweep``: the runs of a design, each computed once, into a table and report pages.

Every design point is the plan's base configuration with the factor values as
overrides: a configuration of its own, with its own data hash. A run is
identified by that hash and the event, model, axle, fidelity and parameters
(:func:`run_key`); runs with the same key are computed once, and a run already in
the sweep folder's ``runs.jsonl`` (a previous or interrupted sweep) is not
computed again. Each finished run is appended to ``runs.jsonl`` at once, so a
sweep stopped at any point keeps what it finished.

The runs themselves are computed by an *evaluator* (dispatch.py over the solver
instances of a ROS graph; tests inject their own), so this module stays free of ROS.
"""
from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
import csv
from dataclasses import dataclass, field
import hashlib
import io
import json
import math
import os
from pathlib import Path
import shutil
import time
from typing import Any

from builtin_interfaces.msg import Time
import numpy as np

from vd_data_server.errors import DataError
from vd_data_server.ros.qos import RESULTS
from vd_events.bags.bag import BagWriter
from vd_events.errors import BagError, RunError
from vd_events.orchestration.runner import RunRequest, validate
from vd_events.sweeps.plan import SweepPlan, convert, points
from vd_solvers.conversions import outcome_to_msg
from vd_solvers.results import EventOutcome

#: evaluator(requests, done) computes every request and calls done(request, outcome, error,
#: instance) as each finishes (outcome None when error names why the run failed)
Done = Callable[[RunRequest, EventOutcome | None, str | None, str], None]
Evaluator = Callable[[Sequence[RunRequest], Done], None]
RUNS_FILE = 'runs.jsonl'


@dataclass(frozen=True)
class RunRecord:
    """One finished run: its metrics (value, unit) or the error."""

    key: str
    event: str
    model: str
    axle: str
    data_hash: str
    metrics: Mapping[str, tuple[float, str]]
    error: str | None = None
    instance: str = ''
    bag: str = ''

    def to_json(self) -> dict[str, Any]:
        return {'key': self.key, 'event': self.event, 'model': self.model, 'axle': self.axle,
                'data_hash': self.data_hash, 'error': self.error, 'instance': self.instance,
                'bag': self.bag,
                'metrics': {k: [v if math.isfinite(v) else None, u]
                            for k, (v, u) in self.metrics.items()}}

    @staticmethod
    def from_json(raw: Mapping[str, Any]) -> RunRecord:
        return RunRecord(raw['key'], raw['event'], raw['model'], raw['axle'], raw['data_hash'],
                         {k: (math.nan if v is None else float(v), str(u))
                          for k, (v, u) in raw['metrics'].items()},
                         raw.get('error'), raw.get('instance', ''), raw.get('bag', ''))


@dataclass
class SweepResult:
    plan: SweepPlan
    points: list[tuple[float, ...]]
    #: per point, per response: the value in the response's unit (nan: failed)
    responses: np.ndarray
    errors: list[str]  # per point: '' or the first error of its runs
    computed: int  # runs computed by this call (the others came from runs.jsonl or repeats)
    cached: int
    files: dict[str, str] = field(default_factory=dict)


def run_key(request: RunRequest) -> str:
    """Return the identity of a run's result: data hash, event, model, axle, fidelity, params."""
    payload = [request.data_hash, request.event, request.model, request.axle, request.fidelity,
               sorted(request.parameters)]
    return hashlib.sha256(json.dumps(payload).encode()).hexdigest()[:20]


def point_label(plan: SweepPlan, values: Sequence[float]) -> str:
    return ', '.join(f'{f.name}={v:.6g}{" " + f.unit if f.unit else ""}'
                     for f, v in zip(plan.factors, values))


def requests_for(plan: SweepPlan, study, values_list: Sequence[Sequence[float]]
                 ) -> list[list[RunRequest]]:
    """
    Return the validated runs of every point (with the data hash each result must carry).

    A point that cannot run (an override out of the key's range, a geometry that does
    not close) is refused here, before anything runs: DataError naming the plan and point.
    """
    out = []
    for i, values in enumerate(values_list):
        overrides = tuple(f.override(v) for f, v in zip(plan.factors, values))
        row = []
        for run in plan.runs:
            request = RunRequest(event=run.event, configuration=plan.configuration,
                                 model=run.model, fidelity=run.fidelity, axle=run.axle,
                                 overrides=overrides, parameters=run.parameters)
            try:
                row.append(validate(study, request))
            except (DataError, RunError, BagError) as err:
                detail = str(err).removeprefix('--set: ')
                raise DataError(f'point {i} ({point_label(plan, values)}), run {run.label}: '
                                f'{detail}', file=str(plan.path)) from None
        out.append(row)
    return out


def load_records(folder: Path) -> dict[str, RunRecord]:
    """Return the runs a sweep in ``folder`` finished before (a torn last line is ignored)."""
    path = folder / RUNS_FILE
    records: dict[str, RunRecord] = {}
    if not path.is_file():
        return records
    for line in path.read_text().splitlines():
        try:
            record = RunRecord.from_json(json.loads(line))
        except (ValueError, KeyError, TypeError):
            continue  # a line cut short by a kill
        if record.error is None:
            records[record.key] = record
    return records


class RecordLog:
    """Append-only ``runs.jsonl``: one line per finished run, flushed to disk at once."""

    def __init__(self, folder: Path) -> None:
        folder.mkdir(parents=True, exist_ok=True)
        self._file = (folder / RUNS_FILE).open('a')

    def append(self, record: RunRecord) -> None:
        self._file.write(json.dumps(record.to_json(), allow_nan=False) + '\n')
        self._file.flush()
        os.fsync(self._file.fileno())

    def close(self) -> None:
        self._file.close()


def record_of(request: RunRequest, outcome: EventOutcome | None, error: str | None,
              instance: str, bag: str = '') -> RunRecord:
    metrics = ({k: (float(m.value), m.unit) for k, m in outcome.metrics.items()}
               if outcome is not None else {})
    return RunRecord(run_key(request), request.event, request.model, request.axle,
                     request.data_hash, metrics, error, instance, bag)


def evaluate(requests: Sequence[RunRequest], evaluator: Evaluator, folder: Path, *,
             bags: bool = True, known: dict[str, RunRecord] | None = None,
             progress: Callable[[int, int], None] | None = None,
             ) -> tuple[dict[str, RunRecord], int]:
    """
    Compute the runs not yet known (by key), each once; return every record and the count.

    Finished runs go to ``folder/runs.jsonl`` as they finish and, with ``bags``, their
    result to a bag ``folder/bags/<event>[_<axle>]_<model>_<data hash>``.
    """
    records = dict(known if known is not None else load_records(folder))
    todo: dict[str, RunRequest] = {}
    for request in requests:
        key = run_key(request)
        if key not in records and key not in todo:
            todo[key] = request
    if not todo:
        return records, 0
    log = RecordLog(folder)
    done_count = [0]

    def done(request: RunRequest, outcome: EventOutcome | None, error: str | None,
             instance: str) -> None:
        bag = ''
        if outcome is not None and bags:
            bag = str(_write_bag(folder / 'bags', request, outcome))
        record = record_of(request, outcome, error, instance, bag)
        records[record.key] = record
        log.append(record)
        done_count[0] += 1
        if progress is not None:
            progress(done_count[0], len(todo))

    try:
        evaluator(list(todo.values()), done)
    finally:
        log.close()
    return records, len(todo)


def _write_bag(folder: Path, request: RunRequest, outcome: EventOutcome) -> Path:
    """One run's EventResult (every channel and metric) as an MCAP bag."""
    name = f"{request.event}{'_' + request.axle if request.axle else ''}_{request.model}_" \
           f'{request.data_hash}'
    if request.fidelity != 'rigid':
        name += f'_{request.fidelity}'
    path = folder / name
    if path.exists():  # the same data computed before: the bag holds the same result
        shutil.rmtree(path)
    stamp = time.time_ns()
    writer = BagWriter(path, {'vd.configuration': request.configuration,
                              'vd.overrides': '; '.join(request.overrides),
                              'vd.data_hash': request.data_hash})
    try:
        msg = outcome_to_msg(outcome, Time(sec=stamp // 10**9, nanosec=stamp % 10**9))
        writer.write(f'/vd/{request.family}/result', msg, stamp, [RESULTS])
        return writer.close()
    except BaseException:
        writer.abort()
        raise


def response_values(plan: SweepPlan, requests: Sequence[Sequence[RunRequest]],
                    records: Mapping[str, RunRecord]) -> tuple[np.ndarray, list[str]]:
    """
    Return the responses of every point in their units (nan where a run failed) and errors.

    A metric a run does not report, or one whose unit cannot be converted to the
    response's, is an error of that point naming the response.
    """
    values = np.full((len(requests), len(plan.responses)), math.nan)
    errors = [''] * len(requests)
    run_index = {spec: j for j, spec in enumerate(plan.runs)}
    for i, row in enumerate(requests):
        for k, response in enumerate(plan.responses):
            record = records.get(run_key(row[run_index[response.run]]))
            if record is None:
                errors[i] = errors[i] or f'{response.run.label}: not computed'
                continue
            if record.error is not None:
                errors[i] = errors[i] or record.error
                continue
            if response.metric not in record.metrics:
                errors[i] = errors[i] or (
                    f"response '{response.name}': run {response.run.label} has no metric "
                    f"'{response.metric}' (metrics: {', '.join(sorted(record.metrics))})")
                continue
            value, unit = record.metrics[response.metric]
            try:
                values[i, k] = convert(value, unit, response.unit)
            except ValueError as err:
                errors[i] = errors[i] or f"response '{response.name}': {err}"
    return values, errors


def check_responses(plan: SweepPlan, row: Sequence[RunRequest],
                    records: Mapping[str, RunRecord]) -> None:
    """
    Refuse a response whose run finished without its metric, or with a unit it cannot have.

    ``row``: one point's requests (as :func:`requests_for` gives them). A run that failed
    says nothing about the metrics: it is left to the table.
    """
    run_index = {spec: j for j, spec in enumerate(plan.runs)}
    for response in plan.responses:
        record = records.get(run_key(row[run_index[response.run]]))
        if record is None or record.error is not None:
            continue
        key = f'responses.{response.name}'
        if response.metric not in record.metrics:
            raise DataError(f"run {response.run.label} has no metric '{response.metric}' "
                            f"(metrics: {', '.join(sorted(record.metrics))})",
                            file=str(plan.path), key=f'{key}.metric')
        value, unit = record.metrics[response.metric]
        try:
            convert(value, unit, response.unit)
        except ValueError as err:
            raise DataError(f"{err} (metric '{response.metric}' is in {unit or '-'})",
                            file=str(plan.path), key=f'{key}.unit') from None


def sweep(plan: SweepPlan, study, evaluator: Evaluator, out: Path, *, bags: bool = True,
          progress: Callable[[int, int], None] | None = None) -> SweepResult:
    """
    Validate every point, compute the missing runs; return the table of responses.

    The table and report pages are written by ``vd_events.reports.sweep.write_outputs``.
    """
    values = points(plan)
    requests = requests_for(plan, study, values)
    known = load_records(out)
    flat = [r for row in requests for r in row]
    # the first point first: a response the runs do not report (an unknown metric, a unit
    # it cannot be converted to) is refused before the rest of the sweep runs
    known, first = evaluate(requests[0], evaluator, out, bags=bags, known=known,
                            progress=progress)
    check_responses(plan, requests[0], known)
    records, computed = evaluate(flat, evaluator, out, bags=bags, known=known,
                                 progress=progress)
    computed += first
    responses, errors = response_values(plan, requests, records)
    result = SweepResult(plan, values, responses, errors, computed,
                         len({run_key(r) for r in flat}) - computed)
    return result


# --- the table and its analysis (ROS-free, pure) --------------------------------------


def columns(plan: SweepPlan) -> list[str]:
    """Column names of the table: point, factors and responses with their units, error."""
    return (['point'] + [_col(f.name, f.unit) for f in plan.factors]
            + [_col(r.name, r.unit) for r in plan.responses] + ['error'])


def _col(name: str, unit: str) -> str:
    return f'{name} [{unit}]' if unit else name


def table_csv(result: SweepResult) -> str:
    """Write the factors x responses table as CSV (every point; empty cells where a run failed)."""
    stream = io.StringIO()
    writer = csv.writer(stream, lineterminator='\n')
    writer.writerow(columns(result.plan))
    for i, values in enumerate(result.points):
        writer.writerow([i, *(repr(float(v)) for v in values),
                         *('' if math.isnan(v) else repr(float(v)) for v in result.responses[i]),
                         result.errors[i]])
    return stream.getvalue()


def src(x: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, float]:
    """
    Return standardised regression coefficients of ``y`` on the columns of ``x``, and R^2.

    ``x`` (n, d), ``y`` (n,); rows with nan are left out. SRC_i = b_i s_i / s_y of
    the least-squares fit y = b0 + sum b_i x_i (Saltelli et al., Global Sensitivity
    Analysis, 2008, sect. 1.2.5); for a linear response sum SRC_i^2 = R^2. nan where
    the design cannot tell (fewer points than coefficients, a constant column).
    """
    ok = np.isfinite(y) & np.all(np.isfinite(x), axis=1)
    x, y = x[ok], y[ok]
    d = x.shape[1]
    if len(y) <= d + 1 or np.std(y) == 0.0:
        return np.full(d, math.nan), math.nan
    sx = np.std(x, axis=0)
    if np.any(sx == 0.0):
        return np.full(d, math.nan), math.nan
    a = np.column_stack([np.ones(len(y)), x])
    coef, *_ = np.linalg.lstsq(a, y, rcond=None)
    fitted = a @ coef
    r2 = 1.0 - float(np.sum((y - fitted) ** 2) / np.sum((y - np.mean(y)) ** 2))
    return coef[1:] * sx / np.std(y), r2


def main_effects(x: np.ndarray, y: np.ndarray, levels: Sequence[float]
                 ) -> tuple[np.ndarray, np.ndarray]:
    """Mean of ``y`` at each level of one factor column ``x`` (a full factorial design)."""
    levels_arr = np.asarray(levels, dtype=float)
    means = np.array([np.nanmean(y[np.isclose(x, lv)]) if np.any(np.isclose(x, lv)) else
                      math.nan for lv in levels_arr])
    return levels_arr, means


def first_order_indices(x: np.ndarray, y: np.ndarray, levels: Sequence[Sequence[float]]
                        ) -> np.ndarray:
    """
    Return first-order Sobol indices of a complete full factorial design (ANOVA).

    Over the grid of levels, each taken equally likely, S_i = Var(E[y | x_i]) / Var(y)
    exactly (the functional ANOVA decomposition; Saltelli et al. 2008, sect. 4.1):
    the variance of factor i's main-effect means over the total variance. nan if a
    run failed (the grid is then incomplete) or y is constant.
    """
    if not np.all(np.isfinite(y)) or np.var(y) == 0.0:
        return np.full(x.shape[1], math.nan)
    out = []
    for i, lv in enumerate(levels):
        _, means = main_effects(x[:, i], y, lv)
        out.append(float(np.var(means) / np.var(y)))
    return np.array(out)


def pareto_front(a: np.ndarray, b: np.ndarray, senses: tuple[str, str]) -> np.ndarray:
    """
    Return the non-dominated points of two responses (nan rows excluded), sorted by ``a``.

    A point is dominated when another is at least as good in both responses and
    better in one; ``senses`` are 'minimize' or 'maximize' per response.
    """
    sa = 1.0 if senses[0] == 'minimize' else -1.0
    sb = 1.0 if senses[1] == 'minimize' else -1.0
    fa, fb = sa * np.asarray(a, float), sb * np.asarray(b, float)
    idx = [i for i in range(len(fa)) if math.isfinite(fa[i]) and math.isfinite(fb[i])]
    front = [i for i in idx if not any(
        fa[j] <= fa[i] and fb[j] <= fb[i] and (fa[j] < fa[i] or fb[j] < fb[i]) for j in idx)]
    return np.array(sorted(front, key=lambda i: fa[i]), dtype=int)


__all__ = ['sweep', 'check_responses', 'evaluate', 'requests_for', 'run_key', 'load_records',
           'RunRecord', 'SweepResult', 'response_values', 'table_csv', 'src', 'main_effects',
           'first_order_indices', 'pareto_front', 'columns', 'RUNS_FILE']
