# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Constant radius turn on the full vehicle: ISO 4138:2021 constant-radius method, steady state.

A curvature controller (:class:`.drivers.CurvatureController`) steers the vehicle on a
left circle of ``radius`` (path curvature r / V = 1 / R); the speed is raised in steps so
that the lateral acceleration V^2 / R climbs in increments of ``lateral_acceleration_step``
(ISO 4138:2021 8.3: no larger than 0.5 m/s^2), and held at each level until the vehicle
is in a steady state: the standard's steady-state method, not a continuous speed ramp,
whose gradients depend on the ramp rate (the sample HMMWV: 0.72 deg/g at 0.25 m/s^2,
0.53 at 0.05 m/s^2 before this method).

**Steady-state criterion** (:class:`Staircase`). Over the last STEADY_WINDOW s of a
level, the least-squares rate of change of each of

* the excess steer u = delta_sw / i_s - L r / V (what the understeer gradient is made of),
* the roll angle and the sideslip angle,
* the lateral acceleration estimate V r,

times SETTLE_HORIZON (the slowest time constant of the driver and the vehicle, about
1 s for the curvature controller's integral action and the speed controller: 2 s allowed)
must be below ``steady_tolerance`` times the change of that quantity since the previous
steady level (with an absolute floor, FLOOR, for quantities that hardly change). Read: the
quantity would still move by less than ``steady_tolerance`` of one level's change if it
kept changing at its present rate for SETTLE_HORIZON. The steady point is then the mean
over that window. Above the linear range the tolerance is LIMIT_TOLERANCE_FACTOR times
larger (those points give the limit, not gradients).

**The limit.** A level fails when the steering reaches its lock (the front axle
saturates: understeer) or when it does not settle within MAX_SETTLE s. The next level is
then half way between the last steady level and the lowest failed one, until the two are
less than ``limit_resolution`` apart (ISO 4138 8.3 note: smaller increments
where the data vary rapidly). A sideslip beyond MAX_SIDESLIP (the vehicle spins:
oversteer) ends the run at once. The maximum lateral acceleration is that of the highest
steady point.

Gradients are least-squares slopes over the steady points whose level lies in
LINEAR_RANGE: understeer gradient K = d(delta_sw / i_s - L r / V) / d a_y, roll and
sideslip gradients. Convergence of the criterion (the gradients move by less than 1 % when
``steady_tolerance`` is halved) is a test (tests/vd_solvers/vehicle/test_constant_radius.py).
"""
from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
import math

import numpy as np

from vd_solvers.analytical.cornering import LINEAR_RANGE  # the gradients' range, every rung
from vd_solvers.constants import STANDARD_GRAVITY as G
from vd_solvers.errors import SolverError
from vd_solvers.event_params import Param
from vd_solvers.results import Metric

from .drivers import CurvatureController, SpeedController
from .model import VehicleModel
from .simulation import Trace, simulate

#: sideslip beyond which the vehicle no longer holds the circle (spin), rad
MAX_SIDESLIP = math.radians(15.0)
#: seconds the driver settles at the start speed before the criterion applies
SETTLE_TIME = 3.0
#: averaging window of a steady point and of the rates of the criterion, s
STEADY_WINDOW = 1.0
#: horizon of the steady-state criterion: the slowest time constant allowed for, s
SETTLE_HORIZON = 2.0
#: longest time one level may take to settle, s
MAX_SETTLE = 30.0
#: speed change between two levels, m/s^2
LEVEL_SPEED_RATE = 0.5
#: absolute floors of the criterion's tolerance: angles (rad), lateral acceleration (m/s^2)
FLOOR = {'excess_steer': 1e-6, 'roll': 1e-6, 'sideslip': 1e-6, 'lateral_acceleration': 1e-4}
#: integration step: the implicit wheel spin keeps 8 ms stable, and a steady state is a
#: fixed point of the step (a(q, v) = 0) whatever its size
TURN_STEP = 0.008
#: recorded every this many steps
RECORD_EVERY = 6
#: the criterion's tolerance above the linear range, as a multiple of ``steady_tolerance``:
#: there the points give the limit, to a fraction of an increment, not gradients
LIMIT_TOLERANCE_FACTOR = 5.0

PARAMS: Mapping[str, Param] = {
    'radius': Param('length', 40.0, 'circle radius (ISO 4138 constant radius)', minimum=10.0,
                    maximum=500.0),
    'start_lateral_acceleration': Param('acceleration', 0.5, 'lateral acceleration of the '
                                        'first level', minimum=0.1, maximum=5.0),
    'lateral_acceleration_step': Param('acceleration', 0.5, 'increment of the lateral '
                                       'acceleration between levels (ISO 4138: at most '
                                       '0.5 m/s^2)', minimum=0.05, maximum=0.5),
    'steady_tolerance': Param('dimensionless', 0.002, 'steady-state criterion: the change a '
                              "level's rates would still make over the horizon, as a share "
                              "of one level's change", minimum=1e-5, maximum=0.1),
    'limit_resolution': Param('acceleration', 0.1, 'the limit is resolved to this: failed '
                              'and highest steady level at most this far apart', minimum=0.01,
                              maximum=2.0),
    'max_lateral_acceleration': Param('acceleration', 20.0, 'last level (the run ends earlier '
                                      'where the radius can no longer be held)', minimum=0.5,
                                      maximum=20.0),
    'max_duration': Param('time', 600.0, 'longest simulated time', minimum=5.0,
                          maximum=3600.0),
    'drive_front': Param('dimensionless', 0.5,
                         'front share of the drive torque (0 rear, 1 front)',
                         minimum=0.0, maximum=1.0),
    'brake_front': Param('dimensionless', 0.65, 'front share of the brake torque', minimum=0.0,
                         maximum=1.0),
}

_QUANTITIES = ('excess_steer', 'roll', 'sideslip', 'lateral_acceleration')


@dataclass
class SteadyPoint:
    """One steady level: the window it was averaged over and the criterion's margins."""

    level: float  # m/s^2, the aimed lateral acceleration V^2/R
    start: float  # s, averaging window
    end: float  # s
    settle_time: float  # s from the end of the speed change
    values: dict[str, float] = field(default_factory=dict)  # means over the window


@dataclass
class Staircase:
    """
    Speed schedule and steady-state detection of the steady-state method (module doc).

    ``reference(t)`` is the speed the controller holds; ``observe(row, at_lock)`` reads
    every recorded row, decides whether the present level is steady (then moves to the
    next) or has failed (then tries half way back to the last steady level), and returns a stop
    reason ('' to go on; 'done' at the last level or when the limit is resolved).
    """

    radius: float
    wheelbase: float
    steering_ratio: float
    start: float  # m/s^2
    step: float  # m/s^2
    tolerance: float
    last_level: float  # m/s^2
    resolution: float  # m/s^2, of the limit
    level: float = 0.0
    points: list[SteadyPoint] = field(default_factory=list)
    failed: list[float] = field(default_factory=list)  # levels that did not settle, m/s^2
    _from: float = 0.0  # m/s, speed at the start of the change
    _change_start: float = 0.0  # s
    _hold_start: float = 0.0  # s, end of the speed change
    _rows: list[tuple[float, ...]] = field(default_factory=list)

    def __post_init__(self) -> None:
        self.level = self.start
        self._from = self.speed_of(self.start)
        self._hold_start = SETTLE_TIME

    def speed_of(self, level: float) -> float:
        return math.sqrt(level * self.radius)

    def reference(self, t: float) -> float:
        target = self.speed_of(self.level)
        if t <= self._change_start:
            return self._from
        moved = LEVEL_SPEED_RATE * (t - self._change_start)
        if self._from <= target:
            return min(self._from + moved, target)
        return max(self._from - moved, target)

    def observe(self, row: Mapping[str, float], at_lock: bool = False) -> str:
        t = row['time']
        if t < self._hold_start:
            return ''
        if at_lock or t - self._hold_start > MAX_SETTLE:
            return self._fail(t)
        speed = max(row['speed'], 1e-9)
        excess = (row['steering_wheel_angle'] / self.steering_ratio
                  - self.wheelbase * row['yaw_rate'] / speed)
        self._rows.append((t, excess, row['roll'], row['sideslip'], row['yaw_rate'] * speed))
        if t - self._hold_start < STEADY_WINDOW:
            return ''
        window = np.array([r for r in self._rows if r[0] >= t - STEADY_WINDOW])
        if window.shape[0] < 3:
            return ''
        means = window[:, 1:].mean(axis=0)
        rates = np.polyfit(window[:, 0], window[:, 1:], 1)[0]
        reference = self._reference_point()
        previous = (np.array([reference.values[q] for q in _QUANTITIES])
                    if reference is not None else np.zeros(len(_QUANTITIES)))
        tolerance = self.tolerance * (1.0 if self.level <= LINEAR_RANGE[1] + 1e-9
                                      else LIMIT_TOLERANCE_FACTOR)
        allowed = np.maximum(tolerance * np.abs(means - previous),
                             [FLOOR[q] for q in _QUANTITIES])
        if np.any(np.abs(rates) * SETTLE_HORIZON > allowed):
            return ''
        self.points.append(SteadyPoint(
            self.level, float(window[0, 0]), t, t - self._hold_start,
            dict(zip(_QUANTITIES, (float(m) for m in means)))))
        if self.level >= self.last_level - 1e-12:
            return 'done'
        above = [f for f in self.failed if f > self.level]
        if above:
            gap = min(above) - self.level
            if gap <= self.resolution:
                return 'done'
            self._go(t, self.level + 0.5 * gap)
        else:
            self._go(t, min(self.level + self.step, self.last_level))
        return ''

    def _reference_point(self) -> SteadyPoint | None:
        """Return the steady point the present level's change is measured from."""
        below = [p for p in self.points if p.level < self.level - 1e-12]
        return below[-1] if below else None

    def _fail(self, t: float) -> str:
        self.failed.append(self.level)
        if not self.points:
            return 'unsteady'
        last = self.points[-1].level
        gap = min((f for f in self.failed if f > last), default=math.inf) - last
        if gap <= self.resolution:
            return 'done'
        self._go(t, last + 0.5 * gap)
        return ''

    def _go(self, t: float, level: float) -> None:
        self._from = self.speed_of(self.level)
        self.level = level
        self._change_start = t
        self._hold_start = t + abs(self.speed_of(level) - self._from) / LEVEL_SPEED_RATE
        self._rows = []


def run_constant_radius(model: VehicleModel, v: Mapping[str, float],
                        progress: Callable[[float, str], None] | None,
                        channels_of: Callable[[VehicleModel, Trace], dict]):
    """Drive and evaluate the steady-state method (module doc): (metrics, channels, notes)."""
    radius = v['radius']
    wheelbase = model.config.group('geometry').scalar('wheelbase')
    maps = model.maps
    steering = CurvatureController(radius=radius, wheelbase=wheelbase,
                                   steering_ratio=maps.steering_ratio,
                                   max_angle=float(min(-maps.steer_swa[0], maps.steer_swa[-1])))
    stairs = Staircase(radius=radius, wheelbase=wheelbase, steering_ratio=maps.steering_ratio,
                       start=v['start_lateral_acceleration'],
                       step=v['lateral_acceleration_step'], tolerance=v['steady_tolerance'],
                       last_level=max(v['max_lateral_acceleration'],
                                      v['start_lateral_acceleration']),
                       resolution=v['limit_resolution'])
    _, r_e = model.tire_radii(model.static_loads())
    speed = SpeedController(stairs.reference, model.total_mass, float(np.mean(r_e)))
    report = progress or (lambda fraction, stage: None)

    def stop(row: dict[str, float]) -> str:
        if abs(row['sideslip']) > MAX_SIDESLIP:
            return 'sideslip'
        before = len(stairs.points)
        reason = stairs.observe(row, steering.at_lock and row['time'] >= SETTLE_TIME)
        if len(stairs.points) > before:
            report(min(stairs.level / max(stairs.last_level, 1e-9), 0.99),
                   f'steady at {stairs.points[-1].level:.2f} m/s^2')
        return reason

    q0 = stairs.speed_of(stairs.start)
    trace = simulate(model, steering, speed, v['max_duration'], event='constant_radius_turn',
                     initial_speed=q0, initial_yaw_rate=q0 / radius, record_every=RECORD_EVERY,
                     h=TURN_STEP, drive_front=v['drive_front'], brake_front=v['brake_front'],
                     stop=stop, progress=None)
    channels = channels_of(model, trace)
    ch = {k: c.values for k, c in channels.items()}
    t = ch['time']
    flag = np.zeros_like(t)
    points = stairs.points
    if not points:
        raise SolverError(f'no steady state at the first level, '
                          f'{stairs.start:g} m/s^2 ({trace.stop_reason or "max_duration"})')
    ratio = maps.steering_ratio
    excess = ch['steering_wheel_angle'] / ratio - wheelbase * ch['yaw_rate'] / np.maximum(
        ch['speed'], 1e-9)
    rows = []
    for p in points:
        inside = (t >= p.start - 1e-9) & (t <= p.end + 1e-9)
        flag[inside] = 1.0
        rows.append([float(np.mean(x[inside])) for x in
                     (ch['lateral_acceleration'], excess, ch['roll'], ch['sideslip'])])
    table = np.array(rows)
    levels = np.array([p.level for p in points])
    linear = (levels >= LINEAR_RANGE[0] - 1e-9) & (levels <= LINEAR_RANGE[1] + 1e-9)

    def gradient(column: int) -> float:
        if linear.sum() < 3:
            return float('nan')
        return float(np.polyfit(table[linear, 0], table[linear, column], 1)[0])

    channels['steady_window'] = type(channels['time'])('-', flag)
    a_max = float(table[:, 0].max())
    if trace.stop_reason == 'sideslip':
        behaviour = 'oversteer: sideslip beyond 15 deg, the vehicle spins out of the circle'
    elif stairs.failed:
        above = [f for f in stairs.failed if f > points[-1].level + 1e-12] or stairs.failed
        behaviour = (f'understeer: no steady state at {min(above):.2f} m/s^2 (the '
                     'steering reaches its lock or does not settle)')
    elif trace.stop_reason == 'done':
        behaviour = f'last level reached ({stairs.last_level:g} m/s^2)'
    else:
        behaviour = f"ended at max_duration ({v['max_duration']:g} s)"
    metrics = {
        'understeer_gradient': Metric(gradient(1), 'rad/(m/s^2)'),
        'roll_gradient': Metric(gradient(2), 'rad/(m/s^2)'),
        'sideslip_gradient': Metric(gradient(3), 'rad/(m/s^2)'),
        'max_lateral_acceleration': Metric(a_max, 'm/s^2'),
        'limit_is_oversteer': Metric(1.0 if behaviour.startswith('oversteer') else 0.0, '-'),
        'radius': Metric(radius, 'm'),
        'steering_ratio': Metric(ratio, '-', maps.provenance['steering']),
        'steady_points': Metric(float(len(points)), '-'),
        'simulated_time': Metric(float(t[-1]), 's'),
    }
    settle = max(p.settle_time for p in points)
    notes = [f'limit: {behaviour}; highest steady point {a_max:.2f} m/s^2 ({a_max / G:.3f} g)',
             f'ISO 4138 steady-state method: {len(points)} steady points, increments of '
             f"{v['lateral_acceleration_step']:g} m/s^2, halved towards the limit; steady "
             f'when the rates over the last {STEADY_WINDOW:g} s would move excess steer, '
             f"roll, sideslip and V r by less than {v['steady_tolerance']:g} of a level's "
             f'change within {SETTLE_HORIZON:g} s (longest settling {settle:.1f} s)',
             f'linear range for the gradients: {LINEAR_RANGE[0]:g}..{LINEAR_RANGE[1]:g} m/s^2 '
             f'({int(linear.sum())} steady points'
             + ('' if linear.sum() >= 3 else ': fewer than three, no gradients') + ')',
             'left-hand circle; curvature controller (r / V held at 1 / R by proportional and '
             'integral action)']
    return metrics, channels, notes


__all__ = ['PARAMS', 'LINEAR_RANGE', 'TURN_STEP', 'Staircase', 'SteadyPoint',
           'run_constant_radius']
