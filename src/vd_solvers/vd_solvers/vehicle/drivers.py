# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Driver models and the driveline: small classes behind two protocols and a registry.

Steering drivers return the steering-wheel angle (rad, + left) at time t from what
they see (:class:`Observation`); the speed controller returns the total wheel torque
(N*m, + drive, - brake) that :func:`wheel_torques` splits over the wheels.

``DRIVERS`` maps the name used in docs/events.md to the class.
"""
from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
import math
from typing import NamedTuple, Protocol

import numpy as np

from vd_solvers.errors import SolverError


class Observation(NamedTuple):
    """What a driver sees at time t (world frame, SI)."""

    t: float
    x: float
    y: float
    yaw: float
    speed: float  # horizontal speed of the body origin
    course: float  # direction of the body origin's velocity, rad


class SteeringDriver(Protocol):
    def steering_wheel_angle(self, obs: Observation, h: float) -> float: ...


class SpeedDriver(Protocol):
    def wheel_torque(self, obs: Observation, h: float) -> float: ...


class OpenLoopSteering:
    """
    Steering-wheel angle from a function of time, or a table.

    A table is linear between its points and held beyond its ends.
    """

    def __init__(self, signal: Callable[[float], float] | None = None,
                 times: Sequence[float] | np.ndarray = (),
                 angles: Sequence[float] | np.ndarray = ()) -> None:
        if signal is None:
            t = np.asarray(times, dtype=float)
            a = np.asarray(angles, dtype=float)
            if t.ndim != 1 or t.size < 2 or t.shape != a.shape:
                raise SolverError('open-loop steering needs a table of at least two '
                                  '(time, angle) points of equal length')
            if np.any(np.diff(t) <= 0.0) or not np.all(np.isfinite(a)):
                raise SolverError('open-loop steering: times must increase and angles be finite')
            self._t, self._a = t, a
            signal = self._table
        self.signal = signal

    def _table(self, t: float) -> float:
        return float(np.interp(t, self._t, self._a))

    def steering_wheel_angle(self, obs: Observation, h: float) -> float:
        return float(self.signal(obs.t))


class ReplaySteering(OpenLoopSteering):
    """
    Steering-wheel angle replayed from a recorded signal, optionally shifted in time.

    The signal is e.g. a bag's ``time`` and ``steering_wheel_angle`` channels.
    """

    def __init__(self, times: Sequence[float] | np.ndarray,
                 angles: Sequence[float] | np.ndarray, offset: float = 0.0) -> None:
        super().__init__(times=[float(t) + offset for t in times], angles=angles)


@dataclass
class CirclePathFollower:
    """
    Path follower with preview on a circle (ISO 4138 constant radius).

    The circle of ``radius`` starts at the origin heading +x and turns left (centre at
    (0, radius)). The driver looks ``preview_time`` * speed (at least ``min_preview``)
    ahead, along an arc of the path's curvature from the body's heading, and steers the
    road wheels by the path's Ackermann angle L / R plus a pure-pursuit correction
    L * 2 e / d^2 for the preview point's radial error e (outside the circle positive)
    at preview distance d, plus the integral of that correction over ``integral_time``:
    the integral removes the steady error the vehicle's understeer would leave. Output
    in steering-wheel angle through the steering ratio, after a first-order lag ``lag``
    (the driver's neuromuscular lag, which also keeps the loop clear of the tire's fast
    modes), limited to ``max_angle``.
    """

    radius: float
    wheelbase: float
    steering_ratio: float
    max_angle: float
    preview_time: float = 1.0
    min_preview: float = 8.0
    integral_time: float = 1.0
    lag: float = 0.1  # s, first-order lag of the driver's steering (neuromuscular)
    _integral: float = field(default=0.0, init=False)
    _output: float | None = field(default=None, init=False)

    def radial_error(self, x: float, y: float) -> float:
        """Distance outside the circle, m."""
        return math.hypot(x, y - self.radius) - self.radius

    def steering_wheel_angle(self, obs: Observation, h: float) -> float:
        preview = max(self.preview_time * obs.speed, self.min_preview)
        # where an arc of the path's curvature from the current course would be after
        # ``preview`` m: on the circle when the vehicle is on it and tangent to it
        turn = preview / (2.0 * self.radius)
        chord = 2.0 * self.radius * math.sin(turn)
        px = obs.x + chord * math.cos(obs.yaw + turn)
        py = obs.y + chord * math.sin(obs.yaw + turn)
        correction = self.wheelbase * 2.0 * self.radial_error(px, py) / preview**2
        self._integral += correction * h / self.integral_time
        wanted = (self.wheelbase / self.radius + correction + self._integral) * self.steering_ratio
        if self._output is None:
            self._output = wanted
        self._output += (wanted - self._output) * (1.0 - math.exp(-h / self.lag))
        return float(np.clip(self._output, -self.max_angle, self.max_angle))


@dataclass
class CurvatureController:
    """
    Steer to hold the path curvature r / V at 1 / ``radius`` (ISO 4138 steady state).

    Road-wheel angle = the Ackermann angle L / R plus a proportional-integral action on
    the curvature error e = L (1 / R - r / V) (rad; r from the yaw angle's change over the
    step): ``gain`` e + integral of e over ``integral_time``. The integral supplies the
    understeer angle K a_y the vehicle needs, so in a steady state the path curvature is
    exactly 1 / R wherever the circle's centre has drifted to during the transients: the
    steady-state quantities of ISO 4138 depend on the radius, not on the circle's place.
    Output through the steering ratio, after a first-order lag ``lag`` (the driver's
    neuromuscular lag), limited to ``max_angle``; ``at_lock`` says whether the limit holds
    the steering (the integral stops growing there).
    """

    radius: float
    wheelbase: float
    steering_ratio: float
    max_angle: float
    gain: float = 0.5
    integral_time: float = 1.0
    lag: float = 0.1
    _integral: float = field(default=0.0, init=False)
    _output: float | None = field(default=None, init=False)
    _yaw: float | None = field(default=None, init=False)
    at_lock: bool = field(default=False, init=False)

    def steering_wheel_angle(self, obs: Observation, h: float) -> float:
        if self._yaw is None or h <= 0.0:
            rate = obs.speed / self.radius
        else:
            rate = math.remainder(obs.yaw - self._yaw, 2.0 * math.pi) / h
        self._yaw = obs.yaw
        error = self.wheelbase * (1.0 / self.radius - rate / max(obs.speed, 1e-3))
        if not self.at_lock:
            self._integral += error * h / self.integral_time
        wanted = (self.wheelbase / self.radius + self.gain * error + self._integral
                  ) * self.steering_ratio
        if self._output is None:
            self._output = wanted
        self._output += (wanted - self._output) * (1.0 - math.exp(-h / self.lag))
        self.at_lock = abs(self._output) >= self.max_angle
        return float(np.clip(self._output, -self.max_angle, self.max_angle))


@dataclass
class PreviewPathFollower:
    """
    Pure-pursuit path follower with preview on a path y(x) (earth frame, x increasing).

    The driver aims at the point of the path ``preview_time`` * speed (at least
    ``min_preview``) ahead of the body origin along x, and steers the road wheels by the
    pure-pursuit angle L 2 sin(a) / l (a the angle from the heading to that point, l its
    distance; Coulter, *Implementation of the pure pursuit path tracking algorithm*, CMU-RI-
    TR-92-01, 1992), times ``gain``. Output in steering-wheel angle through the steering
    ratio, after a first-order lag ``lag`` (the driver's neuromuscular lag), limited to
    ``max_angle``; the path is held straight beyond its ends.
    """

    path_x: np.ndarray
    path_y: np.ndarray
    wheelbase: float
    steering_ratio: float
    max_angle: float
    preview_time: float = 0.5
    min_preview: float = 5.0
    gain: float = 1.0
    lag: float = 0.1
    _output: float | None = field(default=None, init=False)

    def __post_init__(self) -> None:
        x = np.asarray(self.path_x, dtype=float)
        if x.ndim != 1 or x.size < 2 or np.any(np.diff(x) <= 0.0) \
                or np.shape(self.path_y) != x.shape:
            raise SolverError('a path needs increasing x and one y per x (at least two points)')

    def lateral(self, x: float) -> float:
        """Return the path's y at x, m."""
        return float(np.interp(x, self.path_x, self.path_y))

    def steering_wheel_angle(self, obs: Observation, h: float) -> float:
        preview = max(self.preview_time * obs.speed, self.min_preview)
        tx = obs.x + preview
        dx, dy = preview, self.lateral(tx) - obs.y
        angle = math.atan2(dy, dx) - obs.yaw
        wanted = (self.gain * self.wheelbase * 2.0 * math.sin(angle) / math.hypot(dx, dy)
                  * self.steering_ratio)
        if self._output is None:
            self._output = wanted
        self._output += (wanted - self._output) * (1.0 - math.exp(-h / self.lag))
        return float(np.clip(self._output, -self.max_angle, self.max_angle))


@dataclass
class SpeedController:
    """
    PI speed controller on drive/brake torque with feed-forward of the reference slope.

    ``reference(t)`` m/s; torque = mass * radius * (dv_ref/dt + kp e + ki int e), e = v_ref - v.
    """

    reference: Callable[[float], float]
    mass: float
    wheel_radius: float
    kp: float = 2.0  # 1/s
    ki: float = 1.0  # 1/s^2
    _integral: float = field(default=0.0, init=False)

    def wheel_torque(self, obs: Observation, h: float) -> float:
        error = self.reference(obs.t) - obs.speed
        self._integral += error * h
        slope = (self.reference(obs.t + h) - self.reference(obs.t)) / h
        return self.mass * self.wheel_radius * (slope + self.kp * error + self.ki * self._integral)


def wheel_torques(total: float, drive_front: float, brake_front: float, spin: np.ndarray
                  ) -> np.ndarray:
    """
    Split a total wheel torque over FL FR RL RR (N*m about the spin axes).

    Drive (total > 0): ``drive_front`` of it to the front axle, open differentials (equal
    left/right). Brake (total < 0): ``brake_front`` to the front axle, each brake opposing
    its wheel's rotation (zero on a wheel at rest).
    """
    if total >= 0.0:
        axle = np.array([drive_front, drive_front, 1.0 - drive_front, 1.0 - drive_front])
        return 0.5 * total * axle
    axle = np.array([brake_front, brake_front, 1.0 - brake_front, 1.0 - brake_front])
    return 0.5 * total * axle * np.tanh(spin / 0.1)


#: name -> driver class (docs/events.md)
DRIVERS: Mapping[str, type] = {
    'open_loop': OpenLoopSteering,
    'replay': ReplaySteering,
    'path_follower': CirclePathFollower,
    'curvature': CurvatureController,
    'preview_path': PreviewPathFollower,
    'speed': SpeedController,
}

__all__ = ['Observation', 'OpenLoopSteering', 'ReplaySteering', 'CirclePathFollower',
           'CurvatureController', 'PreviewPathFollower',
           'SpeedController', 'wheel_torques', 'DRIVERS']
