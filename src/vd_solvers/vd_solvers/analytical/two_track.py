# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Steady-state two-track model with body roll, thesis 3.1.2 eqs. 3-9.

For a lateral acceleration a_y on a circle of radius R (V^2/R = a_y):

* roll angle (eq. 3)::

      phi = m_s a_y h1 / (K_phi - m_s g h1)

  h1: height of the sprung COG above the roll axis, the axis interpolated
  linearly between the front and rear roll centres at the sprung COG's x;
* lateral load transfer per axle (eq. 4)::

      dF_zf = (M_f a_y h_f + K_phi_f phi + m_uf a_y h_uf) / t_f

  M_f, M_r: the sprung mass split by its weight distribution; h_f, h_r:
  roll-centre heights; m_u, h_u: unsprung mass and its COG height;
* wheel loads (eq. 5): F_z = N/2 -/+ dF_z on the inner/outer wheel;
* the tires' vertical compliance (``tire_vertical_stiffness_*``, the .tir's; 0, the
  thesis' rigid tires, by default): each axle rolls on its tires by
  psi_i = dF_zi t_i / K_ti, K_ti = C_z t_i^2 / 2, so its suspension rolls by phi - psi_i
  only. With r_i = K_phi_i / (K_phi_i + K_ti) the load transfer becomes
  dF_zi t_i = (M_geo,i + K_phi_i phi)(1 - r_i) and the body's balance
  m_s h1 (a_y + g phi) = sum K_phi_i (phi - psi_i) gives::

      phi = (m_s h1 + sum r_i M_geo,i / a_y) a_y / (sum K_phi_i (1 - r_i) - m_s g h1)

  (M_geo,i = M_i a_y h_i + m_ui a_y h_ui, eq. 4's geometric part): the springs and the
  tires in series, and the geometric load transfer rolling the axles on their tires;
* the spinning wheels' gyroscopic moment (``wheel_gyroscopic_*`` = I_spin / R per
  wheel; 0 by default): each wheel's spin momentum I_spin V / R turned at the yaw rate
  V / R_turn rolls the body outward by sum (I_spin / R) a_y, added to m_s h1 a_y;
* load-dependent friction, cornering stiffness and lateral force per wheel
  (eqs. 6-9, :class:`~vd_solvers.tire.simple.SimpleTire`).

Each axle must carry the force that balances the vehicle's lateral inertia
and yaw moment, F_yf = m a_y b/L and F_yr = m a_y a/L; the one slip angle the
axle's two wheels share (the thesis' equal inner/outer slip simplification)
is solved for with a bracketing root finder.  Steer angle: delta = L/R +
alpha_f - alpha_r (Gillespie, "Fundamentals of Vehicle Dynamics", eq. 6-7).

Unsprung masses.  The thesis writes eqs. 3-4 with the total mass m and no
unsprung term; with m_u = 0 (the parameter default) this module reproduces
them exactly.  With unsprung masses it uses the sprung mass m_s = m - m_uf -
m_ur in the roll and roll-centre terms and adds the unsprung term (Milliken &
Milliken, "Race Car Vehicle Dynamics", ch. 18), so that the load transfer
balances the overturning moment m a_y h + m_s g h1 phi exactly.

Signs: ISO 8855.  a_y, R and delta are positive in a left turn; the roll
angle then is positive too (body leans outward, to the right).  Wheels are
ordered as :data:`WHEELS`; in a left turn the right wheels are the outer,
more heavily loaded ones.  Slip angles and lateral forces follow the tire
model's convention, positive in a left turn.  The vehicle is left/right
symmetric, so a right turn mirrors a left turn.

Inner-wheel lift.  When the load transfer of one axle reaches its inner
wheel's static load, that wheel leaves the ground and the outer wheel carries
the whole axle load; the axle's suspension can then resist no more roll
moment than it does at lift-off, so the body rolls further against the other
axle's roll stiffness alone::

    m_s h1 (a_y + g phi) = (N_f t_f / 2 - M_f a_y h_f - m_uf a_y h_uf) + K_phi_r phi

(front lifted; the rear mirrors it), which keeps the overturning-moment
balance exact.  The steady state continues until an axle saturates; when the
other axle's inner wheel lifts too the vehicle rolls over, and there the model
ends (limit cause ``rollover``).

