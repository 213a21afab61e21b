# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The ISO 3888-2:2011 lane change: its driving line, a run, the highest passing speed.

**Procedure** (ISO 3888-2:2011 with its annex's test method): the vehicle approaches on
the centre line of section 1; the driver releases the accelerator pedal at the start of
section 1 (the entry gate) and drives through the track without touching a cone. The
entry speed is the speed at the entry gate; the result of a series of runs is the highest
entry speed that passes. Here the course of :mod:`vd_solvers.standards.iso3888` for the
vehicle's width starts APPROACH m ahead of the start; the speed controller holds the
entry speed up to the gate and no torque at all is applied from the moment the front of
the vehicle reaches it (:class:`.drivers.CoastingSpeed`), so the vehicle coasts through
the track on its rolling resistance, tire drag and (with a driveline group) engine drag.

**Driving line** (:func:`driving_line`): the line of the vehicle's reference point with the
least peak curvature that keeps its plan rectangle inside the gated sections' lanes with
a clearance ``margin`` on every side: a linear programme over the line's lateral position
y_i on a grid of DX m (minimise t subject to |y''| <= t, the curvature's rate
|y'''| <= t / RAMP so that the curvature takes RAMP m to build up, and the rectangle's
corners and edge points inside the lanes, its heading taken from the previous iterate
for the corners' positions: LINE_ITERATIONS sequential solutions, the first at zero
heading). The line starts straight on y = 0 (the approach's centre line) LEAD m before
the course and ends straight after it; what it does between is the optimiser's choice:
for the sample sedan it moves to the right-hand side of section 1, crosses to the near
side of section 3 and back to the near side of section 5. The line is that of the rear
axle's centre (:func:`rear_axle_line`): without tire slip the rear axle moves along the
body, so the body's heading is the line's plus the rear axle's slip angle m_r a_y / C_r
at the run's speed.

**Driver**: :class:`.drivers.OptimalPreviewDriver`, the discrete linear-quadratic preview
driver of :mod:`.preview_design` (Sharp, Casanova & Symonds, VSD 33(5), 2000): its gains
come once per run from the configuration's own single track at the entry speed (the
bicycle model with the K&C compliance and roll steer,
:func:`.analytical.from_config.vehicle_params` with :func:`.analytical.kc_link.kc_inputs`,
rigid K&C) with the steering lag ``lag``; it tracks the rear axle on the line, reads the
line's curvature ``preview_time`` ahead, samples every DRIVER_SAMPLE s and weighs a
lateral error of ERROR_SCALE m against STEER_SCALE rad of road-wheel angle. The steering
wheel turns the road wheels through the configuration's steering ratio, limited at the
lock.

lane_change_limit: the highest passing entry speed by bisection on pass/fail between
``lowest`` and ``highest`` to LIMIT_RESOLUTION: first both bounds, then the middle of
the bracket until it is narrower than the resolution; the metrics of the run at the
highest passing speed are reported beside it. A speed at which the lanes leave no driving
line (the rear slip angle turns the body too far) fails without a run.

The vehicle's plan rectangle is the wheels' outer envelope: the wider track plus a tire
width, the wheelbase plus two unloaded radii (the data has no body overhangs).
"""
from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
import math

import numpy as np
from scipy import sparse
from scipy.optimize import linprog

from vd_solvers.analytical.bicycle import effective_cornering_stiffness
from vd_solvers.analytical.from_config import vehicle_params
from vd_solvers.analytical.kc_link import kc_inputs
from vd_solvers.analytical.params import VehicleParams
from vd_solvers.errors import SolverError
from vd_solvers.event_params import Param
from vd_solvers.results import Channel, Metric
from vd_solvers.standards import iso3888
from vd_solvers.vehicle_data import static_wheel_loads

from .drivers import CoastingSpeed, OptimalPreviewDriver
from .model import STEP, VehicleModel
from .preview_design import preview_gains
from .ride_events import road_note, speed_controller
from .simulation import simulate

#: m from the start of the run to the start of the ISO 3888-2 course
APPROACH = 40.0
#: m driven beyond the end of the course
RUN_OUT = 15.0
#: grid of the driving line, m
DX = 0.25
#: m over which the driving line's curvature may build up from zero to its peak
RAMP = 3.0
#: m of straight line before the course in the line's optimisation (the rest of the
#: approach is straight on y = 0)
LEAD = 20.0
#: sequential linear programmes of the driving line (the rectangle's heading updated)
LINE_ITERATIONS = 3
#: sample time of the lane-change driver, s
DRIVER_SAMPLE = 0.02
#: the driver's cost: a lateral error of ERROR_SCALE m costs as much as STEER_SCALE rad of
#: road-wheel angle (the linear closed loop's slowest time constant then 0.2-0.3 s on the
#: sample cars)
ERROR_SCALE = 0.02
STEER_SCALE = 0.1
#: resolution of the highest passing entry speed, m/s (1 km/h)
LIMIT_RESOLUTION = 1.0 / 3.6

_DRIVER = {
    'preview_time': Param('time', 1.5, "how far ahead the driver reads the line's curvature",
                          minimum=0.2, maximum=5.0),
    'lag': Param('time', 0.15, "the driver's and the steering system's first-order lag",
                 minimum=0.02, maximum=0.5),
    'margin': Param('length', 0.1, "the driving line's clearance to every lane limit",
                    minimum=0.0, maximum=0.5),
}
LANE_CHANGE_PARAMS: Mapping[str, Param] = {
    'speed': Param('velocity', 60.0 / 3.6, 'entry speed (coasting from the entry gate)',
                   minimum=5.0, maximum=50.0),
    **_DRIVER,
}
LIMIT_PARAMS: Mapping[str, Param] = {
    'lowest': Param('velocity', 30.0 / 3.6, 'lowest entry speed tried', minimum=5.0,
                    maximum=50.0),
    'highest': Param('velocity', 100.0 / 3.6, 'highest entry speed tried', minimum=5.0,
                     maximum=50.0),
    **_DRIVER,
}


def vehicle_rectangle(model: VehicleModel) -> tuple[float, float, float]:
    """(length, width, distance of the body origin behind the front) of the plan rectangle."""
    centres = model.wheel_centres
    tire_width = max(float(t.props.number('DIMENSION', 'WIDTH', 0.25)) for t in model.tires)
    width = 2.0 * float(np.max(np.abs(centres[:, 1]))) + tire_width
    r_front, r_rear = float(model.r0[0]), float(model.r0[2])
    length = float(centres[0, 0] - centres[2, 0]) + r_front + r_rear
    return length, width, r_front - float(centres[0, 0])


def _difference(n: int, stencil: tuple[float, ...], scale: float) -> sparse.csr_matrix:
    """Rows of a finite-difference stencil over n unknowns (interior points only)."""
    k = len(stencil)
    return sparse.diags([np.full(n - k + 1, c / scale) for c in stencil], list(range(k)),
                        shape=(n - k + 1, n), format='csr')


def driving_line(track: iso3888.Course, length: float, width: float, front: float,
                 margin: float, slip: float = 0.0, speed: float = 0.0
                 ) -> tuple[np.ndarray, np.ndarray]:
    """
    Return the driving line (x, y) in the course's frame, m (module doc).

    ``length``, ``width``, ``front``: the plan rectangle (:func:`vehicle_rectangle`), its
    reference point the one that follows the line. The rectangle's heading is the line's
    plus ``slip`` (rad per m/s^2) times the lateral acceleration speed^2 kappa of the line
    at ``speed`` m/s: the rear axle's slip angle for a line of the rear axle. SolverError
    when the lanes leave no line with that clearance.
    """
    x = np.arange(-LEAD, track.length + length + LEAD + 0.5 * DX, DX)
    n = x.size
    second = _difference(n, (1.0, -2.0, 1.0), DX**2)
    third = _difference(n, (-1.0, 3.0, -3.0, 1.0), DX**3)
    slope = sparse.diags([np.full(n - 2, -0.5 / DX), np.full(n - 2, 0.5 / DX)], [0, 2],
                         shape=(n - 2, n), format='csr')
    lanes: dict[int, dict[str, iso3888.Boundary]] = {b.section: {} for b in track.boundaries}
    for b in track.boundaries:
        lanes[b.section][b.side] = b
    ahead = np.unique(np.concatenate([np.arange(front - length, front, DX), [front]]))
    peak = np.ones((n - 2, 1))
    heading = np.zeros(n - 2)  # of the rectangle
    tangent = np.zeros(n - 2)  # the line's slope
    y = np.zeros(n)
    for _ in range(LINE_ITERATIONS):
        rows, bounds = [], []
        c, s = np.cos(heading), np.sin(heading)
        # sin(heading) linearised in the slope about the previous iterate
        rate = c / (1.0 + tangent * tangent)
        constant = s - rate * tangent
        for side, sign in (('left', 1.0), ('right', -1.0)):
            for a in ahead:
                # the point a ahead on this side of the rectangle, at the interior points
                xc = x[1:-1] + a * c - sign * 0.5 * width * s
                offset = sign * 0.5 * width * c
                for lane in lanes.values():
                    limit = lane[side]
                    inside = np.nonzero((xc >= limit.x0) & (xc <= limit.x1))[0]
                    if inside.size == 0:
                        continue
                    # y_i + a sin(psi_i) + offset, psi_i linear in the slope y'_i
                    pick = sparse.csr_matrix((np.ones(inside.size), (np.arange(inside.size),
                                              inside + 1)), shape=(inside.size, n))
                    lateral = pick + sparse.diags(a * rate[inside]) @ slope[inside]
                    fixed = offset[inside] + a * constant[inside]
                    if side == 'left':
                        rows.append(lateral)
                        bounds.append(limit.y - margin - fixed)
                    else:
                        rows.append(-lateral)
                        bounds.append(-(limit.y + margin - fixed))
        t_col = sparse.csr_matrix(np.zeros((sum(r.shape[0] for r in rows), 1)))
        a_ub = sparse.vstack([
            sparse.hstack([second, -sparse.csr_matrix(peak[:n - 2])]),
            sparse.hstack([-second, -sparse.csr_matrix(peak[:n - 2])]),
            sparse.hstack([third, -sparse.csr_matrix(np.full((n - 3, 1), 1.0 / RAMP))]),
            sparse.hstack([-third, -sparse.csr_matrix(np.full((n - 3, 1), 1.0 / RAMP))]),
            sparse.hstack([sparse.vstack(rows), t_col])], format='csr')
        b_ub = np.concatenate([np.zeros(2 * (n - 2) + 2 * (n - 3))] + bounds)
        # straight on y = 0 at the start, straight (anywhere) at the end
        a_eq = np.zeros((5, n + 1))
        a_eq[0, 0] = a_eq[1, 1] = a_eq[2, 2] = 1.0
        a_eq[3, [n - 1, n - 2]] = (1.0, -1.0)
        a_eq[4, [n - 2, n - 3]] = (1.0, -1.0)
        cost = np.zeros(n + 1)
        cost[n] = 1.0
        res = linprog(cost, A_ub=a_ub, b_ub=b_ub, A_eq=a_eq, b_eq=np.zeros(5),
                      bounds=[(None, None)] * n + [(0.0, None)], method='highs')
        if res.status != 0:
            raise SolverError(f'the ISO 3888-2 lanes for a vehicle {width:.2f} m wide and '
                              f'{length:.2f} m long leave no driving line with '
                              f'{margin:g} m clearance ({res.message})')
        y = np.asarray(res.x[:n])
        tangent = slope @ y
        heading = np.arctan(tangent) + slip * speed**2 * (second @ y) / (
            1.0 + tangent * tangent) ** 1.5
    return x, y


def rear_axle_line(model: VehicleModel, track: iso3888.Course, margin: float,
                   speed: float) -> tuple[np.ndarray, np.ndarray]:
    """
    Return the driving line (:func:`driving_line`) of the rear axle's centre at ``speed``.

    The body turns against the rear axle's path by the rear slip angle, m_r a_y / C_r
    (the rear axle's mass and effective cornering stiffness, K&C compliance included).
    """
    length, width, front = vehicle_rectangle(model)
    p = _params(model)
    slip = p.axle_load_rear / p.g / effective_cornering_stiffness(p)[1]
    return driving_line(track, length, width, front + _behind(model), margin, slip, speed)


def _params(model: VehicleModel) -> VehicleParams:
    """Return the configuration's bicycle parameters with its K&C compliance (rigid K&C)."""
    config = model.config
    kc = kc_inputs(config, static_wheel_loads(config))
    return vehicle_params(config, kc.suspension, kc.compliance)


def _behind(model: VehicleModel) -> float:
    """Return the distance from the rear axle forward to the body origin, m."""
    return -float(model.wheel_centres[2, 0])


@dataclass(frozen=True)
class Run:
    """One run through the course: its metrics, channels and notes."""

    passed: bool
    metrics: dict[str, Metric]
    channels: dict[str, Channel]
    notes: list[str]


def _driver(model: VehicleModel, line: tuple[np.ndarray, np.ndarray],
            v: Mapping[str, float], speed: float) -> OptimalPreviewDriver:
    """Return the optimal preview driver on ``line`` with gains for ``speed`` m/s."""
    maps = model.maps
    limit = float(min(-maps.steer_swa[0], maps.steer_swa[-1]))
    p = _params(model)
    gains = preview_gains(p, speed, p.cog_to_rear_axle, v['lag'], DRIVER_SAMPLE,
                          v['preview_time'], ERROR_SCALE, STEER_SCALE)
    return OptimalPreviewDriver(line[0] + APPROACH, line[1], gains, maps.steering_ratio,
                                limit, v['lag'], behind=_behind(model),
                                cog_ahead=p.cog_to_rear_axle - _behind(model))


def _at(x: np.ndarray, values: np.ndarray, where: float) -> float:
    """Return a channel's value where the front of the vehicle first reaches ``where``."""
    k = np.nonzero(x >= where)[0]
    return float(values[k[0]]) if k.size else float('nan')


def drive(model: VehicleModel, speed: float, v: Mapping[str, float],
          progress: Callable | None, channels_of,
          line: tuple[np.ndarray, np.ndarray] | None = None) -> Run:
    """One run at entry speed ``speed`` (m/s) along ``line`` (course frame; planned if None)."""
    length, width, front = vehicle_rectangle(model)
    track = iso3888.course(width)
    if line is None:
        line = rear_axle_line(model, track, v['margin'], speed)
    driver = _driver(model, line, v, speed)
    speed_driver = CoastingSpeed(speed_controller(model, speed), APPROACH - front)
    # a coasting vehicle takes longer than at the entry speed: a fifth more time
    duration = 1.2 * (APPROACH + track.length + RUN_OUT) / speed
    trace = simulate(model, driver, speed_driver, duration, event='lane_change',
                     initial_speed=speed, record_every=2, h=STEP, progress=progress)
    ch = trace.channels()
    x_front = ch['x'] - APPROACH + front
    check = iso3888.check_run(track, ch['time'], ch['x'] - APPROACH, ch['y'], ch['yaw'],
                              length=length, width=width, front=front)
    finite = [m for m in check.margins.values() if np.isfinite(m)]
    metrics = {
        'entry_speed': Metric(_at(x_front, ch['speed'], 0.0), 'm/s', 'ISO 3888-2: at the '
                              'entry gate'),
        'exit_speed': Metric(_at(x_front, ch['speed'], track.length), 'm/s',
                             'at the end of section 5'),
        'passed': Metric(1.0 if check.passed else 0.0, '-', 'ISO 3888-2 cone check'),
        'cones_hit': Metric(float(len(check.hits)), '-'),
        'smallest_margin': Metric(min(finite) if finite else float('nan'), 'm'),
        'peak_lateral_acceleration': Metric(float(np.max(np.abs(ch['lateral_acceleration']))),
                                            'm/s^2'),
        'peak_steering_wheel_angle': Metric(float(np.max(np.abs(ch['steering_wheel_angle']))),
                                            'rad'),
        'peak_yaw_rate': Metric(float(np.max(np.abs(ch['yaw_rate']))), 'rad/s'),
        'line_peak_curvature': Metric(max(abs(driver.curvature(float(xi)))
                                          for xi in driver.path_x), '1/m', 'the driving line'),
    }
    hits = '; '.join(f'section {s} {side} at {when:.2f} s' for s, side, when in check.hits)
    verdict = 'passed' if check.passed else 'failed'
    notes = [road_note(model),
             f'ISO 3888-2 course for a vehicle {width:.2f} m wide, {length:.2f} m long '
             f"(the wheels' envelope); entry {speed * 3.6:.1f} km/h, coasting from the entry "
             f'gate; {verdict}' + (f': {hits}' if hits else '')
             + ('' if check.covered else ' (the run did not clear the course)')]
    return Run(check.passed, metrics, channels_of(model, trace), notes)


def run_lane_change(model: VehicleModel, v: Mapping[str, float], progress: Callable | None,
                    channels_of) -> tuple[dict[str, Metric], dict[str, Channel], list[str]]:
    """Run the ISO 3888-2 lane change at one entry speed (module doc)."""
    run = drive(model, v['speed'], v, progress, channels_of)
    return run.metrics, run.channels, run.notes


def run_lane_change_limit(model: VehicleModel, v: Mapping[str, float],
                          progress: Callable | None, channels_of
                          ) -> tuple[dict[str, Metric], dict[str, Channel], list[str]]:
    """Find the highest passing ISO 3888-2 entry speed by bisection (module doc)."""
    low, high = v['lowest'], v['highest']
    if not high - low >= LIMIT_RESOLUTION:
        raise SolverError(f'the highest entry speed ({high * 3.6:g} km/h) must exceed the '
                          f'lowest ({low * 3.6:g} km/h) by at least '
                          f'{LIMIT_RESOLUTION * 3.6:g} km/h')
    tried: list[tuple[float, bool]] = []
    n_runs = 2 + math.ceil(math.log2((high - low) / LIMIT_RESOLUTION))
    track = iso3888.course(vehicle_rectangle(model)[1])

    def attempt(speed: float) -> Run | None:
        """Run at ``speed``; None (a failure) when the lanes leave no line at that speed."""
        if progress is not None:
            progress(len(tried) / n_runs, f'entry speed {speed * 3.6:.1f} km/h')
        try:
            line = rear_axle_line(model, track, v['margin'], speed)
        except SolverError:
            tried.append((speed, False))
            return None
        run = drive(model, speed, v, None, channels_of, line)
        tried.append((speed, run.passed))
        return run

    best = attempt(low)
    if best is None or not best.passed:
        notes = [f'no entry speed passes: the lowest tried ({low * 3.6:.1f} km/h) fails'
                 + ('' if best is not None else ' (the lanes leave no driving line)')]
        if best is None:
            return {'highest_passing_speed': Metric(float('nan'), 'm/s')}, {}, notes
        return ({'highest_passing_speed': Metric(float('nan'), 'm/s'), **best.metrics},
                best.channels, notes + best.notes)
    top = attempt(high)
    if top is not None and top.passed:
        best, low = top, high
    else:
        while high - low > LIMIT_RESOLUTION:
            middle = 0.5 * (low + high)
            run = attempt(middle)
            if run is not None and run.passed:
                best, low = run, middle
            else:
                high = middle
    series = ', '.join(f"{s * 3.6:.1f} {'pass' if p else 'fail'}" for s, p in tried)
    metrics = {'highest_passing_speed': Metric(low, 'm/s', 'ISO 3888-2 entry speed, '
                                               'bisection'),
               'runs': Metric(float(len(tried)), '-'), **best.metrics}
    notes = [f'entry speeds tried (km/h): {series}'
             + (' (the highest tried passes)' if tried[1][1] else ''),
             f'the run at the highest passing entry speed: {best.notes[1]}'] + best.notes[:1]
    return metrics, best.channels, notes


PARAMS: Mapping[str, Mapping[str, Param]] = {
    'lane_change': LANE_CHANGE_PARAMS, 'lane_change_limit': LIMIT_PARAMS}
RUNNERS = {'lane_change': run_lane_change, 'lane_change_limit': run_lane_change_limit}

__all__ = ['APPROACH', 'PARAMS', 'RUNNERS', 'LANE_CHANGE_PARAMS', 'LIMIT_PARAMS', 'Run',
           'driving_line', 'rear_axle_line', 'drive', 'run_lane_change', 'run_lane_change_limit',
           'vehicle_rectangle']
