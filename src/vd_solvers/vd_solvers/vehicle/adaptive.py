# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The full vehicle with a variable step: small where the car is not steady, large where it is.

:func:`run_adaptive` advances the step of :mod:`.dynamics` (the one force evaluation
:func:`.forces.vehicle_forces`, the articulated-body accelerations, semi-implicit Euler,
the transient slips decaying exactly and the wheel spin linearly implicit) with a step
chosen from an error estimate, compiled like the fixed-step loop
:func:`.dynamics.run_open_loop`, for the same drivers (a steering-wheel angle and the
speed controller's reference that depend on time only).

Stiff vertical modes. At a fixed step of 5 ms the largest stable step is set by the
wheel hop (the unsprung mass between the tire's C_z of about 280 kN/m and the
suspension, with the tire's and the damper's damping taken explicitly): 20 ms diverges
on the sample sedan and HMMWV before the steer. Here the carrier's travel acceleration
is taken linearly implicitly with the carrier's own stiffness K (tire C_z plus the
slope of the wheel-force map) and damping D (tire damping plus the damper's slope times
the motion ratio squared) at the step's start, the body held (its mass is ten times the
carrier's)::

    z''+ = z'' / (1 + h D / m_u + h^2 K / m_u)

a W-method with that diagonal Jacobian block (Hairer & Wanner, *Solving Ordinary
Differential Equations II*, 2nd ed. 1996, IV.7): first order like the explicit
update, the same steady states, stable for the wheel hop at any step. The fixed step of
:mod:`.dynamics` stays as it was (the ride events resolve the wheel hop with it).

Step-size control. Semi-implicit Euler's local error in the velocities is
``h^2 / 2 v''``; the difference of the accelerations at the step's end and start,
``e = h / 2 (a+ - a)``, estimates it (Hairer, Norsett & Wanner, *Solving Ordinary
Differential Equations I*, 2nd ed. 1993, II.4, the embedded Euler-Heun pair) from the
evaluation the next step makes anyway. The norm is the largest |e| of the body's six
velocities (m/s and rad/s) over ``tolerance``; a step with a norm over 1 is repeated
with a smaller one (above ``h_min``), and the next step is h SAFETY / sqrt(norm),
within GROWTH of the last (not larger right after a repeated step), ``h_min`` and
``h_max``, kept unchanged inside the
HOLD band (a changed step needs the forces again: the wheel spin's implicit term, the
travel's and the speed controller depend on it). The evaluation at a step's end is made
with the next step guessed from the last error norm, and serves the next step when the
new norm's step is within HOLD of the guess. Steps end on the breakpoints of the inputs (the
corners of a steering table) so a ramp's start is never stepped over, and the step after
a breakpoint starts again from ``h_min``.

Inputs and outputs. The drivers' inputs are given on a base grid of step ``h_base``
(as for the fixed-step loop) and interpolated linearly at each step's time. The recorded
rows lie on the fixed output grid (every ``record_every`` base steps), interpolated
linearly between the two accepted steps around each output time (yaw across the
+-pi cut), so reports, bags and metrics keep their time base.