Compliance (``VehicleParams.compliance_front/_rear``, see ``budget.py``).  The
wheels of an axle steer by ``c F_w + roll_steer phi - c_Mz t F_w`` (F_w = the
axle force / 2) and lean towards +y by ``roll_camber phi -
lateral_compliance_camber F_w``, which gives each tire the camber thrust
``C_gamma lean``.  The tires carry the rest of the axle force at the shared
tire slip angle; the axle's kinematic slip (what enters delta) is the tire slip
minus the steer change.  With zero compliance both slips are the same.

Beyond an axle's peak force the model has no steady state: it raises
:class:`~vd_solvers.errors.BeyondLimitError` rather than return numbers, as it
does when both inner wheels have lifted (rollover).
"""
from __future__ import annotations

from dataclasses import dataclass
import math
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike
from scipy import optimize

from vd_solvers.analytical.params import VehicleParams
from vd_solvers.errors import BeyondLimitError, SolverError
from vd_solvers.tire.simple import SimpleTire

Axle = Literal['front', 'rear']
AXLES: tuple[Axle, Axle] = ('front', 'rear')
LimitCause = Literal['saturation', 'rollover']

WHEELS = ('front_left', 'front_right', 'rear_left', 'rear_right')

SLIP_TOLERANCE = 1e-13  # rad, root-finder tolerance; keeps force residuals ~1e-8 N
# rad, axle force peak search; the peak is flat, force error ~1e-15 relative
PEAK_TOLERANCE = 1e-10
LIMIT_TOLERANCE = 1e-4  # m/s^2, width of the final bisection bracket on the maximum a_y
LIMIT_MAX_DOUBLINGS = 8  # growth steps from 1 g for an infeasible upper bracket (256 g)
LINEAR_FIT_LIMIT = 1.0  # m/s^2, upper end of the linear-range fit of the understeer gradient
LINEAR_FIT_SAMPLES = 16  # points in that fit
HANDLING_DIAGRAM_POINTS = 50  # default a_y steps from 0 to the limit


@dataclass(frozen=True)
class RollGeometry:
    """Sprung-body quantities behind eqs. 3-4."""

    sprung_mass: float  # m_s, kg
    sprung_mass_front: float  # M_f of eq. 4, kg
    sprung_mass_rear: float  # M_r of eq. 4, kg
    sprung_cog_height: float  # m
    roll_axis_height: float  # m, roll axis below the sprung COG
    roll_arm: float  # h1 of eq. 3, m
    roll_gradient: float  # d(phi)/d(a_y), rad/(m/s^2)


@dataclass(frozen=True)
class CorneringLimit:
    """Largest steady lateral acceleration and what ends it."""

    radius: float  # m, positive for a left turn
    lateral_acceleration: float  # m/s^2, signed like the radius
    speed: float  # m/s
    limiting_axle: Axle
    cause: LimitCause

    @property
    def behaviour(self) -> str:
        """'limit understeer' (front saturates), 'limit oversteer' (rear) or 'rollover'."""
        if self.cause == 'rollover':
            return 'rollover'
        return 'limit understeer' if self.limiting_axle == 'front' else 'limit oversteer'


# Holds numpy arrays, whose element-wise == makes a generated __eq__ useless.
@dataclass(frozen=True, eq=False)
class TwoTrackPoint:
    """Steady state at one lateral acceleration.  Per-wheel arrays (4,), :data:`WHEELS` order."""

    radius: float  # m
    lateral_acceleration: float  # m/s^2
    speed: float  # m/s
    steer_angle: float  # rad, road wheel
    slip_angle_front: float  # rad, the axle's kinematic slip (tire slip - steer change)
    slip_angle_rear: float  # rad
    roll_angle: float  # rad
    wheel_loads: np.ndarray  # N (eq. 5), 0 on a lifted wheel
    friction: np.ndarray  # - (eq. 6)
    cornering_stiffness: np.ndarray  # N/rad (eq. 7)
    lateral_force: np.ndarray  # N (eq. 9 plus camber thrust)
    tire_slip_angle: np.ndarray  # rad, slip angle of each tire

    @property
    def axle_force_front(self) -> float:
        """Front axle lateral force, N."""
        return float(self.lateral_force[0] + self.lateral_force[1])

    @property
    def axle_force_rear(self) -> float:
        """Rear axle lateral force, N."""
        return float(self.lateral_force[2] + self.lateral_force[3])


# Holds numpy arrays, whose element-wise == makes a generated __eq__ useless.
@dataclass(frozen=True, eq=False)
class HandlingDiagram:
    """
    Steady states from a_y = 0 up to the limit on one radius.

    Arrays have shape (n,) or, per wheel in :data:`WHEELS` order, (n, 4).
    """

    radius: float  # m
    lateral_acceleration: np.ndarray  # m/s^2
    speed: np.ndarray  # m/s
    steer_angle: np.ndarray  # rad
    slip_angle_front: np.ndarray  # rad
    slip_angle_rear: np.ndarray  # rad
    roll_angle: np.ndarray  # rad
    wheel_loads: np.ndarray  # N, (n, 4)
    friction: np.ndarray  # -, (n, 4)
    cornering_stiffness: np.ndarray  # N/rad, (n, 4)
    lateral_force: np.ndarray  # N, (n, 4)
    limit: CorneringLimit

    @property
    def slip_angle_difference(self) -> np.ndarray:
        """alpha_f - alpha_r, rad: the handling diagram's abscissa."""
        return self.slip_angle_front - self.slip_angle_rear

    @property
    def axle_force_front(self) -> np.ndarray:
        """Front axle lateral force, N, (n,)."""
        return self.lateral_force[:, 0] + self.lateral_force[:, 1]

    @property
    def axle_force_rear(self) -> np.ndarray:
        """Rear axle lateral force, N, (n,)."""
        return self.lateral_force[:, 2] + self.lateral_force[:, 3]


