# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Replay of measured inputs through the full vehicle: the open-loop validation run.

The steering-wheel angle of a vehicle log drives :class:`.drivers.ReplaySteering`
(linear interpolation between the logged samples, held beyond the ends); the logged
speed is the reference of the PI :class:`.drivers.SpeedController` (linear
interpolation too), so the model sees the driver's inputs and produces its own yaw
rate, lateral acceleration and sideslip for comparison with the log. The run starts
straight ahead at the log's first speed and yaw rate: start the log on a straight.

The logged speed is smoothed before it becomes the reference: the controller feeds the
reference's slope forward, and the slope of a logged speed between samples is mostly
its noise and resolution (0.05 km/h at 20 Hz is 0.4 m/s^2 of slope). The smoothing is a
cubic smoothing spline whose smoothness generalised cross-validation chooses
(``scipy.interpolate.make_smoothing_spline``), which needs no uniform time step.
"""
from __future__ import annotations

from collections.abc import Callable

import numpy as np
from scipy.interpolate import make_smoothing_spline

from vd_data_server.model import Configuration
from vd_solvers.errors import SolverError
from vd_solvers.results import EventOutcome, Metric

from .drivers import ReplaySteering, SpeedController
from .events import _channels
from .model import STEP, VehicleModel
from .simulation import simulate

#: recorded every this many integration steps (5 ms): 100 Hz
RECORD_EVERY = 2


def check_inputs(time: np.ndarray, swa: np.ndarray, speed: np.ndarray) -> None:
    t = np.asarray(time, dtype=float)
    if t.ndim != 1 or t.size < 2 or np.any(np.diff(t) <= 0.0):
        raise SolverError('replay: the log time must increase, with at least two samples')
    for name, x in (('steering_wheel_angle', swa), ('speed', speed)):
        x = np.asarray(x, dtype=float)
        if x.shape != t.shape or not np.all(np.isfinite(x)):
            raise SolverError(f'replay: {name} must be finite, one value per sample')


def smoothed_speed(t: np.ndarray, speed: np.ndarray) -> Callable[[float], float]:
    """Return the logged speed as a smooth function of time (module doc)."""
    if t.size < 5:
        return lambda s: float(np.interp(s, t, speed))
    spline = make_smoothing_spline(t, speed)
    return lambda s: float(spline(s))


def replay_vehicle(config: Configuration, time: np.ndarray, swa: np.ndarray,
                   speed: np.ndarray, *, event: str = 'vehicle_test', fidelity: str = '',
                   initial_yaw_rate: float = 0.0, model: VehicleModel | None = None,
                   progress: Callable[[float, str], None] | None = None) -> EventOutcome:
    """Drive the full vehicle of ``config`` by the logged steering and speed (module doc)."""
    check_inputs(time, swa, speed)
    t = np.asarray(time, dtype=float) - float(time[0])
    model = model if model is not None else VehicleModel(config, fidelity)
    _, r_e = model.tire_radii(model.static_loads())
    steering = ReplaySteering(t, np.asarray(swa, dtype=float))
    v = np.asarray(speed, dtype=float)
    reference = smoothed_speed(t, v)
    driver = SpeedController(lambda s: float(reference(min(max(s, t[0]), t[-1]))),
                             model.total_mass, float(np.mean(r_e)))
    trace = simulate(model, steering, driver, float(t[-1]), event=event,
                     initial_speed=float(v[0]), initial_yaw_rate=float(initial_yaw_rate),
                     record_every=RECORD_EVERY, progress=progress)
    channels = _channels(model, trace)
    notes = ('open-loop replay of a log: steering-wheel angle (ReplaySteering, linear '
             'between samples) and speed (PI speed controller on the logged speed, smoothed '
             'by a cubic smoothing spline chosen by generalised cross-validation)',
             f'integrator step {STEP * 1e3:g} ms, recorded at '
             f'{1.0 / (STEP * RECORD_EVERY):g} Hz; start straight ahead at '
             f'{v[0]:.2f} m/s',
             *(f'{k}: {p}' for k, p in sorted(model.maps.provenance.items())))
    metrics = {'steering_ratio': Metric(model.maps.steering_ratio, '-',
                                        model.maps.provenance['steering']),
               'duration': Metric(float(t[-1]), 's')}
    return EventOutcome(event=event, configuration=config.name, model='vehicle',
                        fidelity=model.fidelity, axle='', data_hash=config.data_hash,
                        metrics=metrics, channels=channels, notes=notes)


__all__ = ['replay_vehicle', 'check_inputs']
