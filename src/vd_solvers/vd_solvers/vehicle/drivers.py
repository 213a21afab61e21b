# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Driver models and the driveline: small classes behind two protocols and a registry.

Steering drivers return the steering-wheel angle (rad, + left) at time t from what
they see (:class:`Observation`); the speed controller returns the total wheel torque
(N*m, + drive, - brake), a longitudinal driver the pedals (:class:`Pedals`: throttle and
master-cylinder pressure). :class:`WheelTorques` turns either into the four wheel torques
of a step: through the vehicle's brakes (anti-lock per wheel) and driveline
(:mod:`vd_solvers.chassis`) where its configuration has them, through the fixed shares
of :func:`wheel_torques` where it has not.

``DRIVERS`` maps the name used in docs/events.md to the class.
"""
from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
import math
from typing import Any, NamedTuple, Protocol

import numpy as np

from vd_solvers.analytical.bicycle import curvature_steer_angle
from vd_solvers.chassis.antilock import controller_step
from vd_solvers.chassis.brakes import master_pressure_for_torque, rear_line_pressure
from vd_solvers.chassis.driveline import (
    available_torque,
    choose_gear,
    drive_torques,
    driven_speed,
    inertia_torque,
)
from vd_solvers.chassis.from_config import Chassis
from vd_solvers.compiled import jit
from vd_solvers.errors import SolverError

from .preview_design import PreviewGains


class Observation(NamedTuple):
    """What a driver sees at time t (world frame, SI)."""

    t: float
    x: float
    y: float
    yaw: float
    speed: float  # horizontal speed of the body origin
    course: float  # direction of the body origin's velocity, rad


class Pedals(NamedTuple):
    """A longitudinal driver's command: throttle 0..1 and master-cylinder pressure, Pa."""

    throttle: float
    pressure: float


class SteeringDriver(Protocol):
    def steering_wheel_angle(self, obs: Observation, h: float) -> float: ...


class SpeedDriver(Protocol):
    def wheel_torque(self, obs: Observation, h: float) -> float | Pedals: ...


class OpenLoopSteering:
    """
    Steering-wheel angle from a function of time, or a table.

    A table is linear between its points and held beyond its ends. A ``vectorized``
    signal takes an array of times and returns the angles. :meth:`schedule` gives the
    angles at many times at once (the compiled loop of :mod:`.simulation` takes them so).
    """

    def __init__(self, signal: Callable[[Any], Any] | None = None,
                 times: Sequence[float] | np.ndarray = (),
                 angles: Sequence[float] | np.ndarray = (), vectorized: bool = False) -> None:
        self._table_points: tuple[np.ndarray, np.ndarray] | None = None
        self.vectorized = vectorized
        if signal is None:
            t = np.asarray(times, dtype=float)
            a = np.asarray(angles, dtype=float)
            if t.ndim != 1 or t.size < 2 or t.shape != a.shape:
                raise SolverError('open-loop steering needs a table of at least two '
                                  '(time, angle) points of equal length')
            if np.any(np.diff(t) <= 0.0) or not np.all(np.isfinite(a)):
                raise SolverError('open-loop steering: times must increase and angles be finite')
            self._table_points = (t, a)
            signal = self._table
        self.signal: Callable[[Any], Any] = signal

    @property
    def table_points(self) -> tuple[np.ndarray, np.ndarray] | None:
        """The table's (times s, angles rad), None for a signal."""
        return self._table_points

    def _table(self, t: float) -> float:
        assert self._table_points is not None
        return float(np.interp(t, *self._table_points))

    def steering_wheel_angle(self, obs: Observation, h: float) -> float:
        if self.vectorized:
            return float(self.signal(np.array([obs.t]))[0])
        return float(self.signal(obs.t))

    def schedule(self, times: Sequence[float]) -> np.ndarray:
        """Return the steering-wheel angles at ``times`` (s), rad."""
        if self._table_points is not None:
            return np.interp(np.asarray(times, dtype=float), *self._table_points)
        if self.vectorized:
            return np.asarray(self.signal(np.asarray(times, dtype=float)), dtype=float)
        return np.array([float(self.signal(t)) for t in times])


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


