# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The brakes, anti-lock brakes and driveline inside the compiled loop.

References: the per-step loop (``compiled_loop=False``: the drivers asked in Python at
every step, the wheel torques of :class:`.drivers.WheelTorques`, the compiled step called
from Python) must give the compiled loop's trace on every channel, the actuation channels
included, for straight-line stops with and without anti-lock brakes (both sample vehicles,
and on split friction), a 0-100 km/h run through the gears and a limited-slip
differential on split friction; the same runs uncompiled (``VD_NO_JIT=1``, in a child
process) must give the compiled trace. The actuation itself against closed forms: the four
brake torques of a braking request add up to the request below and above the
proportioning valve's knee, and the drive torques of a drive request add up to it.
"""
from __future__ import annotations

import os
from pathlib import Path
import subprocess
import sys

import numpy as np
import numpy.testing as npt
import pytest

from vd_solvers import compiled
from vd_solvers.vehicle.longitudinal_events import LOCK_SLIP

STUDIES = Path(__file__).resolve().parents[3] / 'src' / 'vd_data_server' / 'data' / 'studies'
#: largest difference of two traces, relative to each channel's largest magnitude
TOLERANCE = 1e-9

# The runs, here (compiled) and in a child with VD_NO_JIT=1 (uncompiled).
RUNS = """
from pathlib import Path

import numpy as np

from vd_data_server.study import load_study
from vd_solvers.road.arrays import flat
from vd_solvers.vehicle.drivers import OpenLoopSteering
from vd_solvers.vehicle.longitudinal_events import PedalRamp
from vd_solvers.vehicle.model import VehicleModel
from vd_solvers.vehicle.simulation import simulate

SPEED = 100.0 / 3.6


def model(studies, study, configuration, split=False):
    config = load_study(Path(studies) / f'{study}_longitudinal.yaml').configurations[configuration]
    base = VehicleModel(config)
    if not split:
        return base
    return VehicleModel(config, maps=base.maps, road=flat(1.0, friction_left=0.3))


def braking(model, compiled_loop=True):
    pressure = model.chassis.brakes.pressure_from_pedal(500.0)
    return simulate(model, OpenLoopSteering(lambda t: 0.0),
                    PedalRamp(0.0, 0.15, (0.0, 0.0), (0.0, pressure)), 8.0,
                    event='straight_line_braking', initial_speed=SPEED, record_every=2,
                    compiled_loop=compiled_loop,
                    stop=lambda row: 'end speed' if row['speed'] < 1.0 else '')


def acceleration(model, compiled_loop=True, duration=30.0):
    return simulate(model, OpenLoopSteering(lambda t: 0.0),
                    PedalRamp(0.0, 1e-3, (1.0, 1.0), (0.0, 0.0)), duration,
                    event='straight_line_acceleration', initial_speed=0.5, record_every=2,
                    compiled_loop=compiled_loop,
                    stop=lambda row: 'end speed' if row['speed'] >= SPEED else '')


CASES = {
    'sedan_abs_braking': (('sedan', 'abs'), braking),
    'hmmwv_abs_braking': (('hmmwv', 'abs'), braking),
    'sedan_no_abs_braking': (('sedan', 'no_abs'), braking),
    'hmmwv_no_abs_braking': (('hmmwv', 'no_abs'), braking),
    'sedan_abs_split_braking': (('sedan', 'abs', True), braking),
    'sedan_acceleration': (('sedan', 'abs'), acceleration),
    'sedan_limited_slip_split': (('sedan', 'abs', True),
                                 lambda m, c=True: acceleration(m, c, duration=3.0)),
}


def evaluate(studies, names):
    models = {}
    out = {}
    for name in names:
        key, run = CASES[name]
        if key not in models:
            models[key] = model(studies, *key)
        for channel, values in run(models[key]).channels().items():
            out[f'{name}/{channel}'] = values
    return out
