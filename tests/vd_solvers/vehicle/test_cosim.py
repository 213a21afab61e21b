# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The lock-step core.

One step per command, the same integration as ``simulate``, and
commands that cannot be applied refused with the state unchanged.
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from vd_data_server.study import load_study
from vd_solvers.errors import SolverError
from vd_solvers.vehicle.cosim import STEERING_TORQUE, Command, CommandError, Stepper
from vd_solvers.vehicle.drivers import OpenLoopSteering
from vd_solvers.vehicle.model import STEP, VehicleModel
from vd_solvers.vehicle.simulation import simulate

STUDIES = Path(__file__).resolve().parents[3] / 'src' / 'vd_data_server' / 'data' / 'studies'


@pytest.fixture(scope='module')
def model():
    return VehicleModel(load_study(STUDIES / 'sedan.yaml').configurations['baseline'])


def test_stepping_reproduces_the_simulation_of_the_same_inputs(model):
    """
    Step command by command exactly as ``simulate`` integrates.

    A coasting steer ramp stepped command by command equals ``simulate`` with the same
    open-loop steering and no speed driver, to the last bit of the recorded channels.
    """
    steps, v0 = 200, 20.0

    def swa(t: float) -> float:
        return 0.5 * min(t, 0.5)

    trace = simulate(model, OpenLoopSteering(swa), None, steps * STEP, event='check',
                     initial_speed=v0, record_every=1)
    stepper = Stepper(model, STEP, v0)
    ch = trace.channels()
    for k in range(steps):
        stepper.advance(Command(steering_wheel_angle=swa(stepper.time)))
        row = stepper.state()
        for name in ('x', 'y', 'yaw', 'roll', 'yaw_rate', 'speed', 'sideslip'):
            assert row[name] == ch[name][k + 1], (name, k)
    assert stepper.step == steps and stepper.time == pytest.approx(steps * STEP)


def test_the_lateral_acceleration_is_the_cog_velocity_change_over_the_step(model):
    stepper = Stepper(model, STEP, 20.0)
    for _ in range(100):
        stepper.advance(Command(steering_wheel_angle=0.3))
    before = stepper.state()
    stepper.advance(Command(steering_wheel_angle=0.3))
    after = stepper.state()
    c, s = math.cos(after['yaw']), math.sin(after['yaw'])
    ay = (-(after['cog_velocity_x'] - before['cog_velocity_x']) * s
          + (after['cog_velocity_y'] - before['cog_velocity_y']) * c) / STEP
    assert after['lateral_acceleration'] == pytest.approx(ay, rel=1e-12)
    # in a steady left turn, a_y is close to r * v
    assert ay == pytest.approx(after['yaw_rate'] * after['speed'], rel=0.05)


def test_drive_and_brake_torques_change_the_speed_their_way(model):
    drive, brake = Stepper(model, STEP, 15.0), Stepper(model, STEP, 15.0)
    for _ in range(200):
        drive.advance(Command(drive_torque=1500.0))
        brake.advance(Command(brake_torque=1500.0))
    assert drive.state()['speed'] > 15.05 and brake.state()['speed'] < 14.8


@pytest.mark.parametrize('command, message', [
    (Command(steering_wheel_angle=math.nan),
     'steering_wheel_angle is not finite (nan)'),
    (Command(drive_torque=math.inf), 'drive_torque is not finite (inf)'),
    (Command(brake_torque=-5.0), 'brake_torque must be >= 0 N*m, got -5'),
    (Command(steering_mode=STEERING_TORQUE, steering_wheel_torque=2.0),
     'steering by torque is not available: the vehicle model has no steering-system '
     'inertia; command the steering-wheel angle (steering_mode 0)'),
    (Command(steering_mode=7), 'unknown steering_mode 7 (0 angle, 1 torque)'),
])
def test_a_command_that_cannot_be_applied_is_refused_and_nothing_moves(model, command, message):
    stepper = Stepper(model, STEP, 10.0)
    stepper.advance(Command())
    q, v, step = stepper.q.copy(), stepper.v.copy(), stepper.step
    with pytest.raises(CommandError) as err:
        stepper.advance(command)
    assert str(err.value) == message
    assert stepper.step == step and np.array_equal(stepper.q, q) and np.array_equal(stepper.v, v)


def test_an_angle_beyond_the_lock_is_refused(model):
    stepper = Stepper(model, STEP, 10.0)
    with pytest.raises(CommandError) as err:
        stepper.advance(Command(steering_wheel_angle=stepper.max_angle * 1.01))
    assert 'beyond the steering lock of the model' in str(err.value)
    assert stepper.step == 0


@pytest.mark.parametrize('h', [0.0, 0.05, math.nan])
def test_an_unusable_step_size_is_an_error(model, h):
    with pytest.raises(SolverError) as err:
        Stepper(model, h)
    assert str(err.value) == f'lock-step size must lie in [0.0001, 0.02] s, got {h!r}'