class PathLookup:
    """A path y(x) (earth frame, x increasing): its y, heading and curvature at any x."""

    path_x: np.ndarray
    path_y: np.ndarray

    def _set_path(self, path_x, path_y) -> None:
        """Check and keep the path's samples; heading and curvature by finite differences."""
        x = np.asarray(path_x, dtype=float)
        y = np.asarray(path_y, dtype=float)
        if x.ndim != 1 or x.size < 3 or np.any(np.diff(x) <= 0.0) or y.shape != x.shape \
                or not np.all(np.isfinite(y)):
            raise SolverError('a path needs increasing x and one finite y per x (at least '
                              'three points)')
        self.path_x, self.path_y = x, y
        slope = np.gradient(y, x)
        self._heading = np.arctan(slope)
        self._curvature = np.gradient(slope, x) / (1.0 + slope * slope) ** 1.5

    def lateral(self, x: float) -> float:
        """Return the path's y at x, m."""
        return float(np.interp(x, self.path_x, self.path_y))

    def heading(self, x: float) -> float:
        """Return the path's heading at x, rad (0 beyond its ends)."""
        return float(np.interp(x, self.path_x, self._heading, left=0.0, right=0.0))

    def curvature(self, x: float) -> float:
        """Return the path's curvature at x, 1/m (+ left; 0 beyond its ends)."""
        return float(np.interp(x, self.path_x, self._curvature, left=0.0, right=0.0))


@dataclass
class PreviewPathFollower(PathLookup):
    """
    Two-level path follower on a path y(x) (earth frame, x increasing): Donges' driver.

    Donges, *A two-level model of driver steering behavior*, Human Factors 20(6), 1978:
    an anticipatory (open-loop) level steers for the curvature of the path ahead, a
    compensatory (closed-loop) level corrects the lateral and heading errors. Here the
    anticipatory level takes the path's curvature kappa_a ``anticipation`` * speed ahead of
    the body origin; the compensatory level asks for the curvature of the arc that
    would close the path's lateral error e (m, path left of the vehicle positive) and
    heading error dpsi (path heading less the direction of the point's velocity, from the
    body origin's velocity and the yaw rate of the last step) over the preview
    distance d = ``preview_time`` * speed (at least ``min_preview``), both at the point
    ``behind`` m behind the body origin along the body (the rear axle: without tire slip
    it moves along the body's heading, and its path's curvature is tan(delta) / L at every
    instant):
    kappa_c = ``gain`` (2 e / d^2 + 2 dpsi / d) (the pure-pursuit law linearised, Coulter,
    CMU-RI-TR-92-01, 1992). The road wheels steer by the vehicle's steady-state angle for
    kappa_a + kappa_c, (L + K V^2) kappa (:func:`.analytical.bicycle.curvature_steer_angle`
    with the configuration's understeer gradient K, rad/(m/s^2)): on a steady circle the
    anticipatory level alone gives the angle L / R + K a_y. Output in steering-wheel angle
    through the steering ratio, after a first-order lag ``lag`` (the driver's
    neuromuscular lag), limited to ``max_angle``; the path is held straight beyond its
    ends. Heading and curvature are the path's own (finite differences of the samples).
    """

    path_x: np.ndarray
    path_y: np.ndarray
    wheelbase: float
    steering_ratio: float
    max_angle: float
    understeer_gradient: float = 0.0  # rad/(m/s^2)
    preview_time: float = 0.5
    min_preview: float = 5.0
    anticipation: float = 0.2  # s
    behind: float = 0.0  # m
    gain: float = 1.0
    curvature_gain: float = 0.0
    lag: float = 0.1
    _output: float | None = field(default=None, init=False)
    _yaw: float | None = field(default=None, init=False)
    _heading: np.ndarray = field(default_factory=lambda: np.zeros(0), init=False)
    _curvature: np.ndarray = field(default_factory=lambda: np.zeros(0), init=False)

    def __post_init__(self) -> None:
        self._set_path(self.path_x, self.path_y)

    def steering_wheel_angle(self, obs: Observation, h: float) -> float:
        speed = max(obs.speed, 0.0)
        preview = max(self.preview_time * speed, self.min_preview)
        x = obs.x - self.behind * math.cos(obs.yaw)
        y = obs.y - self.behind * math.sin(obs.yaw)
        # the reference point's velocity: the body origin's less yaw rate x ``behind``
        rate = 0.0 if self._yaw is None or h <= 0.0 else \
            math.remainder(obs.yaw - self._yaw, 2.0 * math.pi) / h
        self._yaw = obs.yaw
        slip = obs.course - obs.yaw
        course = obs.yaw + math.atan2(speed * math.sin(slip) - rate * self.behind,
                                      max(speed * math.cos(slip), 1e-3))
        psi = self.heading(x)
        error = (self.lateral(x) - y) * math.cos(psi)
        heading_error = math.remainder(psi - course, 2.0 * math.pi)
        curvature_error = self.curvature(x) - rate / max(speed, 1.0)
        compensatory = self.gain * (2.0 * error / preview**2 + 2.0 * heading_error / preview
                                    + self.curvature_gain * curvature_error)
        anticipatory = self.curvature(x + self.anticipation * speed)
        wanted = self.steering_ratio * float(curvature_steer_angle(
            self.wheelbase, self.understeer_gradient, anticipatory + compensatory, speed))
        if self._output is None:
            self._output = wanted
        self._output += (wanted - self._output) * (1.0 - math.exp(-h / self.lag))
        return float(np.clip(self._output, -self.max_angle, self.max_angle))