def roll_geometry(p: VehicleParams) -> RollGeometry:
    """
    Sprung mass, its axle split, roll arm h1 and roll gradient (eq. 3).

    Raises SolverError when K_phi <= m_s g h1: the roll stiffness cannot hold
    the body against the gravity moment of its own roll (roll instability).
    """
    length = p.wheelbase
    sprung = p.mass - p.unsprung_mass_front - p.unsprung_mass_rear
    # Unsprung masses sit at the axles (x = 0 and x = L from the front axle).
    sprung_x = (p.mass * p.cog_to_front_axle - p.unsprung_mass_rear * length) / sprung
    sprung_height = (
        p.mass * p.cog_height
        - p.unsprung_mass_front * p.unsprung_cog_height_front
        - p.unsprung_mass_rear * p.unsprung_cog_height_rear
    ) / sprung
    axis_height = p.roll_centre_height_front + (
        p.roll_centre_height_rear - p.roll_centre_height_front
    ) * sprung_x / length
    roll_arm = sprung_height - axis_height
    stiffness = sum(_roll_stiffness(p, axle) * (1.0 - _tire_share(p, axle)) for axle in AXLES)
    net_stiffness = stiffness - sprung * p.g * roll_arm
    if net_stiffness <= 0.0:
        raise SolverError(
            f'roll instability: roll stiffness {stiffness:.6g} N*m/rad does not exceed '
            f'm_s g h1 = {sprung * p.g * roll_arm:.6g} N*m/rad (h1 = {roll_arm:.4g} m)'
        )
    front, rear = sprung * (length - sprung_x) / length, sprung * sprung_x / length
    # the geometric load transfer per m/s^2 rolls the axles on their tires, and the
    # spinning wheels' gyroscopic moment (I_spin omega r = I_spin / R a_y) rolls the body
    gyroscopic = 2.0 * (p.wheel_gyroscopic_front + p.wheel_gyroscopic_rear)
    tilt = gyroscopic + (_tire_share(p, 'front') * (front * p.roll_centre_height_front
                                       + p.unsprung_mass_front * p.unsprung_cog_height_front)
            + _tire_share(p, 'rear') * (rear * p.roll_centre_height_rear
                                        + p.unsprung_mass_rear * p.unsprung_cog_height_rear))
    return RollGeometry(
        sprung_mass=sprung,
        sprung_mass_front=front,
        sprung_mass_rear=rear,
        sprung_cog_height=sprung_height,
        roll_axis_height=axis_height,
        roll_arm=roll_arm,
        roll_gradient=(sprung * roll_arm + tilt) / net_stiffness,
    )


def _tire_stiffness(p: VehicleParams, axle: Axle) -> float:
    """Roll stiffness of the axle's two tires, C_z t^2 / 2, N*m/rad (0: rigid tires)."""
    c_z = p.tire_vertical_stiffness_front if axle == 'front' else p.tire_vertical_stiffness_rear
    return c_z * _track(p, axle) ** 2 / 2.0


