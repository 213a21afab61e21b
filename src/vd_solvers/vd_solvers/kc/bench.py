# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Wall-clock timings of the K&C solver (not run by the unit tests).

Targets (2-core machine): a 101-step parallel-wheel-travel sweep of one axle
well under a second; the six-event suite of both axles a few seconds.

Example::

    from vd_solvers.kc.bench import bench_kc
    print(bench_kc(front_input, rear_input))
"""
from __future__ import annotations

import time

from .events import KCModel, run_suite
from .model import SuspensionInput


def bench_kc(inp_front: SuspensionInput, inp_rear: SuspensionInput) -> dict[str, float]:
    """
    Return the seconds taken by the K&C benchmark steps.

    Seconds for: assembling the front axle, one 101-step parallel travel
    sweep per axle, and the full suite (all events, plus the bar-less roll
    run) per axle and for both.
    """
    out: dict[str, float] = {}
    t0 = time.perf_counter()
    front = KCModel(inp_front)
    out['assemble_front'] = time.perf_counter() - t0
    rear = KCModel(inp_rear)
    for name, model in (('front', front), ('rear', rear)):
        t0 = time.perf_counter()
        model.run('parallel_wheel_travel')
        out[f'parallel_wheel_travel_{name}'] = time.perf_counter() - t0
    total = 0.0
    for name, inp in (('front', inp_front), ('rear', inp_rear)):
        t0 = time.perf_counter()
        run_suite(inp)
        out[f'suite_{name}'] = time.perf_counter() - t0
        total += out[f'suite_{name}']
    out['suite_both_axles'] = total
    return out