class OptimalPreviewDriver(PathLookup):
    """
    Optimal preview path follower on a path y(x) (earth frame, x increasing).

    The discrete linear-quadratic preview control of :mod:`.preview_design` (Sharp,
    Casanova & Symonds, VSD 33(5), 2000): every ``gains.sample`` s the driver measures the
    reference point's lateral offset e from the path (m, + left of it; the point ``behind``
    m behind the body origin along the body, the path's station its x), the yaw angle less
    the path's heading there, the lateral velocity of the CoG (``cog_ahead`` m ahead of the
    body origin) and the yaw rate (the yaw's change over the last step), knows its own
    road-wheel angle, and reads the path's curvature at the stations ``gains.spacing`` * j
    of arc length ahead of the reference point; the command u = -K_x x - K_w w is held over
    the sample. The road-wheel angle follows it through the first-order lag ``lag`` (the
    one the gains were designed with) and stops at the lock: the steering wheel is that
    angle times the steering ratio, at most ``max_angle``. Heading and curvature are the
    path's own (finite differences of the samples), zero beyond its ends.
    """

    def __init__(self, path_x: np.ndarray, path_y: np.ndarray, gains: PreviewGains,
                 steering_ratio: float, max_angle: float, lag: float, behind: float = 0.0,
                 cog_ahead: float = 0.0) -> None:
        self._set_path(path_x, path_y)
        x, y = self.path_x, self.path_y
        self.gains = gains
        self.steering_ratio, self.max_angle, self.lag = steering_ratio, max_angle, lag
        self.behind, self.cog_ahead = behind, cog_ahead
        # arc length along the path, for the preview stations
        self._arc = np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(x), np.diff(y)))])
        self._ahead = gains.spacing * np.arange(gains.preview.size)
        self._delta = 0.0  # road-wheel angle, rad
        self._command = 0.0
        self._next = -math.inf  # time of the next sample
        self._yaw: float | None = None

    def preview(self, x: float) -> np.ndarray:
        """Return the path's curvature at the preview stations from x on, 1/m."""
        start = np.interp(x, self.path_x, self._arc) + (x - np.clip(x, self.path_x[0],
                                                                       self.path_x[-1]))
        return np.interp(start + self._ahead, self._arc, self._curvature, left=0.0, right=0.0)

    def steering_wheel_angle(self, obs: Observation, h: float) -> float:
        rate = 0.0 if self._yaw is None or h <= 0.0 else \
            math.remainder(obs.yaw - self._yaw, 2.0 * math.pi) / h
        self._yaw = obs.yaw
        if obs.t >= self._next - 1e-9:
            self._next = obs.t + self.gains.sample
            x = obs.x - self.behind * math.cos(obs.yaw)
            y = obs.y - self.behind * math.sin(obs.yaw)
            psi = self.heading(x)
            state = np.array([
                (y - self.lateral(x)) * math.cos(psi),
                math.remainder(obs.yaw - psi, 2.0 * math.pi),
                obs.speed * math.sin(obs.course - obs.yaw) + rate * self.cog_ahead,
                rate,
                self._delta])
            self._command = -float(self.gains.feedback @ state
                                   + self.gains.preview @ self.preview(x))
        # the lag's state is the road wheels' angle, which stops at the lock
        lock = self.max_angle / self.steering_ratio
        self._delta += (self._command - self._delta) * (1.0 - math.exp(-h / self.lag))
        self._delta = min(max(self._delta, -lock), lock)
        return self.steering_ratio * self._delta