def _tire_share(p: VehicleParams, axle: Axle) -> float:
    """Share r = K_phi / (K_phi + K_t) of the axle's roll its tires take (0 if rigid)."""
    k_t = _tire_stiffness(p, axle)
    if k_t == 0.0:
        return 0.0
    k_phi = _roll_stiffness(p, axle)
    return k_phi / (k_phi + k_t)


def roll_angle(p: VehicleParams, lateral_acceleration: ArrayLike) -> np.ndarray:
    """
    Return the body roll angle, rad, for any shape of a_y (m/s^2) (eq. 3).

    Beyond an inner wheel's lift the lifted axle resists no further roll (module doc).
    """
    return _roll_state(p, lateral_acceleration)[0]


def load_transfer(p: VehicleParams, lateral_acceleration: ArrayLike) -> np.ndarray:
    """
    Lateral load transfer per axle (front, rear), N, shape (..., 2) (eq. 4).

    Signed like a_y: positive values load the right wheels. An axle whose
    inner wheel has lifted transfers its whole static load N/2.  Where both
    inner wheels would lift (rollover) the values are nan.
    """
    _, front, rear = _roll_state(p, lateral_acceleration)
    return np.stack([front, rear], axis=-1)


def wheel_loads(p: VehicleParams, lateral_acceleration: ArrayLike) -> np.ndarray:
    """Vertical wheel loads, N, shape (..., 4) in :data:`WHEELS` order (eq. 5)."""
    transfer = load_transfer(p, lateral_acceleration)
    front, rear = transfer[..., 0], transfer[..., 1]
    half_front, half_rear = p.axle_load_front / 2.0, p.axle_load_rear / 2.0
    return np.stack([half_front - front, half_front + front, half_rear - rear, half_rear + rear],
                    axis=-1)


def wheel_lift_onset(p: VehicleParams) -> tuple[Axle, float] | None:
    """
    Return the axle whose inner wheel lifts first and the a_y (m/s^2, > 0) where it does.

    Both follow from the linear load transfer of eq. 4; the result is None if neither ever lifts.
    """
    geometry = roll_geometry(p)
    per_g: list[tuple[float, float, Axle]] = [
        (float(_linear_transfer(p, geometry, 'front', 1.0)), p.axle_load_front / 2.0, 'front'),
        (float(_linear_transfer(p, geometry, 'rear', 1.0)), p.axle_load_rear / 2.0, 'rear')]
    onsets = [(cap / rate, axle) for rate, cap, axle in per_g if rate > 0.0]
    if not onsets:
        return None
    a_y, axle = min(onsets)
    return axle, a_y


def _linear_transfer(p: VehicleParams, geometry: RollGeometry, axle: Axle,
                     a_y: ArrayLike) -> np.ndarray:
    """Load transfer of ``axle`` by eq. 4 with both wheels on the ground, N."""
    a_y = np.asarray(a_y, dtype=float)
    phi = geometry.roll_gradient * a_y
    return ((_geometric_moment(p, geometry, axle, a_y) + _roll_stiffness(p, axle) * phi)
            * (1.0 - _tire_share(p, axle)) / _track(p, axle))


def _geometric_moment(p: VehicleParams, geometry: RollGeometry, axle: Axle,
                      a_y: np.ndarray) -> np.ndarray:
    """Return the roll-centre and unsprung-mass part of the axle's load-transfer moment, N*m."""
    if axle == 'front':
        return (geometry.sprung_mass_front * a_y * p.roll_centre_height_front
                + p.unsprung_mass_front * a_y * p.unsprung_cog_height_front)
    return (geometry.sprung_mass_rear * a_y * p.roll_centre_height_rear
            + p.unsprung_mass_rear * a_y * p.unsprung_cog_height_rear)


def _roll_stiffness(p: VehicleParams, axle: Axle) -> float:
    return p.roll_stiffness_front if axle == 'front' else p.roll_stiffness_rear


def _track(p: VehicleParams, axle: Axle) -> float:
    return p.track_front if axle == 'front' else p.track_rear


