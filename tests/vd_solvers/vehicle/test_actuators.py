# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The steering and speed actuators against closed forms.

First-order lag step response ``x(t) = x*(1 - exp(-t/tau))``; steady-state steering-wheel
angle = tire angle x steering ratio; the rack-travel lock and the rate limits; the PI
speed loop on a point mass (``m dv/dt = T / r``) reaches the set speed without a
steady-state error; a Twist's tire angle holds its yaw rate on the kinematic single track
(``omega = v tan(delta) / L``).
"""
from __future__ import annotations

import math

import numpy as np
from numpy.testing import assert_allclose
import pytest

from vd_solvers.vehicle.actuators import (
    ActuatorParameters,
    Actuators,
    Setpoint,
    lag_factor,
    twist_setpoint,
)
from vd_solvers.vehicle.cosim import CommandError

H = 0.005
PARAMS = ActuatorParameters(steering_ratio=16.0, steering_lock=math.radians(540.0),
                            mass=1500.0, wheel_radius=0.3, wheelbase=2.7,
                            steering_lag=0.08, torque_lag=0.1)


def test_steering_follows_a_step_as_a_first_order_lag():
    act = Actuators(PARAMS)
    delta = 0.05
    swa = [act.command(Setpoint(steering_angle=delta), 0.0, H).steering_wheel_angle
           for _ in range(200)]
    t = H * (1 + np.arange(200))
    assert_allclose(swa, PARAMS.steering_ratio * delta * (1 - np.exp(
        -t / PARAMS.steering_lag)), rtol=1e-12)


def test_steady_state_steering_wheel_angle_is_tire_angle_times_ratio():
    act = Actuators(PARAMS)
    for delta in (0.1, -0.03):
        for _ in range(2000):  # 10 s = 125 time constants
            cmd = act.command(Setpoint(steering_angle=delta), 0.0, H)
        assert cmd.steering_wheel_angle == pytest.approx(delta * PARAMS.steering_ratio,
                                                         rel=1e-12)


def test_steering_stops_at_the_rack_travel_lock():
    act = Actuators(PARAMS)
    for _ in range(2000):
        cmd = act.command(Setpoint(steering_angle=-1.0), 0.0, H)  # 16 rad asked
    assert cmd.steering_wheel_angle == pytest.approx(-PARAMS.steering_lock, rel=1e-12)
    assert abs(cmd.steering_wheel_angle) <= PARAMS.steering_lock


def test_steering_angle_velocity_limits_the_rate():
    act = Actuators(PARAMS)
    rate = 0.2  # rad/s of tire angle
    swa = [act.command(Setpoint(steering_angle=0.3, steering_angle_velocity=rate), 0.0,
                       H).steering_wheel_angle for _ in range(50)]
    # the lag would move faster than the limit at first: the ramp of the limit
    assert_allclose(swa[:10], [PARAMS.steering_ratio * rate * H * (k + 1) for k in range(10)],
                    rtol=1e-12)


def test_a_torque_step_is_a_first_order_lag_and_splits_into_drive_and_brake():
    # no integral, a speed error held constant: the torque target is constant
    p = ActuatorParameters(**{**PARAMS.__dict__, 'speed_integral': 0.0, 'speed_gain': 1.0})
    act = Actuators(p)
    torques = [act.command(Setpoint(speed=2.0), 0.0, H).drive_torque for _ in range(100)]
    target = p.mass * p.wheel_radius * 2.0  # k_p e = 2 m/s^2 < a_drive
    t = H * (1 + np.arange(100))
    assert_allclose(torques, target * (1 - np.exp(-t / p.torque_lag)),
                    rtol=1e-12)
    act = Actuators(p, speed=10.0)
    cmd = act.command(Setpoint(speed=5.0), 10.0, H)  # slower: brake, no drive
    assert cmd.drive_torque == 0.0 and cmd.brake_torque > 0.0


def test_acceleration_is_limited_by_the_drive_and_brake_limits():
    act = Actuators(PARAMS)
    for _ in range(1000):  # 50 torque time constants
        cmd = act.command(Setpoint(speed=50.0), 0.0, H)
    assert cmd.drive_torque == pytest.approx(PARAMS.mass * PARAMS.wheel_radius
                                             * PARAMS.max_acceleration, rel=1e-9)


def test_the_speed_loop_reaches_the_set_speed_on_a_point_mass():
    act = Actuators(PARAMS)
    v = 0.0
    for _ in range(int(60.0 / H)):
        cmd = act.command(Setpoint(speed=15.0), v, H)
        resistance = 300.0  # N, constant: the integral must take it up
        force = (cmd.drive_torque - cmd.brake_torque) / PARAMS.wheel_radius - resistance
        v += force / PARAMS.mass * H
    assert v == pytest.approx(15.0, abs=1e-3)


def test_the_acceleration_setpoint_ramps_the_speed_reference():
    act = Actuators(PARAMS)
    for _ in range(100):  # 0.5 s at 2 m/s^2
        act.command(Setpoint(speed=10.0, acceleration=2.0), 0.0, H)
    assert act.speed_reference == pytest.approx(1.0, rel=1e-12)


def test_a_twist_tire_angle_holds_its_yaw_rate_on_the_kinematic_single_track():
    for v, omega in ((10.0, 0.3), (5.0, -0.5)):
        sp = twist_setpoint(v, omega, PARAMS.wheelbase)
        assert v * math.tan(sp.steering_angle) / PARAMS.wheelbase == pytest.approx(omega)
        assert math.copysign(1.0, sp.steering_angle) == math.copysign(1.0, omega)  # REP 103
    assert twist_setpoint(0.0, 0.5, PARAMS.wheelbase).steering_angle == 0.0


def test_lag_factor_of_zero_time_constant_follows_at_once():
    assert lag_factor(H, 0.0) == 1.0
    assert lag_factor(H, 0.1) == pytest.approx(1 - math.exp(-0.05), rel=1e-14)


@pytest.mark.parametrize('setpoint, message', [
    (Setpoint(speed=-1.0), 'speed -1 m/s: reverse is not available (the driveline model has '
     'no reverse gear)'),
    (Setpoint(steering_angle=math.nan), 'steering_angle is not finite (nan)'),
    (Setpoint(speed=math.inf), 'speed is not finite (inf)'),
])
def test_a_setpoint_the_actuators_cannot_follow_is_refused_and_changes_nothing(setpoint,
                                                                                message):
    act = Actuators(PARAMS)
    before = dict(act.__dict__)
    with pytest.raises(CommandError) as err:
        act.command(setpoint, 0.0, H)
    assert str(err.value) == message
    assert act.__dict__ == before


@pytest.mark.parametrize('name, value', [('steering_ratio', 0.0), ('mass', -1.0),
                                         ('steering_lag', -0.1), ('torque_lag', math.nan)])
def test_unusable_actuator_parameters_are_refused_with_their_name(name, value):
    with pytest.raises(ValueError) as err:
        ActuatorParameters(**{**PARAMS.__dict__, name: value})
    assert f"actuator parameter '{name}'" in str(err.value)