@dataclass
class CoastingSpeed:
    """
    A speed driver up to a gate, then no torque at all: the driver lifts off (ISO 3888-2).

    ``controller`` requests the wheel torque while the body origin is short of ``gate``
    (m, earth x); from the first step at or beyond it the request is 0 N*m for good.
    ``released_at`` is then the time of that step, s, and ``speed_at_release`` the speed.
    """

    controller: SpeedDriver
    gate: float
    released_at: float | None = field(default=None, init=False)
    speed_at_release: float = field(default=math.nan, init=False)

    def wheel_torque(self, obs: Observation, h: float) -> float | Pedals:
        if self.released_at is None and obs.x >= self.gate:
            self.released_at, self.speed_at_release = obs.t, obs.speed
        if self.released_at is not None:
            return 0.0
        return self.controller.wheel_torque(obs, h)


class SpeedSchedule(NamedTuple):
    """
    A speed driver's commands on the time grid of a run, when they depend on time only.

    Per step: :class:`Pedals` (``throttle``, ``pressure``) where ``pedals`` is True, else
    the torque of :func:`speed_law` on ``reference`` and ``reference_next`` (v_ref at the
    step's time and at its end, m/s) with ``gains`` (mass, wheel radius, kp, ki; empty:
    no controller, no torque) and the integral of ``controller``, which the run carries on.
    A speed driver whose commands depend on time only has a method ``schedule(times, h)``
    that returns this (the compiled loop of :mod:`.simulation` takes it).
    """

    pedals: np.ndarray  # (n,) bool
    throttle: np.ndarray  # (n,) 0..1
    pressure: np.ndarray  # (n,) Pa
    reference: np.ndarray  # (n,) m/s
    reference_next: np.ndarray  # (n,) m/s
    gains: np.ndarray  # (4,) or (0,)
    controller: SpeedController | None


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

    def schedule(self, times: np.ndarray, h: float) -> SpeedSchedule:
        """Return the requests at ``times`` (s; steps of ``h``) for the compiled loop."""
        n = times.size
        return SpeedSchedule(
            pedals=np.zeros(n, dtype=bool), throttle=np.zeros(n), pressure=np.zeros(n),
            reference=np.array([float(self.reference(t)) for t in times]),
            reference_next=np.array([float(self.reference(t + h)) for t in times]),
            gains=np.array([self.mass, self.wheel_radius, self.kp, self.ki], dtype=float),
            controller=self)

    def wheel_torque(self, obs: Observation, h: float) -> float:
        torque, self._integral = speed_law(self.reference(obs.t), self.reference(obs.t + h),
                                           obs.speed, self._integral, self.mass,
                                           self.wheel_radius, self.kp, self.ki, h)
        return torque