"""

NAMES = ('sedan_abs_braking', 'hmmwv_abs_braking', 'sedan_no_abs_braking',
         'hmmwv_no_abs_braking', 'sedan_abs_split_braking', 'sedan_acceleration',
         'sedan_limited_slip_split')


@pytest.fixture(scope='module')
def runs():
    scope: dict[str, object] = {}
    exec(RUNS, scope)  # noqa: S102  (the same code the uncompiled child runs)
    return scope


@pytest.fixture(scope='module')
def models():
    """Build each vehicle model of the runs once: (study, configuration, split) -> model."""
    return {}


def _model(runs, models, name):
    key, _ = runs['CASES'][name]
    if key not in models:
        models[key] = runs['model'](STUDIES, *key)
    return models[key]


def _same(a: dict[str, np.ndarray], b: dict[str, np.ndarray], label: str) -> None:
    assert a.keys() == b.keys(), label
    for key in a:
        scale = max(float(np.max(np.abs(b[key]))), 1.0) if b[key].size else 1.0
        npt.assert_allclose(a[key], b[key], rtol=0.0, atol=TOLERANCE * scale,
                            err_msg=f'{label}: {key}')


@pytest.mark.parametrize('name', NAMES)
def test_the_compiled_loop_gives_the_per_step_trace_with_brakes_and_driveline(runs, models,
                                                                            name):
    model = _model(runs, models, name)
    _, run = runs['CASES'][name]
    fast, slow = run(model, True), run(model, False)
    assert fast.steps == slow.steps and fast.stop_reason == slow.stop_reason
    assert fast.actuation and len(fast.actuation) == len(slow.actuation)
    a, b = fast.channels(), slow.channels()
    assert {'throttle', 'gear', 'brake_pressure', 'applied_torque'} <= a.keys()
    _same(a, b, name)
    moving = a['speed'] > 2.0
    if name.endswith('braking'):
        # the master pressure of the pedal ramp: 500 N in 0.15 s
        master = (model.chassis.brakes.pressure_from_pedal(500.0)
                  * np.minimum(a['time'] / 0.15, 1.0))
        assert fast.stop_reason == 'end speed'
        if 'no_abs' not in name:  # the controllers dumped pressure: the case exercises them
            front = a['brake_pressure'][moving, 0:2]
            assert np.any(front < 0.9 * master[moving, None])
        else:  # the wheels locked without them
            assert np.any(a['slip_ratio'][moving] < -0.9)
    elif name == 'sedan_acceleration':
        assert fast.stop_reason == 'end speed'
        assert len(np.unique(a['gear'])) >= 3  # through the gears
    else:
        # the left front wheel spins on low friction: the limited-slip clutch locks and
        # carries its full locking torque to the right wheel, dT = T_lock
        torque = a['applied_torque'][moving]
        locking = model.chassis.driveline.front.locking_torque
        assert model.chassis.driveline.front.kind == 'limited_slip' and locking > 0.0
        npt.assert_allclose(np.max(torque[:, 1] - torque[:, 0]), locking, rtol=1e-3)


@pytest.mark.skipif(not compiled.ENABLED, reason='VD_NO_JIT is set: nothing compiled to compare')
def test_the_compiled_loop_with_brakes_and_driveline_equals_the_uncompiled_one(runs, models,
                                                                               tmp_path):
    """
    Compiled = uncompiled while the wheels roll.

    A locked wheel (no anti-lock brakes) spins about zero, where its brake torque reverses
    over BRAKE_SPIN_SCALE: from there on differences at the rounding level (compiled and
    uncompiled evaluations agree to rounding, not to the bit: test_compiled.py) grow, so
    the stop without anti-lock brakes is compared up to its first locked wheel.
    """
    names = ('sedan_abs_braking', 'hmmwv_abs_braking', 'sedan_no_abs_braking',
             'sedan_acceleration', 'sedan_limited_slip_split')
    fast = {}
    for name in names:
        _, run = runs['CASES'][name]
        for channel, values in run(_model(runs, models, name)).channels().items():
            fast[f'{name}/{channel}'] = values
    out = tmp_path / 'uncompiled.npz'
    code = (RUNS + '\nimport sys\nfrom vd_solvers import compiled\nassert not compiled.ENABLED\n'
            'np.savez(sys.argv[2], **evaluate(sys.argv[1], sys.argv[3].split(",")))\n')
    env = dict(os.environ, VD_NO_JIT='1')
    env['PYTHONPATH'] = os.pathsep.join(
        [str(Path(p).resolve()) for p in sys.path if p] + [env.get('PYTHONPATH', '')])
    subprocess.run([sys.executable, '-c', code, str(STUDIES), str(out), ','.join(names)],
                   env=env, check=True)
    with np.load(out) as data:
        slow = {k: data[k] for k in data.files}
    assert fast.keys() == slow.keys()
    for name in names:
        rows = len(slow[f'{name}/time'])
        if 'no_abs' in name:
            locked = np.any(slow[f'{name}/slip_ratio'] < -LOCK_SLIP, axis=1)
            rows = int(np.argmax(locked))
            assert locked.any() and rows >= 20  # 0.2 s of braking before the lock
        keys = [k for k in fast if k.startswith(f'{name}/')]
        _same({k: fast[k][:rows] for k in keys}, {k: slow[k][:rows] for k in keys}, name)


def test_a_braking_request_gives_its_torque_below_and_above_the_valve_knee(runs, models):
    from vd_solvers.vehicle.drivers import WheelTorques

    chassis = _model(runs, models, 'sedan_abs_braking').chassis
    brakes = chassis.brakes
    spin = np.full(4, 80.0)  # rolling at about 100 km/h: tanh(spin / 0.1) = 1
    for pressure in (0.5 * brakes.knee_pressure, 2.0 * brakes.knee_pressure):
        # the torque of that master pressure, written out: 2 (g_f p + g_r p_rear)
        rear = brakes.knee_pressure + brakes.knee_slope * (pressure - brakes.knee_pressure) \
            if pressure > brakes.knee_pressure else pressure
        total = 2.0 * (brakes.front.gain * pressure + brakes.rear.gain * rear)
        actuate = WheelTorques(chassis)
        torques = actuate(-total, spin, np.zeros(4), 27.8, 0.005)
        npt.assert_allclose(np.sum(torques), -total, rtol=1e-12)
        npt.assert_allclose(actuate.pressures, [pressure, pressure, rear, rear], rtol=1e-12)
        assert actuate.throttle == 0.0


def test_a_drive_request_opens_the_throttle_for_its_torque(runs, models):
    from vd_solvers.vehicle.drivers import WheelTorques

    chassis = _model(runs, models, 'sedan_acceleration').chassis
    spin = np.full(4, 30.0)
    actuate = WheelTorques(chassis)
    torques = actuate(500.0, spin, np.zeros(4), 10.0, 0.005)
    # equal wheel speeds: every differential splits evenly, the request is met in full
    npt.assert_allclose(np.sum(torques), 500.0, rtol=1e-12)
    assert 0.0 < actuate.throttle < 1.0 and actuate.gear >= 1
    npt.assert_array_equal(actuate.pressures, np.zeros(4))