def _roll_state(p: VehicleParams, lateral_acceleration: ArrayLike) -> tuple[np.ndarray, ...]:
    """
    Roll angle (rad) and front and rear load transfer (N), signed like a_y.

    Eqs. 3-4 up to an inner wheel's lift; beyond it the lifted axle's
    transfer stays at N/2 and the body rolls against the other axle alone
    (module doc). nan where both inner wheels are off the ground.
    """
    geometry = roll_geometry(p)
    a_y = np.asarray(lateral_acceleration, dtype=float)
    sign, a = np.sign(a_y), np.abs(a_y)
    phi = geometry.roll_gradient * a
    front = _linear_transfer(p, geometry, 'front', a)
    rear = _linear_transfer(p, geometry, 'rear', a)
    caps = {'front': p.axle_load_front / 2.0, 'rear': p.axle_load_rear / 2.0}
    net = geometry.sprung_mass * p.g * geometry.roll_arm
    lifted = {'front': front > caps['front'], 'rear': rear > caps['rear']}
    first_front = front / caps['front'] >= rear / caps['rear']
    sides: tuple[tuple[Axle, Axle, np.ndarray], ...] = (('front', 'rear', first_front),
                                                        ('rear', 'front', ~first_front))
    for axle, other, first in sides:
        case = lifted[axle] & first
        if not np.any(case):
            continue
        moment = caps[axle] * _track(p, axle) - _geometric_moment(p, geometry, axle, a)
        share = _tire_share(p, other)
        k_other = _roll_stiffness(p, other) * (1.0 - share)
        geometric_other = _geometric_moment(p, geometry, other, a)
        with np.errstate(divide='ignore', invalid='ignore'):
            phi_lift = np.where(k_other > net,
                                (geometry.sprung_mass * geometry.roll_arm * a - moment
                                 + share * geometric_other
                                 + 2.0 * (p.wheel_gyroscopic_front + p.wheel_gyroscopic_rear)
                                 * a) / (k_other - net),
                                np.nan)
        other_transfer = ((geometric_other + _roll_stiffness(p, other) * phi_lift)
                          * (1.0 - share) / _track(p, other))
        over = ~(other_transfer < caps[other])  # nan (no roll stiffness left) counts as over
        phi = np.where(case, np.where(over, np.nan, phi_lift), phi)
        capped = np.where(over, np.nan, caps[axle])
        other_value = np.where(over, np.nan, other_transfer)
        if axle == 'front':
            front, rear = np.where(case, capped, front), np.where(case, other_value, rear)
        else:
            rear, front = np.where(case, capped, rear), np.where(case, other_value, front)
    return sign * phi, sign * front, sign * rear


def roll_state(p: VehicleParams, lateral_acceleration: float
               ) -> tuple[float, np.ndarray, np.ndarray]:
    """
    Return the body roll (rad), load transfer (front, rear; N) and the axles' roll on their tires.

    At one lateral acceleration (m/s^2), signed like a_y; the tire roll of an axle is
    psi = dF_z t / K_t (rad, 0 with rigid tires). Beyond an inner wheel's lift as
    :func:`load_transfer`.
    """
    phi, front, rear = (float(v) for v in _roll_state(p, lateral_acceleration))
    transfer = np.array([front, rear])
    tilt = np.array([transfer[k] * _track(p, axle) / _tire_stiffness(p, axle)
                     if _tire_stiffness(p, axle) > 0.0 else 0.0
                     for k, axle in enumerate(AXLES)])
    return phi, transfer, tilt


def axle_lateral_force(tire: SimpleTire, loads: ArrayLike, alpha: ArrayLike) -> np.ndarray:
    """
    Lateral force of an axle's two wheels at a common slip angle, N.

    ``loads``: the two wheel loads (2,), N; ``alpha``: slip angle(s), rad,
    any shape (eqs. 6-9 summed over the wheels).
    """
    total = np.zeros(np.shape(alpha))
    for fz in np.asarray(loads, dtype=float):
        if fz > 0.0:  # a lifted wheel carries no force
            total = total + tire.lateral_force(fz, alpha)
    return total


def tire_peak_slip(tire: SimpleTire, fz: ArrayLike) -> np.ndarray:
    """
    Slip angle of the tire's force peak at load ``fz`` (N), rad.

    The peak is where C arctan(x) = pi/2 with x = B a - E (B a - arctan(B a)),
    so B a = u* solves (1 - E) u + E arctan(u) = tan(pi/(2 C)); u* does not
    depend on the load, only B does (eq. 8).  Needs 1 < C < 2 and E < 1
    (checked by VehicleParams).
    """
    fz = np.asarray(fz, dtype=float)
    target = math.tan(math.pi / (2.0 * tire.shape))
    e = tire.curvature
    # (1 - E) u + E arctan(u) >= (1 - E) u - |E| pi/2 for u >= 0, which
    # reaches the target at the upper end of this bracket.
    upper = (target + abs(e) * math.pi / 2.0) / (1.0 - e)

    u_peak = optimize.brentq(lambda u: (1.0 - e) * u + e * math.atan(u) - target, 0.0, upper)
    stiffness_factor = tire.cornering_stiffness(fz) / (tire.friction(fz) * tire.shape * fz)
    return u_peak / stiffness_factor