@jit
def speed_law(reference: float, reference_next: float, speed: float, integral: float,
              mass: float, wheel_radius: float, kp: float, ki: float, h: float
              ) -> tuple[float, float]:
    """
    Return the torque law of :class:`SpeedController`: (torque N*m, integral after the step).

    ``reference`` and ``reference_next`` are v_ref at t and t + h, m/s.
    """
    error = reference - speed
    integral = integral + error * h
    slope = (reference_next - reference) / h
    return mass * wheel_radius * (slope + kp * error + ki * integral), integral


#: spin speed over which a brake's torque reverses with the wheel's rotation, rad/s
BRAKE_SPIN_SCALE = 0.1
#: time constant of the vehicle acceleration the driveline inertia is taken at, s
ACCELERATION_FILTER = 0.05
#: vehicle speed below which the driveline inertia is left out (dv/dt / v undefined), m/s
INERTIA_SPEED_FLOOR = 0.1


@jit
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
    return 0.5 * total * axle * np.tanh(spin / BRAKE_SPIN_SCALE)


class ActuationArrays(NamedTuple):
    """
    A chassis's brakes, anti-lock brakes and driveline as :func:`actuate` takes them.

    Float vectors; an empty one: the configuration has no such group.
    """

    brakes: np.ndarray  # (4,) front and rear torque per line pressure (N m / Pa), valve knee
    # (Pa) and slope (-)
    anti_lock: np.ndarray  # (5,) AntiLock's dump_slip, build_slip, dump_rate, build_rate,
    # min_speed
    engine_speeds: np.ndarray  # (n,) full-load map, rad/s
    engine_torques: np.ndarray  # (n,) N m
    ratios: np.ndarray  # (gears,) total ratios i_gear i_final; empty: no driveline
    driveline: np.ndarray  # (4,) efficiency, front drive share, inertia (kg m^2), upshift
    # engine speed (rad/s)
    front_differential: np.ndarray  # (3,) Differential.values()
    rear_differential: np.ndarray  # (3,)


def actuation_arrays(chassis: Chassis) -> ActuationArrays:
    """Return the :class:`ActuationArrays` of a chassis's systems."""
    none = np.zeros(0)
    brakes = anti_lock = speeds = torques = ratios = driveline = none
    front = rear = np.zeros(3)
    b, a, line = chassis.brakes, chassis.anti_lock, chassis.driveline
    if b is not None:
        brakes = np.array([b.front.gain, b.rear.gain, b.knee_pressure, b.knee_slope])
    if b is not None and a is not None:
        anti_lock = np.array([a.dump_slip, a.build_slip, a.dump_rate, a.build_rate,
                              a.min_speed], dtype=float)
    if line is not None:
        speeds, torques, ratios = line.engine.speeds, line.engine.torques, line.ratios
        driveline = np.array([line.efficiency, line.front_share, line.inertia,
                              chassis.shift_speed], dtype=float)
        front, rear = line.front.values(), line.rear.values()
    return ActuationArrays(brakes, anti_lock, np.ascontiguousarray(speeds, dtype=float),
                           np.ascontiguousarray(torques, dtype=float), ratios, driveline,
                           front, rear)


#: size of the state :func:`actuate` carries from step to step (a float vector, zero at
#: the start): whether a previous speed is known (0/1), that speed (m/s), its smoothed rate
#: of change (m/s^2), then per wheel FL FR RL RR the anti-lock controller's activity (0/1)
#: and its modulated pressure (Pa)
ACTUATION_STATE = 11


