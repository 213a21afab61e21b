# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Full-vehicle braking and acceleration events, through the configuration's chassis systems.

The brakes, anti-lock option, driveline and aerodynamics are the configuration's
``brakes``, ``driveline`` and ``aero`` groups (:mod:`vd_solvers.chassis.from_config`);
the events that need a group refuse a configuration without it, naming both.

straight_line_braking (ISO 21994:2022, stopping distance at straight-line braking; the
mean fully developed deceleration of UN Regulation No. 13-H, Annex 3, 1.1.1): straight
ahead at ``speed`` with the steering wheel held at zero, the master pressure ramps in
``ramp_time`` to the pressure of ``pedal_force`` (or, with ``deceleration`` > 0, to the
pressure whose brake torque decelerates the vehicle's mass at that rate with the wheels'
static rolling radius) and is held to standstill; the anti-lock brakes work if the
configuration has them. The run ends when the speed falls to END_SPEED (the slip
definitions' speed floor, below which the tire model's creep is not physical) and the
last tenth of a second's deceleration, held, takes the vehicle to standstill. Metrics
(:mod:`vd_solvers.standards.braking`): stopping distance
and time from the start of the pedal ramp, MFDD (from 0.8 v_0 to 0.1 v_0), mean
deceleration, the largest pitch angle (ISO 8855: nose down positive), the wheels that
locked (braking slip above LOCK_SLIP while the vehicle moves faster than LOCK_SPEED) and
how long the first one stayed locked, the lateral drift and the heading change at
standstill.