def axle_peak(tire: SimpleTire, loads: ArrayLike) -> tuple[float, float]:
    """
    Slip angle (rad) and force (N) of the axle's lateral force peak.

    Each wheel's force rises up to its own peak slip and falls beyond it, so
    the sum peaks between the two wheels' peak slips; it is maximised there.
    """
    loads = np.asarray(loads, dtype=float)
    slips = [float(a) for a in tire_peak_slip(tire, loads[loads > 0.0])]
    low, high = min(slips), max(slips)

    def force(alpha: float) -> float:
        return float(axle_lateral_force(tire, loads, alpha))

    candidates = [low, high]
    if high - low > PEAK_TOLERANCE:
        found = optimize.minimize_scalar(
            lambda alpha: -force(alpha), bounds=(low, high), method='bounded',
            options={'xatol': PEAK_TOLERANCE}
        )
        candidates.append(float(found.x))
    alpha_peak = max(candidates, key=force)
    return alpha_peak, force(alpha_peak)


def steady_state(p: VehicleParams, lateral_acceleration: float, radius: float) -> TwoTrackPoint:
    """
    Steady state at ``lateral_acceleration`` (m/s^2) on ``radius`` (m).

    a_y and the radius share their sign (a_y = V^2/R).  Raises
    BeyondLimitError naming the axle when an axle cannot produce the force
    the turn needs or both inner wheels have lifted, and SolverError on roll
    instability.
    """
    a_y = float(lateral_acceleration)
    radius = _check_radius(radius)
    if not math.isfinite(a_y) or a_y * radius < 0.0:
        raise ValueError(f'lateral_acceleration {a_y!r} must be finite and share the sign of '
                         f'radius {radius!r}')
    loads = _checked_wheel_loads(p, a_y)
    front, rear = _axle_states(p, a_y, loads)
    tires = (p.tire_front, p.tire_front, p.tire_rear, p.tire_rear)
    tire_slip = np.array([front.tire_slip, front.tire_slip, rear.tire_slip, rear.tire_slip])
    thrust = (front.camber_thrust, front.camber_thrust, rear.camber_thrust, rear.camber_thrust)
    on = loads > 0.0
    safe = np.where(on, loads, 1.0)
    return TwoTrackPoint(
        radius=radius,
        lateral_acceleration=a_y,
        speed=math.sqrt(a_y * radius),
        steer_angle=p.wheelbase / radius + front.slip - rear.slip,
        slip_angle_front=front.slip,
        slip_angle_rear=rear.slip,
        roll_angle=float(roll_angle(p, a_y)),
        wheel_loads=loads,
        friction=np.array([float(t.friction(fz)) if o else 0.0
                           for t, fz, o in zip(tires, safe, on)]),
        cornering_stiffness=np.array([float(t.cornering_stiffness(fz)) if o else 0.0
                                      for t, fz, o in zip(tires, safe, on)]),
        lateral_force=np.array([float(t.lateral_force(fz, al)) + f_c if o else 0.0
                                for t, fz, al, f_c, o in zip(tires, safe, tire_slip, thrust, on)]),
        tire_slip_angle=tire_slip,
    )


def max_lateral_acceleration(p: VehicleParams, radius: float) -> CorneringLimit:
    """
    Largest a_y with a steady state on both axles, and the limiting axle.

    Bisection on a_y between a solvable lower and an unsolvable upper bound
    until they are :data:`LIMIT_TOLERANCE` apart; the returned a_y is the
    solvable end, so :func:`steady_state` succeeds at it.  The equal-slip
    model has no radius dependence in a_y; the radius sets speed and sign.
    """
    radius = _check_radius(radius)
    roll_geometry(p)  # roll instability is no limit of a_y: report it as such
    lower, upper = 0.0, p.g
    violation = _violation(p, upper)
    doublings = 0
    while violation is None:
        if doublings == LIMIT_MAX_DOUBLINGS:
            raise SolverError(f'no cornering limit found up to {upper:.6g} m/s^2')
        lower, upper, doublings = upper, 2.0 * upper, doublings + 1
        violation = _violation(p, upper)
    while upper - lower > LIMIT_TOLERANCE:
        middle = 0.5 * (lower + upper)
        found = _violation(p, middle)
        if found is None:
            lower = middle
        else:
            upper, violation = middle, found
    axle, cause = violation
    return CorneringLimit(
        radius=radius,
        lateral_acceleration=math.copysign(lower, radius),
        speed=math.sqrt(lower * abs(radius)),
        limiting_axle=axle,
        cause=cause,
    )


