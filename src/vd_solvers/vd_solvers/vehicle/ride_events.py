# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Ride events on the configuration's road.

Every event drives on the road of the configuration's ``road`` group
(:mod:`vd_solvers.road.from_config`; the flat road of friction 1 without one) and names it
in its notes (ISO 8608 class and seed, the obstacle, the OpenCRG file and its hash).

ride (constant speed over the road, ISO 2631-1:1997): the speed controller holds
``speed``; the body's vertical acceleration at the CoG (world z) and its pitch acceleration
are weighted by Wk and We of ISO 2631-1 (Annex A) and reported as weighted r.m.s. (6.1),
VDV (6.3.2) and crest factor (6.2) over the evaluated stretch: from where the front axle
has passed the road's blend-in (``FADE_IN`` m, ISO 8608 roads) to the end of ``distance``.
The wheel-load variation is the standard deviation of each wheel's load over its static
load (the road-holding measure), per axle the mean of its two wheels. The acceleration
is taken at the CoG, not at a seat; the unweighted accelerations are the channels
``vertical_acceleration`` and ``pitch_acceleration`` (also of the bump event).

bump (a single obstacle, the configuration's ``obstacle`` road): at constant ``speed``
over the obstacle; the peaks of the body's vertical and pitch accelerations and of the
wheel loads over their static values, the smallest wheel load (0: a wheel left the
ground) and the settling time: from the front wheels reaching the obstacle to the last
instant the vertical acceleration exceeds SETTLE_FRACTION of its peak.

The ISO 3888-2 lane change is in :mod:`.lane_change`.
"""
from __future__ import annotations

from collections.abc import Callable, Mapping

import numpy as np

from vd_solvers.errors import SolverError
from vd_solvers.event_params import Param
from vd_solvers.results import Channel, Metric
from vd_solvers.road import from_config
from vd_solvers.standards import iso2631

from .drivers import OpenLoopSteering, SpeedController
from .model import VehicleModel
from .simulation import Trace, simulate

#: settling threshold of the bump event, fraction of the peak vertical acceleration
SETTLE_FRACTION = 0.05
RIDE_PARAMS: Mapping[str, Param] = {
    'speed': Param('velocity', 80.0 / 3.6, 'constant speed', minimum=2.0, maximum=60.0),
    'distance': Param('length', 150.0, 'distance driven (at most the road length)',
                      minimum=20.0, maximum=5000.0),
}
BUMP_PARAMS: Mapping[str, Param] = {
    'speed': Param('velocity', 30.0 / 3.6, 'constant speed', minimum=1.0, maximum=40.0),
    'after': Param('time', 3.0, 'time simulated after the rear wheels leave the obstacle',
                   minimum=0.5, maximum=20.0),
}
def road_note(model: VehicleModel) -> str:
    """Return the note naming the road a full-vehicle event drove on."""
    return f'road: {model.road.description}'


def speed_controller(model: VehicleModel, speed: float) -> SpeedController:
    """Return a speed controller holding ``speed`` (m/s) for the vehicle."""
    _, r_e = model.tire_radii(model.static_loads())
    return SpeedController(lambda t: speed, model.total_mass, float(np.mean(r_e)))


def _accelerations(trace: Trace) -> tuple[np.ndarray, np.ndarray, np.ndarray, float]:
    """(time, vertical acceleration at the CoG, pitch acceleration, rate) of a trace."""
    ch = trace.channels()
    t = ch['time']
    rate = 1.0 / float(t[1] - t[0])
    vertical = np.gradient(ch['cog_velocity_z'], t)
    pitch = np.gradient(np.gradient(np.unwrap(ch['pitch']), t), t)
    return t, vertical, pitch, rate


def _acceleration_channels(vertical: np.ndarray, pitch: np.ndarray) -> dict[str, Channel]:
    return {'vertical_acceleration': Channel('m/s^2', vertical),
            'pitch_acceleration': Channel('rad/s^2', pitch)}


def _straight(model: VehicleModel, speed: float, duration: float, event: str, progress,
              channels_of) -> tuple[Trace, dict[str, Channel]]:
    trace = simulate(model, OpenLoopSteering(lambda t: 0.0), speed_controller(model, speed),
                     duration, event=event, initial_speed=speed, record_every=1, progress=progress)
    return trace, channels_of(model, trace)


def run_ride(model: VehicleModel, v: Mapping[str, float], progress: Callable | None,
             channels_of) -> tuple[dict[str, Metric], dict[str, Channel], list[str]]:
    """Run the ride event (module doc)."""
    speed, distance = v['speed'], v['distance']
    surface = from_config.road_surface(model.config)
    length = getattr(surface, 'length', None)
    if length is not None and distance > float(length):
        raise SolverError(f'the ride distance ({distance:g} m) is longer than the road '
                          f'({float(length):g} m)')
    trace, channels = _straight(model, speed, distance / speed, 'ride', progress, channels_of)
    t, vertical, pitch, rate = _accelerations(trace)
    channels = {**channels, **_acceleration_channels(vertical, pitch)}
    x_front = trace.channels()['x'] + model.wheel_centres[0, 0]
    window = x_front >= from_config.FADE_IN + 5.0
    if np.count_nonzero(window) < 2.0 * rate:
        raise SolverError(f'the ride distance ({distance:g} m) leaves less than 2 s to '
                          'evaluate after the blend-in')
    wk = iso2631.weighted(vertical[window], rate, 'Wk')
    we = iso2631.weighted(pitch[window], rate, 'We')
    loads = trace.channels()['wheel_load'][window]
    static = model.static_loads()
    variation = loads.std(axis=0) / static
    metrics = {
        'speed': Metric(speed, 'm/s'),
        'vertical_acceleration_rms_wk': Metric(iso2631.rms(wk), 'm/s^2', 'ISO 2631-1 Wk, 6.1'),
        'vertical_vdv_wk': Metric(iso2631.vdv(wk, rate), 'm/s^1.75', 'ISO 2631-1 Wk, 6.3.2'),
        'vertical_crest_factor': Metric(iso2631.crest_factor(wk), '-', 'ISO 2631-1 6.2'),
        'pitch_acceleration_rms_we': Metric(iso2631.rms(we), 'rad/s^2', 'ISO 2631-1 We, 6.1'),
        'pitch_vdv_we': Metric(iso2631.vdv(we, rate), 'rad/s^1.75', 'ISO 2631-1 We, 6.3.2'),
        'vertical_acceleration_rms': Metric(iso2631.rms(vertical[window]), 'm/s^2'),
        'wheel_load_variation_front': Metric(float(variation[:2].mean()), '-'),
        'wheel_load_variation_rear': Metric(float(variation[2:].mean()), '-'),
    }
    notes = [road_note(model),
             f'evaluated from the front axle at {from_config.FADE_IN + 5.0:g} m to '
             f'{distance:g} m: {np.count_nonzero(window) / rate:.1f} s at {rate:g} Hz; '
             'accelerations at the CoG']
    return metrics, channels, notes


def run_bump(model: VehicleModel, v: Mapping[str, float], progress: Callable | None,
             channels_of) -> tuple[dict[str, Metric], dict[str, Channel], list[str]]:
    """Run the bump event (module doc)."""
    config = model.config
    if 'road' not in config.groups or config.group('road').text('surface') != 'obstacle':
        raise SolverError("the bump event needs a road with an obstacle (a 'road' group of "
                          "surface 'obstacle')")
    g = config.group('road')
    start = g.scalar('start')
    end = start + g.scalar('obstacle_length')
    speed = v['speed']
    x_front, x_rear = model.wheel_centres[0, 0], model.wheel_centres[2, 0]
    duration = (end - x_rear) / speed + v['after']
    trace, channels = _straight(model, speed, duration, 'bump', progress, channels_of)
    t, vertical, pitch, rate = _accelerations(trace)
    channels = {**channels, **_acceleration_channels(vertical, pitch)}
    x = trace.channels()['x']
    reach = np.nonzero(x + x_front >= start - 0.5)[0]
    if reach.size == 0:
        raise SolverError('the run ends before the obstacle')
    t0 = float(t[reach[0]])
    after = t >= t0
    peak = float(np.max(np.abs(vertical[after])))
    above = np.nonzero(after & (np.abs(vertical) > SETTLE_FRACTION * peak))[0]
    loads = trace.channels()['wheel_load'][after] / model.static_loads()
    metrics = {
        'speed': Metric(speed, 'm/s'),
        'peak_vertical_acceleration': Metric(peak, 'm/s^2'),
        'peak_pitch_acceleration': Metric(float(np.max(np.abs(pitch[after]))), 'rad/s^2'),
        'peak_wheel_load_ratio': Metric(float(loads.max()), '-'),
        'min_wheel_load_ratio': Metric(float(loads.min()), '-'),
        'settling_time': Metric(float(t[above[-1]] - t0) if above.size else 0.0, 's'),
    }
    if above.size and above[-1] >= t.size - 2:
        metrics['settling_time'] = Metric(float('nan'), 's')
    notes = [road_note(model), f'front wheels at the obstacle at t = {t0:.2f} s; settled: '
             f'|a_z| below {100 * SETTLE_FRACTION:g} % of its peak']
    return metrics, channels, notes


PARAMS: Mapping[str, Mapping[str, Param]] = {'ride': RIDE_PARAMS, 'bump': BUMP_PARAMS}
RUNNERS = {'ride': run_ride, 'bump': run_bump}

__all__ = ['PARAMS', 'RUNNERS', 'run_ride', 'run_bump', 'road_note', 'speed_controller',
           'RIDE_PARAMS', 'BUMP_PARAMS']