brake_in_turn (ISO 7975:2019, braking in a turn, open loop): a steady circle of
``radius`` at ``lateral_acceleration`` (the curvature controller of ISO 4138's steady
state and the speed controller for ``settle_time``), then at t_0 the steering wheel is
held where it is and the master pressure ramps in ``ramp_time`` to the pressure of
``deceleration`` (as above), held for EVALUATION_TIME. Metrics at
t_n = t_0 + EVALUATION_TIME (1 s, the standard's time of its characteristic values):
:func:`turn_response`.

power_off_in_turn (ISO 9816:2018, power-off reaction in a turn, constant-radius method,
open loop): the same steady circle, then at t_0 the steering wheel is held and the
throttle closes within ``ramp_time`` (no engine drag torque is modelled: the power-off
deceleration is the tires' rolling resistance and the aerodynamic drag). Metrics at
t_n = t_0 + EVALUATION_TIME: :func:`turn_response`.

straight_line_acceleration (0 to ``end_speed`` at full throttle from ``start_speed``,
the steering wheel at zero): the engine's full-load torque through the gear the
automatic gearbox chooses (:meth:`vd_solvers.chassis.driveline.Driveline.gear`: upshift
at the data's shift speed), the differentials and the tires' traction limit. Metrics:
the time to ``end_speed`` (0-100 km/h by default), the distance, the largest
acceleration (mean over ACCELERATION_WINDOW), the driven wheels' largest slip ratio and
the squat (largest nose-up pitch).
"""
from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
import math

import numpy as np

from vd_solvers.constants import STANDARD_GRAVITY
from vd_solvers.errors import SolverError
from vd_solvers.event_params import Param
from vd_solvers.results import Channel, Metric
from vd_solvers.standards.braking import STANDSTILL, grade_stop

from .drivers import (
    CurvatureController,
    Observation,
    OpenLoopSteering,
    Pedals,
    SpeedController,
    SpeedSchedule,
)
from .model import STEP, VehicleModel
from .simulation import Trace, simulate

#: time after t_0 at which the turn events' characteristic values are taken, s
EVALUATION_TIME = 1.0
#: braking slip above which a wheel counts as locked, and the speed below which none does
LOCK_SLIP, LOCK_SPEED = 0.9, 2.0
#: window of the acceleration event's largest mean acceleration, s
ACCELERATION_WINDOW = 0.5
#: a stop is simulated down to this speed and finished at the deceleration reached, m/s
END_SPEED = 1.0
#: the deceleration that finishes a stop is the mean over this last part of it, s
END_WINDOW = 0.1
#: sampling period of the channels, s
RECORD_PERIOD = 0.01

_SPEED = Param('velocity', 100.0 / 3.6, 'speed at the brake application (ISO 21994: '
               '100 km/h)', minimum=5.0, maximum=70.0)
_RAMP = Param('time', 0.15, 'pedal ramp time from zero to the held pressure', minimum=0.01,
              maximum=1.0)
BRAKING_PARAMS: Mapping[str, Param] = {
    'speed': _SPEED,
    'pedal_force': Param('force', 500.0, 'brake-pedal force held to standstill (used when '
                         'deceleration is 0)', minimum=0.0, maximum=2000.0),
    'deceleration': Param('acceleration', 0.0, 'deceleration whose brake pressure is held '
                          'instead of a pedal force (0: pedal_force)', minimum=0.0,
                          maximum=15.0),
    'ramp_time': _RAMP,
    'max_duration': Param('time', 20.0, 'longest simulated time', minimum=2.0, maximum=120.0),
}
_TURN = {
    'radius': Param('length', 100.0, 'radius of the initial steady circle (ISO 7975, ISO 9816: '
                    '100 m preferred)', minimum=20.0, maximum=500.0),
    'lateral_acceleration': Param('acceleration', 5.0, 'lateral acceleration of the initial '
                                  'steady circle', minimum=1.0, maximum=9.0),
    'settle_time': Param('time', 8.0, 'time on the circle before t_0', minimum=3.0,
                         maximum=60.0),
}
BRAKE_IN_TURN_PARAMS: Mapping[str, Param] = {
    **_TURN,
    'deceleration': Param('acceleration', 4.0, 'deceleration whose brake pressure is applied '
                          'at t_0', minimum=0.5, maximum=12.0),
    'ramp_time': _RAMP,
}
POWER_OFF_PARAMS: Mapping[str, Param] = {
    **_TURN,
    'lateral_acceleration': Param('acceleration', 4.0, 'lateral acceleration of the initial '
                                  'steady circle (ISO 9816: from 4 m/s^2 up)', minimum=1.0,
                                  maximum=9.0),
    'ramp_time': Param('time', 0.1, 'throttle closing time', minimum=0.01, maximum=1.0),
}
ACCELERATION_PARAMS: Mapping[str, Param] = {
    'start_speed': Param('velocity', 0.5, 'speed at the start (a standing start is taken at '
                         'walking pace: the slips need a rolling wheel)', minimum=0.1,
                         maximum=30.0),
    'end_speed': Param('velocity', 100.0 / 3.6, 'speed the time is taken to (100 km/h)',
                       minimum=5.0, maximum=70.0),
    'max_duration': Param('time', 60.0, 'longest simulated time', minimum=5.0, maximum=300.0),
}

Channels = Callable[[VehicleModel, Trace], dict[str, Channel]]
Outcome = tuple[dict[str, Metric], dict[str, Channel], list[str]]


def _need(model: VehicleModel, group: str, event: str) -> None:
    chassis = model.chassis
    have = {'brakes': chassis.brakes, 'driveline': chassis.driveline}[group]
    if have is None:
        raise SolverError(f"configuration '{model.config.name}': event '{event}' needs the "
                          f"'{group}' group (docs/data-format.md), which it does not pick")


def _record_every(h: float = STEP) -> int:
    return max(1, round(RECORD_PERIOD / h))


def rolling_radius(model: VehicleModel) -> float:
    """Mean effective rolling radius of the four tires at the static loads, m."""
    return float(np.mean(model.tire_radii(model.static_loads())[1]))


def pressure_for_deceleration(model: VehicleModel, deceleration: float) -> float:
    """Master pressure whose brake torque decelerates the vehicle's mass, Pa (rigid wheels)."""
    assert model.chassis.brakes is not None
    torque = model.total_mass * deceleration * rolling_radius(model)
    return model.chassis.brakes.pressure_for_torque(torque)


@dataclass
class PedalRamp:
    """Throttle and master pressure: ramped from their values at ``start`` to the held ones."""

    start: float
    ramp: float
    throttle: tuple[float, float]  # before, after
    pressure: tuple[float, float]
    before: SpeedController | None = None  # the speed held before ``start``

    def wheel_torque(self, obs: Observation, h: float) -> float | Pedals:
        if obs.t < self.start and self.before is not None:
            return self.before.wheel_torque(obs, h)
        return self.pedals(obs.t)

    def pedals(self, t: float) -> Pedals:
        """Return the pedals at time ``t`` (s)."""
        k = min(max((t - self.start) / self.ramp, 0.0), 1.0)
        return Pedals(self.throttle[0] + k * (self.throttle[1] - self.throttle[0]),
                      self.pressure[0] + k * (self.pressure[1] - self.pressure[0]))

    def schedule(self, times: np.ndarray, h: float) -> SpeedSchedule:
        """Return the commands at ``times`` (s; steps of ``h``) for the compiled loop."""
        pedals = np.array([self.pedals(float(t)) for t in times]).reshape(-1, 2)
        use = np.ones(times.size, dtype=bool)
        if self.before is None:
            return SpeedSchedule(use, pedals[:, 0].copy(), pedals[:, 1].copy(), np.zeros(0),
                                 np.zeros(0), np.zeros(0), None)
        use = times >= self.start
        held = self.before.schedule(times, h)
        return held._replace(pedals=use, throttle=pedals[:, 0].copy(),
                             pressure=pedals[:, 1].copy())


@dataclass
class HoldAfter:
    """Steer with ``driver`` until ``start``, then hold the steering-wheel angle reached."""

    driver: CurvatureController
    start: float
    _held: float | None = None

    def steering_wheel_angle(self, obs: Observation, h: float) -> float:
        if obs.t < self.start:
            return self.driver.steering_wheel_angle(obs, h)
        if self._held is None:
            self._held = self.driver.steering_wheel_angle(obs, h)
        return self._held


def _with_actuation(trace: Trace, channels: dict[str, Channel]) -> dict[str, Channel]:
    from .maps import WHEELS
    ch = trace.channels()
    out = dict(channels)
    out['throttle'] = Channel('-', ch['throttle'])
    out['gear'] = Channel('-', ch['gear'])
    for w, name in enumerate(WHEELS):
        out[f'brake_pressure_{name}'] = Channel('Pa', ch['brake_pressure'][:, w])
        out[f'applied_torque_{name}'] = Channel('N*m', ch['applied_torque'][:, w])
    return out


def _distance(t: np.ndarray, speed: np.ndarray) -> np.ndarray:
    """Distance travelled along the path, m (trapezoids of the speed)."""
    return np.concatenate([[0.0], np.cumsum(0.5 * (speed[1:] + speed[:-1]) * np.diff(t))])


def finish_stop(t: np.ndarray, speed: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """
    Time, speed and distance of a stop, finished from its last sample to standstill.

    The deceleration d of the last END_WINDOW s is held: TAIL samples of v_f - d tau and
    s_f + v_f tau - d tau^2 / 2 up to tau = v_f / d. A series that ends at standstill
    already, or whose speed does not fall at its end, is returned as it is.
    """
    s = _distance(t, speed)
    last = t >= t[-1] - END_WINDOW
    if speed[-1] <= STANDSTILL or np.count_nonzero(last) < 2:
        return t, speed, s
    k = int(np.flatnonzero(last)[0])
    decel = (speed[k] - speed[-1]) / (t[-1] - t[k])
    if not decel > 0.0:
        return t, speed, s
    tau = np.linspace(0.0, speed[-1] / decel, TAIL + 1)[1:]
    return (np.concatenate([t, t[-1] + tau]),
            np.concatenate([speed, np.maximum(speed[-1] - decel * tau, 0.0)]),
            np.concatenate([s, s[-1] + speed[-1] * tau - 0.5 * decel * tau**2]))


#: samples of a finished stop's tail
TAIL = 20


def _locked(ch: Mapping[str, np.ndarray], h: float) -> tuple[int, float]:
    """Count the wheels that locked and return it with the longest time one stayed locked, s."""
    moving = ch['speed'] > LOCK_SPEED
    locked = (ch['slip_ratio'] < -LOCK_SLIP) & moving[:, None]
    longest = 0.0
    for w in range(4):
        run = best = 0
        for flag in locked[:, w]:
            run = run + 1 if flag else 0
            best = max(best, run)
        longest = max(longest, best * h)
    return int(np.sum(locked.any(axis=0))), longest


def braking_run(model: VehicleModel, v: Mapping[str, float], pressure: float, progress=None,
                compiled_loop: bool = True) -> Trace:
    """Run the stop of :func:`straight_line_braking` at a master ``pressure`` (Pa)."""
    pedals = PedalRamp(0.0, v['ramp_time'], (0.0, 0.0), (0.0, pressure))
    return simulate(model, OpenLoopSteering(lambda t: 0.0), pedals, v['max_duration'],
                    event='straight_line_braking', initial_speed=v['speed'],
                    record_every=_record_every(), progress=progress,
                    stop=lambda row: 'end speed' if row['speed'] < END_SPEED else '',
                    compiled_loop=compiled_loop)


def acceleration_run(model: VehicleModel, v: Mapping[str, float], progress=None,
                     compiled_loop: bool = True) -> Trace:
    """Run the full-throttle run of :func:`straight_line_acceleration`."""
    end = v['end_speed']
    pedals = PedalRamp(0.0, 1e-3, (1.0, 1.0), (0.0, 0.0))
    return simulate(model, OpenLoopSteering(lambda t: 0.0), pedals, v['max_duration'],
                    event='straight_line_acceleration', initial_speed=v['start_speed'],
                    record_every=_record_every(), progress=progress,
                    stop=lambda row: 'end speed' if row['speed'] >= end else '',
                    compiled_loop=compiled_loop)


def straight_line_braking(model: VehicleModel, v: Mapping[str, float], progress,
                          channels: Channels) -> Outcome:
    """ISO 21994 straight-line stop (module doc)."""
    _need(model, 'brakes', 'straight_line_braking')
    brakes = model.chassis.brakes
    assert brakes is not None
    speed = v['speed']
    if v['deceleration'] > 0.0:
        pressure = pressure_for_deceleration(model, v['deceleration'])
        aim = f"deceleration {v['deceleration']:g} m/s^2"
    else:
        pressure = brakes.pressure_from_pedal(v['pedal_force'])
        aim = f"pedal force {v['pedal_force']:g} N"
    if not pressure > 0.0:
        raise SolverError('straight_line_braking needs a pedal force or a deceleration above 0')
    trace = braking_run(model, v, pressure, progress)
    out = _with_actuation(trace, channels(model, trace))
    ch = {**{k: c.values for k, c in out.items()}, 'slip_ratio': trace.channels()['slip_ratio']}
    t, speed_t, distance = finish_stop(ch['time'], ch['speed'])
    try:
        stop = grade_stop(t, speed_t, distance, 0.0)
    except ValueError as err:
        raise SolverError(f'straight_line_braking: {err} (raise max_duration or the pedal '
                          f'force)') from err
    n_locked, lock_time = _locked(ch, RECORD_PERIOD)
    metrics = {
        'stopping_distance': Metric(stop.stopping_distance, 'm'),
        'stopping_time': Metric(stop.stopping_time, 's'),
        'mean_fully_developed_deceleration': Metric(stop.mfdd, 'm/s^2'),
        'mean_deceleration': Metric(stop.mean_deceleration, 'm/s^2'),
        'brake_pressure': Metric(pressure, 'Pa'),
        'max_pitch': Metric(float(np.max(ch['pitch'])), 'rad'),
        'locked_wheels': Metric(float(n_locked), '-'),
        'longest_lock': Metric(lock_time, 's'),
        'lateral_drift': Metric(float(ch['y'][-1]), 'm'),
        'heading_change': Metric(float(ch['yaw'][-1] - ch['yaw'][0]), 'rad'),
    }
    abs_note = 'anti-lock brakes on all wheels' if model.chassis.anti_lock is not None else \
        'no anti-lock brakes'
    notes = [f'stop from {speed * 3.6:.0f} km/h, {aim}: master pressure '
             f'{pressure / 1e5:.1f} bar after a {v["ramp_time"]:g} s ramp; {abs_note}',
             'stopping distance from the start of the pedal ramp (ISO 21994); MFDD from '
             '0.8 v_0 to 0.1 v_0 (UN R13-H Annex 3)']
    return metrics, out, notes


def _turn_start(model: VehicleModel, v: Mapping[str, float]
                ) -> tuple[float, CurvatureController, SpeedController]:
    radius = v['radius']
    speed = math.sqrt(v['lateral_acceleration'] * radius)
    maps = model.maps
    wheelbase = model.config.group('geometry').scalar('wheelbase')
    limit = float(min(-maps.steer_swa[0], maps.steer_swa[-1]))
    follower = CurvatureController(radius, wheelbase, maps.steering_ratio, limit)
    controller = SpeedController(lambda t: speed, model.total_mass, rolling_radius(model))
    return speed, follower, controller


def turn_response(ch: Mapping[str, np.ndarray], t0: float) -> dict[str, Metric]:
    """
    Return the characteristic values of a disturbance in a steady turn (ISO 7975, ISO 9816).

    From the steady state at t_0 (means over the STEADY_BEFORE s before it: yaw rate r_0,
    speed v_0, the initial circle's radius R = v_0 / r_0) to t_n = t_0 + EVALUATION_TIME:
    the yaw-rate ratio r(t_n) / r_0, the lateral acceleration ratio a_y(t_n) / a_y,0, the
    yaw-rate difference to the initial circle at the present speed r(t_n) - v(t_n) / R,
    the heading deviation psi(t_n) - psi(t_0) - (s(t_n) - s(t_0)) / R (the heading change
    the initial circle would give over the same path length s), the path deviation
    (distance from the initial circle at t_n, + outwards; its centre from the position
    and course at t_0), the sideslip change and the mean longitudinal deceleration over
    t_0..t_n.
    """
    t = ch['time']
    before = (t >= t0 - STEADY_BEFORE) & (t < t0)
    if not before.any() or t[-1] < t0 + EVALUATION_TIME:
        raise SolverError('the run does not cover the steady state before t_0 and '
                          f'{EVALUATION_TIME:g} s after it')
    n = int(np.searchsorted(t, t0 + EVALUATION_TIME))
    k0 = int(np.searchsorted(t, t0))
    r0 = float(np.mean(ch['yaw_rate'][before]))
    ay0 = float(np.mean(ch['lateral_acceleration'][before]))
    radius = float(np.mean(ch['speed'][before])) / abs(r0)
    s = _distance(t, ch['speed'])
    course = ch['yaw'][k0] + ch['sideslip'][k0]
    sign = 1.0 if r0 >= 0.0 else -1.0
    centre = (ch['x'][k0] - sign * radius * math.sin(course),
              ch['y'][k0] + sign * radius * math.cos(course))
    off = math.hypot(ch['x'][n] - centre[0], ch['y'][n] - centre[1]) - radius
    heading = ch['yaw'][n] - ch['yaw'][k0] - sign * (s[n] - s[k0]) / radius
    return {
        'radius_initial': Metric(radius, 'm'),
        'yaw_rate_initial': Metric(r0, 'rad/s'),
        'lateral_acceleration_initial': Metric(ay0, 'm/s^2'),
        'yaw_rate_ratio': Metric(float(ch['yaw_rate'][n]) / r0, '-'),
        'lateral_acceleration_ratio': Metric(float(ch['lateral_acceleration'][n]) / ay0, '-'),
        'yaw_rate_difference': Metric(float(ch['yaw_rate'][n] - sign * ch['speed'][n] / radius),
                                      'rad/s'),
        'heading_deviation': Metric(float(heading), 'rad'),
        'path_deviation': Metric(float(off), 'm'),
        'sideslip_change': Metric(float(ch['sideslip'][n] - ch['sideslip'][k0]), 'rad'),
        'mean_longitudinal_deceleration': Metric(
            float(ch['speed'][k0] - ch['speed'][n]) / float(t[n] - t[k0]), 'm/s^2'),
    }


#: the steady state before t_0 is averaged over this, s
STEADY_BEFORE = 0.5


def _turn_event(model: VehicleModel, v: Mapping[str, float], progress, channels: Channels,
                event: str, pressure: float) -> tuple[dict[str, Metric], dict[str, Channel],
                                                      float]:
    speed, follower, controller = _turn_start(model, v)
    t0 = v['settle_time']
    pedals = PedalRamp(t0, v['ramp_time'], (0.0, 0.0), (0.0, pressure), before=controller)
    trace = simulate(model, HoldAfter(follower, t0), pedals, t0 + EVALUATION_TIME + 0.5,
                     event=event, initial_speed=speed, initial_yaw_rate=speed / v['radius'],
                     record_every=_record_every(), progress=progress)
    out = _with_actuation(trace, channels(model, trace))
    ch = {k: c.values for k, c in out.items()}
    metrics = turn_response(ch, t0)
    metrics['speed_initial'] = Metric(speed, 'm/s')
    return metrics, out, speed


def brake_in_turn(model: VehicleModel, v: Mapping[str, float], progress,
                  channels: Channels) -> Outcome:
    """ISO 7975 braking in a turn (module doc)."""
    _need(model, 'brakes', 'brake_in_turn')
    pressure = pressure_for_deceleration(model, v['deceleration'])
    metrics, out, speed = _turn_event(model, v, progress, channels, 'brake_in_turn', pressure)
    metrics['brake_pressure'] = Metric(pressure, 'Pa')
    abs_note = 'anti-lock brakes on all wheels' if model.chassis.anti_lock is not None else \
        'no anti-lock brakes'
    notes = [f'steady circle R = {v["radius"]:g} m at {speed * 3.6:.1f} km/h '
             f'({v["lateral_acceleration"]:g} m/s^2), then at t_0 = {v["settle_time"]:g} s the '
             f'steering wheel held and {pressure / 1e5:.1f} bar master pressure (aimed '
             f'deceleration {v["deceleration"]:g} m/s^2) in {v["ramp_time"]:g} s; {abs_note}',
             f'characteristic values at t_0 + {EVALUATION_TIME:g} s (ISO 7975)']
    return metrics, out, notes


def power_off_in_turn(model: VehicleModel, v: Mapping[str, float], progress,
                      channels: Channels) -> Outcome:
    """ISO 9816 power-off in a turn (module doc)."""
    metrics, out, speed = _turn_event(model, v, progress, channels, 'power_off_in_turn', 0.0)
    drive = ('the driveline of the configuration' if model.chassis.driveline is not None
             else 'fixed drive shares (no driveline group)')
    notes = [f'steady circle R = {v["radius"]:g} m at {speed * 3.6:.1f} km/h '
             f'({v["lateral_acceleration"]:g} m/s^2) on {drive}, then at t_0 = '
             f'{v["settle_time"]:g} s the steering wheel held and the throttle closed in '
             f'{v["ramp_time"]:g} s (no engine drag torque modelled)',
             f'characteristic values at t_0 + {EVALUATION_TIME:g} s (ISO 9816)']
    return metrics, out, notes


def straight_line_acceleration(model: VehicleModel, v: Mapping[str, float], progress,
                               channels: Channels) -> Outcome:
    """Full-throttle acceleration (module doc)."""
    _need(model, 'driveline', 'straight_line_acceleration')
    if not v['end_speed'] > v['start_speed']:
        raise SolverError('straight_line_acceleration: end_speed must lie above start_speed')
    end = v['end_speed']
    trace = acceleration_run(model, v, progress)
    out = _with_actuation(trace, channels(model, trace))
    ch = {k: c.values for k, c in out.items()}
    t, speed = ch['time'], ch['speed']
    if speed[-1] < end:
        raise SolverError(f'straight_line_acceleration: the vehicle reaches only '
                          f'{speed[-1] * 3.6:.1f} km/h in {v["max_duration"]:g} s (end speed '
                          f'{end * 3.6:.0f} km/h)')
    k = int(np.argmax(speed >= end))
    t_end = float(t[k - 1] + (t[k] - t[k - 1]) * (end - speed[k - 1]) / (speed[k] - speed[k - 1]))
    window = max(1, round(ACCELERATION_WINDOW / RECORD_PERIOD))
    ax = np.convolve(ch['longitudinal_acceleration'], np.ones(window) / window, mode='valid')
    line = model.chassis.driveline
    assert line is not None
    driven = [w for w, share in enumerate([line.front_share] * 2 + [1.0 - line.front_share] * 2)
              if share > 0.0]
    slip = trace.channels()['slip_ratio'][:, driven]
    metrics = {
        'acceleration_time': Metric(t_end, 's'),
        'acceleration_distance': Metric(float(np.interp(t_end, t, _distance(t, speed))), 'm'),
        'max_longitudinal_acceleration': Metric(float(np.max(ax)), 'm/s^2'),
        'max_drive_slip': Metric(float(np.max(slip)), '-'),
        'max_squat': Metric(float(-np.min(ch['pitch'])), 'rad'),
        'top_gear_reached': Metric(float(np.max(ch['gear'])), '-'),
    }
    notes = [f'full throttle from {v["start_speed"] * 3.6:.1f} to {end * 3.6:.0f} km/h, '
             f'automatic upshifts at {model.chassis.shift_speed * 30 / math.pi:.0f} rpm; '
             f'traction limit of the tires (peak mu x load)',
             f'largest acceleration {float(np.max(ax)) / STANDARD_GRAVITY:.2f} g '
             f'(mean over {ACCELERATION_WINDOW:g} s)']
    return metrics, out, notes


#: event name -> (parameters, run function)
LONGITUDINAL_EVENTS: Mapping[str, tuple[Mapping[str, Param], Callable[..., Outcome]]] = {
    'straight_line_braking': (BRAKING_PARAMS, straight_line_braking),
    'brake_in_turn': (BRAKE_IN_TURN_PARAMS, brake_in_turn),
    'power_off_in_turn': (POWER_OFF_PARAMS, power_off_in_turn),
    'straight_line_acceleration': (ACCELERATION_PARAMS, straight_line_acceleration),
}

__all__ = ['LONGITUDINAL_EVENTS', 'BRAKING_PARAMS', 'BRAKE_IN_TURN_PARAMS', 'POWER_OFF_PARAMS',
           'ACCELERATION_PARAMS', 'turn_response', 'pressure_for_deceleration',
           'EVALUATION_TIME', 'LOCK_SLIP', 'LOCK_SPEED', 'PedalRamp', 'braking_run',
           'acceleration_run']
