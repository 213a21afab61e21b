# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Linear single-track (bicycle) model, thesis 3.1.1 eqs. 1-2.

Steady state (thesis eq. 1, Gillespie "Fundamentals of Vehicle Dynamics"
eq. 6-7)::

    delta = L/R + (N_f/C_af - N_r/C_ar) * V^2/(g R) = L/R + K * a_y

Units of the understeer gradient.  In eq. 1-2 N is a normal load (N) and C a
cornering stiffness (N/rad), so ``N_f/C_af - N_r/C_ar`` is an angle in rad
*per g* of lateral acceleration; eq. 2's ``d(alpha_f - alpha_r)/d a_y``
agrees with it only when a_y is expressed in g.  This module works in SI:
``understeer_gradient`` returns K in rad/(m/s^2), i.e. eq. 2's value divided
by g, so that ``delta = L/R + K * a_y`` with a_y in m/s^2;
``understeer_gradient_deg_per_g`` gives the customary deg/g.  N and C may be
taken per tire (thesis Table 3.1.1) or per axle; the ratio is the same.  Here
C_a is the *effective* axle cornering stiffness (``budget.py``): two tires at
the static wheel load N/2 (thesis eq. 7), softened or stiffened by the
axle's compliance steer, roll steer and camber (Milliken & Milliken ch. 5);
for a rigid axle it is the bare tires' value.  Slip angles are then the
axle's kinematic slip (delta - beta - a r/V at the front), not the tires'.

Slip angles are magnitudes in the tire model's convention (a positive slip
angle gives a positive, leftward force), so in a left turn alpha_f and
alpha_r are positive and delta = L/R + alpha_f - alpha_r.  Steer angle, yaw
rate, sideslip and lateral acceleration follow ISO 8855: positive for a left
turn.

