# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Steady-state cornering of the two-track vehicle, wheel by wheel.

The thesis' two-track model (:mod:`.two_track`, eqs. 3-9) gives the roll angle and the
wheel loads; its equal-slip axles and simple tire are where it stops. This model keeps
its roll and load transfer (eqs. 3-5, with the tires' vertical compliance, see
:func:`.two_track.roll_geometry`) and solves the planar equilibrium of the four wheels
on a circle of radius R at speed V (r = V/R, a_y = V r), each wheel with

* its steer: the road-wheel angle of the K&C steering map at the steering-wheel angle
  (Ackermann included) for the front wheels, the static toe of the alignment group,
  roll steer times the suspension's roll (body roll less the axle's roll on its tires),
  lateral-force and aligning-moment compliance steer of its own forces (K&C, linear);
* its inclination to the road: static camber, roll camber, compliance camber (same
  sources), :class:`AxleCompliance` signs;
* its load (eq. 5; between the axles m (-r v) h / L, the centripetal acceleration's
  part along the body with the sideslip, and sum M_y cos(delta) / L, the tires'
  rolling-resistance moments: the contact pressure's centre ahead of each wheel centre,
  about the body's y axis, unloads the front axle and loads the rear, the body's pitch
  balance as in the full vehicle) and the full Magic Formula of its axle's .tir
  (combined slip, aligning and rolling-resistance moments; the side it is mounted on
  mirrored as in the full vehicle);
* its slip from the body's motion: the wheel-centre velocity (u - r y, v + r x) in the
  wheel's heading;
