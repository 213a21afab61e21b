# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Full-vehicle events: constant radius turn (ISO 4138), step steer (ISO 7401), sine with dwell.

``run_vehicle_event(config, event, params, fidelity, progress)`` builds the vehicle of
``config`` (suspension maps from the K&C results of the same data hash and fidelity),
drives the manoeuvre with the drivers of :mod:`.drivers` and returns an
:class:`EventOutcome` with SI channels over time and the metrics of the standard.

constant_radius_turn (ISO 4138:2021, constant-radius method, steady state): see
:mod:`.constant_radius`.

step_steer (ISO 7401:2011, step input; the variable step of :mod:`.adaptive` by
default): straight at ``speed``, then a steering-wheel ramp of ``ramp_time`` to the
angle giving ``lateral_acceleration`` in the steady state (first guess from the linear
bicycle model, then scaled once or twice by the ratio aimed/reached), speed held by the
PI controller. Response times are measured from the instant the steering-wheel angle
passes 50 % of its step (ISO 7401 5.3):
t90 (first reaching 90 % of the steady value) and the peak time; overshoot is
peak / steady - 1; steady values are means over the last STEADY_WINDOW s.

sine_with_dwell (FMVSS 126 / UN R140 / GTR 8, the whole procedure): see
:mod:`.sine_with_dwell`.