Transient: the two-degree-of-freedom linear single track (Milliken &
Milliken, "Race Car Vehicle Dynamics", ch. 5; Wong, "Theory of Ground
Vehicles", ch. 5) with states lateral velocity v (m/s) and yaw rate r
(rad/s) at constant forward speed u::

    m (v' + u r) = F_yf + F_yr,    I_zz r' = a F_yf - b F_yr
    F_yf = C_af (delta - (v + a r)/u),    F_yr = C_ar (b r - v)/u
"""
from __future__ import annotations

from dataclasses import dataclass
import math

import numpy as np
from numpy.typing import ArrayLike

from vd_solvers.analytical.budget import effective_axle_cornering_stiffness
from vd_solvers.analytical.params import VehicleParams
from vd_solvers.errors import BeyondLimitError


@dataclass(frozen=True)
class SteadyStateResult:
    """
    Steady-state cornering of the linear single track at one point.

    Angles in rad, ISO 8855 signs (left turn positive); slip angles in the
    tire model's convention (positive in a left turn).
    """

    radius: float  # m, positive for a left turn
    speed: float  # m/s
    lateral_acceleration: float  # m/s^2, V^2/R
    steer_angle: float  # rad, road-wheel angle (eq. 1)
    yaw_rate: float  # rad/s, V/R
    sideslip: float  # rad, at the COG
    slip_angle_front: float  # rad
    slip_angle_rear: float  # rad


@dataclass(frozen=True)
class BicycleResult:
    """Linear single-track characteristics at one forward speed."""

    speed: float  # m/s
    understeer_gradient: float  # rad/(m/s^2)
    yaw_rate_gain: float  # (rad/s)/rad, steady state r/delta
    lateral_acceleration_gain: float  # (m/s^2)/rad, steady state a_y/delta
    sideslip_gain: float  # rad/rad, steady state beta/delta
    natural_frequency: float  # rad/s, undamped, of the yaw/lateral mode
    damping_ratio: float  # -


# Holds numpy arrays, whose element-wise == makes a generated __eq__ useless.
@dataclass(frozen=True, eq=False)
class StateSpace:
    """
    x' = A x + B delta, y = C x + D delta.

    States x = (v, r): lateral velocity (m/s) and yaw rate (rad/s); input
    delta: road-wheel steer angle (rad); outputs y = (r, a_y) with a_y the
    lateral acceleration v' + u r (m/s^2).
    """

    a: np.ndarray  # (2, 2)
    b: np.ndarray  # (2, 1)
    c: np.ndarray  # (2, 2)
    d: np.ndarray  # (2, 1)


# Holds numpy arrays, whose element-wise == makes a generated __eq__ useless.
@dataclass(frozen=True, eq=False)
class StepResponse:
    """
    Response to a steer step applied at t = 0 from straight running.

    All arrays have shape (n,); SI units, ISO 8855 signs.
    """

    time: np.ndarray  # s
    yaw_rate: np.ndarray  # rad/s
    lateral_acceleration: np.ndarray  # m/s^2
    lateral_velocity: np.ndarray  # m/s


STEP_RESPONSE_SAMPLES = 1001  # default time samples of a step response


def axle_cornering_stiffness(p: VehicleParams) -> tuple[float, float]:
    """
    Front and rear axle cornering stiffness C_af, C_ar, N/rad.

    Two tires at the static wheel load N/2 (thesis eq. 7).
    """
    front = 2.0 * float(p.tire_front.cornering_stiffness(p.axle_load_front / 2.0))
    rear = 2.0 * float(p.tire_rear.cornering_stiffness(p.axle_load_rear / 2.0))
    return front, rear


def effective_cornering_stiffness(p: VehicleParams) -> tuple[float, float]:
    """
    Return the front and rear effective axle cornering stiffness C_af, C_ar, N/rad.

    See :func:`~vd_solvers.analytical.budget.effective_axle_cornering_stiffness`.
    """
    return effective_axle_cornering_stiffness(p)


def understeer_gradient(p: VehicleParams) -> float:
    """
    Understeer gradient K, rad/(m/s^2) (thesis eq. 2 divided by g).

    K = (N_f/C_af - N_r/C_ar)/g with the effective axle cornering
    stiffnesses; it equals the total of the understeer budget. Positive:
    understeer, negative: oversteer.
    """
    c_front, c_rear = effective_cornering_stiffness(p)
    return (p.axle_load_front / c_front - p.axle_load_rear / c_rear) / p.g


def to_deg_per_g(gradient: float, g: float) -> float:
    """Convert a gradient in rad/(m/s^2) to deg/g."""
    return math.degrees(gradient * g)


def understeer_gradient_deg_per_g(p: VehicleParams) -> float:
    """Understeer gradient in deg/g (Gillespie ch. 6 units)."""
    return to_deg_per_g(understeer_gradient(p), p.g)


def curvature_steer_angle(wheelbase: float, gradient: float, curvature: ArrayLike,
                          speed: ArrayLike) -> np.ndarray:
    """
    Steady-state road-wheel angle for a path ``curvature`` (1/m, + left), rad (eq. 1).

    (L + K V^2) kappa: the Ackermann angle plus the understeer angle K a_y at
    a_y = V^2 kappa, with K = ``gradient`` in rad/(m/s^2). The form of :func:`steer_angle`
    that takes a curvature (zero on a straight) and bare numbers, for a driver's
    feed-forward. Both arrays broadcast.
    """
    v = np.asarray(speed, dtype=float)
    return (wheelbase + gradient * v * v) * np.asarray(curvature, dtype=float)


def steer_angle(p: VehicleParams, radius: ArrayLike, speed: ArrayLike) -> np.ndarray:
    """
    Steady-state road-wheel steer angle, rad (thesis eq. 1).

    ``radius`` in m (positive for a left turn, nonzero), ``speed`` in m/s;
    both broadcast.  Above the critical speed of an oversteering vehicle the
    result is the (unstable) counter-steer equilibrium.
    """
    radius = _nonzero_radius(radius)
    speed = _non_negative_speed(speed)
    return curvature_steer_angle(p.wheelbase, understeer_gradient(p), 1.0 / radius, speed)


def characteristic_speed(p: VehicleParams) -> float:
    """
    Characteristic speed sqrt(L/K), m/s, of an understeering vehicle.

    At this speed the yaw-rate gain peaks at half the neutral-steer value
    V/L (Gillespie eq. 6-13).  Raises ValueError unless K > 0.
    """
    k = understeer_gradient(p)
    if k <= 0.0:
        raise ValueError(
            f'characteristic speed needs understeer (K > 0), got K = {k!r} rad/(m/s^2)'
        )
    return math.sqrt(p.wheelbase / k)


def critical_speed(p: VehicleParams) -> float:
    """
    Critical speed sqrt(-L/K), m/s, of an oversteering vehicle.

    Above it the linear vehicle is directionally unstable: the gain
    denominator L + K V^2 vanishes (Gillespie eq. 6-16).  Raises ValueError
    unless K < 0.
    """
    k = understeer_gradient(p)
    if k >= 0.0:
        raise ValueError(f'critical speed needs oversteer (K < 0), got K = {k!r} rad/(m/s^2)')
    return math.sqrt(-p.wheelbase / k)


def yaw_rate_gain(p: VehicleParams, speed: ArrayLike) -> np.ndarray:
    """
    Steady-state yaw-rate gain r/delta = V/(L + K V^2), 1/s.

    ``speed`` in m/s, any shape (Gillespie eq. 6-15).
    """
    speed = _non_negative_speed(speed)
    return speed / _gain_denominator(p, speed)


def lateral_acceleration_gain(p: VehicleParams, speed: ArrayLike) -> np.ndarray:
    """
    Steady-state lateral-acceleration gain a_y/delta = V^2/(L + K V^2), m/s^2/rad.

    ``speed`` in m/s, any shape (Gillespie eq. 6-17).
    """
    speed = _non_negative_speed(speed)
    return speed**2 / _gain_denominator(p, speed)


def sideslip_gain(p: VehicleParams, speed: ArrayLike) -> np.ndarray:
    """
    Steady-state COG sideslip gain beta/delta, rad/rad.

    beta = b/R - alpha_r with alpha_r = m a_y a/(L C_ar) (Gillespie eq.
    6-20), hence beta/delta = (b - m a V^2/(L C_ar))/(L + K V^2).  Positive
    at low speed (the COG velocity points into the turn), it changes sign at
    V = sqrt(b L C_ar/(m a)).  ``speed`` in m/s, any shape.
    """
    speed = _non_negative_speed(speed)
    _, c_rear = effective_cornering_stiffness(p)
    numerator = p.cog_to_rear_axle - p.mass * p.cog_to_front_axle * speed**2 / (
        p.wheelbase * c_rear
    )
    return numerator / _gain_denominator(p, speed)


def steady_state(p: VehicleParams, radius: float, speed: float) -> SteadyStateResult:
    """Steady-state cornering on a circle of ``radius`` (m) at ``speed`` (m/s)."""
    radius = float(_nonzero_radius(radius))
    speed = float(_non_negative_speed(speed))
    c_front, c_rear = effective_cornering_stiffness(p)
    a_y = speed**2 / radius
    # Moment balance about each axle: F_yf = m a_y b/L, F_yr = m a_y a/L.
    alpha_front = p.mass * a_y * p.cog_to_rear_axle / (p.wheelbase * c_front)
    alpha_rear = p.mass * a_y * p.cog_to_front_axle / (p.wheelbase * c_rear)
    return SteadyStateResult(
        radius=radius,
        speed=speed,
        lateral_acceleration=a_y,
        steer_angle=float(steer_angle(p, radius, speed)),
        yaw_rate=speed / radius,
        sideslip=p.cog_to_rear_axle / radius - alpha_rear,
        slip_angle_front=alpha_front,
        slip_angle_rear=alpha_rear,
    )


def state_space(p: VehicleParams, speed: float,
                cornering: tuple[float, float] | None = None) -> StateSpace:
    """
    State matrices of the linear single track at forward ``speed`` > 0, m/s.

    ``cornering``: :func:`effective_cornering_stiffness` of ``p`` when the caller has it
    (it does not depend on the speed; a replay asks for the matrices at every step).
    """
    if not speed > 0.0:
        raise ValueError(f'speed must be positive for the transient model, got {speed!r}')
    c_front, c_rear = cornering if cornering is not None else effective_cornering_stiffness(p)
    m, izz, u = p.mass, p.yaw_inertia, speed
    a, b = p.cog_to_front_axle, p.cog_to_rear_axle
    # Force and moment derivatives with respect to v and r (Milliken ch. 5).
    y_v = -(c_front + c_rear) / u
    y_r = -(a * c_front - b * c_rear) / u
    n_v = -(a * c_front - b * c_rear) / u
    n_r = -(a**2 * c_front + b**2 * c_rear) / u
    a_matrix = np.array([[y_v / m, y_r / m - u], [n_v / izz, n_r / izz]])
    b_matrix = np.array([[c_front / m], [a * c_front / izz]])
    # a_y = v' + u r = (F_yf + F_yr)/m: the front force reacts to the steer
    # at once, hence the direct feedthrough.
    c_matrix = np.array([[0.0, 1.0], [y_v / m, y_r / m]])
    d_matrix = np.array([[0.0], [c_front / m]])
    return StateSpace(a=a_matrix, b=b_matrix, c=c_matrix, d=d_matrix)


def bicycle_response(p: VehicleParams, speed: float) -> BicycleResult:
    """
    Steady-state gains and yaw-mode frequency/damping at ``speed``, m/s.

    Raises BeyondLimitError at or above the critical speed, where the yaw
    mode has no natural frequency because the vehicle is unstable.
    """
    natural_frequency, damping_ratio = _mode(p, speed)
    return BicycleResult(
        speed=speed,
        understeer_gradient=understeer_gradient(p),
        yaw_rate_gain=float(yaw_rate_gain(p, speed)),
        lateral_acceleration_gain=float(lateral_acceleration_gain(p, speed)),
        sideslip_gain=float(sideslip_gain(p, speed)),
        natural_frequency=natural_frequency,
        damping_ratio=damping_ratio,
    )


def steer_step_response(
    p: VehicleParams,
    speed: float,
    steer: float,
    duration: float,
    samples: int = STEP_RESPONSE_SAMPLES,
) -> StepResponse:
    """
    Linear response to a road-wheel steer step ``steer`` (rad) at t = 0.

    ``speed`` in m/s (below any critical speed), ``duration`` in s, sampled at
    ``samples`` equally spaced instants from 0.  A step is constant between
    samples, so scipy's interpolating lsim is exact for it.
    """
    _mode(p, speed)  # refuse the unstable case before integrating it
    if not duration > 0.0:
        raise ValueError(f'duration must be positive, got {duration!r}')
    if samples < 2:
        raise ValueError(f'samples must be at least 2, got {samples!r}')
    # imported here: scipy.signal (with scipy.stats) costs over a second of CPU, which the
    # steady-state events, and a command line that never asks for a step, need not pay
    from scipy import signal

    ss = state_space(p, speed)
    time = np.linspace(0.0, duration, samples)
    _, y, x = signal.lsim((ss.a, ss.b, ss.c, ss.d), U=np.full(samples, float(steer)), T=time)
    return StepResponse(
        time=time, yaw_rate=y[:, 0], lateral_acceleration=y[:, 1], lateral_velocity=x[:, 0]
    )


def _mode(p: VehicleParams, speed: float) -> tuple[float, float]:
    """
    Natural frequency (rad/s) and damping ratio of the state matrix.

    The characteristic polynomial is s^2 - tr(A) s + det(A) = s^2 + 2 zeta
    w_n s + w_n^2; det(A) <= 0 means a real positive root (oversteer at or
    above the critical speed).
    """
    a_matrix = state_space(p, speed).a
    det = float(np.linalg.det(a_matrix))
    if det <= 0.0:
        raise BeyondLimitError(
            f'single track unstable at {speed!r} m/s: at or above the critical speed '
            f'(det A = {det:.3g})'
        )
    natural_frequency = math.sqrt(det)
    return natural_frequency, -float(np.trace(a_matrix)) / (2.0 * natural_frequency)


def _gain_denominator(p: VehicleParams, speed: np.ndarray) -> np.ndarray:
    return p.wheelbase + understeer_gradient(p) * speed**2


def _nonzero_radius(radius: ArrayLike) -> np.ndarray:
    radius = np.asarray(radius, dtype=float)
    if np.any(radius == 0.0) or not np.all(np.isfinite(radius)):
        raise ValueError(f'radius must be finite and nonzero, got {radius!r}')
    return radius


def _non_negative_speed(speed: ArrayLike) -> np.ndarray:
    speed = np.asarray(speed, dtype=float)
    if np.any(speed < 0.0) or not np.all(np.isfinite(speed)):
        raise ValueError(f'speed must be finite and non-negative, got {speed!r}')
    return speed