@jit
def actuate(pedals: bool, request: float, throttle: float, pressure: float, spin: np.ndarray,
            kappa: np.ndarray, speed: float, h: float, drive_front: float, brake_front: float,
            a: ActuationArrays, state: np.ndarray) -> tuple[np.ndarray, float, int, np.ndarray]:
    """
    Return the wheel torques of a step from the driver's command (:class:`WheelTorques`).

    The command is ``pedals`` (``throttle`` 0..1, master ``pressure`` Pa) or the total
    wheel torque ``request`` (N m); ``spin`` the wheels' spin speeds (rad/s), ``kappa``
    their slips at the previous step (-), ``speed`` the vehicle's (m/s), ``h`` the step
    (s); ``state`` (ACTUATION_STATE) is advanced in place. Returns the torques FL FR RL RR
    (N m about the spin axes), the throttle 0..1, the gear (0: none) and the four line
    pressures (Pa).
    """
    if state[0] > 0.0 and h > 0.0:
        rate = (speed - state[1]) / h
        state[2] += min(h / ACCELERATION_FILTER, 1.0) * (rate - state[2])
    state[0] = 1.0
    state[1] = speed
    has_line = a.ratios.size > 0
    has_brakes = a.brakes.size > 0
    wanted = 0.0  # the drive torque the throttle is opened for
    if not pedals:
        if request >= 0.0 and has_line:
            throttle, pressure, wanted = -1.0, 0.0, request
        elif request < 0.0 and has_brakes:
            throttle = 0.0
            pressure = master_pressure_for_torque(-request, a.brakes[0], a.brakes[1],
                                                  a.brakes[2], a.brakes[3])
        else:
            return wheel_torques(request, drive_front, brake_front, spin), 0.0, 0, np.zeros(4)
    torques = np.zeros(4)
    gear = 0
    if has_line:
        speeds, maps, line = a.engine_speeds, a.engine_torques, a.driveline
        driven = driven_speed(line[1], spin)
        gear = choose_gear(a.ratios, driven, line[3])
        ratio = a.ratios[gear - 1]
        if throttle < 0.0:
            available = available_torque(speeds, maps, ratio, line[0], driven)
            throttle = min(wanted / available, 1.0) if available > 0.0 else 0.0
        inertia = 0.0
        if throttle > 0.0 and line[2] > 0.0 and speed > INERTIA_SPEED_FLOOR:
            spin_up = driven * state[2] / speed
            inertia = inertia_torque(line[2], speeds[0], ratio, line[0], driven, spin_up)
        torques += drive_torques(speeds, maps, ratio, line[0], line[1], a.front_differential,
                                 a.rear_differential, throttle, spin, inertia)
    pressures = np.zeros(4)
    if has_brakes:
        b = a.brakes
        rear = rear_line_pressure(pressure, b[2], b[3])
        pressures[0] = pressure
        pressures[1] = pressure
        pressures[2] = rear
        pressures[3] = rear
        if a.anti_lock.size:
            c = a.anti_lock
            for w in range(4):
                active, line_pressure = controller_step(
                    c[0], c[1], c[2], c[3], c[4], state[3 + w] > 0.5, state[7 + w], h,
                    pressures[w], -kappa[w], speed)
                state[3 + w] = 1.0 if active else 0.0
                state[7 + w] = line_pressure
                pressures[w] = line_pressure
        gains = np.array([b[0], b[0], b[1], b[1]])
        torques -= gains * pressures * np.tanh(spin / BRAKE_SPIN_SCALE)
    return torques, max(throttle, 0.0), gear, pressures


