# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The full vehicle's multibody step as compiled functions: accelerations, update, whole runs.

The tree of :mod:`.model` has a fixed topology (a free-flying body, four carriers on
prismatic joints along the body's z axis at the design wheel centres, four wheels on
revolute joints about the carriers' y axes), so its forward dynamics is written out here
as the articulated-body algorithm (Featherstone, *Rigid Body Dynamics Algorithms*, 2008,
ch. 7) for exactly that tree, in the body frame with spatial vectors ordered (linear,
angular) as Pinocchio orders them:

* leaves first: each wheel's spin joint (motion subspace the carrier's angular y; the
  wheel's rotational inertia diag(a, b, a) is symmetric about that axis, so it is the
  same in the carrier's axes whatever the spin angle), then the carrier's travel joint
  (linear z; point mass at the joint), their articulated inertias and bias forces moved
  to the body's origin;
* the body: its articulated inertia (6 x 6, solved by a Cholesky factorisation) gives the
  free flyer's acceleration, with gravity as a fictitious acceleration of the root;
* out again: each carrier's travel and each wheel's spin acceleration.

The inertial data are read from the Pinocchio model (:func:`multibody_arrays`), which
stays the reference: the tests compare :func:`accelerations` with ``pin.aba`` and the
update with ``pin.integrate``.

:func:`vehicle_step` is one step of the integrator of :mod:`.model` (forces from
:func:`.forces.vehicle_forces`, the one force evaluation; semi-implicit Euler; the free
flyer's configuration advanced by the SE(3) exponential, its quaternion by the exact
rotation; the transient slips moved as :class:`.model.SlipUpdate` says).
:func:`run_open_loop` advances many steps in one call when the drivers depend on time
only (a steering-wheel angle per step; per step the pedals or the speed controller's
reference), the wheel torques through the chassis's brakes, anti-lock brakes and
driveline (:func:`.drivers.actuate`, the function the per-step loop calls too), and
records every ``record_every`` steps into preallocated arrays; :func:`record_row` and
:func:`observation` are the recorded channels and what a driver sees, the same for the
per-step path of :mod:`.simulation`.
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np
import pinocchio as pin

from vd_solvers.compiled import jit
from vd_solvers.errors import SolverError

from .drivers import ActuationArrays, actuate, speed_law, wheel_torques
from .forces import WHEEL_ROWS, VehicleArrays, _rotation, vehicle_forces

#: rows of the wheel array of :func:`.forces.vehicle_forces` the next step's compliances use
#: (Fx, Fy, Mz, steer; see ``previous`` there)
PREVIOUS_ROWS = np.array([1, 2, 3, 7])
#: number of values of a recorded row (simulation.TRACE)
ROW_SIZE = 16
#: row of the wheel array of :func:`.forces.vehicle_forces` the anti-lock brakes read
KAPPA_ROW = WHEEL_ROWS.index('kappa')
#: values per recorded row of what the brakes and driveline did: throttle, gear, line
#: pressures (4), wheel torques (4) (simulation.ACTUATION, ACTUATION_WHEEL)
ACTUATION_SIZE = 10


class MultibodyArrays(NamedTuple):
    """The inertial data of the tree, read from the Pinocchio model (contiguous floats)."""

    body: np.ndarray  # (6, 6) spatial inertia of the body about its origin, body axes
    offsets: np.ndarray  # (4, 3) carrier joint placements (design wheel centres), m
    carrier_mass: np.ndarray  # (4,) kg
    wheel_inertia: np.ndarray  # (4, 2) a (about x and z), b (about the spin axis y), kg*m^2
    gravity: np.ndarray  # (3,) world, m/s^2


def multibody_arrays(model: pin.Model) -> MultibodyArrays:
    """Read :class:`MultibodyArrays` from the tree of :mod:`.model` (SolverError if not it)."""
    expected = ['JointModelFreeFlyer'] + ['JointModelPZ', 'JointModelRY'] * 4
    names = [j.shortname() for j in model.joints][1:]
    if names != expected or list(model.parents)[1:] != [0] + [1, 2, 1, 4, 1, 6, 1, 8]:
        raise SolverError(f'the compiled multibody step needs the tree {expected}, '
                          f'not {names}')
    offsets = np.empty((4, 3))
    mass = np.empty(4)
    wheel = np.empty((4, 2))
    for w in range(4):
        travel, spin = 2 + 2 * w, 3 + 2 * w
        placement = model.jointPlacements[travel]
        inertia = model.inertias[travel]
        spin_inertia = model.inertias[spin]
        ok = (np.allclose(placement.rotation, np.eye(3), atol=0.0)
              and np.allclose(inertia.lever, 0.0, atol=0.0)
              and np.allclose(inertia.inertia, 0.0, atol=0.0)
              and model.jointPlacements[spin] == pin.SE3.Identity()
              and spin_inertia.mass == 0.0
              and np.count_nonzero(spin_inertia.inertia - np.diag(np.diag(spin_inertia.inertia)))
              == 0 and spin_inertia.inertia[0, 0] == spin_inertia.inertia[2, 2])
        if not ok:
            raise SolverError('the compiled multibody step needs carriers with a point mass '
                              'at the joint and wheels with a mass-less inertia diag(a, b, a)')
        offsets[w] = placement.translation
        mass[w] = inertia.mass
        wheel[w] = spin_inertia.inertia[0, 0], spin_inertia.inertia[1, 1]
    return MultibodyArrays(body=np.ascontiguousarray(model.inertias[1].matrix()),
                           offsets=offsets, carrier_mass=mass, wheel_inertia=wheel,
                           gravity=np.ascontiguousarray(model.gravity.linear, dtype=float))


@jit
def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    out = np.empty(3)
    out[0] = a[1] * b[2] - a[2] * b[1]
    out[1] = a[2] * b[0] - a[0] * b[2]
    out[2] = a[0] * b[1] - a[1] * b[0]
    return out


@jit
def _solve_spd6(m: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Solve m x = b for a symmetric positive definite (6, 6) m (Cholesky)."""
    n = 6
    low = np.zeros((n, n))
    for j in range(n):
        s = m[j, j]
        for k in range(j):
            s -= low[j, k] * low[j, k]
        d = np.sqrt(s)
        low[j, j] = d
        for i in range(j + 1, n):
            s = m[i, j]
            for k in range(j):
                s -= low[i, k] * low[j, k]
            low[i, j] = s / d
    y = np.empty(n)
    for i in range(n):
        s = b[i]
        for k in range(i):
            s -= low[i, k] * y[k]
        y[i] = s / low[i, i]
    x = np.empty(n)
    for i in range(n - 1, -1, -1):
        s = y[i]
        for k in range(i + 1, n):
            s -= low[k, i] * x[k]
        x[i] = s / low[i, i]
    return x


@jit
def accelerations(q: np.ndarray, v: np.ndarray, tau: np.ndarray,
                  mb: MultibodyArrays) -> np.ndarray:
    """Return the accelerations (nv,) of the tree for forces ``tau`` (module doc; = pin.aba)."""
    rot = _rotation(q)
    u = v[0:3]
    w = v[3:6]
    body = mb.body
    # the body's velocity-product bias force v x* (I v)
    momentum = body @ v[0:6]
    inertia = body.copy()  # articulated inertia, body origin
    bias = np.empty(6)
    bias[0:3] = _cross(w, momentum[0:3])
    bias[3:6] = _cross(w, momentum[3:6]) + _cross(u, momentum[0:3])
    travel_force = np.empty(4)
    spin_force = np.empty(4)
    carrier_bias = np.empty((4, 3))  # c of each carrier (linear part; angular is zero)
    arms = np.empty((4, 3))
    for i in range(4):
        m = mb.carrier_mass[i]
        a_w, b_w = mb.wheel_inertia[i, 0], mb.wheel_inertia[i, 1]
        r = mb.offsets[i].copy()
        r[2] += q[7 + 2 * i]
        arms[i] = r
        zd = v[6 + 2 * i]
        th = v[7 + 2 * i]
        nu = u + _cross(w, r)
        nu[2] += zd  # carrier velocity, linear (angular: w)
        # wheel: angular velocity w + th e_y, bias force (0, w_w x J w_w)
        ww = w.copy()
        ww[1] += th
        jw = np.array([a_w * ww[0], b_w * ww[1], a_w * ww[2]])
        pw = _cross(ww, jw)
        # spin joint: U = b e_y (angular), D = b, u = tau - S^T p
        spin_u = tau[7 + 2 * i] - pw[1]
        spin_force[i] = spin_u
        # c_w angular = w x th e_y (its linear part meets a zero inertia)
        cw_x = -w[2] * th
        cw_z = w[0] * th
        # carrier articulated bias: p_c + p_w + Ia_w c_w + U u / D
        p_lin = m * _cross(w, nu)
        p_ang = pw.copy()
        p_ang[0] += a_w * cw_x
        p_ang[1] += spin_u
        p_ang[2] += a_w * cw_z
        # travel joint: U = m e_z (linear), D = m
        travel_u = tau[6 + 2 * i] - p_lin[2]
        travel_force[i] = travel_u
        # c_c = zd w x e_z (linear)
        cc = np.array([w[1] * zd, -w[0] * zd, 0.0])
        carrier_bias[i] = cc
        # handed to the body: Ia = diag(m, m, 0, a, 0, a), pa = pA + Ia c_c + U u / D
        f = np.array([p_lin[0] + m * cc[0], p_lin[1] + m * cc[1], tau[6 + 2 * i]])
        n = p_ang + _cross(r, f)
        bias[0:3] += f
        bias[3:6] += n
        # X^T Ia X, X = [[1, -[r]x], [0, 1]]: [[M, -M [r]x], [[r]x M, -[r]x M [r]x + A]]
        rx = np.array([[0.0, -r[2], r[1]], [r[2], 0.0, -r[0]], [-r[1], r[0], 0.0]])
        mm = np.array([m, m, 0.0])
        m_rx = np.empty((3, 3))
        for j in range(3):
            m_rx[j] = mm[j] * rx[j]
        rx_m_rx = rx @ m_rx
        for j in range(3):
            for k in range(3):
                inertia[j, 3 + k] -= m_rx[j, k]
                inertia[3 + k, j] -= m_rx[j, k]
                inertia[3 + j, 3 + k] -= rx_m_rx[j, k]
        inertia[3, 3] += a_w
        inertia[5, 5] += a_w
        inertia[0, 0] += m
        inertia[1, 1] += m
    # the root's acceleration with gravity as a fictitious upward acceleration
    total = _solve_spd6(inertia, tau[0:6] - bias)
    out = np.empty(v.size)
    g = mb.gravity
    for k in range(3):
        out[k] = total[k] + rot[0, k] * g[0] + rot[1, k] * g[1] + rot[2, k] * g[2]
    out[3:6] = total[3:6]
    for i in range(4):
        r = arms[i]
        lin = total[0:3] + _cross(total[3:6], r) + carrier_bias[i]
        zdd = travel_force[i] / mb.carrier_mass[i] - lin[2]
        out[6 + 2 * i] = zdd
        # c_w's angular y is zero: the spin acceleration is u / D less the body's about y
        out[7 + 2 * i] = spin_force[i] / mb.wheel_inertia[i, 1] - total[4]
    return out


@jit
def _quat_product(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Return a * b for quaternions (x, y, z, w)."""
    out = np.empty(4)
    out[0] = a[3] * b[0] + b[3] * a[0] + a[1] * b[2] - a[2] * b[1]
    out[1] = a[3] * b[1] + b[3] * a[1] + a[2] * b[0] - a[0] * b[2]
    out[2] = a[3] * b[2] + b[3] * a[2] + a[0] * b[1] - a[1] * b[0]
    out[3] = a[3] * b[3] - a[0] * b[0] - a[1] * b[1] - a[2] * b[2]
    return out


@jit
def integrate(q: np.ndarray, dq: np.ndarray) -> np.ndarray:
    """Return q moved by the tangent vector ``dq`` (= pin.integrate for this tree)."""
    out = q.copy()
    nu = dq[0:3]
    phi = dq[3:6]
    angle = np.sqrt(phi[0] ** 2 + phi[1] ** 2 + phi[2] ** 2)
    sq = angle * angle
    if angle < 1e-4:  # Taylor series, exact to rounding here
        c1 = 0.5 - sq / 24.0
        c2 = 1.0 / 6.0 - sq / 120.0
        half = 0.5 - sq / 48.0
    else:
        c1 = (1.0 - np.cos(angle)) / sq
        c2 = (angle - np.sin(angle)) / (sq * angle)
        half = np.sin(0.5 * angle) / angle
    # SE(3) exponential: translation V(phi) nu in the body frame, then to the world
    cross = _cross(phi, nu)
    shift = nu + c1 * cross + c2 * _cross(phi, cross)
    rot = _rotation(q)
    out[0:3] = q[0:3] + rot @ shift
    turn = np.array([half * phi[0], half * phi[1], half * phi[2], np.cos(0.5 * angle)])
    quat = _quat_product(q[3:7], turn)
    out[3:7] = quat / np.sqrt(quat[0] ** 2 + quat[1] ** 2 + quat[2] ** 2 + quat[3] ** 2)
    out[7:] = q[7:] + dq[6:]
    return out


@jit
def kappa_next(update: np.ndarray, spin: np.ndarray) -> np.ndarray:
    """
    Return kappa' at the end of a step for the spin rates ``spin`` reached (rad/s).

    ``update`` is the slip update of :func:`.forces.vehicle_forces` (UPDATE_ROWS): kappa'
    moves towards the steady slip of the new spin with the decay over the step.
    """
    target = (spin * update[3] - update[4]) / update[5]
    return target + (update[1] - target) * update[2]


@jit
def vehicle_step(q: np.ndarray, v: np.ndarray, swa: float, wheel_torque: np.ndarray,
                 slip: np.ndarray, previous: np.ndarray, has_previous: bool, h: float,
                 c: VehicleArrays, vx_floor: float, total_mass: float, road: bool,
                 dampers: bool, mb: MultibodyArrays
                 ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """
    Advance one step: (q, v, slip) at its end, the wheels' state (WHEEL_ROWS, 4) at its start.

    Arguments as :func:`.forces.vehicle_forces`; semi-implicit Euler on
    :func:`accelerations`, the slips moved as :class:`.model.SlipUpdate` says.
    """
    tau, wheel, update = vehicle_forces(q, v, swa, wheel_torque, slip, previous, has_previous,
                                        h, c, vx_floor, total_mass, road, dampers)
    q_next, v_next, slip_next = advance(q, v, accelerations(q, v, tau, mb), update, h)
    return q_next, v_next, slip_next, wheel


@jit
def advance(q: np.ndarray, v: np.ndarray, a: np.ndarray, update: np.ndarray, h: float
            ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """
    Return (q, v, slip) at the end of a step from its accelerations ``a``.

    Semi-implicit Euler, ``v+ = v + h a``, ``q+ = integrate(q, h v+)``; kappa' with the
    spin rates reached, alpha' as ``update`` (:func:`.forces.vehicle_forces`) says.
    """
    v_next = v + h * a
    q_next = integrate(q, h * v_next)
    slip_next = np.empty((2, 4))
    slip_next[0] = kappa_next(update, np.ascontiguousarray(v_next[7::2]))
    slip_next[1] = update[0]
    return q_next, v_next, slip_next


@jit
def observation(q: np.ndarray, v: np.ndarray) -> tuple[float, float, float]:
    """Return (yaw, horizontal speed of the body origin, course) of a state, rad and m/s."""
    rot = _rotation(q)
    vw = rot @ v[0:3]
    return (np.arctan2(rot[1, 0], rot[0, 0]), np.hypot(vw[0], vw[1]),
            np.arctan2(vw[1], vw[0]))


@jit
def record_row(q: np.ndarray, v: np.ndarray, t: float, swa: float, wheel: np.ndarray,
               cog: np.ndarray, torque: float) -> np.ndarray:
    """Return the recorded channels (simulation.TRACE) of a state, SI, ISO 8855 signs."""
    rot = _rotation(q)
    v_cog = rot @ (v[0:3] + _cross(v[3:6], cog))
    yaw = np.arctan2(rot[1, 0], rot[0, 0])
    roll = np.arcsin(max(-1.0, min(1.0, rot[2, 1])))
    pitch = -np.arcsin(max(-1.0, min(1.0, rot[2, 0])))
    omega_w = rot @ v[3:6]
    c, s = np.cos(yaw), np.sin(yaw)
    u = v_cog[0] * c + v_cog[1] * s
    w = -v_cog[0] * s + v_cog[1] * c
    return np.array([t, q[0], q[1], yaw, roll, pitch, omega_w[2], np.hypot(u, w),
                     np.arctan2(w, u), swa, wheel[7, 0], wheel[7, 1], v_cog[0], v_cog[1],
                     v_cog[2], torque])


@jit
def cosim_step(q: np.ndarray, v: np.ndarray, slip: np.ndarray, previous: np.ndarray,
               has_previous: bool, wheel: np.ndarray, row: np.ndarray, swa: float,
               drive: float, brake: float, drive_front: float, brake_front: float, t: float,
               h: float, c: VehicleArrays, vx_floor: float, total_mass: float, road: bool,
               dampers: bool, mb: MultibodyArrays, cog: np.ndarray) -> bool:
    """
    Advance a lock-step state one step in place: :func:`vehicle_step` under a command.

    The command: steering-wheel angle ``swa`` (rad), total ``drive`` and ``brake`` torques
    (N*m, >= 0) split by :func:`.drivers.wheel_torques`. Updated in place: ``q``, ``v``,
    ``slip`` (2, 4), ``previous`` (4, 4, the wheel rows PREVIOUS_ROWS), ``wheel``
    (WHEEL_ROWS, 4: the wheels' state at the step's start) and ``row[:ROW_SIZE]`` (the
    recorded channels of the new state, whose time is ``t``, as :func:`record_row`).
    Returns False, and writes nothing, when the new state is not finite.
    """
    spin = np.ascontiguousarray(v[7::2])
    torques = (wheel_torques(drive, drive_front, brake_front, spin)
               + wheel_torques(-brake, drive_front, brake_front, spin))
    q_next, v_next, slip_next, wheel_next = vehicle_step(
        q, v, swa, torques, slip, previous, has_previous, h, c, vx_floor, total_mass, road,
        dampers, mb)
    if not (np.all(np.isfinite(q_next)) and np.all(np.isfinite(v_next))):
        return False
    row[:ROW_SIZE] = record_row(q_next, v_next, t, swa, wheel_next, cog, drive - brake)
    q[:] = q_next
    v[:] = v_next
    slip[:] = slip_next
    wheel[:] = wheel_next
    for j in range(4):
        previous[j] = wheel_next[PREVIOUS_ROWS[j]]
    return True


@jit
def run_open_loop(q: np.ndarray, v: np.ndarray, slip: np.ndarray, previous: np.ndarray,
                  has_previous: bool, start: int, end: int, last: int, record_every: int,
                  h: float, swa: np.ndarray, pedals: np.ndarray, throttle: np.ndarray,
                  pressure: np.ndarray, reference: np.ndarray, reference_next: np.ndarray,
                  speed_gains: np.ndarray, integral: float, drive_front: float,
                  brake_front: float, systems: ActuationArrays, state: np.ndarray,
                  kappa: np.ndarray, c: VehicleArrays, vx_floor: float, total_mass: float,
                  road: bool, dampers: bool, mb: MultibodyArrays, cog: np.ndarray,
                  rows: np.ndarray, wheels: np.ndarray, actuation: np.ndarray):
    """
    Advance steps ``start`` .. ``end`` - 1 of a run of ``last`` steps (module doc).

    Step k (time k h): the drivers (``swa[k]`` rad; ``pedals[k]`` True: the pedals
    ``throttle[k]`` and ``pressure[k]`` Pa, else, when ``speed_gains`` (mass, radius, kp,
    ki) is not empty, the speed controller's torque law on ``reference[k]`` and
    ``reference_next[k]``, its value at k h + h, m/s), the wheel torques through the
    chassis's ``systems`` (:func:`.drivers.actuate`, its ``state`` and the previous step's
    slips ``kappa`` advanced in place), the forces, a recorded row into ``rows`` /
    ``wheels`` / ``actuation`` (throttle, gear, four line pressures Pa, four wheel torques
    N*m) when k is a multiple of ``record_every``, and, unless k = ``last``, the update.
    Returns (q, v, slip, previous, the next step, rows recorded, the controller's
    integral, the first step whose update became non-finite or -1).
    """
    n = 0
    k = start
    while k < end:
        t = k * h
        speed = observation(q, v)[1]
        request = 0.0
        if not pedals[k] and speed_gains.size:
            request, integral = speed_law(reference[k], reference_next[k], speed, integral,
                                          speed_gains[0], speed_gains[1], speed_gains[2],
                                          speed_gains[3], h)
        spin = np.ascontiguousarray(v[7::2])
        torques, lever, gear, lines = actuate(pedals[k], request, throttle[k], pressure[k],
                                              spin, kappa, speed, h, drive_front,
                                              brake_front, systems, state)
        q_next, v_next, slip_next, wheel = vehicle_step(
            q, v, swa[k], torques, slip, previous, has_previous, h, c, vx_floor, total_mass,
            road, dampers, mb)
        if k % record_every == 0:
            torque = np.sum(torques) if pedals[k] else request
            rows[n] = record_row(q, v, t, swa[k], wheel, cog, torque)
            wheels[n] = wheel
            actuation[n, 0] = lever
            actuation[n, 1] = gear
            actuation[n, 2:6] = lines
            actuation[n, 6:10] = torques
            n += 1
        if k == last:
            return q, v, slip, previous, k + 1, n, integral, -1
        if not (np.all(np.isfinite(q_next)) and np.all(np.isfinite(v_next))):
            return q, v, slip, previous, k + 1, n, integral, k
        q, v, slip = q_next, v_next, slip_next
        previous = np.empty((4, 4))
        for j in range(4):
            previous[j] = wheel[PREVIOUS_ROWS[j]]
        kappa[:] = wheel[KAPPA_ROW]
        has_previous = True
        k += 1
    return q, v, slip, previous, k, n, integral, -1


__all__ = ['MultibodyArrays', 'multibody_arrays', 'accelerations', 'integrate', 'kappa_next',
           'vehicle_step', 'cosim_step', 'advance', 'observation', 'record_row',
           'run_open_loop', 'PREVIOUS_ROWS', 'KAPPA_ROW', 'ROW_SIZE', 'ACTUATION_SIZE']
