# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Time integration of the full vehicle with its drivers, and the recorded trace.

``simulate`` advances :class:`.model.VehicleModel` with a fixed step, asks the drivers
every step, records every ``record_every`` steps and stops at ``duration`` or when
``stop(trace_row)`` says so. The speed driver's request becomes wheel torques through
:class:`.drivers.WheelTorques` (the configuration's brakes and driveline, or the fixed
shares ``drive_front`` and ``brake_front`` without them). Channels are SI, ISO 8855
signs: roll positive left side up (outward in a left turn), sideslip and yaw rate positive
to the left.

When the drivers depend on time only (an :class:`.drivers.OpenLoopSteering`, and none or a
speed driver with a ``schedule(times, h)``: the :class:`.drivers.SpeedController`, the
longitudinal events' pedal ramps), the whole run is one compiled loop
(:func:`.dynamics.run_open_loop`, in blocks of recorded rows when there is a ``stop`` or a
``progress``), the brakes, anti-lock controllers and driveline inside it
(:func:`.drivers.actuate`); otherwise each step asks the drivers in Python and calls the
same :func:`.drivers.actuate` (through :class:`.drivers.WheelTorques`) and the compiled
step (:meth:`.model.VehicleModel.step`). Both give the same trace.

With a ``tolerance`` the compiled loop takes variable steps (:mod:`.adaptive`: large where
the car is steady, small where it is not, the error of each step estimated and held to
the tolerance) between ``h_min`` and ``h_max``, the drivers' inputs sampled at the step
times and the rows still on the fixed grid of ``record_every`` steps of ``h``, when the
configuration has no brakes or driveline group and the speed driver asks for no pedals;
otherwise (closed-loop drivers, brakes, driveline) the step stays the fixed ``h``.
"""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from vd_solvers.errors import SolverError

from .adaptive import run_adaptive
from .drivers import (
    ACTUATION_STATE,
    Observation,
    OpenLoopSteering,
    Pedals,
    SpeedDriver,
    SpeedSchedule,
    SteeringDriver,
    WheelTorques,
    actuation_arrays,
)
from .dynamics import (
    ACTUATION_SIZE,
    KAPPA_ROW,
    PREVIOUS_ROWS,
    ROW_SIZE,
    observation,
    record_row,
    run_open_loop,
)
from .forces import WHEEL_ROWS
from .model import STEP, VehicleModel

#: recorded per-sample channels besides the per-wheel ones
TRACE = ('time', 'x', 'y', 'yaw', 'roll', 'pitch', 'yaw_rate', 'speed', 'sideslip',
         'steering_wheel_angle', 'steer_angle_front_left', 'steer_angle_front_right',
         'cog_velocity_x', 'cog_velocity_y', 'cog_velocity_z', 'wheel_torque')
assert len(TRACE) == ROW_SIZE
PER_WHEEL = ('wheel_load', 'wheel_travel', 'slip_angle', 'slip_ratio', 'inclination',
             'tire_force_x', 'tire_force_y', 'wheel_steer', 'aligning_moment')
#: what the brakes and driveline did per sample (recorded when the configuration has them):
#: throttle 0..1, gear (0: no driveline), and per wheel the brake line pressure (Pa) and the
#: wheel torque (N*m)
ACTUATION = ('throttle', 'gear')
ACTUATION_WHEEL = ('brake_pressure', 'applied_torque')
#: the row of the wheels' state (forces.WHEEL_ROWS) each per-wheel channel is
WHEEL_ROW = dict(zip(PER_WHEEL, (WHEEL_ROWS.index(k) for k in (
    'fz', 'travel', 'alpha', 'kappa', 'gamma', 'fx', 'fy', 'steer', 'mz'))))
#: recorded rows per call of the compiled loop when a stop or progress needs to see them
BLOCK_ROWS = 50
#: default bounds of a variable step, s: the largest keeps the tire's relaxation and the
#: speed controller resolved (docs/models.md, "Variable step")
H_MIN = 2.5e-4
H_MAX = 0.04


@dataclass
class Trace:
    """Recorded samples: blocks of TRACE rows (n, len(TRACE)) and wheel states (n, 9, 4)."""

    blocks: list[tuple[np.ndarray, np.ndarray]] = field(default_factory=list)
    #: per recorded row: (ACTUATION values (2,), ACTUATION_WHEEL values (2, 4)); empty when
    #: the configuration has no brakes or driveline to report
    actuation: list[tuple[np.ndarray, np.ndarray]] = field(default_factory=list)
    steps: int = 0
    #: steps repeated with a smaller step, and force evaluations (variable step only)
    rejected: int = 0
    evaluations: int = 0
    stop_reason: str = ''

    def append(self, rows: np.ndarray, wheels: np.ndarray) -> None:
        self.blocks.append((rows, wheels))

    def channels(self) -> dict[str, np.ndarray]:
        """Every channel as an array over the samples, plus accelerations (m/s^2)."""
        data = np.concatenate([b[0] for b in self.blocks])
        wheels = np.concatenate([b[1] for b in self.blocks])
        out = {name: data[:, i] for i, name in enumerate(TRACE)}
        for key, row in WHEEL_ROW.items():
            out[key] = np.ascontiguousarray(wheels[:, row, :])
        if self.actuation:
            scalars = np.array([a[0] for a in self.actuation])
            per_wheel = np.array([a[1] for a in self.actuation])
            for i, key in enumerate(ACTUATION):
                out[key] = scalars[:, i]
            for i, key in enumerate(ACTUATION_WHEEL):
                out[key] = per_wheel[:, i, :]
        t = out['time']
        if t.size >= 3:
            ax_w = np.gradient(out['cog_velocity_x'], t)
            ay_w = np.gradient(out['cog_velocity_y'], t)
        else:
            ax_w = ay_w = np.zeros_like(t)
        c, s = np.cos(out['yaw']), np.sin(out['yaw'])
        out['lateral_acceleration'] = -ax_w * s + ay_w * c
        out['longitudinal_acceleration'] = ax_w * c + ay_w * s
        return out


def observe(model: VehicleModel, q: np.ndarray, v: np.ndarray, t: float) -> Observation:
    yaw, speed, course = observation(q, v)
    return Observation(t=t, x=float(q[0]), y=float(q[1]), yaw=float(yaw), speed=float(speed),
                       course=float(course))


def simulate(model: VehicleModel, steering: SteeringDriver, speed: SpeedDriver | None,
             duration: float, *, event: str, initial_speed: float, initial_yaw_rate: float = 0.0,
             record_every: int = 10, h: float = STEP, drive_front: float = 0.5,
             brake_front: float = 0.65,
             stop: Callable[[dict[str, float]], str] | None = None,
             progress: Callable[[float, str], None] | None = None,
             compiled_loop: bool = True, tolerance: float | None = None,
             h_min: float = H_MIN, h_max: float = H_MAX) -> Trace:
    """
    Integrate from straight-ahead motion at ``initial_speed`` (module doc).

    ``compiled_loop`` False asks the drivers step by step in Python whatever they are.
    ``tolerance`` (m/s and rad/s, the local error of the body's velocities per step) asks
    the compiled loop for variable steps in [``h_min``, ``h_max``] (s).
    """
    q, v = model.initial_state(initial_speed, initial_yaw_rate)
    cog = np.array(model.config.group('mass').point('sprung_cog'), dtype=float)
    n_steps = int(round(duration / h))
    chassis = model.chassis
    inputs = _inputs(steering, speed, n_steps, h) if compiled_loop else None
    systems = chassis.brakes is not None or chassis.driveline is not None
    if inputs is not None and tolerance is not None and not systems \
            and not inputs[1].pedals.any():
        if not (tolerance > 0.0 and 0.0 < h_min <= h_max):
            raise SolverError(f'{model.label(event, 0.0)}: a variable step needs a positive '
                              f'tolerance and 0 < h_min <= h_max (got {tolerance}, {h_min}, '
                              f'{h_max})')
        return _adaptive(model, steering, inputs, q, v, cog, n_steps, event=event, h=h,
                         record_every=record_every, drive_front=drive_front,
                         brake_front=brake_front, stop=stop, progress=progress,
                         tolerance=tolerance, h_min=h_min, h_max=h_max)
    if inputs is not None:
        return _open_loop(model, inputs, q, v, cog, n_steps, event=event, h=h,
                          record_every=record_every, drive_front=drive_front,
                          brake_front=brake_front, stop=stop, progress=progress)
    return _per_step(model, steering, speed, q, v, cog, n_steps, event=event, h=h,
                     record_every=record_every, drive_front=drive_front,
                     brake_front=brake_front, stop=stop, progress=progress)


def _per_step(model, steering, speed, q, v, cog, n_steps, *, event, h, record_every,
              drive_front, brake_front, stop, progress) -> Trace:
    trace = Trace()
    slip = np.zeros((2, 4))
    previous = None
    last = None  # the previous step's wheel state (its transient slips feed the ABS)
    actuate = WheelTorques(model.chassis, drive_front, brake_front)
    # what the brakes and driveline did, recorded when the configuration has them (the
    # same channels as the compiled loop otherwise)
    systems = model.chassis.brakes is not None or model.chassis.driveline is not None
    for step in range(n_steps + 1):
        t = step * h
        obs = observe(model, q, v, t)
        swa = steering.steering_wheel_angle(obs, h)
        request = speed.wheel_torque(obs, h) if speed is not None else 0.0
        kappa = last[KAPPA_ROW] if last is not None else np.zeros(4)
        torques = actuate(request, np.ascontiguousarray(v[7::2]), kappa, obs.speed, h)
        torque = float(np.sum(torques)) if isinstance(request, Pedals) else float(request)
        q_next, v_next, slip_next, wheel = model.step(q, v, swa, torques, slip, previous, h)
        if step % record_every == 0:
            row = record_row(q, v, t, swa, wheel, cog, torque)
            trace.append(row[None], wheel[None])
            if systems:
                trace.actuation.append((np.array([actuate.throttle, float(actuate.gear)]),
                                        np.stack([actuate.pressures, torques])))
            if stop is not None:
                reason = stop(dict(zip(TRACE, row)))
                if reason:
                    trace.stop_reason = reason
                    break
            if progress is not None and step % (record_every * BLOCK_ROWS) == 0:
                progress(step / max(n_steps, 1), 'simulating')
        if step == n_steps:
            break
        if not (np.all(np.isfinite(q_next)) and np.all(np.isfinite(v_next))):
            raise SolverError(f'{model.label(event, t + h)}: the state became non-finite')
        q, v, slip, previous, last = q_next, v_next, slip_next, wheel[PREVIOUS_ROWS], wheel
        trace.steps += 1
    return trace


def _open_loop(model, inputs, q, v, cog, n_steps, *, event, h, record_every, drive_front,
               brake_front, stop, progress) -> Trace:
    trace = Trace()
    swa, plan = inputs
    integral = float(plan.controller._integral) if plan.controller is not None else 0.0
    slip, previous, has_previous = np.zeros((2, 4)), np.zeros((4, 4)), False
    systems = actuation_arrays(model.chassis)
    state, kappa = np.zeros(ACTUATION_STATE), np.zeros(4)
    recorded = model.chassis.brakes is not None or model.chassis.driveline is not None
    block = (record_every * BLOCK_ROWS if stop is not None or progress is not None
             else n_steps + 1)
    capacity = -(-block // record_every)
    rows, wheels = np.empty((capacity, ROW_SIZE)), np.empty((capacity, len(WHEEL_ROWS), 4))
    actuation = np.empty((capacity, ACTUATION_SIZE))
    step = 0
    while step <= n_steps:
        if progress is not None:
            progress(step / max(n_steps, 1), 'simulating')
        first = step
        q, v, slip, previous, step, n, integral, failed = run_open_loop(
            q, v, slip, previous, has_previous, first, min(first + block, n_steps + 1),
            n_steps, record_every, h, swa, plan.pedals, plan.throttle, plan.pressure,
            plan.reference, plan.reference_next, plan.gains, integral, float(drive_front),
            float(brake_front), systems, state, kappa, model.arrays, model.vx_floor,
            model.total_mass, model.options.road, model.options.dampers, model.multibody, cog,
            rows, wheels, actuation)
        has_previous = step > 0
        stopped = _append_rows(trace, rows, wheels, n, stop,
                               actuation if recorded else None)
        if stopped is not None:
            trace.steps = int(round(rows[stopped, 0] / h))
            return trace
        if failed >= 0:
            raise SolverError(f'{model.label(event, failed * h + h)}: the state became '
                              'non-finite')
        trace.steps = min(step, n_steps)
    if plan.controller is not None:
        plan.controller._integral = integral
    return trace


def _append_rows(trace: Trace, rows: np.ndarray, wheels: np.ndarray, n: int,
                 stop: Callable[[dict[str, float]], str] | None,
                 actuation: np.ndarray | None = None) -> int | None:
    """
    Append the loop's first ``n`` rows to ``trace`` up to the first one ``stop`` stops at.

    With ``actuation`` (rows of dynamics.ACTUATION_SIZE) its rows go to
    ``trace.actuation``. Return the index of that row (its reason in
    ``trace.stop_reason``), None if none.
    """
    stopped = None
    if stop is not None:
        for i in range(n):
            reason = stop(dict(zip(TRACE, rows[i])))
            if reason:
                n, stopped = i + 1, i
                trace.stop_reason = reason
                break
    trace.append(rows[:n].copy(), wheels[:n].copy())
    if actuation is not None:
        trace.actuation.extend((a[0:2].copy(), a[2:10].reshape(2, 4).copy())
                               for a in actuation[:n])
    return stopped


def _inputs(steering, speed, n_steps: int, h: float
            ) -> tuple[np.ndarray, SpeedSchedule] | None:
    """
    Return the drivers' inputs on the grid of ``h``: (swa, the speed driver's commands).

    None when they do not depend on time only (the per-step loop asks them).
    """
    if not isinstance(steering, OpenLoopSteering):
        return None
    times = [k * h for k in range(n_steps + 1)]
    if speed is None:
        none = np.zeros(0)
        plan = SpeedSchedule(np.zeros(n_steps + 1, dtype=bool), none, none, none, none, none,
                             None)
    elif callable(getattr(speed, 'schedule', None)):
        plan = speed.schedule(np.array(times), h)
    else:
        return None
    return np.ascontiguousarray(steering.schedule(times), dtype=float), plan


def _adaptive(model, steering, inputs, q, v, cog, n_steps, *, event, h, record_every,
              drive_front, brake_front, stop, progress, tolerance, h_min, h_max) -> Trace:
    trace = Trace()
    swa, plan = inputs
    reference, gains = plan.reference, plan.gains
    integral = float(plan.controller._integral) if plan.controller is not None else 0.0
    table = steering.table_points
    t_end = n_steps * h
    breakpoints = (np.ascontiguousarray(table[0][(table[0] > 0.0) & (table[0] < t_end)])
                   if table is not None else np.zeros(0))
    slip, previous, has_previous = np.zeros((2, 4)), np.zeros((4, 4)), False
    period = record_every * h
    capacity = (BLOCK_ROWS if stop is not None or progress is not None
                else n_steps // record_every + 1) + int(h_max / period) + 2
    rows, wheels = np.empty((capacity, ROW_SIZE)), np.empty((capacity, len(WHEEL_ROWS), 4))
    t, step, output = 0.0, min(h, h_max), 0
    while True:
        if progress is not None:
            progress(t / max(t_end, h), 'simulating')
        (q, v, slip, previous, has_previous, t, step, output, n, integral, accepted,
         rejected, evaluations, failed) = run_adaptive(
            q, v, slip, previous, has_previous, t, step, t_end, period, output, breakpoints,
            tolerance, h_min, h_max, h, swa, reference, gains, integral, drive_front,
            brake_front, model.arrays, model.vx_floor, model.total_mass, model.options.road,
            model.options.dampers, model.multibody, cog, rows, wheels)
        trace.steps += accepted
        trace.rejected += rejected
        trace.evaluations += evaluations
        if _append_rows(trace, rows, wheels, n, stop) is not None:
            return trace
        if failed >= 0.0:
            raise SolverError(f'{model.label(event, failed)}: the state became non-finite')
        if n == 0 or t >= t_end - 1e-9 * max(h_max, t_end):
            break
    if plan.controller is not None:
        plan.controller._integral = integral
    return trace


__all__ = ['simulate', 'Trace', 'TRACE', 'PER_WHEEL', 'ACTUATION', 'ACTUATION_WHEEL', 'observe']