Where the events take it. The handling events whose drivers depend on time only (the
step steer, the sine-with-dwell procedure) run with the variable step by default, their
``step_tolerance`` parameter (:data:`STEP_TOLERANCE_PARAM`, 0 the fixed step);
:func:`event_tolerance` turns it into ``simulate``'s ``tolerance``: none on a road with
relief, whose wheel hop the fixed step resolves and the implicit travel would damp, and
none with brakes or a driveline (the anti-lock controllers' and the speed filter's state
advance once per accepted step).
"""
from __future__ import annotations

import numpy as np

from vd_solvers.compiled import jit
from vd_solvers.event_params import Param

from .drivers import speed_law, wheel_torques
from .dynamics import (
    PREVIOUS_ROWS,
    MultibodyArrays,
    accelerations,
    advance,
    observation,
    record_row,
)
from .forces import VehicleArrays, vehicle_forces
from .maps import grid_lookup
from .model import VehicleModel

#: the next step is at most GROWTH times the last
GROWTH = 2.0
#: the next step is at least SHRINK times the last
SHRINK = 0.2
#: the step proposed is SAFETY times the one the estimate would put on the tolerance
SAFETY = 0.8
#: a proposal within HOLD (lower, upper) times the last step keeps the last
HOLD = (0.9, 1.3)
#: travel (m) and travel speed (m/s) increments of the wheel-force map's and the damper's
#: slopes
TRAVEL_DELTA = 1e-3
SPEED_DELTA = 1e-2
#: index of the yaw channel in a recorded row (simulation.TRACE)
YAW = 3
#: the events' default local error tolerance (m/s, rad/s): the step steer's and the sine
#: with dwell's yaw rate and lateral acceleration within 1 % of their peaks of the converged
#: run on the sample cars (tests/vd_solvers/vehicle/test_adaptive.py, test_event_steps.py)
STEP_TOLERANCE = 3e-5
#: the events' parameter choosing it
STEP_TOLERANCE_PARAM = Param(
    'velocity', STEP_TOLERANCE, "variable step: local error tolerance of the body's velocities "
    'per step (m/s, and rad/s for the angular ones); 0: the fixed step. On a road with relief '
    'the fixed step runs whatever it says (the wheel hop)', minimum=0.0, maximum=0.01)


def event_tolerance(model: VehicleModel, step_tolerance: float) -> float | None:
    """
    Return the ``simulate`` tolerance of an event (None: the fixed step).

    None for 0, for a road with relief, and for a configuration with brakes or a
    driveline (their controllers' state cannot be stepped back when a step is rejected).
    """
    chassis = model.chassis
    if step_tolerance <= 0.0 or np.any(model.road.height != 0.0) \
            or chassis.brakes is not None or chassis.driveline is not None:
        return None
    return step_tolerance


@jit
def travel_rates(q: np.ndarray, v: np.ndarray, c: VehicleArrays, road: bool, dampers: bool
                 ) -> tuple[np.ndarray, np.ndarray]:
    """
    Return the carriers' own vertical stiffness K (N/m) and damping D (N*s/m), (4,) each.

    K: the tire's C_z (in contact, ``road``) plus the slope of the wheel-force map; D: the
    tire's damping plus the damper's slope at its speed times the motion ratio squared
    (module doc; a Jacobian, so slopes by central differences of the same maps).
    """
    z = np.ascontiguousarray(q[7::2])
    zdot = np.ascontiguousarray(v[6::2])
    low = grid_lookup(c.travel_table, c.travel0, c.travel_step, z - TRAVEL_DELTA)
    high = grid_lookup(c.travel_table, c.travel0, c.travel_step, z + TRAVEL_DELTA)
    stiffness = np.maximum((high[0] - low[0]) / (2.0 * TRAVEL_DELTA), 0.0)
    damping = np.zeros(4)
    if road:
        stiffness = stiffness + c.wheel[2]
        damping = damping + c.wheel[3]
    if dampers:
        ratio = 0.5 * (low[3] + high[3])
        for w in range(4):
            x, y = ((c.damper_front_x, c.damper_front_y) if w < 2
                    else (c.damper_rear_x, c.damper_rear_y))
            s = ratio[w] * zdot[w]
            slope = (np.interp(s + SPEED_DELTA, x, y) - np.interp(s - SPEED_DELTA, x, y)) / (
                2.0 * SPEED_DELTA)
            damping[w] += ratio[w] * ratio[w] * max(slope, 0.0)
    return stiffness, damping


@jit
def _sample(values: np.ndarray, h_base: float, t: float) -> float:
    """Linear interpolation of ``values`` given at k h_base, held beyond the ends."""
    u = t / h_base
    n = values.size
    if u <= 0.0:
        return values[0]
    if u >= n - 1:
        return values[n - 1]
    i = int(u)
    return values[i] + (u - i) * (values[i + 1] - values[i])


@jit
def _evaluate(q: np.ndarray, v: np.ndarray, slip: np.ndarray, previous: np.ndarray,
              has_previous: bool, integral: float, t: float, h: float, h_base: float,
              swa: np.ndarray, reference: np.ndarray, speed_gains: np.ndarray,
              drive_front: float, brake_front: float, c: VehicleArrays, vx_floor: float,
              total_mass: float, road: bool, dampers: bool, mb: MultibodyArrays):
    """Drivers, forces and accelerations of a step of ``h`` from time ``t`` (module doc)."""
    steer = _sample(swa, h_base, t)
    torque = 0.0
    if speed_gains.size:
        speed = observation(q, v)[1]
        torque, integral = speed_law(_sample(reference, h_base, t),
                                     _sample(reference, h_base, t + h), speed, integral,
                                     speed_gains[0], speed_gains[1], speed_gains[2],
                                     speed_gains[3], h)
    torques = wheel_torques(torque, drive_front, brake_front, np.ascontiguousarray(v[7::2]))
    tau, wheel, update = vehicle_forces(q, v, steer, torques, slip, previous, has_previous, h,
                                        c, vx_floor, total_mass, road, dampers)
    a = accelerations(q, v, tau, mb)
    stiffness, damping = travel_rates(q, v, c, road, dampers)
    for w in range(4):
        m = mb.carrier_mass[w]
        # the body's acceleration at the carrier's joint, along the travel (body z)
        r = mb.offsets[w]
        x, y = r[0], r[1]
        body = a[2] + a[3] * y - a[4] * x
        carrier = a[6 + 2 * w] + body
        a[6 + 2 * w] = carrier / (1.0 + h * damping[w] / m + h * h * stiffness[w] / m) - body
    return a, wheel, update, steer, torque, integral


@jit
def error_norm(a_start: np.ndarray, a_end: np.ndarray, h: float, tolerance: float) -> float:
    """Return the local error estimate of a step in the body's velocities over ``tolerance``."""
    worst = 0.0
    for k in range(6):
        worst = max(worst, abs(a_end[k] - a_start[k]))
    return 0.5 * h * worst / tolerance


@jit
def _next_step(h: float, norm: float) -> float:
    """Return the step after one of ``h`` with an error ``norm`` (before the limits)."""
    if norm <= 0.0:
        return GROWTH * h
    factor = min(GROWTH, max(SHRINK, SAFETY / np.sqrt(norm)))
    if HOLD[0] <= factor <= HOLD[1]:
        return h
    return factor * h


@jit
def _interpolated(row0: np.ndarray, row1: np.ndarray, weight: float) -> np.ndarray:
    out = row0 + weight * (row1 - row0)
    turn = row1[YAW] - row0[YAW]
    turn = (turn + np.pi) % (2.0 * np.pi) - np.pi
    out[YAW] = row0[YAW] + weight * turn
    out[YAW] = (out[YAW] + np.pi) % (2.0 * np.pi) - np.pi
    return out


@jit
def run_adaptive(q: np.ndarray, v: np.ndarray, slip: np.ndarray, previous: np.ndarray,
                 has_previous: bool, t: float, h: float, t_end: float, output_period: float,
                 next_output: int, breakpoints: np.ndarray, tolerance: float, h_min: float,
                 h_max: float, h_base: float, swa: np.ndarray, reference: np.ndarray,
                 speed_gains: np.ndarray, integral: float, drive_front: float,
                 brake_front: float, c: VehicleArrays, vx_floor: float, total_mass: float,
                 road: bool, dampers: bool, mb: MultibodyArrays, cog: np.ndarray,
                 rows: np.ndarray, wheels: np.ndarray):
    """
    Advance from ``t`` towards ``t_end``, each step's error held to ``tolerance`` (module doc).

    ``h`` the first step; rows at the output times ``k output_period`` from k =
    ``next_output`` go into ``rows`` / ``wheels`` (as :func:`.dynamics.run_open_loop`)
    until they are full or ``t_end`` is reached. Returns (q, v, slip, previous,
    has_previous, t, the next step, the next output index, rows recorded, the
    controller's integral, steps accepted, steps repeated, force evaluations, the time a
    step became non-finite or -1).
    """
    capacity = rows.shape[0]
    n = 0
    accepted = 0
    rejected = 0
    repeated = False
    last_norm = 0.0
    evaluations = 1
    a, wheel, update, steer, torque, integral_end = _evaluate(
        q, v, slip, previous, has_previous, integral, t, h, h_base, swa, reference,
        speed_gains, drive_front, brake_front, c, vx_floor, total_mass, road, dampers, mb)
    row = record_row(q, v, t, steer, wheel, cog, torque)
    span = 1e-9 * max(h_max, t_end)  # times within this of each other are the same
    while True:
        if abs(next_output * output_period - t) <= span and n < capacity:
            rows[n] = row
            rows[n, 0] = next_output * output_period
            wheels[n] = wheel
            n += 1
            next_output += 1
        if t >= t_end - span:
            return (q, v, slip, previous, has_previous, t, h, next_output, n, integral,
                    accepted, rejected, evaluations, -1.0)
        # room for the rows the longest step can give
        if n + int(h_max / output_period) + 2 > capacity:
            return (q, v, slip, previous, has_previous, t, h, next_output, n, integral,
                    accepted, rejected, evaluations, -1.0)
        # the step, cut at the next breakpoint and at the end
        stop = t_end
        for b in breakpoints:
            if b > t + span:
                stop = min(stop, b)
                break
        step = h
        if t + step > stop - span or t + 1.5 * step > stop:
            step_new = stop - t if t + step > stop - span else 0.5 * (stop - t)
            if step_new != h:
                step = step_new
                evaluations += 1
                a, wheel, update, steer, torque, integral_end = _evaluate(
                    q, v, slip, previous, has_previous, integral, t, step, h_base, swa,
                    reference, speed_gains, drive_front, brake_front, c, vx_floor,
                    total_mass, road, dampers, mb)
                row = record_row(q, v, t, steer, wheel, cog, torque)
        q1, v1, slip1 = advance(q, v, a, update, step)
        if not (np.all(np.isfinite(q1)) and np.all(np.isfinite(v1))):
            return (q, v, slip, previous, has_previous, t, h, next_output, n, integral,
                    accepted, rejected, evaluations, t + step)
        previous1 = np.empty((4, 4))
        for j in range(4):
            previous1[j] = wheel[PREVIOUS_ROWS[j]]
        # the next step guessed from the last error, so that the evaluation serves both
        # the estimate and the next step when the guess holds
        guess = min(h_max, max(h_min, _next_step(step, last_norm)))
        if repeated:
            guess = min(guess, step)
        evaluations += 1
        a1, wheel1, update1, steer1, torque1, integral1 = _evaluate(
            q1, v1, slip1, previous1, True, integral_end, t + step, guess, h_base, swa,
            reference, speed_gains, drive_front, brake_front, c, vx_floor, total_mass, road,
            dampers, mb)
        norm = error_norm(a, a1, step, tolerance)
        if (not norm <= 1.0) and step > h_min * (1.0 + 1e-9):
            rejected += 1
            repeated = True
            h = (max(h_min, step * max(SHRINK, SAFETY / np.sqrt(norm))) if np.isfinite(norm)
                 else max(h_min, SHRINK * step))
            evaluations += 1
            a, wheel, update, steer, torque, integral_end = _evaluate(
                q, v, slip, previous, has_previous, integral, t, h, h_base, swa, reference,
                speed_gains, drive_front, brake_front, c, vx_floor, total_mass, road,
                dampers, mb)
            row = record_row(q, v, t, steer, wheel, cog, torque)
            continue
        accepted += 1
        row1 = record_row(q1, v1, t + step, steer1, wheel1, cog, torque1)
        while n < capacity and next_output * output_period < t + step - span:
            weight = (next_output * output_period - t) / step
            rows[n] = _interpolated(row, row1, weight)
            rows[n, 0] = next_output * output_period
            wheels[n] = wheel + weight * (wheel1 - wheel)
            n += 1
            next_output += 1
        q, v, slip, previous, has_previous = q1, v1, slip1, previous1, True
        t += step
        integral = integral_end
        h_next = min(h_max, max(h_min, _next_step(step, norm)))
        if repeated:
            h_next = min(h_next, step)  # no growth right after a repeated step
        if HOLD[0] * guess <= h_next <= HOLD[1] * guess:
            h_next = guess
        repeated = False
        last_norm = norm
        if stop < t_end and abs(t - stop) <= span:
            h_next = h_min  # an input's corner: the response starts afresh
        a, wheel, update, steer, torque, integral_end = a1, wheel1, update1, steer1, torque1, \
            integral1
        row = row1
        if h_next != guess:
            evaluations += 1
            a, wheel, update, steer, torque, integral_end = _evaluate(
                q, v, slip, previous, has_previous, integral, t, h_next, h_base, swa,
                reference, speed_gains, drive_front, brake_front, c, vx_floor, total_mass,
                road, dampers, mb)
            row = record_row(q, v, t, steer, wheel, cog, torque)
        h = h_next


__all__ = ['run_adaptive', 'travel_rates', 'error_norm', 'event_tolerance', 'GROWTH', 'SHRINK',
           'SAFETY', 'HOLD', 'STEP_TOLERANCE', 'STEP_TOLERANCE_PARAM']
