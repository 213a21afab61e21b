# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The compiled force evaluation is the Python one: the same functions, compiled and not.

The full vehicle's forces (``VehicleModel.forces``) and the four-wheel Magic Formula are
evaluated on random states here (on the flat road and on a class C road with split
friction), with numba, and in a second process with ``VD_NO_JIT=1``
(the same functions run as Python); both must agree to 1e-10 relative.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
import numpy.testing as npt
import pytest

from vd_solvers import compiled
from vdtest import run_uncompiled

STUDIES = Path(__file__).resolve().parents[3] / 'src' / 'vd_data_server' / 'data' / 'studies'
RTOL = 1e-10

# Run in this process (compiled) and in a child with VD_NO_JIT=1 (uncompiled): random
# states around a cornering state at 100 km/h, with and without the previous step's forces,
# and random loads, slips and inclinations for the tires of both axles.
EVALUATE = """
import numpy as np
from vd_data_server.study import load_study
from vd_solvers.road.arrays import road_grid
from vd_solvers.road.iso8608 import random_road
from vd_solvers.vehicle.forces import wheel_radii, wheel_tires
from vd_solvers.vehicle.model import VehicleModel


def evaluate(study):
    config = load_study(study).configurations['baseline']
    model = VehicleModel(config)
    # a class C road with split friction under the same car
    road = road_grid(random_road('C', 60.0, 1.6, 3, 0.02), -5.0, 60.0, -3.0, 3.0, 0.02, 0.75,
                     friction_left=0.4)
    rough = VehicleModel(config, maps=model.maps, road=road)
    rng = np.random.default_rng(27)
    q0, v0 = model.initial_state(27.8, 0.15)
    out = {}
    for trial in range(12):
        if trial >= 8:
            model = rough
            q0[0] = 20.0 + 3.0 * trial
        q, v = q0.copy(), v0.copy()
        q[:3] += rng.normal(0.0, 0.01, 3)
        q[7::2] += rng.normal(0.0, 0.01, 4)
        quat = q[3:7] + rng.normal(0.0, 0.02, 4)
        q[3:7] = quat / np.linalg.norm(quat)
        v += rng.normal(0.0, 0.3, v.size)
        slip = rng.normal(0.0, 0.03, (2, 4))
        torque = rng.normal(0.0, 100.0, 4)
        swa = float(rng.normal(0.0, 0.3))
        previous = None
        if trial % 2:
            previous = model.forces(q, v, 0.5 * swa, torque, slip, None, 0.005)[1]
        tau, wheel, update = model.forces(q, v, swa, torque, slip, previous, 0.005)
        out[f'tau{trial}'] = tau
        out[f'wheel{trial}'] = np.array(wheel)
        out[f'update{trial}'] = np.array(update)
    fz = rng.uniform(-500.0, 12000.0, (50, 4))
    kappa = rng.normal(0.0, 0.2, (50, 4))
    alpha = rng.normal(0.0, 0.2, (50, 4))
    gamma = rng.normal(0.0, 0.05, (50, 4))
    vx = rng.uniform(-5.0, 60.0, (50, 4))
    friction = np.where(rng.uniform(size=(50, 4)) < 0.5, 1.0, rng.uniform(0.2, 1.2, (50, 4)))
    a = model.arrays
    out['tires'] = np.array([wheel_tires(a.tire_front, a.tire_rear, fz[i], kappa[i], alpha[i],
                                         gamma[i], vx[i], model.mirror, friction[i])
                             for i in range(50)])
    out['radii'] = np.array([wheel_radii(a.tire_front, a.tire_rear, np.abs(fz[i]))
                             for i in range(50)])
    return out
"""


def _evaluate_here() -> dict[str, np.ndarray]:
    scope: dict[str, object] = {}
    exec(EVALUATE, scope)  # noqa: S102  (the same code the child runs)
    return scope['evaluate'](STUDIES / 'sedan.yaml')  # type: ignore[operator]


def _evaluate_uncompiled(tmp_path: Path) -> dict[str, np.ndarray]:
    return run_uncompiled(EVALUATE, 'evaluate', STUDIES / 'sedan.yaml', tmp_path)


@pytest.mark.skipif(not compiled.ENABLED, reason='VD_NO_JIT is set: nothing compiled to compare')
def test_compiled_forces_equal_the_uncompiled_functions(tmp_path):
    """Forces, wheel states, slip updates, tire forces and radii: compiled = Python, 1e-10."""
    fast = _evaluate_here()
    slow = _evaluate_uncompiled(tmp_path)
    assert set(fast) == set(slow)
    for key, value in fast.items():
        scale = float(np.max(np.abs(slow[key])))
        assert scale > 0.0, key
        npt.assert_allclose(value, slow[key], rtol=RTOL, atol=RTOL * scale, err_msg=key)