* its longitudinal force: a share of the drive torque (``drive_front`` to the front,
  open differentials) plus the rolling-resistance moment, over the loaded radius (the
  wheel-spin balance; the slip ratio that gives it, with the .tir's shifts, by Newton).

Unknowns: steering-wheel angle, body sideslip, drive torque, each wheel's lateral
force and aligning moment and the front axle's load from the rolling-resistance moments;
equations: the longitudinal (m a_x = -m r v), lateral (m r u) and yaw (0) balances of the
body at the CoG, each wheel's force and moment equal to its tire's and that load equal
to sum M_y cos(delta) / L (Powell's hybrid method, scipy ``fsolve``). Residuals are recomputed
from the returned state in the tests.

The understeer gradient is, as for the full vehicle (ISO 4138), the least-squares slope
over LINEAR_RANGE of the excess steer delta_sw / i_s - L / R at GRADIENT_POINTS lateral
accelerations; the roll and sideslip gradients likewise. What the thesis' model and the
bicycle budget leave out and this one holds is listed, with the size of each, by
:mod:`.ladder`.
"""
from __future__ import annotations

from dataclasses import dataclass, replace
import math

import numpy as np
from scipy import optimize

from vd_solvers.analytical.params import AxleCompliance, VehicleParams
from vd_solvers.analytical.two_track import roll_angle, roll_state
from vd_solvers.errors import BeyondLimitError, SolverError
from vd_solvers.kc.steering_map import SteeringMap
from vd_solvers.tire.magic_formula import MagicFormula

#: lateral-acceleration range of the gradients (the full vehicle's), m/s^2
LINEAR_RANGE = (1.0, 3.0)
#: steady states the gradients are fitted through
GRADIENT_POINTS = 5
#: lateral accelerations of the slope at a_y -> 0 (where the tires and the load transfer
#: are linear to 0.1 %), m/s^2
ORIGIN_RANGE = (0.02, 0.1)
#: side sign per wheel FL FR RL RR: +1 left, -1 right
SIDE = np.array([1.0, -1.0, 1.0, -1.0])
#: relative residual the steady state must reach
TOLERANCE = 1e-10
#: Newton steps on each wheel's slip ratio (the force is nearly linear in it here)
KAPPA_ITERATIONS = 3


@dataclass(frozen=True)
class Effects:
    """What the model holds (defaults: everything); the ladder switches them off one by one."""

    aligning_moment: bool = True  # the tires' aligning moments in the yaw balance
    # drive and rolling resistance: their yaw moment, and the rolling-resistance moments'
    # pitch (load from the front axle to the rear)
    longitudinal: bool = True
    # False: no lateral or inertial load transfer (the wheels at their static loads but
    # for the rolling-resistance moments' pitch, a longitudinal effect)
    load_transfer: bool = True
    steering_map: bool = True  # False: both front wheels at delta_sw / i_s


@dataclass(frozen=True, eq=False)
class CorneringVehicle:
    """
    Everything the model needs: parameters, tires, alignment, steering map.

    ``toe`` (4,) static toe-in and ``camber`` (4,) static camber (top outward) per wheel,
    rad; ``tires`` the front and rear Magic Formula.
    """

    params: VehicleParams
    tires: tuple[MagicFormula, MagicFormula]
    toe: np.ndarray
    camber: np.ndarray
    steering: SteeringMap
    drive_front: float = 0.5
    effects: Effects = Effects()

    def with_effects(self, **changes: bool) -> CorneringVehicle:
        return replace(self, effects=replace(self.effects, **changes))


@dataclass(frozen=True, eq=False)
class CorneringPoint:
    """One steady state; per-wheel arrays (4,) in FL FR RL RR order, SI, ISO 8855."""

    radius: float
    speed: float
    lateral_acceleration: float  # V r
    steering_wheel_angle: float
    sideslip: float  # at the CoG
    roll: float
    drive_torque: float  # N*m, all four wheels
    steer: np.ndarray  # road-wheel angle of each wheel, + left
    slip_angle: np.ndarray  # + gives a force to the left
    inclination: np.ndarray  # .tir convention, + top to the right
    load: np.ndarray
    force_x: np.ndarray  # wheel axes
    force_y: np.ndarray
    aligning_moment: np.ndarray
    rolling_moment: np.ndarray  # M_y about the wheel's spin axis, N*m (< 0 resists rolling)
    residual: np.ndarray  # the balances at the solution, relative

    def excess_steer(self, ratio: float, wheelbase: float) -> float:
        """delta_sw / i_s - L / R, rad."""
        return self.steering_wheel_angle / ratio - wheelbase / self.radius


def _mirror(tire: MagicFormula) -> np.ndarray:
    measured = str(tire.props.get('MODEL', 'TYRESIDE', 'LEFT')).upper()
    left = 1.0 if measured == 'LEFT' else -1.0
    return np.array([left, -left])


def _compliance(p: VehicleParams) -> tuple[AxleCompliance, ...]:
    return (p.compliance_front, p.compliance_front, p.compliance_rear, p.compliance_rear)


def steady_state(vehicle: CorneringVehicle, lateral_acceleration: float,
                 radius: float) -> CorneringPoint:
    """
    Steady state at ``lateral_acceleration`` (m/s^2, > 0) on a left circle of ``radius`` (m).

    Raises BeyondLimitError when no steady state is found (beyond the axles' limit).
    """
    p = vehicle.params
    fx_on = vehicle.effects.longitudinal
    a_y = float(lateral_acceleration)
    speed = math.sqrt(a_y * radius)
    r = speed / radius
    a, b = p.cog_to_front_axle, p.cog_to_rear_axle
    x = np.array([a, a, -b, -b])
    y = 0.5 * np.array([p.track_front, -p.track_front, p.track_rear, -p.track_rear])
    if vehicle.effects.load_transfer:
        phi, transfer, tilt = roll_state(p, a_y)
        half = np.array([p.axle_load_front, p.axle_load_front, p.axle_load_rear,
                         p.axle_load_rear]) / 2.0
        load = half + np.array([-transfer[0], transfer[0], -transfer[1], transfer[1]])
    else:
        phi = float(roll_angle(p, a_y))
        tilt = np.zeros(2)
        load = np.array([p.axle_load_front, p.axle_load_front, p.axle_load_rear,
                         p.axle_load_rear]) / 2.0
    if np.any(load <= 0.0):
        raise BeyondLimitError(f'an inner wheel lifts at a_y = {a_y:.4g} m/s^2')
    axle_tilt = np.repeat(tilt, 2)  # the axles' roll on their tires, rad
    suspension_roll = phi - axle_tilt
    comp = _compliance(p)
    roll_steer = np.array([c.roll_steer for c in comp]) * suspension_roll
    roll_lean = (np.array([c.roll_camber for c in comp]) * suspension_roll - axle_tilt)
    c_y = np.array([c.lateral_compliance_steer for c in comp])
    c_mz = np.array([c.aligning_torque_compliance_steer for c in comp])
    chi = np.array([c.lateral_compliance_camber for c in comp])
    static_steer = -SIDE * vehicle.toe
    static_lean = SIDE * vehicle.camber
    tires = vehicle.tires
    mirror = np.concatenate([_mirror(tires[0]), _mirror(tires[1])])
    radii = np.concatenate([tires[0].radii(load[:2])[0], tires[1].radii(load[2:])[0]])
    k_x = np.concatenate([tires[0].slip_stiffness(load[:2]), tires[1].slip_stiffness(load[2:])])
    share = np.array([vehicle.drive_front, vehicle.drive_front, 1.0 - vehicle.drive_front,
                      1.0 - vehicle.drive_front]) / 2.0
    weight = p.mass * p.g
    ratio = vehicle.steering.ratio

    def tire(fz, kappa, alpha, gamma, vx):
        out = [t.steady_state(fz[s], kappa[s], alpha[s], gamma[s], vx[s], mirror=mirror[s])
               for t, s in zip(tires, (slice(0, 2), slice(2, 4)))]
        return type(out[0])(*(np.concatenate([f, r_]) for f, r_ in zip(*out)))

    def state(z: np.ndarray):
        swa, beta, torque = z[0], z[1], z[2] * weight * radii.mean()
        u, v = speed * math.cos(beta), speed * math.sin(beta)
        if vehicle.effects.load_transfer:
            # the centripetal acceleration's body-x part -r v at the CoG height moves
            # load between the axles (second order: v grows with a_y)
            pitch = p.mass * (-r * v) * p.cog_height / p.wheelbase / 2.0
            fz = load + np.array([-pitch, -pitch, pitch, pitch])
        else:
            fz = load
        if fx_on:
            # the rolling-resistance moments' pitch: the front axle's load changes by
            # sum M_y cos(delta) / L (z[11], solved with the tires' M_y at these loads)
            fz = fz + np.array([0.5, 0.5, -0.5, -0.5]) * z[11] * weight
        fy_w, mz_w = z[3:7] * weight, z[7:11] * weight * p.wheelbase
        steer = static_steer + roll_steer
        if vehicle.effects.steering_map:
            steer[:2] += vehicle.steering.road_wheel_angles(swa)
        else:
            steer[:2] += swa / ratio
        # compliance from the wheel's own force along body y and its aligning moment
        f_body_y = fy_w * np.cos(steer)
        steer = steer + c_y * f_body_y + c_mz * mz_w
        lean = static_lean + roll_lean - chi * f_body_y
        gamma = -lean
        wx, wy = u - r * y, v + r * x
        vx = wx * np.cos(steer) + wy * np.sin(steer)
        vy = -wx * np.sin(steer) + wy * np.cos(steer)
        alpha_t = np.arctan2(vy, np.abs(vx))  # .tir convention
        kappa = np.zeros(4)
        f = tire(fz, kappa, alpha_t, gamma, vx)
        if fx_on:
            # the wheel spins until its force is (T + M_y) / R_l: Newton on the slip ratio
            for _ in range(KAPPA_ITERATIONS):
                target = (share * torque + f.my) / radii
                kappa = kappa + (target - f.fx) / k_x
                f = tire(fz, kappa, alpha_t, gamma, vx)
        fx = f.fx if fx_on else np.zeros(4)
        return steer, alpha_t, gamma, fx, f, fy_w, mz_w, u, v, fz

    def residual(z: np.ndarray) -> np.ndarray:
        steer, _, _, fx, f, fy_w, mz_w, u, v, _ = state(z)
        cs, sn = np.cos(steer), np.sin(steer)
        fxb = fx * cs - fy_w * sn
        fyb = fx * sn + fy_w * cs
        yaw = np.sum(x * fyb - y * fxb)
        if vehicle.effects.aligning_moment:
            yaw += np.sum(mz_w)
        pitch = (z[11] * weight * p.wheelbase - np.sum(f.my * cs) if fx_on
                 else z[11] * weight * p.wheelbase)
        return np.concatenate([
            [(np.sum(fxb) + p.mass * r * v) / weight if fx_on else z[2],
             (np.sum(fyb) - p.mass * r * u) / weight,
             yaw / (weight * p.wheelbase)],
            (fy_w - f.fy) / weight, (mz_w - f.mz) / (weight * p.wheelbase),
            [pitch / (weight * p.wheelbase)]])

    guess = _guess(vehicle, a_y, radius, load, weight)
    solution, info, flag, message = optimize.fsolve(residual, guess, full_output=True,
                                                    xtol=1e-13)
    res = residual(solution)
    if flag != 1 or np.max(np.abs(res)) > TOLERANCE:
        raise BeyondLimitError(f'no steady state at a_y = {a_y:.4g} m/s^2 on {radius:g} m '
                               f'({message.strip()})')
    steer, alpha_t, gamma, fx, f, fy_w, mz_w, u, v, load = state(solution)
    return CorneringPoint(
        radius=radius, speed=speed, lateral_acceleration=a_y,
        steering_wheel_angle=float(solution[0]), sideslip=float(solution[1]),
        roll=float(phi), drive_torque=float(solution[2] * weight * radii.mean()),
        steer=steer, slip_angle=-alpha_t, inclination=gamma, load=load, force_x=fx,
        force_y=fy_w, aligning_moment=mz_w, rolling_moment=f.my if fx_on else np.zeros(4),
        residual=res)


def _guess(vehicle: CorneringVehicle, a_y: float, radius: float, load: np.ndarray,
           weight: float) -> np.ndarray:
    """Start from the linear single track with the bare tires."""
    p = vehicle.params
    c = np.concatenate([-vehicle.tires[0].cornering_stiffness(load[:2]),
                        -vehicle.tires[1].cornering_stiffness(load[2:])])
    front = p.mass * a_y * p.cog_to_rear_axle / p.wheelbase
    rear = p.mass * a_y * p.cog_to_front_axle / p.wheelbase
    alpha_f, alpha_r = front / c[:2].sum(), rear / c[2:].sum()
    delta = p.wheelbase / radius + alpha_f - alpha_r
    beta = p.cog_to_rear_axle / radius - alpha_r
    fy = np.concatenate([c[:2] * alpha_f, c[2:] * alpha_r])
    return np.concatenate([[delta * vehicle.steering.ratio, beta, 0.0], fy / weight,
                           np.zeros(5)])


@dataclass(frozen=True)
class Gradients:
    """Least-squares slopes over LINEAR_RANGE, rad/(m/s^2), and the points they came from."""

    understeer: float
    roll: float
    sideslip: float
    points: tuple[CorneringPoint, ...]


def gradients(vehicle: CorneringVehicle, radius: float,
              lateral_accelerations: tuple[float, float] = LINEAR_RANGE) -> Gradients:
    """Understeer, roll and sideslip gradients on ``radius`` (module doc)."""
    a_y = np.linspace(*lateral_accelerations, GRADIENT_POINTS)
    points = tuple(steady_state(vehicle, float(a), radius) for a in a_y)
    p = vehicle.params
    excess = [q.excess_steer(vehicle.steering.ratio, p.wheelbase) for q in points]

    def slope(values) -> float:
        return float(np.polyfit(a_y, values, 1)[0])

    return Gradients(slope(excess), slope([q.roll for q in points]),
                     slope([q.sideslip for q in points]), points)


def range_terms(vehicle: CorneringVehicle, radius: float) -> dict[str, tuple[float, str]]:
    """
    Return the budget's terms second order in a_y, rad/(m/s^2), with their source.

    ``load_transfer``: the gradient over LINEAR_RANGE less that with every wheel at its
    static load; ``tire_nonlinearity``: the latter less the slope at a_y -> 0
    (ORIGIN_RANGE) at static loads.
    """
    full = gradients(vehicle, radius).understeer
    static = vehicle.with_effects(load_transfer=False)
    at_static = gradients(static, radius).understeer
    origin = gradients(static, radius, ORIGIN_RANGE).understeer
    where = (f'two-track wheel by wheel (cornering.py) on {radius:g} m, '
             f'{LINEAR_RANGE[0]:g}..{LINEAR_RANGE[1]:g} m/s^2')
    return {'load_transfer': (full - at_static, f'{where}: with the loads less at static loads'),
            'tire_nonlinearity': (at_static - origin,
                                  f'{where} at static loads less the slope at a_y -> 0')}


def yaw_rate_gain(vehicle: CorneringVehicle, speed: float, lateral_acceleration: float
                  ) -> float:
    """Steady yaw rate over steering-wheel angle, 1/s, at a speed and lateral acceleration."""
    if not (speed > 0.0 and lateral_acceleration > 0.0):
        raise SolverError(f'yaw-rate gain needs a positive speed and lateral acceleration, '
                          f'got {speed!r} m/s, {lateral_acceleration!r} m/s^2')
    radius = speed**2 / lateral_acceleration
    point = steady_state(vehicle, lateral_acceleration, radius)
    return (speed / radius) / point.steering_wheel_angle


__all__ = ['LINEAR_RANGE', 'ORIGIN_RANGE', 'GRADIENT_POINTS', 'Effects', 'CorneringVehicle',
           'CorneringPoint', 'Gradients', 'steady_state', 'gradients', 'range_terms',
           'yaw_rate_gain']
