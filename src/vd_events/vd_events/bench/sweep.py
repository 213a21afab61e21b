# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
``vd bench``'s sweep figures: a 40-run K&C sweep on one and two solver processes.

The runs are 101-step parallel wheel travel of the front axle at 40 Latin-hypercube
points of two hard-point heights (40 data hashes: nothing is cached). Timed from the
first goal to the last result, with the instances started, discovered and warmed up
(one run each) before; the same 40 runs computed in this process, one by one, with
the solver's own core (``run_kc_event`` on the configuration with the overrides)
give the compute time.

The dispatch overhead per run is measured in pairs, so that the load of a shared
machine falls on both halves alike: a run computed here, then the same run as a
goal to the one solver process (its result back, converted and checked); the
overhead is the median of (goal time - local time) / local time over
:data:`PAIRS` pairs.
"""
from __future__ import annotations

import dataclasses
from pathlib import Path
import statistics
import tempfile
import time
from typing import Any

from vd_data_server.master import parse_set, with_overrides
from vd_data_server.study import load_study
from vd_events.orchestration.dispatch import SolverGraph
from vd_events.orchestration.runner import validate
from vd_events.sweeps.plan import load_plan, points
from vd_events.sweeps.sweep import requests_for
from vd_solvers.kc.from_config import run_kc_event

RUNS = 40
PAIRS = 10
PLAN = """\
name: bench_sweep
master: {master}
configuration: baseline
design: latin_hypercube
samples: {runs}
seed: 7
factors:
  tierod_z: {{key: front_hardpoints.points.tierod_inner.z, unit: mm, range: [326, 346]}}
  lca_z: {{key: front_hardpoints.points.lca_outer.z, unit: mm, range: [171, 191]}}
runs:
  - {{event: parallel_wheel_travel, axle: front}}
responses:
  bump_steer: {{metric: bump_steer, event: parallel_wheel_travel, unit: deg/m}}
"""


def bench_sweep(master: Path, runs: int = RUNS) -> dict[str, Any]:

    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / 'bench.yaml'
        path.write_text(PLAN.format(master=master, runs=runs))
        plan = load_plan(path)
    study = load_study(master)
    requests = [row[0] for row in requests_for(plan, study, points(plan))]
    def local(r) -> None:
        config = with_overrides(study.configurations[r.configuration], parse_set(r.overrides))
        run_kc_event(config, r.event, r.axle, list(r.parameters))

    t0 = time.perf_counter()
    for r in requests:
        local(r)
    compute = time.perf_counter() - t0
    out: dict[str, Any] = {'runs': runs, 'in_process_s': compute,
                           'per_run_s': compute / runs}


    # a warm-up run per instance (imports, first allocation) on the base configuration
    warm = validate(study, dataclasses.replace(requests[0], overrides=(), data_hash=''))
    pairs: list[tuple[float, float]] = []
    for n in (1, 2):
        out[f'{n}_process_s'] = _timed(master, requests, [warm] * n, n,
                                       local if n == 1 else None, pairs)
    one, two = out['1_process_s'], out['2_process_s']
    out['speed_up'] = one / two

    out['overhead_per_run_s'] = statistics.median(goal - here for here, goal in pairs)
    out['overhead_fraction'] = statistics.median((goal - here) / here for here, goal in pairs)
    out['pairs'] = len(pairs)
    return out


def _timed(master: Path, requests, warm, n: int, local=None,
           pairs: list[tuple[float, float]] | None = None) -> float:

    failures: list[str] = []

    def done(request, outcome, error, instance) -> None:
        if error:
            failures.append(error)

    with SolverGraph(master, {'kc': n}) as dispatcher:
        deadline = time.monotonic() + 60.0
        while time.monotonic() < deadline and sum(
                1 for i in dispatcher.live('kc') if i.ready_since is not None) < n:
            dispatcher.discover()
            dispatcher.executor.spin_once(timeout_sec=0.05)
        dispatcher.run(warm, done)
        t0 = time.perf_counter()
        dispatcher.run(requests, done)
        elapsed = time.perf_counter() - t0
        if local is not None and pairs is not None:
            for r in requests[:PAIRS]:
                t0 = time.perf_counter()
                local(r)
                t1 = time.perf_counter()
                dispatcher.run([r], done)
                pairs.append((t1 - t0, time.perf_counter() - t1))
    if failures:
        raise RuntimeError(failures[0])
    return elapsed


__all__ = ['bench_sweep', 'RUNS']