def handling_diagram(p: VehicleParams, radius: float,
                     n: int = HANDLING_DIAGRAM_POINTS) -> HandlingDiagram:
    """Steady states at ``n`` equally spaced a_y from 0 to the limit on ``radius`` (m)."""
    if n < 2:
        raise ValueError(f'n must be at least 2, got {n!r}')
    limit = max_lateral_acceleration(p, radius)
    points = [steady_state(p, a_y, limit.radius)
              for a_y in np.linspace(0.0, limit.lateral_acceleration, n)]

    def stack(name: str) -> np.ndarray:
        return np.array([getattr(point, name) for point in points])

    return HandlingDiagram(
        radius=limit.radius,
        lateral_acceleration=stack('lateral_acceleration'),
        speed=stack('speed'),
        steer_angle=stack('steer_angle'),
        slip_angle_front=stack('slip_angle_front'),
        slip_angle_rear=stack('slip_angle_rear'),
        roll_angle=stack('roll_angle'),
        wheel_loads=stack('wheel_loads'),
        friction=stack('friction'),
        cornering_stiffness=stack('cornering_stiffness'),
        lateral_force=stack('lateral_force'),
        limit=limit,
    )


def understeer_gradient_linear(p: VehicleParams, fit_limit: float = LINEAR_FIT_LIMIT) -> float:
    """
    Linear-range understeer gradient d(alpha_f - alpha_r)/d(a_y), rad/(m/s^2).

    Thesis eq. 2 evaluated on the two-track model: the slope at a_y -> 0 of
    alpha_f - alpha_r, fitted on a_y in (0, ``fit_limit``] m/s^2.  Left/right
    symmetry makes the curve odd in a_y, so it is fitted with k1 a + k3 a^3 +
    k5 a^5 and k1 returned; a straight line would carry the curvature from
    load transfer and tire nonlinearity into the slope.
    """
    if not fit_limit > 0.0:
        raise ValueError(f'fit_limit must be positive, got {fit_limit!r}')
    a_y = fit_limit * np.arange(1, LINEAR_FIT_SAMPLES + 1) / LINEAR_FIT_SAMPLES
    difference = np.array([np.subtract(*_slip_angles(p, a, _checked_wheel_loads(p, a)))
                           for a in a_y])
    basis = np.stack([a_y, a_y**3, a_y**5], axis=1)
    coefficients, *_ = np.linalg.lstsq(basis, difference, rcond=None)
    return float(coefficients[0])


def _check_radius(radius: float) -> float:
    radius = float(radius)
    if radius == 0.0 or not math.isfinite(radius):
        raise ValueError(f'radius must be finite and nonzero, got {radius!r}')
    return radius


def _checked_wheel_loads(p: VehicleParams, a_y: float) -> np.ndarray:
    """Wheel loads at ``a_y``; BeyondLimitError if both inner wheels have lifted."""
    loads = wheel_loads(p, a_y)
    if not np.all(np.isfinite(loads)):
        lift = wheel_lift_onset(p)
        axle = lift[0] if lift is not None else 'front'
        raise BeyondLimitError(
            f'the vehicle rolls over at a_y = {a_y:.6g} m/s^2 ({a_y / p.g:.4g} g): '
            f'after the inner {axle} wheel, the other inner wheel lifts too')
    return loads


@dataclass(frozen=True)
class _AxleState:
    slip: float  # rad, kinematic axle slip (enters delta)
    tire_slip: float  # rad, shared slip angle of the axle's tires
    camber_thrust: float  # N, per wheel


def _required_forces(p: VehicleParams, a_y: float) -> tuple[float, float]:
    """M a_y b/L and m a_y a/L, N."""
    return (p.mass * a_y * p.cog_to_rear_axle / p.wheelbase,
            p.mass * a_y * p.cog_to_front_axle / p.wheelbase)


