# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Events of the analytical rung.

Steady-state circular (ISO 4138 constant radius), handling diagram, and the linear
step steer (ISO 7401) of the bicycle model.

``run_event(config, event, model, params)`` returns an :class:`EventOutcome`
with SI channels and metrics (display units such as deg/g and km/h are the
CLI's and the report's business: ``vd_events.reports.display``).
The roll properties and the compliance of both axles come from the K&C
results of the same configuration and data hash, computed on demand and
cached (``kc_link.py``); the understeer budget is part of every result.
"""
from __future__ import annotations

from collections.abc import Mapping, Sequence
import math

import numpy as np

from vd_data_server.model import Configuration
from vd_solvers.analytical import bicycle, cornering, two_track
from vd_solvers.analytical.budget import TERMS, understeer_budget
from vd_solvers.analytical.cornering import CorneringVehicle
from vd_solvers.analytical.from_config import cornering_vehicle, vehicle_params
from vd_solvers.analytical.kc_link import try_kc_inputs
from vd_solvers.analytical.params import VehicleParams
from vd_solvers.constants import STANDARD_GRAVITY as G
from vd_solvers.errors import BeyondLimitError, SolverError
from vd_solvers.event_params import Param, parse_params
from vd_solvers.results import Channel, EventOutcome, Metric
from vd_solvers.vehicle_data import static_wheel_loads

#: the budget's range terms from the two-track model, or None
Ranges = Mapping[str, tuple[float, str]] | None
MODELS = ('bicycle', 'two_track')
#: lateral acceleration of the two-track's yaw-rate gain at the gain speed, m/s^2
GAIN_LATERAL_ACCELERATION = 1.0

_SWEEP = {
    'radius': Param('length', 100.0, 'circle radius (ISO 4138 constant-radius method)',
                    minimum=1.0),
    'steps': Param('integer', 41, 'number of lateral-acceleration steps', minimum=3,
                   maximum=2001),
    'max_lateral_acceleration': Param('acceleration', 6.0, "end of the bicycle model's sweep "
                                      "(the two-track model goes to its limit)", minimum=0.1),
    'speed': Param('velocity', 100.0 / 3.6, 'speed of the reported gains', minimum=0.1),
}
EVENT_PARAMS: Mapping[str, Mapping[str, Param]] = {
    'steady_state_circular': _SWEEP,
    'handling_diagram': _SWEEP,
    'step_steer': {
        'speed': Param('velocity', 100.0 / 3.6, 'constant speed', minimum=0.1),
        'lateral_acceleration': Param('acceleration', 4.0, 'steady-state lateral acceleration '
                                      'the steer step aims at (ISO 7401: 4 m/s^2)', minimum=0.01),
        'duration': Param('time', 3.0, 'simulated time', minimum=0.1, maximum=60.0),
        'steps': Param('integer', 301, 'output samples', minimum=10, maximum=100001),
    },
}
EVENT_MODELS: Mapping[str, tuple[str, ...]] = {
    'steady_state_circular': MODELS,
    'handling_diagram': MODELS,
    'step_steer': ('bicycle',),
}


def run_event(config: Configuration, event: str, model: str,
              params: Sequence[str] = ()) -> EventOutcome:
    """Run ``event`` with ``model`` on ``config``. Raises SolverError naming both."""
    label = f"configuration '{config.name}', event '{event}', model '{model}'"
    if event not in EVENT_PARAMS:
        raise SolverError(f"{label}: the analytical solver has no event '{event}' "
                          f"(events: {', '.join(EVENT_PARAMS)})")
    if model not in EVENT_MODELS[event]:
        raise SolverError(f"{label}: event '{event}' runs on models "
                          f"{', '.join(EVENT_MODELS[event])}")
    values = parse_params(event, EVENT_PARAMS[event], params)
    try:
        kc = try_kc_inputs(config, static_wheel_loads(config))
    except SolverError as err:
        raise SolverError(f'{label}: K&C results: {err}') from err
    wheels: CorneringVehicle | None = None
    if isinstance(kc, str):
        p = vehicle_params(config)
        kc_notes = [f'bare tire and design targets: {kc}']
    else:
        p = vehicle_params(config, kc.suspension, kc.compliance)
        wheels = cornering_vehicle(config, p)
        kc_notes = [f'roll stiffness, roll centres and compliance from the K&C model '
                    f'(data hash {config.data_hash})']
    try:
        ranges = (cornering.range_terms(wheels, values.get('radius', _SWEEP['radius'].default))
                  if wheels is not None else None)
        if event == 'step_steer':
            metrics, channels, notes = _step_steer(p, values, ranges)
        elif model == 'bicycle':
            metrics, channels, notes = _bicycle_sweep(p, values, ranges)
        else:
            metrics, channels, notes = _two_track_sweep(p, values, ranges, wheels)
    except SolverError as err:
        raise SolverError(f'{label}: {err}') from err
    notes = [*notes, *kc_notes, *(f'{k}: {v}' for k, v in sorted(p.sources.items()))]
    return EventOutcome(event=event, configuration=config.name, model=model, fidelity='rigid',
                        axle='', data_hash=config.data_hash, metrics=metrics, channels=channels,
                        notes=tuple(notes))


def budget_metrics(p: VehicleParams, ranges: Ranges = None) -> dict[str, Metric]:
    """
    Return the understeer budget metrics.

    ``understeer_budget_<term>`` in rad/(m/s^2), each with its source, and the total;
    ``ranges``: the range terms of :func:`.cornering.range_terms` (absent: zero, said so).
    """
    budget = understeer_budget(p, ranges)
    metrics = {}
    for term in budget.terms:
        metrics[f'understeer_budget_{term.name}'] = Metric(term.value, 'rad/(m/s^2)', term.source)
    metrics['understeer_budget_total'] = Metric(budget.total, 'rad/(m/s^2)',
                                                'sum of the terms ' + ', '.join(TERMS))
    return metrics


def _common_bicycle_metrics(p: VehicleParams, speed: float,
                            ranges: Ranges = None) -> dict[str, Metric]:
    k = bicycle.understeer_gradient(p)
    c_f, c_r = bicycle.axle_cornering_stiffness(p)
    e_f, e_r = bicycle.effective_cornering_stiffness(p)
    k_source = ('effective axle cornering stiffness: tires with K&C compliance'
                if not (p.compliance_front.is_rigid and p.compliance_rear.is_rigid)
                else 'bare tire: no K&C results')
    metrics = {
        'understeer_gradient': Metric(k, 'rad/(m/s^2)', k_source),
        'cornering_stiffness_front_axle': Metric(c_f, 'N/rad', p.sources.get('tire_front', '')),
        'cornering_stiffness_rear_axle': Metric(c_r, 'N/rad', p.sources.get('tire_rear', '')),
        'effective_cornering_stiffness_front_axle': Metric(e_f, 'N/rad', k_source),
        'effective_cornering_stiffness_rear_axle': Metric(e_r, 'N/rad', k_source),
        **budget_metrics(p, ranges),
        'mass': Metric(p.mass, 'kg', p.sources.get('mass', '')),
        'cog_to_front_axle': Metric(p.cog_to_front_axle, 'm'),
        'cog_height': Metric(p.cog_height, 'm'),
    }
    if k > 0.0:
        v = bicycle.characteristic_speed(p)
        metrics['characteristic_speed'] = Metric(v, 'm/s')
    elif k < 0.0:
        v = bicycle.critical_speed(p)
        metrics['critical_speed'] = Metric(v, 'm/s')
    try:
        response = bicycle.bicycle_response(p, speed)
    except BeyondLimitError:
        return metrics
    metrics.update({
        'gain_speed': Metric(speed, 'm/s'),
        'yaw_rate_gain': Metric(response.yaw_rate_gain, '1/s'),
        'lateral_acceleration_gain': Metric(response.lateral_acceleration_gain, 'm/s^2/rad'),
        'sideslip_gain': Metric(response.sideslip_gain, 'rad/rad'),
        'natural_frequency': Metric(response.natural_frequency / (2.0 * math.pi), 'Hz'),
        'damping_ratio': Metric(response.damping_ratio, '-'),
    })
    return metrics


def _bicycle_sweep(p: VehicleParams, v: Mapping[str, float], ranges: Ranges = None):
    radius = v['radius']
    a_y = np.linspace(0.0, v['max_lateral_acceleration'], int(v['steps']))
    speed = np.sqrt(a_y * radius)
    points = [bicycle.steady_state(p, radius, float(s)) for s in speed]
    channels = {
        'lateral_acceleration': Channel('m/s^2', a_y),
        'speed': Channel('m/s', speed),
        'steer_angle': Channel('rad', np.array([q.steer_angle for q in points])),
        'yaw_rate': Channel('rad/s', np.array([q.yaw_rate for q in points])),
        'sideslip': Channel('rad', np.array([q.sideslip for q in points])),
        'slip_angle_front': Channel('rad', np.array([q.slip_angle_front for q in points])),
        'slip_angle_rear': Channel('rad', np.array([q.slip_angle_rear for q in points])),
    }
    channels['slip_angle_difference'] = Channel(
        'rad', channels['slip_angle_front'].values - channels['slip_angle_rear'].values)
    metrics = _common_bicycle_metrics(p, v['speed'], ranges)
    metrics['radius'] = Metric(radius, 'm')
    notes = ["linear single-track model (thesis eqs. 1-2): no limit; swept to "
             f"{v['max_lateral_acceleration']:.3g} m/s^2"]
    return metrics, channels, notes


def _two_track_sweep(p: VehicleParams, v: Mapping[str, float], ranges: Ranges = None,
                     wheels: CorneringVehicle | None = None):
    radius = v['radius']
    diagram = two_track.handling_diagram(p, radius, int(v['steps']))
    geometry = two_track.roll_geometry(p)
    k_lin = two_track.understeer_gradient_linear(p)
    limit = diagram.limit
    channels = {
        'lateral_acceleration': Channel('m/s^2', diagram.lateral_acceleration),
        'speed': Channel('m/s', diagram.speed),
        'steer_angle': Channel('rad', diagram.steer_angle),
        'slip_angle_front': Channel('rad', diagram.slip_angle_front),
        'slip_angle_rear': Channel('rad', diagram.slip_angle_rear),
        'slip_angle_difference': Channel('rad', diagram.slip_angle_difference),
        'roll_angle': Channel('rad', diagram.roll_angle),
        # kinematic steady-state sideslip at the COG, as in the bicycle model
        'sideslip': Channel('rad', p.cog_to_rear_axle / radius - diagram.slip_angle_rear),
        'lateral_force_front_axle': Channel('N', diagram.axle_force_front),
        'lateral_force_rear_axle': Channel('N', diagram.axle_force_rear),
    }
    for i, wheel in enumerate(two_track.WHEELS):
        channels[f'wheel_load_{wheel}'] = Channel('N', diagram.wheel_loads[:, i])
    metrics = {
        'max_lateral_acceleration': Metric(limit.lateral_acceleration, 'm/s^2'),
        'limit_speed': Metric(limit.speed, 'm/s'),
        'limiting_axle_is_rear': Metric(1.0 if limit.limiting_axle == 'rear' else 0.0, '-'),
        'understeer_gradient_linear': Metric(k_lin, 'rad/(m/s^2)'),
        'roll_gradient': Metric(geometry.roll_gradient, 'rad/(m/s^2)'),
        'roll_stiffness_front': Metric(p.roll_stiffness_front, 'N*m/rad',
                                       p.sources.get('roll_stiffness_front', '')),
        'roll_stiffness_rear': Metric(p.roll_stiffness_rear, 'N*m/rad',
                                      p.sources.get('roll_stiffness_rear', '')),
        'roll_centre_height_front': Metric(p.roll_centre_height_front, 'm',
                                           p.sources.get('roll_centre_height_front', '')),
        'roll_centre_height_rear': Metric(p.roll_centre_height_rear, 'm',
                                          p.sources.get('roll_centre_height_rear', '')),
        'radius': Metric(radius, 'm'),
        **budget_metrics(p, ranges),
    }
    if wheels is not None:
        grads = cornering.gradients(wheels, radius)
        span = f'{cornering.LINEAR_RANGE[0]:g}..{cornering.LINEAR_RANGE[1]:g} m/s^2'
        source = f'two-track wheel by wheel (cornering.py), {span} on {radius:g} m'
        gain_radius = v['speed']**2 / GAIN_LATERAL_ACCELERATION
        point = cornering.steady_state(wheels, GAIN_LATERAL_ACCELERATION, gain_radius)
        metrics.update({
            'understeer_gradient': Metric(grads.understeer, 'rad/(m/s^2)', source),
            'sideslip_gradient': Metric(grads.sideslip, 'rad/(m/s^2)', source),
            'yaw_rate_gain': Metric((v['speed'] / gain_radius)
                                    / (point.steering_wheel_angle / wheels.steering.ratio),
                                    '1/s', f'{source}; at {GAIN_LATERAL_ACCELERATION:g} m/s^2 '
                                    'per rad of steering-wheel angle over the ratio'),
        })
    notes = [f'limit: {limit.behaviour} at {limit.lateral_acceleration:.3f} m/s^2 '
             f'({limit.lateral_acceleration / G:.3f} g), {limit.limiting_axle} axle, '
             f'{limit.cause}; the model has no steady state beyond it']
    lift = two_track.wheel_lift_onset(p)
    if lift is not None and lift[1] < abs(limit.lateral_acceleration):
        metrics['wheel_lift_lateral_acceleration'] = Metric(lift[1], 'm/s^2')
        notes.append(f'inner {lift[0]} wheel lifts at {lift[1]:.3f} m/s^2 ({lift[1] / G:.3f} g); '
                     'from there the outer wheel carries the axle load up to the limit')
    return metrics, channels, notes


def _step_steer(p: VehicleParams, v: Mapping[str, float], ranges: Ranges = None):
    speed = v['speed']
    response = bicycle.bicycle_response(p, speed)
    steer = v['lateral_acceleration'] / response.lateral_acceleration_gain
    step = bicycle.steer_step_response(p, speed, steer, v['duration'], int(v['steps']))
    r_ss = response.yaw_rate_gain * steer
    peak = float(np.max(step.yaw_rate))
    reached = np.nonzero(step.yaw_rate >= 0.9 * r_ss)[0]
    channels = {
        'time': Channel('s', step.time),
        'steer_angle': Channel('rad', np.full_like(step.time, steer)),
        'yaw_rate': Channel('rad/s', step.yaw_rate),
        'lateral_acceleration': Channel('m/s^2', step.lateral_acceleration),
        'lateral_velocity': Channel('m/s', step.lateral_velocity),
    }
    metrics = _common_bicycle_metrics(p, speed, ranges)
    metrics.update({
        'steer_step': Metric(steer, 'rad'),
        'steady_state_yaw_rate': Metric(r_ss, 'rad/s'),
        'peak_yaw_rate': Metric(peak, 'rad/s'),
        'yaw_rate_overshoot': Metric(100.0 * (peak / r_ss - 1.0), '%'),
        'yaw_rate_response_time_90': Metric(float(step.time[reached[0]]) if reached.size
                                            else float('nan'), 's'),
    })
    notes = ['linear single-track model; ideal steer step at t = 0 (ISO 7401 uses a ramp '
             'of 0.1-0.2 s, the full-vehicle model will)']
    return metrics, channels, notes