straight_line_braking (ISO 21994), brake_in_turn (ISO 7975), power_off_in_turn (ISO 9816)
and straight_line_acceleration: see :mod:`.longitudinal_events`.
ride, bump (ISO 2631-1 ride on the road, a single obstacle): see :mod:`.ride_events`;
lane_change, lane_change_limit (ISO 3888-2 at one entry speed, the highest passing entry
speed): see :mod:`.lane_change`. Every event drives on the configuration's road
(:mod:`vd_solvers.road.from_config`).
"""
from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence

import numpy as np

from vd_data_server.errors import DataError
from vd_data_server.model import Configuration
from vd_solvers.analytical import bicycle
from vd_solvers.analytical.from_config import vehicle_params
from vd_solvers.constants import DEG
from vd_solvers.errors import SolverError
from vd_solvers.event_params import Param, parse_params
from vd_solvers.results import Channel, EventOutcome, Metric

from . import lane_change, ride_events
from .adaptive import STEP_TOLERANCE_PARAM, event_tolerance
from .constant_radius import LINEAR_RANGE, TURN_STEP, run_constant_radius
from .constant_radius import PARAMS as CRT_PARAMS
from .drivers import OpenLoopSteering, SpeedController
from .longitudinal_events import LONGITUDINAL_EVENTS
from .maps import WHEELS
from .model import STEP, VehicleModel
from .simulation import Trace, simulate
from .sine_with_dwell import PARAMS as SWD_PARAMS
from .sine_with_dwell import run_procedure

#: steady-state averaging window at the end of a step steer, s
STEADY_WINDOW = 1.0
#: steering-wheel angle of the step scaled until the steady a_y is within this of the aim
STEP_AIM_TOLERANCE = 0.02
STEP_AIM_ITERATIONS = 3
#: time of the steer step (after a straight run), s
STEP_TIME = 1.0
#: sampling period of the step steer's channels, s
RECORD_PERIOD = 0.01
EVENT_PARAMS: Mapping[str, Mapping[str, Param]] = {
    'constant_radius_turn': CRT_PARAMS,
    'step_steer': {
        'speed': Param('velocity', 100.0 / 3.6, 'constant speed', minimum=5.0, maximum=70.0),
        'lateral_acceleration': Param('acceleration', 4.0, 'steady lateral acceleration the '
                                      'step aims at (ISO 7401: 4 m/s^2)', minimum=0.2,
                                      maximum=8.0),
        'ramp_time': Param('time', 0.1, 'steering-wheel ramp time (ISO 7401: <= 0.15 s)',
                           minimum=0.01, maximum=1.0),
        'duration': Param('time', 6.0, 'simulated time', minimum=3.0, maximum=60.0),
        'time_step': Param('time', STEP, 'fixed integration step with step_tolerance 0 (the '
                           'overshoot converges at first order in it)', minimum=5e-4,
                           maximum=STEP),
        'step_tolerance': STEP_TOLERANCE_PARAM,
        'drive_front': Param('dimensionless', 0.5,
                             'front share of the drive torque (0 rear, 1 front)',
                             minimum=0.0, maximum=1.0),
        'brake_front': Param('dimensionless', 0.65, 'front share of the brake torque', minimum=0.0,
                             maximum=1.0),
    },
    'sine_with_dwell': SWD_PARAMS,
    'straight_line_braking': LONGITUDINAL_EVENTS['straight_line_braking'][0],
    'brake_in_turn': LONGITUDINAL_EVENTS['brake_in_turn'][0],
    'power_off_in_turn': LONGITUDINAL_EVENTS['power_off_in_turn'][0],
    'straight_line_acceleration': LONGITUDINAL_EVENTS['straight_line_acceleration'][0],
    'ride': ride_events.RIDE_PARAMS,
    'bump': ride_events.BUMP_PARAMS,
    **lane_change.PARAMS,
}
EVENTS = tuple(EVENT_PARAMS)


def run_vehicle_event(config: Configuration, event: str, params: Sequence[str] = (),
                      fidelity: str = '',
                      progress: Callable[[float, str], None] | None = None) -> EventOutcome:
    """Run a full-vehicle event on ``config`` (module doc). SolverError names both."""
    label = f"configuration '{config.name}', event '{event}'"
    if event not in EVENT_PARAMS:
        raise SolverError(f"{label}: the full-vehicle model has no event '{event}' "
                          f"(events: {', '.join(EVENTS)})")
    values = parse_params(event, EVENT_PARAMS[event], params)
    if progress is not None:
        progress(0.0, 'K&C suspension maps')
    try:
        model = VehicleModel(config, fidelity)  # on the configuration's road
    except (SolverError, DataError, ValueError) as err:
        raise SolverError(f'{label}: {err}') from err
    if event == 'sine_with_dwell':
        try:
            metrics, channels, notes = run_procedure(model, values, progress, _channels)
        except SolverError as err:
            if config.name in str(err):
                raise
            raise SolverError(f'{label}: {err}') from err
    elif event in ride_events.RUNNERS or event in lane_change.RUNNERS:
        runner = {**ride_events.RUNNERS, **lane_change.RUNNERS}[event]
        try:
            metrics, channels, notes = runner(model, values, progress, _channels)
        except SolverError as err:
            raise SolverError(f'{label}: {err}') from err
    elif event == 'constant_radius_turn':
        metrics, channels, notes = run_constant_radius(model, values, progress, _channels)
    elif event in LONGITUDINAL_EVENTS:
        try:
            metrics, channels, notes = LONGITUDINAL_EVENTS[event][1](model, values, progress,
                                                                     _channels)
        except SolverError as err:
            if config.name in str(err):
                raise
            raise SolverError(f'{label}: {err}') from err
    else:
        metrics, channels, notes = _step_steer(model, values, progress)
    step = (TURN_STEP if event == 'constant_radius_turn' else
            values.get('time_step', STEP))
    variable = event_tolerance(model, values.get('step_tolerance', 0.0))
    notes = [*notes, 'integrator: semi-implicit Euler on the articulated-body algorithm, '
             + (f'variable step (tolerance {variable:g}, wheel travel linearly implicit)'
                if variable else f'step {step * 1e3:g} ms')
             + '; transient slip integrated exactly per step, wheel spin linearly implicit',
             *(f'{k}: {v}' for k, v in sorted(model.maps.provenance.items()))]
    return EventOutcome(event=event, configuration=config.name, model='vehicle',
                        fidelity=model.fidelity, axle='', data_hash=config.data_hash,
                        metrics=metrics,
                        channels=channels, notes=tuple(notes))


def _speed_controller(model: VehicleModel, reference: Callable[[float], float]) -> SpeedController:
    _, r_e = model.tire_radii(model.static_loads())
    return SpeedController(reference, model.total_mass, float(np.mean(r_e)))


def _channels(model: VehicleModel, trace: Trace) -> dict[str, Channel]:
    ch = trace.channels()
    units = {'time': 's', 'x': 'm', 'y': 'm', 'yaw': 'rad', 'roll': 'rad', 'pitch': 'rad',
             'yaw_rate': 'rad/s', 'speed': 'm/s', 'sideslip': 'rad',
             'steering_wheel_angle': 'rad', 'steer_angle_front_left': 'rad',
             'steer_angle_front_right': 'rad', 'lateral_acceleration': 'm/s^2',
             'longitudinal_acceleration': 'm/s^2', 'wheel_torque': 'N*m'}
    out = {name: Channel(unit, ch[name]) for name, unit in units.items()}
    wheel_units = {'wheel_load': 'N', 'wheel_travel': 'm', 'slip_angle': 'rad',
                   'slip_ratio': '-', 'inclination': 'rad', 'tire_force_x': 'N',
                   'tire_force_y': 'N', 'wheel_steer': 'rad', 'aligning_moment': 'N*m'}
    for key, unit in wheel_units.items():
        for w, name in enumerate(WHEELS):
            out[f'{key}_{name}'] = Channel(unit, ch[key][:, w])
    return out


def _step_steer(model: VehicleModel, v: Mapping[str, float], progress):
    speed = v['speed']
    target = v['lateral_acceleration']
    maps = model.maps
    p = vehicle_params(model.config)
    wheelbase = model.config.group('geometry').scalar('wheelbase')
    delta = target * (wheelbase / speed**2 + bicycle.understeer_gradient(p))
    swa = delta * maps.steering_ratio
    limit = float(min(-maps.steer_swa[0], maps.steer_swa[-1]))
    ramp = v['ramp_time']
    trace = None
    reached = float('nan')
    for _ in range(STEP_AIM_ITERATIONS):
        if not 0.0 < swa <= limit:
            raise SolverError(f'step steer to {target:g} m/s^2 at {speed:g} m/s needs a '
                              f'steering-wheel angle beyond the lock ({limit / DEG:.0f} deg)')
        steering = OpenLoopSteering(times=[0.0, STEP_TIME, STEP_TIME + ramp, v['duration']],
                                    angles=[0.0, 0.0, swa, swa])
        trace = simulate(model, steering, _speed_controller(model, lambda t: speed),
                         v['duration'], event='step_steer', initial_speed=speed,
                         record_every=max(1, round(RECORD_PERIOD / v['time_step'])),
                         h=v['time_step'], drive_front=v['drive_front'],
                         brake_front=v['brake_front'], progress=progress,
                         tolerance=event_tolerance(model, v['step_tolerance']))
        ch = trace.channels()
        steady = ch['time'] >= ch['time'][-1] - STEADY_WINDOW
        reached = float(np.mean(ch['lateral_acceleration'][steady]))
        if reached <= 0.0:
            raise SolverError(f'the step steer gives no steady lateral acceleration '
                              f'({reached:.3g} m/s^2)')
        if abs(reached / target - 1.0) <= STEP_AIM_TOLERANCE:
            break
        swa *= target / reached
    assert trace is not None
    channels = _channels(model, trace)
    ch = {k: c.values for k, c in channels.items()}
    t = ch['time']
    steady = t >= t[-1] - STEADY_WINDOW
    t50 = STEP_TIME + 0.5 * ramp
    metrics = {'steering_wheel_angle_step': Metric(swa, 'rad'),
               'speed': Metric(speed, 'm/s'),
               'steering_ratio': Metric(maps.steering_ratio, '-', maps.provenance['steering'])}
    for name, key in (('yaw_rate', 'yaw_rate'), ('lateral_acceleration', 'lateral_acceleration')):
        y = ch[key]
        y_ss = float(np.mean(y[steady]))
        after = t >= t50
        i90 = np.nonzero(after & (y >= 0.9 * y_ss))[0]
        i_peak = int(np.argmax(np.where(after, y, -np.inf)))
        unit = 'rad/s' if name == 'yaw_rate' else 'm/s^2'
        metrics[f'steady_{name}'] = Metric(y_ss, unit)
        metrics[f'{name}_gain'] = Metric(y_ss / swa, f'{unit}/rad')
        metrics[f'{name}_response_time_90'] = Metric(
            float(t[i90[0]] - t50) if i90.size else float('nan'), 's')
        metrics[f'{name}_peak_response_time'] = Metric(float(t[i_peak] - t50), 's')
        metrics[f'{name}_overshoot'] = Metric(100.0 * (float(y[i_peak]) / y_ss - 1.0), '%')
    metrics['sideslip_gain'] = Metric(float(np.mean(ch['sideslip'][steady])) / swa, 'rad/rad')
    metrics['roll_gain'] = Metric(float(np.mean(ch['roll'][steady])) / swa, 'rad/rad')
    notes = [f'steering-wheel step {swa / DEG:.1f} deg in {ramp:g} s at t = {STEP_TIME:g} s; '
             f'steady a_y {reached:.3f} m/s^2 (aimed {target:g})',
             'response times from the 50 % steering-wheel instant (ISO 7401)']
    return metrics, channels, notes


__all__ = ['EVENT_PARAMS', 'EVENTS', 'run_vehicle_event', 'LINEAR_RANGE']