def _compliance(p: VehicleParams, axle: Axle, a_y: float, required: float) -> tuple[float, float]:
    """Steer change of the axle's wheels (rad, + left) and camber thrust per wheel (N)."""
    c = p.compliance_front if axle == 'front' else p.compliance_rear
    if c.is_rigid:
        return 0.0, 0.0
    phi = float(roll_angle(p, a_y))
    per_wheel = required / 2.0
    steer = (c.lateral_compliance_steer * per_wheel + c.roll_steer * phi
             - c.aligning_torque_compliance_steer * c.pneumatic_trail * per_wheel)
    lean = c.roll_camber * phi - c.lateral_compliance_camber * per_wheel
    return steer, c.camber_stiffness * lean


def _axle_states(p: VehicleParams, a_y: float, loads: np.ndarray) -> tuple[_AxleState, _AxleState]:
    """Front and rear axle states that carry m a_y b/L and m a_y a/L."""
    out = []
    for axle, tire, pair, required in zip(AXLES, (p.tire_front, p.tire_rear),
                                          (loads[:2], loads[2:]), _required_forces(p, a_y)):
        steer, thrust = _compliance(p, axle, a_y, required)
        tire_slip = _axle_slip(p, axle, tire, pair, required - 2.0 * thrust, a_y)
        out.append(_AxleState(tire_slip - steer, tire_slip, thrust))
    return out[0], out[1]


def _slip_angles(p: VehicleParams, a_y: float, loads: np.ndarray) -> tuple[float, float]:
    """Front and rear kinematic slip angles at ``a_y``, rad."""
    front, rear = _axle_states(p, a_y, loads)
    return front.slip, rear.slip


def _axle_slip(
    p: VehicleParams, axle: Axle, tire: SimpleTire, loads: np.ndarray, required: float, a_y: float
) -> float:
    """
    Slip angle giving the tire force ``required`` (N, signed), rad.

    The axle is symmetric in slip, so the magnitude is solved on [0,
    alpha_peak], where the force rises monotonically, and given the sign.
    """
    _check_tire_range(p, axle, tire, loads, a_y)
    alpha_peak, force_peak = axle_peak(tire, loads)
    magnitude = abs(required)
    if magnitude > force_peak:
        raise BeyondLimitError(
            f'{axle} axle saturates at a_y = {a_y:.6g} m/s^2 ({a_y / p.g:.4g} g): '
            f'needs {magnitude:.1f} N, peak {force_peak:.1f} N at '
            f'{math.degrees(alpha_peak):.2f} deg'
        )

    def residual(alpha: float) -> float:
        return float(axle_lateral_force(tire, loads, alpha)) - magnitude


    alpha = optimize.brentq(residual, 0.0, alpha_peak, xtol=SLIP_TOLERANCE)
    return math.copysign(alpha, required)


def _check_tire_range(p: VehicleParams, axle: Axle, tire: SimpleTire, loads: np.ndarray,
                      a_y: float) -> None:
    """
    Raise SolverError when eqs. 6-7 leave their physical range at these loads.

    A lifted wheel, load 0, carries nothing and is not checked.
    """
    on = loads[loads > 0.0]
    if np.any(tire.friction(on) <= 0.0) or np.any(tire.cornering_stiffness(on) <= 0.0):
        raise SolverError(
            f'{axle} tire model gives no friction or cornering stiffness at wheel loads '
            f'{loads[0]:.1f} N, {loads[1]:.1f} N (a_y = {a_y:.6g} m/s^2)'
        )


def _violation(p: VehicleParams, a_y: float) -> tuple[Axle, LimitCause] | None:
    """
    Return the constraint that a_y (>= 0, m/s^2) breaks first, or None if solvable.

    Rollover (both inner wheels off the ground) is checked first because the
    axle forces are undefined after it; between two saturated axles the one
    short by the larger fraction of its required force limits.
    """
    loads = wheel_loads(p, a_y)
    if not np.all(np.isfinite(loads)):
        lift = wheel_lift_onset(p)
        return (lift[0] if lift is not None else 'front'), 'rollover'
    shortfalls: list[tuple[float, Axle]] = []
    for axle, tire, pair, required in zip(AXLES, (p.tire_front, p.tire_rear),
                                          (loads[:2], loads[2:]), _required_forces(p, a_y)):
        _check_tire_range(p, axle, tire, pair, a_y)
        _, thrust = _compliance(p, axle, a_y, required)
        _, force_peak = axle_peak(tire, pair)
        shortfalls.append(((abs(required - 2.0 * thrust) - force_peak) / required, axle))
    shortfall, axle = max(shortfalls)
    return (axle, 'saturation') if shortfall > 0.0 else None
