# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The variable step of :mod:`vd_solvers.vehicle.adaptive` against converged fixed-step runs.

The reference is the fixed-step semi-implicit Euler of :mod:`.dynamics` made converged by
Richardson extrapolation of its runs at 1 ms and 0.5 ms (its error is first order in the
step: 2 y(h/2) - y(h) removes that term), on the output grid both share.
"""
from __future__ import annotations

import os
from pathlib import Path
import subprocess
import sys

import numpy as np
import pytest

from vd_data_server.study import load_study
from vd_solvers import compiled
from vd_solvers.errors import SolverError
from vd_solvers.vehicle.drivers import OpenLoopSteering, SpeedController
from vd_solvers.vehicle.model import VehicleModel
from vd_solvers.vehicle.simulation import simulate

STUDIES = Path(__file__).resolve().parents[3] / 'src' / 'vd_data_server' / 'data' / 'studies'
SPEED = 100.0 / 3.6
DURATION = 4.0
SAMPLE = 0.01
#: the local error tolerance of the variable-step runs, m/s and rad/s
TOLERANCE = 3e-5
#: their accuracy: the largest yaw-rate and lateral-acceleration error over the run, as a
#: fraction of the reference's peak
ACCURACY = 0.01


def _model(study: str) -> VehicleModel:
    configurations = load_study(STUDIES / study).configurations
    return VehicleModel(configurations[next(iter(configurations))])


@pytest.fixture(scope='module', params=['sedan.yaml', 'hmmwv.yaml', 'sedan_mf62.yaml'])
def vehicle(request):
    return _model(request.param)


def _step_steer(model: VehicleModel, h: float, **variable):
    _, r_e = model.tire_radii(model.static_loads())
    steering = OpenLoopSteering(times=[0.0, 1.0, 1.1, DURATION], angles=[0.0, 0.0, 0.4, 0.4])
    speed = SpeedController(lambda t: SPEED, model.total_mass, float(np.mean(r_e)))
    return simulate(model, steering, speed, DURATION, event='step_steer', initial_speed=SPEED,
                    record_every=max(1, round(SAMPLE / h)), h=h, **variable)


def _converged(model: VehicleModel) -> dict[str, np.ndarray]:
    fine = _step_steer(model, 0.0005).channels()
    coarse = _step_steer(model, 0.001).channels()
    np.testing.assert_array_equal(fine['time'], coarse['time'])
    return {k: 2.0 * fine[k] - coarse[k] for k in ('yaw_rate', 'lateral_acceleration')}


def test_the_variable_step_follows_the_converged_reference(vehicle):
    """Step steer: yaw rate and lateral acceleration within 1 % of their peaks, fewer steps."""
    reference = _converged(vehicle)
    trace = _step_steer(vehicle, 0.005, tolerance=TOLERANCE)
    ch = trace.channels()
    np.testing.assert_allclose(ch['time'], np.arange(ch['time'].size) * SAMPLE, atol=1e-12)
    for key in ('yaw_rate', 'lateral_acceleration'):
        peak = np.max(np.abs(reference[key]))
        assert np.max(np.abs(ch[key] - reference[key])) <= ACCURACY * peak, key
    # the fixed step needs 2.5 ms for about this accuracy (0.5 to 0.8 % of the yaw rate's
    # peak on these cars, docs/models.md "Variable step")
    assert trace.steps < 0.5 * DURATION / 0.0025


def test_a_steady_run_costs_few_steps():
    """Straight ahead at 100 km/h: 10 s more cost 10 s / h_max steps, one repeated at most."""
    model = _model('sedan.yaml')

    def straight(duration: float):
        steering = OpenLoopSteering(times=[0.0, duration], angles=[0.0, 0.0])
        return simulate(model, steering, None, duration, event='straight', initial_speed=SPEED,
                        record_every=2, h=0.005, tolerance=TOLERANCE, h_max=0.04)

    short, long = straight(10.0), straight(20.0)
    assert long.steps - short.steps <= 10.0 / 0.04 + 2
    assert long.rejected - short.rejected <= 1
    ch = long.channels()
    assert ch['time'].size == 2001
    assert np.max(np.abs(ch['yaw_rate'])) < 1e-9


def test_forty_millisecond_steps_are_stable_where_the_explicit_step_diverges():
    """Sedan: fixed 20 ms steps diverge (wheel hop); the travel linearly implicit holds 40 ms."""
    model = _model('sedan.yaml')
    with pytest.raises(SolverError, match='non-finite'):
        _step_steer(model, 0.02)
    reference = _converged(model)
    ch = _step_steer(model, 0.005, tolerance=TOLERANCE, h_min=0.04, h_max=0.04).channels()
    assert np.all(np.isfinite(ch['wheel_travel']))
    # the steady state does not depend on the step
    steady = ch['time'] >= DURATION - 1.0
    np.testing.assert_allclose(np.mean(ch['yaw_rate'][steady]),
                               np.mean(reference['yaw_rate'][steady]), rtol=0.005)


def test_a_variable_step_needs_a_positive_tolerance():
    model = _model('sedan.yaml')
    with pytest.raises(SolverError, match="event 'step_steer'.*positive tolerance"):
        _step_steer(model, 0.005, tolerance=0.0)


# a short step steer with the variable step, run here (compiled) and in a child with
# VD_NO_JIT=1 (the same functions as Python)
SHORT = """
import sys
import numpy as np
from vd_data_server.study import load_study
from vd_solvers.vehicle.drivers import OpenLoopSteering, SpeedController
from vd_solvers.vehicle.model import VehicleModel
from vd_solvers.vehicle.simulation import simulate


def short(study):
    model = VehicleModel(load_study(study).configurations['baseline'])
    steering = OpenLoopSteering(times=[0.0, 0.2, 0.3, 0.6], angles=[0.0, 0.0, 0.4, 0.4])
    speed = SpeedController(lambda t: 27.8, model.total_mass, 0.3)
    trace = simulate(model, steering, speed, 0.6, event='step_steer', initial_speed=27.8,
                     record_every=2, h=0.005, tolerance=3e-5)
    ch = trace.channels()
    return np.concatenate([ch[k] for k in ('time', 'yaw_rate', 'roll', 'speed')]
                          + [[trace.steps, trace.rejected, trace.evaluations]])
"""


@pytest.mark.skipif(not compiled.ENABLED, reason='VD_NO_JIT is set: nothing compiled to compare')
def test_the_variable_step_runs_uncompiled_as_compiled(tmp_path):
    """VD_NO_JIT=1: the same steps and channels (1e-9) as the compiled loop."""
    scope: dict[str, object] = {}
    exec(SHORT, scope)  # noqa: S102  (the same code the child runs)
    fast = scope['short'](STUDIES / 'sedan.yaml')  # type: ignore[operator]
    out = tmp_path / 'slow.npy'
    code = (SHORT + '\nfrom vd_solvers import compiled\nassert not compiled.ENABLED\n'
            'np.save(sys.argv[2], short(sys.argv[1]))\n')
    env = dict(os.environ, VD_NO_JIT='1')
    env['PYTHONPATH'] = os.pathsep.join(
        [str(Path(p).resolve()) for p in sys.path if p] + [env.get('PYTHONPATH', '')])
    subprocess.run([sys.executable, '-c', code, str(STUDIES / 'sedan.yaml'), str(out)],
                   env=env, check=True)
    slow = np.load(out)
    np.testing.assert_array_equal(fast[-3:], slow[-3:])
    np.testing.assert_allclose(fast, slow, rtol=1e-9, atol=1e-12)
