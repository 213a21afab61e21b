# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Steering and speed actuators: a tire-angle and speed setpoint into a vehicle command.

ROS-free. The lock-step vehicle takes, beside its own :class:`~.cosim.Command`
(steering-wheel angle and wheel torques), the setpoints of the controllers a robotics
team already has: ``ackermann_msgs/AckermannDrive`` (tire angle of a virtual front
wheel, speed, acceleration) and ``geometry_msgs/Twist`` (forward speed, yaw rate). Each
step, :meth:`Actuators.command` turns the current :class:`Setpoint` into the command of
that step:

Steering (a position-controlled steering system)::

    theta* = clip(ratio * delta*, -theta_lock, theta_lock)
    theta[k+1] = theta[k] + (1 - exp(-h / tau_s)) (theta* - theta[k])      (1)

``ratio`` is the configuration's steering ratio at the centre (steering-wheel angle
per road-wheel angle, from the steering map) and ``theta_lock`` the steering-wheel angle
at the end of the rack travel (the ends of the steering map). (1) is the exact
discretisation of the first-order lag ``tau_s dtheta/dt = theta* - theta`` for a
setpoint held over the step, so the response to a step is ``theta*(1 - exp(-t/tau_s))``
at every sample. A positive ``steering_angle_velocity`` limits the change per step to
``ratio * steering_angle_velocity * h``. ``tau_s = 0`` follows the setpoint at once.

Speed (a PI controller on acceleration, a first-order torque actuator)::

    v_ref[k+1] = v_ref[k] + clip(v* - v_ref[k], -a h, a h)    (a > 0; else v_ref = v*)
    e = v_ref - v
    a_cmd = clip(dv_ref/dt + k_p e + k_i (I + e h), -a_brake, a_drive)        (2)
    T* = m r a_cmd,  T[k+1] = T[k] + (1 - exp(-h / tau_T)) (T* - T[k])         (3)

``m`` the vehicle's total mass, ``r`` the tires' unloaded radius; the integral ``I``
grows only while (2) is not clipped (conditional integration against wind-up). A
positive ``T`` is the total drive torque, a negative one the total brake torque; the
vehicle splits them over the axles with its driveline shares (``drive_front``,
``brake_front``). ``v`` is the speed of the centre of gravity. Reverse is not modelled
(the driveline has no reverse gear): a negative speed setpoint is refused.

Twist (REP 103: ``angular.z`` > 0 turns left): the kinematic single-track relation
``delta* = atan(L omega / v)`` (wheelbase ``L``) gives the tire angle that holds yaw rate
``omega`` at speed ``v`` at low lateral acceleration; with ``v`` below ``TWIST_MIN_SPEED``
the tire angle is zero (a yaw rate cannot be held at standstill).
"""
from __future__ import annotations

from dataclasses import dataclass
import math

import numpy as np

from .cosim import Command, CommandError, steering_lock
from .model import VehicleModel

#: m/s: below this forward speed a Twist's yaw rate commands no steering
TWIST_MIN_SPEED = 0.1


@dataclass(frozen=True)
class Setpoint:
    """What the vehicle should do: tire angle (rad, + left), speed (m/s, >= 0), limits."""

    steering_angle: float = 0.0
    speed: float = 0.0
    acceleration: float = 0.0  # m/s^2, limit of the speed reference's rate (0: none)
    steering_angle_velocity: float = 0.0  # rad/s, limit of the tire angle's rate (0: none)


@dataclass(frozen=True)
class ActuatorParameters:
    """The vehicle's steering and driveline as the actuators see them (module doc)."""

    steering_ratio: float  # steering-wheel angle per tire angle, -
    steering_lock: float  # rad, steering-wheel angle at the end of the rack travel
    mass: float  # kg, the whole vehicle
    wheel_radius: float  # m
    wheelbase: float  # m
    steering_lag: float = 0.05  # s, tau_s of (1)
    torque_lag: float = 0.05  # s, tau_T of (3)
    speed_gain: float = 1.5  # 1/s, k_p of (2)
    speed_integral: float = 0.3  # 1/s^2, k_i of (2)
    max_acceleration: float = 4.0  # m/s^2, a_drive of (2)
    max_deceleration: float = 8.0  # m/s^2, a_brake of (2)

    def __post_init__(self) -> None:
        for name in ('steering_ratio', 'steering_lock', 'mass', 'wheel_radius', 'wheelbase',
                     'max_acceleration', 'max_deceleration'):
            value = getattr(self, name)
            if not (math.isfinite(value) and value > 0.0):
                raise ValueError(f"actuator parameter '{name}' must be a positive number, "
                                 f'got {value!r}')
        for name in ('steering_lag', 'torque_lag', 'speed_gain', 'speed_integral'):
            value = getattr(self, name)
            if not (math.isfinite(value) and value >= 0.0):
                raise ValueError(f"actuator parameter '{name}' must be >= 0, got {value!r}")


