# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Cost of one steady-state Magic Formula evaluation per tire, compiled and as plain numpy.

``python -m vd_solvers.tire.bench`` prints, as JSON, the microseconds per tire of
``magic_formula.combined_forces`` (pure and combined slip forces and moments) with the sample
sedan's front tire, called from Python on 4 wheels (one car) and on 400 wheels, and
(``vehicle step``) of ``magic_formula.four_wheel_forces``, the four wheels as the compiled
vehicle step evaluates them (``vehicle.forces.wheel_tires``; the sedan's front and rear
tires), called from a compiled loop so that Python's call overhead is not counted; in this
process's mode: compiled, or plain Python / numpy under ``VD_NO_JIT=1``. :func:`per_tire`
runs both, the uncompiled one in a second process (the mode is fixed when the functions are
first imported), for ``make bench``.
"""
from __future__ import annotations

import json
import os
import subprocess
import sys
import time

import numpy as np

from vd_data_server.paths import default_master
from vd_data_server.study import load_study
from vd_data_server.tire_group import tire_properties
from vd_solvers import compiled
from vd_solvers.compiled import jit
from vd_solvers.tire.magic_formula import MagicFormula, combined_forces, four_wheel_forces

#: wheels per call: one car, and many
SIZES = (4, 400)
#: calls timed per size (the best of REPEATS runs)
CALLS, REPEATS = 2000, 5
#: calls of four_wheel_forces per compiled loop
STEP_CALLS = 20000
#: the key of the vehicle step's figure
VEHICLE_STEP = 'vehicle step'


@jit
def _repeat_four_wheels(front: np.ndarray, rear: np.ndarray, fz: np.ndarray,
                        kappa: np.ndarray, alpha: np.ndarray, gamma: np.ndarray,
                        vx: np.ndarray, mirror: np.ndarray, calls: int) -> float:
    """Call ``four_wheel_forces`` ``calls`` times; return a sum of its results (kept live)."""
    total = 0.0
    for _ in range(calls):
        total += four_wheel_forces(front, rear, fz, kappa, alpha, gamma, vx, mirror)[0, 0]
    return total


def measure() -> dict[str, float]:
    """Microseconds per tire for each call size, in this process's mode (module doc)."""
    config = next(iter(load_study(default_master()).configurations.values()))
    p = MagicFormula(tire_properties(config.group('front_tire'))).coefficients
    rear = MagicFormula(tire_properties(config.group('rear_tire'))).coefficients
    out = {}
    for n in SIZES:
        rng = np.random.default_rng(n)
        fz = rng.uniform(2000.0, 7000.0, n)
        kappa, alpha = rng.uniform(-0.1, 0.1, n), rng.uniform(-0.1, 0.1, n)
        gamma, vx = rng.uniform(-0.03, 0.03, n), np.full(n, 25.0)
        mirror, phit = np.ones(n), np.zeros(n)
        combined_forces(p, fz, kappa, alpha, gamma, vx, mirror, phit)
        calls = max(CALLS // n * 4, 20)
        best = float('inf')
        for _ in range(REPEATS):
            t0 = time.process_time()
            for _ in range(calls):
                combined_forces(p, fz, kappa, alpha, gamma, vx, mirror, phit)
            best = min(best, (time.process_time() - t0) / calls)
        out[str(n)] = best / n * 1e6
    rng = np.random.default_rng(4)
    fz = rng.uniform(2000.0, 7000.0, 4)
    kappa, alpha = rng.uniform(-0.1, 0.1, 4), rng.uniform(-0.1, 0.1, 4)
    gamma, vx = rng.uniform(-0.03, 0.03, 4), np.full(4, 25.0)
    mirror = np.array([1.0, -1.0, 1.0, -1.0])
    args = (p, rear, fz, kappa, alpha, gamma, vx, mirror)
    _repeat_four_wheels(*args, 1)
    calls = STEP_CALLS if compiled.ENABLED else STEP_CALLS // 100
    best = float('inf')
    for _ in range(REPEATS):
        t0 = time.process_time()
        _repeat_four_wheels(*args, calls)
        best = min(best, (time.process_time() - t0) / calls)
    out[VEHICLE_STEP] = best / 4 * 1e6
    return out


def per_tire() -> dict[str, dict[str, float]]:
    """Both modes: compiled in this process (if it runs compiled), numpy in a child process."""
    env = dict(os.environ, VD_NO_JIT='1')
    child = subprocess.run([sys.executable, '-m', 'vd_solvers.tire.bench'], env=env,
                           capture_output=True, text=True, check=True)
    return {'compiled' if compiled.ENABLED else 'numpy': measure(),
            'numpy': json.loads(child.stdout)}


if __name__ == '__main__':
    print(json.dumps(measure()))
