# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The full vehicle's force evaluation of one step, as one compiled function on arrays.

:func:`vehicle_forces` is the physics of :meth:`.model.VehicleModel.forces` (the equations
are stated in :mod:`.model`'s doc): wheel kinematics from the body state, steer and camber
from the suspension maps and the compliances, tire loads, slips and their first-order
transients, the Magic Formula (:func:`vd_solvers.tire.magic_formula.four_wheel_forces`, the
one implementation), the contact wrenches mapped to the generalised forces, the linearly
implicit wheel spin, springs, anti-roll bars, dampers and jacking, and the aerodynamic
drag and lift (:mod:`vd_solvers.chassis.aero`'s equations on the body's x speed). It is
compiled with numba (:mod:`vd_solvers.compiled`); ``VD_NO_JIT=1`` runs it as Python.

The road (:func:`road_contact`) is a regular grid of heights z(x, y) over the earth plane
with bilinear interpolation (constant beyond its border) and a second grid of the friction
factor, both constant arrays of :class:`VehicleArrays` (:mod:`vd_solvers.road.arrays`
builds them from a surface). The tire meets the road through the tandem elliptical cam
enveloping model of Schmeitz (Schmeitz, Besselink & Jansen 2007, Vehicle System Dynamics
45 sup. 1; Pacejka, *Tire and Vehicle Dynamics*, 3rd ed. 2012, section 10.2): two cams
of half-length a_e, height b_e and order c_e, l_s apart along the wheel's heading, each
resting on the road (its lowest point at max over s of z(s) - b_e (1 - (1 - |s / a_e|^c_e)
^(1 / c_e))); the effective road height is their mean and the effective forward slope
their difference over l_s. The tire deflection and its damping are taken against the
effective height (the road's vertical speed under the wheel is the slope times V_x), and
the contact forces act in the effective road plane (F_z along its normal, F_x along its
forward line), which gives a short obstacle its longitudinal force. The friction factor at
the contact point scales the tire's LMUX and LMUY. The flat road (zero heights, friction
factor 1) gives every operation exactly the flat-road values.

Wheel order FL FR RL RR; SI; body frame ISO 8855 / REP 103 (x forward, y left, z up).
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np

from vd_solvers.compiled import jit
from vd_solvers.tire.magic_formula import (
    four_wheel_forces,
    four_wheel_springs,
    radii_at,
    relaxation_at,
)

from .maps import grid_lookup, half_difference

#: rows of the ``wheel`` array :func:`vehicle_forces` returns
WHEEL_ROWS = ('fz', 'fx', 'fy', 'mz', 'kappa', 'alpha', 'gamma', 'steer', 'travel')
#: rows of the ``update`` array: alpha' at the end of the step, kappa' at its start,
#: exp(-|V_x| h / sigma_kappa), R_e (m), V_x (m/s), max(|V_x|, floor) (m/s)
UPDATE_ROWS = ('alpha', 'kappa', 'decay', 'radius', 'vx', 'denominator')
#: rows of the per-wheel constant array (:class:`VehicleArrays`)
CONSTANT_ROWS = ('side', 'r0', 'cz', 'cd', 'mirror', 'unsprung', 'spin_inertia',
                 'unsprung_arm', 'slip_stiffness_static', 'static_load')
#: rows of the compliance / jacking array: steer per N of Fy, camber per N of Fy, steer per
#: N*m of Mz, steer per N of Fx braking / traction, d(pad force)/dFy, d(pad force)/dFx
#: braking / traction
COMPLIANCE_ROWS = ('steer_y', 'camber_y', 'steer_mz', 'steer_x_braking', 'steer_x_traction',
                   'jacking_y', 'jacking_x_braking', 'jacking_x_traction')
#: rows of the enveloping-cam array: half-length a_e (m), height b_e (m), order c_e,
#: spacing l_s of the two cams (m)
CAM_ROWS = ('half_length', 'height', 'order', 'spacing')
#: road samples along each half of a cam
CAM_POINTS = 24
#: entries of the road-grid axes array: the height grid's x0, y0, dx, dy and the friction
#: grid's x0, y0, dx, dy (m)
ROAD_AXES = ('height_x0', 'height_y0', 'height_dx', 'height_dy',
             'friction_x0', 'friction_y0', 'friction_dx', 'friction_dy')


#: the aerodynamic constants (:class:`VehicleArrays` ``aero``): 1/2 rho C_d A (kg/m),
#: 1/2 rho C_l A of the front and rear axle (kg/m), the axles' x and the drag's height
#: (the sprung centre of gravity's z), body frame, m; zeros: no aerodynamics
AERO_ROWS = ('drag', 'lift_front', 'lift_rear', 'x_front', 'x_rear', 'z_drag')


class VehicleArrays(NamedTuple):
    """The constant inputs of :func:`vehicle_forces` for one vehicle (contiguous float arrays)."""

    centres: np.ndarray  # (4, 3) design wheel centres, body frame, m
    wheel: np.ndarray  # (len(CONSTANT_ROWS), 4)
    tire_front: np.ndarray  # Magic Formula coefficient vectors
    tire_rear: np.ndarray
    travel0: np.ndarray  # suspension maps (maps.SuspensionMaps)
    travel_step: np.ndarray
    travel_table: np.ndarray
    arb0: np.ndarray
    arb_step: np.ndarray
    arb_table: np.ndarray  # (1, 4, GRID_POINTS)
    roll0: np.ndarray
    roll_step: np.ndarray
    roll_table: np.ndarray
    compliance: np.ndarray  # (len(COMPLIANCE_ROWS), 4)
    damper_front_x: np.ndarray
    damper_front_y: np.ndarray
    damper_rear_x: np.ndarray
    damper_rear_y: np.ndarray
    steer_swa: np.ndarray
    steer_left: np.ndarray
    steer_right: np.ndarray
    aero: np.ndarray  # (len(AERO_ROWS),)
    road_axes: np.ndarray  # (len(ROAD_AXES),) the road grids' origins and spacings, m
    road_height: np.ndarray  # (nx, ny) road heights, m, earth frame
    road_friction: np.ndarray  # (mx, my) friction factor (1: the tire as measured)
    cam: np.ndarray  # (len(CAM_ROWS), 4) the enveloping cams of each wheel


@jit
def grid_value(table: np.ndarray, x0: float, y0: float, dx: float, dy: float, x: float,
               y: float) -> float:
    """Bilinear value of a regular grid ``table`` (nx, ny) at (x, y), held beyond its border."""
    nx, ny = table.shape
    u = min(max((x - x0) / dx, 0.0), nx - 1.0)
    w = min(max((y - y0) / dy, 0.0), ny - 1.0)
    i = min(int(u), nx - 2)
    j = min(int(w), ny - 2)
    fu = u - i
    fw = w - j
    low = table[i, j] + fu * (table[i + 1, j] - table[i, j])
    high = table[i, j + 1] + fu * (table[i + 1, j + 1] - table[i, j + 1])
    return low + fw * (high - low)


@jit
def cam_height(table: np.ndarray, axes: np.ndarray, x: float, y: float, ch: float, sh: float,
               half_length: float, height: float, order: float) -> float:
    """Height of the lowest point of an elliptical cam centred at (x, y) resting on the road."""
    x0, y0, dx, dy = axes[0], axes[1], axes[2], axes[3]
    best = grid_value(table, x0, y0, dx, dy, x, y)
    for k in range(1, CAM_POINTS + 1):
        s = half_length * k / CAM_POINTS
        drop = height * (1.0 - (1.0 - (s / half_length) ** order) ** (1.0 / order))
        ahead = grid_value(table, x0, y0, dx, dy, x + s * ch, y + s * sh) - drop
        behind = grid_value(table, x0, y0, dx, dy, x - s * ch, y - s * sh) - drop
        best = max(best, ahead, behind)
    return best


@jit
def road_contact(table: np.ndarray, friction: np.ndarray, axes: np.ndarray, cam: np.ndarray,
                 x: np.ndarray, y: np.ndarray, ch: np.ndarray, sh: np.ndarray
                 ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """
    Effective road height (m), forward slope and friction factor under the four wheels.

    (x, y) the wheel centres' earth positions, (ch, sh) their headings' cosine and sine;
    the tandem cams of ``cam`` (module doc).
    """
    ground = np.empty(4)
    slope = np.empty(4)
    mu = np.empty(4)
    for w in range(4):
        a_e, b_e, c_e, l_s = cam[0, w], cam[1, w], cam[2, w], cam[3, w]
        ox, oy = 0.5 * l_s * ch[w], 0.5 * l_s * sh[w]
        front = cam_height(table, axes, x[w] + ox, y[w] + oy, ch[w], sh[w], a_e, b_e, c_e)
        rear = cam_height(table, axes, x[w] - ox, y[w] - oy, ch[w], sh[w], a_e, b_e, c_e)
        ground[w] = 0.5 * (front + rear)
        slope[w] = (front - rear) / l_s
        mu[w] = grid_value(friction, axes[4], axes[5], axes[6], axes[7], x[w], y[w])
    return ground, slope, mu



@jit
def _rotation(q: np.ndarray) -> np.ndarray:
    """World R body of the unit quaternion q[3:7] = (x, y, z, w)."""
    x, y, z, w = q[3], q[4], q[5], q[6]
    tx, ty, tz = 2.0 * x, 2.0 * y, 2.0 * z
    twx, twy, twz = tx * w, ty * w, tz * w
    txx, txy, txz = tx * x, ty * x, tz * x
    tyy, tyz, tzz = ty * y, tz * y, tz * z
    rot = np.empty((3, 3))
    rot[0, 0] = 1.0 - (tyy + tzz)
    rot[0, 1] = txy - twz
    rot[0, 2] = txz + twy
    rot[1, 0] = txy + twz
    rot[1, 1] = 1.0 - (txx + tzz)
    rot[1, 2] = tyz - twx
    rot[2, 0] = txz - twy
    rot[2, 1] = tyz + twx
    rot[2, 2] = 1.0 - (txx + tyy)
    return rot


@jit
def _rows_times(a: np.ndarray, m: np.ndarray) -> np.ndarray:
    """Return a @ m for a (n, 3), m (3, 3)."""
    out = np.empty((a.shape[0], 3))
    for i in range(a.shape[0]):
        for j in range(3):
            out[i, j] = a[i, 0] * m[0, j] + a[i, 1] * m[1, j] + a[i, 2] * m[2, j]
    return out


@jit
def _cross_rows(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Return a x b row by row, a and b (n, 3)."""
    out = np.empty_like(b)
    out[:, 0] = a[:, 1] * b[:, 2] - a[:, 2] * b[:, 1]
    out[:, 1] = a[:, 2] * b[:, 0] - a[:, 0] * b[:, 2]
    out[:, 2] = a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]
    return out


@jit
def _per_axle2(front: np.ndarray, rear: np.ndarray, fz: np.ndarray, x: np.ndarray
               ) -> tuple[np.ndarray, np.ndarray]:
    """Relaxation lengths of the four wheels, front tire on FL FR, rear on RL RR."""
    kf, af = relaxation_at(front, fz[:2], x[:2])
    kr, ar = relaxation_at(rear, fz[2:], x[2:])
    return np.concatenate((kf, kr)), np.concatenate((af, ar))


@jit
def wheel_radii(front: np.ndarray, rear: np.ndarray,
                fz: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(R_l, R_e) of the four wheels at loads ``fz`` (4,) N, at zero spin speed, m."""
    omega = np.zeros(2)
    lf, ef = radii_at(front, fz[:2], omega)
    lr, er = radii_at(rear, fz[2:], omega)
    return np.concatenate((lf, lr)), np.concatenate((ef, er))


@jit
def wheel_tires(front: np.ndarray, rear: np.ndarray, fz: np.ndarray, kappa: np.ndarray,
                alpha: np.ndarray, gamma: np.ndarray, vx: np.ndarray, mirror: np.ndarray,
                road_friction: np.ndarray | float = 1.0) -> np.ndarray:
    """
    (5, 4) Fx, Fy, Mx, My, Mz of the four wheels (file convention, ``mirror`` per wheel).

    ``road_friction`` is the road friction per wheel (or for all), the factor on the tire's
    LMUX and LMUY (:mod:`vd_solvers.tire.magic_formula`, "Road friction"); 1 is the tire's
    own.
    """
    return four_wheel_forces(front, rear, fz, kappa, alpha, gamma, vx, mirror, road_friction)


@jit
def vehicle_forces(q: np.ndarray, v: np.ndarray, swa: float, wheel_torque: np.ndarray,
                   slip: np.ndarray, previous: np.ndarray, has_previous: bool, h: float,
                   c: VehicleArrays, vx_floor: float, total_mass: float, road: bool,
                   dampers: bool) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """
    Generalised forces tau (nv,), the wheels' state (len(WHEEL_ROWS), 4) and the slip update.

    ``q``, ``v`` Pinocchio's configuration and velocity of :mod:`.model`; ``swa`` rad;
    ``wheel_torque`` (4,) N*m; ``slip`` (2, 4) transient [kappa', alpha'] at the start of the
    step; ``previous`` (4, 4) the previous step's Fx, Fy, Mz, steer per wheel (used when
    ``has_previous``; otherwise the slips start in the steady state). The update is
    (len(UPDATE_ROWS), 4).
    """
    side = c.wheel[0]
    r0, cd, mirror = c.wheel[1], c.wheel[3], c.wheel[4]
    unsprung, spin_inertia, unsprung_arm = c.wheel[5], c.wheel[6], c.wheel[7]
    slip_stiffness_static, static_load = c.wheel[8], c.wheel[9]
    comp = c.compliance
    rot = _rotation(q)  # world R body
    z = np.ascontiguousarray(q[7::2])
    zdot = np.ascontiguousarray(v[6::2])
    spin = np.ascontiguousarray(v[7::2])
    r = c.centres.copy()
    r[:, 2] += z  # wheel centres, body frame
    omega = np.empty((4, 3))
    omega[:, 0], omega[:, 1], omega[:, 2] = v[3], v[4], v[5]
    v_body = _cross_rows(omega, r)
    for k in range(3):
        v_body[:, k] += v[k]
    v_body[:, 2] += zdot  # wheel-centre velocity, body axes
    rot_t = np.ascontiguousarray(rot.T)
    p_world = _rows_times(r, rot_t)
    for k in range(3):
        p_world[:, k] += q[k]
    v_world = _rows_times(v_body, rot_t)
    tau = np.zeros(v.size)
    table = grid_lookup(c.travel_table, c.travel0, c.travel_step, z)
    half = half_difference(z)
    # --- tire kinematics
    steer = np.zeros(4)
    steer[0] = np.interp(swa, c.steer_swa, c.steer_left)
    steer[1] = np.interp(swa, c.steer_swa, c.steer_right)
    if has_previous:
        # body-axis tire forces and the aligning moments of the previous step for the
        # compliances
        p_fx, p_fy, p_steer = previous[0], previous[1], previous[3]
        fy_b = p_fx * np.sin(p_steer) + p_fy * np.cos(p_steer)
        fx_b = p_fx * np.cos(p_steer) - p_fy * np.sin(p_steer)
        mz_prev = previous[2].copy()
    else:
        fy_b = np.zeros(4)
        fx_b = np.zeros(4)
        mz_prev = np.zeros(4)
    roll = grid_lookup(c.roll_table, c.roll0, c.roll_step, half)
    steer_x = np.where(fx_b < 0.0, comp[3], comp[4])
    toe = table[1] + roll[0] + comp[0] * fy_b + steer_x * fx_b + comp[2] * mz_prev
    camber = table[2] + roll[1] + comp[1] * fy_b
    steer = steer - side * toe
    # the wheel's spin axis: body y turned by the inclination to the body (+ top to the
    # right, the .tir convention) about the wheel's heading, then by the steer about z
    lean = -side * camber
    cos_l = np.cos(lean)
    axis_b = np.empty((4, 3))
    axis_b[:, 0] = -np.sin(steer) * cos_l
    axis_b[:, 1] = np.cos(steer) * cos_l
    axis_b[:, 2] = np.sin(lean)
    axis = _rows_times(axis_b, rot_t)  # world
    gamma = np.arcsin(np.clip(axis[:, 2], -1.0, 1.0))
    # heading on the road: spin axis x road normal
    level = np.hypot(axis[:, 0], axis[:, 1])
    ch, sh = axis[:, 1] / level, -axis[:, 0] / level
    vx = v_world[:, 0] * ch + v_world[:, 1] * sh
    vy = -v_world[:, 0] * sh + v_world[:, 1] * ch
    ground, slope, mu = road_contact(c.road_height, c.road_friction, c.road_axes, c.cam,
                                     p_world[:, 0], p_world[:, 1], ch, sh)
    height = p_world[:, 2] - ground  # wheel centre above the effective road
    if road:
        # the tire's vertical force at its deflection: the 6.x load-deflection curve (with
        # the previous step's Fx, Fy) or the linear C_z, plus damping, >= 0 in contact
        tire_fx = previous[0] if has_previous else np.zeros(4)
        tire_fy = previous[1] if has_previous else np.zeros(4)
        spring = four_wheel_springs(c.tire_front, c.tire_rear, r0 - height, gamma, tire_fx,
                                    tire_fy, spin, mirror)
        # damping of the deflection rate, against the road's vertical speed under the wheel
        fz = np.where(spring > 0.0,
                      np.maximum(spring - cd * (v_world[:, 2] - slope * vx), 0.0), 0.0)
    else:
        fz = np.zeros(4)
    r_e = wheel_radii(c.tire_front, c.tire_rear, fz)[1]
    denom = np.maximum(np.abs(vx), vx_floor)
    kappa = (spin * r_e - vx) / denom
    alpha = np.arctan(vy / denom)
    sigma_k, sigma_a = _per_axle2(c.tire_front, c.tire_rear, fz, gamma)
    # The transient slips follow the steady ones with the time constant sigma / V, V the
    # same floored speed as in the slip definitions: at standstill the tire then acts as
    # a damper instead of freezing a slip (a limit cycle at rest).
    decay_k = np.where(sigma_k > 0.0, np.exp(-denom * h / np.maximum(sigma_k, 1e-9)), 0.0)
    decay_a = np.where(sigma_a > 0.0, np.exp(-denom * h / np.maximum(sigma_a, 1e-9)), 0.0)
    if has_previous:
        k_t = slip[0].copy()
        a_t = slip[1].copy()
    else:
        k_t = kappa.copy()  # start in the steady state
        a_t = alpha.copy()
    update = np.empty((6, 4))
    update[0] = alpha + (a_t - alpha) * decay_a
    update[1] = k_t
    update[2] = decay_k
    update[3] = r_e
    update[4] = vx
    update[5] = denom
    f = wheel_tires(c.tire_front, c.tire_rear, fz, k_t, a_t, gamma, vx, mirror, mu)
    f_x, f_y, m_x, m_y, m_z = f[0], f[1], f[2], f[3], f[4]
    wheel = np.empty((9, 4))
    wheel[0], wheel[1], wheel[2], wheel[3] = fz, f_x, f_y, m_z
    wheel[4], wheel[5], wheel[6], wheel[7], wheel[8] = k_t, a_t, gamma, steer, z
    # --- tire wrench (world) at the contact point, moment about the wheel centre; F_x
    # along the effective road plane's forward line, F_z along its normal
    cos_b = 1.0 / np.sqrt(1.0 + slope * slope)
    sin_b = slope * cos_b
    forward = f_x * cos_b - fz * sin_b
    force = np.empty((4, 3))
    force[:, 0] = forward * ch - f_y * sh
    force[:, 1] = forward * sh + f_y * ch
    force[:, 2] = f_x * sin_b + fz * cos_b
    # (contact point - wheel centre) x force, the lever being (0, 0, -height)
    moment = np.empty((4, 3))
    moment[:, 0] = height * force[:, 1] + m_x * ch - m_y * sh
    moment[:, 1] = -height * force[:, 0] + m_x * sh + m_y * ch
    moment[:, 2] = m_z
    force_b = _rows_times(force, rot)
    moment_b = _rows_times(moment, rot)
    # carrier Jacobian: body linear, body angular (about the origin), travel
    arm = _cross_rows(r, force_b) + moment_b
    for k in range(3):
        tau[k] = force_b[:, k].sum()
        tau[3 + k] = arm[:, k].sum()
    tau[6::2] = force_b[:, 2]
    # Linearly implicit wheel spin. With Fx linearised in the transient slip (slope K_x)
    # and kappa' advanced with the spin rate at the end of the step,
    #   I dw = h (T - R_e K_x ((1 - d)(kappa - kappa') + (1 - d) R_e dw / V)),
    # so dw = h T_eff / I with T_eff below. The explicit form is unstable for
    # h > V / (sigma omega_n^2) (omega_n of the spin/slip mode): 1.7 ms at 10 m/s.
    k_x = slip_stiffness_static * fz / static_load
    # the wheel-spin equation I dw/dt = T - R F_x + M_y: the contact force's moment
    # about the wheel's own spin axis plus the rolling-resistance moment M_y; the
    # aligning and overturning moments are about road axes and reach the body through
    # the bearing (M_z's share along a cambered axis would roll a car at rest)
    lever = height * force[:, 1] * axis[:, 0] - height * force[:, 0] * axis[:, 1]
    spin_torque = lever + m_y + wheel_torque
    lag = (1.0 - decay_k) * r_e * k_x
    tau[7::2] = (spin_torque - lag * (kappa - k_t)) * spin_inertia / (
        spin_inertia + h * lag * r_e / denom)
    # --- suspension
    suspension = table[0] + grid_lookup(c.arb_table, c.arb0, c.arb_step, half)[0]
    if dampers:
        ratio = table[3]
        damper = np.empty(4)
        for w in range(4):
            if w < 2:
                damper[w] = np.interp(ratio[w] * zdot[w], c.damper_front_x, c.damper_front_y)
            else:
                damper[w] = np.interp(ratio[w] * zdot[w], c.damper_rear_x, c.damper_rear_y)
        suspension = suspension + ratio * damper
    # The carriers slide along the body's z axis only, so an unsprung mass's lateral
    # inertia reaches the body at its wheel centre. In the car it is the links that
    # carry the tire force less that inertia (the force roll centre's jacking acts on
    # that share) while the unsprung mass's own overturning moment loads its tires
    # (the unsprung term of the load transfer): the lateral acceleration of the
    # previous step's tire forces restores both.
    inertia = unsprung * fy_b.sum() / total_mass
    jacking_x = np.where(force_b[:, 0] < 0.0, comp[6], comp[7])
    jacking = (comp[5] * (force_b[:, 1] - inertia) + jacking_x * force_b[:, 0]
               + unsprung_arm * inertia)
    if road:
        tau[6::2] -= suspension + jacking
    else:
        tau[6::2] -= suspension
    # --- aerodynamics in still air: drag against the body's x speed at the height z_drag,
    # lift (+ up) through each axle's line
    air = c.aero
    drag = -air[0] * v[0] * abs(v[0])
    lift_front = air[1] * v[0] * v[0]
    lift_rear = air[2] * v[0] * v[0]
    tau[0] += drag
    tau[2] += lift_front + lift_rear
    tau[4] += air[5] * drag - air[3] * lift_front - air[4] * lift_rear
    return tau, wheel, update


__all__ = ['vehicle_forces', 'wheel_radii', 'wheel_tires', 'VehicleArrays', 'WHEEL_ROWS',
           'AERO_ROWS', 'UPDATE_ROWS', 'CONSTANT_ROWS', 'COMPLIANCE_ROWS', 'CAM_ROWS',
           'CAM_POINTS', 'ROAD_AXES', 'grid_value', 'cam_height', 'road_contact']