class WheelTorques:
    """
    The wheel torques of each step from the driver's request and the chassis systems.

    A request is a total torque (the speed controller) or :class:`Pedals`. With a
    driveline, a drive torque request opens the throttle as far as it needs
    (at most fully) in the gear :meth:`.Driveline.gear` chooses with the upshift speed,
    and the differentials split it by the wheels' speeds; with brakes, a brake torque
    request becomes the master pressure that gives it
    (:meth:`.BrakeSystem.pressure_for_torque`), the rear line passes the proportioning
    valve, and with anti-lock brakes each wheel's controller
    (:func:`vd_solvers.chassis.antilock.step`) modulates its own line pressure from the
    wheel's braking slip. Each brake opposes its wheel's rotation (tanh over
    BRAKE_SPIN_SCALE). Without a driveline or brakes group the request is split by the
    fixed shares ``drive_front`` and ``brake_front`` (:func:`wheel_torques`). After a
    call, ``throttle``, ``gear`` and ``pressures`` (the four brakes' line pressures, Pa)
    say what it did.

    While the engine drives (throttle open) the driveline's inertia takes its share of the
    drive torque (:meth:`.Driveline.inertia_torque`) at the driven wheels' angular
    acceleration, taken as their speed times the vehicle's relative acceleration
    (dv/dt / v, the slip held), with dv/dt the speed's change over the previous step
    smoothed over ACCELERATION_FILTER: the body's acceleration, not the wheels' stiff spin,
    so the lagged feedback stays below one (J i^2 / r^2 under the vehicle's mass).

    Each call is one call of the compiled :func:`actuate` on the chassis's
    :class:`ActuationArrays`, the function the compiled loop
    (:func:`.dynamics.run_open_loop`) calls at each of its steps.
    """

    def __init__(self, chassis: Chassis | None, drive_front: float = 0.5,
                 brake_front: float = 0.65) -> None:
        self.chassis = chassis if chassis is not None else Chassis()
        self.drive_front, self.brake_front = float(drive_front), float(brake_front)
        self.arrays = actuation_arrays(self.chassis)
        self.state = np.zeros(ACTUATION_STATE)
        self.throttle = 0.0
        self.gear = 0
        self.pressures = np.zeros(4)

    def __call__(self, request: float | Pedals, spin: np.ndarray, kappa: np.ndarray,
                 speed: float, h: float) -> np.ndarray:
        """Torques FL FR RL RR (N*m) at wheel spin speeds ``spin`` and slips ``kappa``."""
        if isinstance(request, Pedals):
            pedals, total, throttle, pressure = True, 0.0, request[0], request[1]
        else:
            pedals, total, throttle, pressure = False, request, 0.0, 0.0
        torques, throttle, gear, self.pressures = actuate(
            pedals, float(total), float(throttle), float(pressure),
            np.ascontiguousarray(spin, dtype=float), np.ascontiguousarray(kappa, dtype=float),
            float(speed), float(h), self.drive_front, self.brake_front, self.arrays,
            self.state)
        self.throttle, self.gear = float(throttle), int(gear)
        return torques


#: name -> driver class (docs/events.md)
DRIVERS: Mapping[str, type] = {
    'open_loop': OpenLoopSteering,
    'replay': ReplaySteering,
    'path_follower': CirclePathFollower,
    'curvature': CurvatureController,
    'preview_path': PreviewPathFollower,
    'optimal_preview': OptimalPreviewDriver,
    'speed': SpeedController,
}

__all__ = ['Observation', 'OpenLoopSteering', 'ReplaySteering', 'CirclePathFollower',
           'CurvatureController', 'PreviewPathFollower', 'OptimalPreviewDriver',
           'CoastingSpeed',
           'SpeedController', 'speed_law', 'wheel_torques', 'DRIVERS', 'Pedals', 'WheelTorques',
           'ActuationArrays', 'actuation_arrays', 'actuate', 'ACTUATION_STATE', 'SpeedSchedule',
           'BRAKE_SPIN_SCALE', 'ACCELERATION_FILTER', 'INERTIA_SPEED_FLOOR']