def parameters_of(model: VehicleModel, **settings: float) -> ActuatorParameters:
    """
    Return the actuator parameters of ``model``'s configuration; ``settings`` the tunables.

    Steering ratio at the centre and rack-travel lock from the steering map, total mass,
    unloaded tire radius, wheelbase from the geometry group.
    """
    return ActuatorParameters(
        steering_ratio=float(model.maps.steering_ratio), steering_lock=steering_lock(model),
        mass=float(model.total_mass), wheel_radius=float(np.mean(model.r0)),
        wheelbase=float(model.config.group('geometry').scalar('wheelbase')), **settings)


def lag_factor(h: float, tau: float) -> float:
    """Return ``1 - exp(-h / tau)``: the share of a step a first-order lag covers in ``h``."""
    return 1.0 if tau <= 0.0 else -math.expm1(-h / tau)


def twist_setpoint(speed: float, yaw_rate: float, wheelbase: float) -> Setpoint:
    """Return the setpoint of a Twist: forward speed (m/s) and yaw rate (rad/s, + left)."""
    for name, value in (('linear.x', speed), ('angular.z', yaw_rate)):
        if not math.isfinite(value):
            raise CommandError(f'{name} is not finite ({value})')
    angle = math.atan(wheelbase * yaw_rate / speed) if speed >= TWIST_MIN_SPEED else 0.0
    return Setpoint(steering_angle=angle, speed=speed)


def check_setpoint(setpoint: Setpoint) -> None:
    """Raise CommandError for a setpoint the actuators cannot follow (module doc)."""
    for name in ('steering_angle', 'speed', 'acceleration', 'steering_angle_velocity'):
        value = getattr(setpoint, name)
        if not math.isfinite(value):
            raise CommandError(f'{name} is not finite ({value})')
    if setpoint.speed < 0.0:
        raise CommandError(f'speed {setpoint.speed:.4g} m/s: reverse is not available (the '
                           'driveline model has no reverse gear)')


class Actuators:
    """The actuator states (steering-wheel angle, torque, speed reference, integral)."""

    def __init__(self, parameters: ActuatorParameters, speed: float = 0.0) -> None:
        self.p = parameters
        self.steering_wheel_angle = 0.0  # rad
        self.torque = 0.0  # N*m, total at the wheels, + drive, - brake
        self.speed_reference = speed  # m/s
        self.integral = 0.0  # m, of the speed error

    def command(self, setpoint: Setpoint, speed: float, h: float) -> Command:
        """Advance the actuators over one step of ``h`` s; return the step's command."""
        check_setpoint(setpoint)
        p = self.p
        # steering, (1)
        lock = p.steering_lock
        target = min(max(p.steering_ratio * setpoint.steering_angle, -lock), lock)
        change = lag_factor(h, p.steering_lag) * (target - self.steering_wheel_angle)
        if setpoint.steering_angle_velocity > 0.0:
            limit = p.steering_ratio * setpoint.steering_angle_velocity * h
            change = min(max(change, -limit), limit)
        self.steering_wheel_angle = min(max(self.steering_wheel_angle + change, -lock), lock)
        # speed, (2)
        before = self.speed_reference
        if setpoint.acceleration > 0.0:
            step = setpoint.acceleration * h
            self.speed_reference += min(max(setpoint.speed - before, -step), step)
        else:
            self.speed_reference = setpoint.speed
        feedforward = (self.speed_reference - before) / h if setpoint.acceleration > 0.0 else 0.0
        error = self.speed_reference - speed
        wanted = feedforward + p.speed_gain * error + p.speed_integral * (self.integral
                                                                          + error * h)
        accel = min(max(wanted, -p.max_deceleration), p.max_acceleration)
        if accel == wanted:
            self.integral += error * h
        # torque, (3)
        target_torque = p.mass * p.wheel_radius * accel
        self.torque += lag_factor(h, p.torque_lag) * (target_torque - self.torque)
        return Command(steering_wheel_angle=self.steering_wheel_angle,
                       drive_torque=max(self.torque, 0.0), brake_torque=max(-self.torque, 0.0))

    def follow(self, command: Command) -> None:
        """Take over the state a directly applied command leaves (a VehicleCommand)."""
        self.steering_wheel_angle = command.steering_wheel_angle
        self.torque = command.drive_torque - command.brake_torque


__all__ = ['Actuators', 'ActuatorParameters', 'Setpoint', 'TWIST_MIN_SPEED', 'check_setpoint',
           'lag_factor', 'parameters_of', 'twist_setpoint']
