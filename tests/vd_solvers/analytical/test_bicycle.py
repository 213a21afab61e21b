# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""Linear single track: closed forms, thesis eqs. 1-2 and the transient model."""
from __future__ import annotations

import math

import numpy as np
import pytest

from vd_solvers.analytical import bicycle
from vd_solvers.analytical.params import VehicleParams
from vd_solvers.errors import BeyondLimitError

RADIUS = 50.0  # m


def _by_hand_gradient(p: VehicleParams) -> float:
    """K in rad/(m/s^2) from the tire formula written out (eqs. 2 and 7)."""
    tire = p.tire_front  # the fixture uses one tire on both axles
    b = p.wheelbase - p.cog_to_front_axle
    n_front = p.mass * p.g * b / p.wheelbase
    n_rear = p.mass * p.g * p.cog_to_front_axle / p.wheelbase
    per_wheel_front, per_wheel_rear = n_front / 2, n_rear / 2
    c_front = tire.c0 * per_wheel_front * (1 - tire.c1 * (per_wheel_front - tire.fz0))
    c_rear = tire.c0 * per_wheel_rear * (1 - tire.c1 * (per_wheel_rear - tire.fz0))
    return (per_wheel_front / c_front - per_wheel_rear / c_rear) / p.g


def test_understeer_gradient_matches_eq2_by_hand(passenger_car: VehicleParams) -> None:
    k = bicycle.understeer_gradient(passenger_car)
    assert k == pytest.approx(_by_hand_gradient(passenger_car), rel=1e-12)
    assert k > 0.0  # front-heavy with load-sensitive tires: understeer
    assert bicycle.understeer_gradient_deg_per_g(passenger_car) == pytest.approx(
        math.degrees(k * passenger_car.g), rel=1e-12
    )


def test_oversteering_variant_has_negative_gradient(oversteering_car: VehicleParams) -> None:
    k = bicycle.understeer_gradient(oversteering_car)
    assert k == pytest.approx(_by_hand_gradient(oversteering_car), rel=1e-12)
    assert k < 0.0


def test_ackermann_steer_at_vanishing_speed(passenger_car: VehicleParams) -> None:
    p = passenger_car
    assert bicycle.steer_angle(p, RADIUS, 0.0) == pytest.approx(p.wheelbase / RADIUS, rel=1e-15)
    assert bicycle.steer_angle(p, RADIUS, 1e-3) == pytest.approx(p.wheelbase / RADIUS, rel=1e-9)


def test_right_turn_mirrors_left_turn(passenger_car: VehicleParams) -> None:
    speeds = np.array([5.0, 15.0, 25.0])
    np.testing.assert_allclose(
        bicycle.steer_angle(passenger_car, -RADIUS, speeds),
        -bicycle.steer_angle(passenger_car, RADIUS, speeds),
    )
    left = bicycle.steady_state(passenger_car, RADIUS, 20.0)
    right = bicycle.steady_state(passenger_car, -RADIUS, 20.0)
    assert (right.steer_angle, right.yaw_rate, right.sideslip) == pytest.approx(
        (-left.steer_angle, -left.yaw_rate, -left.sideslip), rel=1e-14
    )


@pytest.mark.parametrize('car', ['passenger_car', 'oversteering_car'])
def test_eq2_gradient_is_slope_of_excess_steer_over_lateral_acceleration(
    car: str, request: pytest.FixtureRequest
) -> None:
    """Thesis eq. 2: K_us = d(delta - L/R)/d(a_y/g), here from eq. 1 results."""
    p: VehicleParams = request.getfixturevalue(car)
    speeds = np.array([10.0, 12.0])
    excess = bicycle.steer_angle(p, RADIUS, speeds) - p.wheelbase / RADIUS
    a_y_in_g = speeds**2 / RADIUS / p.g
    slope_rad_per_g = np.diff(excess)[0] / np.diff(a_y_in_g)[0]
    assert slope_rad_per_g == pytest.approx(bicycle.understeer_gradient(p) * p.g, rel=1e-9)
    assert math.degrees(slope_rad_per_g) == pytest.approx(
        bicycle.understeer_gradient_deg_per_g(p), rel=1e-9
    )


def test_yaw_rate_gain_peaks_at_characteristic_speed(passenger_car: VehicleParams) -> None:
    p = passenger_car
    v_char = bicycle.characteristic_speed(p)
    # Half the neutral-steer gain V/L at V_char.
    assert bicycle.yaw_rate_gain(p, v_char) == pytest.approx(0.5 * v_char / p.wheelbase, rel=1e-12)
    speeds = np.linspace(0.2, 3.0, 2801) * v_char
    peak_speed = speeds[np.argmax(bicycle.yaw_rate_gain(p, speeds))]
    assert peak_speed == pytest.approx(v_char, rel=1e-3)
    with pytest.raises(ValueError, match='needs oversteer'):
        bicycle.critical_speed(p)


def test_critical_speed_zeroes_the_gain_denominator(oversteering_car: VehicleParams) -> None:
    p = oversteering_car
    v_crit = bicycle.critical_speed(p)
    with pytest.raises(ValueError, match='needs understeer'):
        bicycle.characteristic_speed(p)
    # V/(r/delta) = L + K V^2 goes to zero, so the gain grows without bound ...
    just_below = v_crit * (1.0 - 1e-9)
    assert just_below / bicycle.yaw_rate_gain(p, just_below) == pytest.approx(
        0.0, abs=1e-7 * p.wheelbase
    )
    # ... and the transient model loses its stiffness (det A -> 0) there too.
    det_low = np.linalg.det(bicycle.state_space(p, 0.5 * v_crit).a)
    det_crit = np.linalg.det(bicycle.state_space(p, v_crit).a)
    assert abs(det_crit) < 1e-9 * det_low
    bicycle.bicycle_response(p, 0.99 * v_crit)
    with pytest.raises(BeyondLimitError, match='critical speed'):
        bicycle.bicycle_response(p, 1.01 * v_crit)
    with pytest.raises(BeyondLimitError):
        bicycle.steer_step_response(p, 1.01 * v_crit, 0.01, 2.0)


def test_lateral_acceleration_gain_is_speed_times_yaw_rate_gain(
    passenger_car: VehicleParams,
) -> None:
    speeds = np.array([0.0, 10.0, 30.0])
    np.testing.assert_allclose(
        bicycle.lateral_acceleration_gain(passenger_car, speeds),
        speeds * bicycle.yaw_rate_gain(passenger_car, speeds),
        rtol=1e-14,
    )


def test_steady_state_point(passenger_car: VehicleParams) -> None:
    p = passenger_car
    speed = 18.0
    point = bicycle.steady_state(p, RADIUS, speed)
    assert point.lateral_acceleration == pytest.approx(speed**2 / RADIUS)
    assert point.yaw_rate == pytest.approx(speed / RADIUS)
    assert point.steer_angle == pytest.approx(
        float(bicycle.steer_angle(p, RADIUS, speed)), rel=1e-14
    )
    assert point.slip_angle_front - point.slip_angle_rear == pytest.approx(
        bicycle.understeer_gradient(p) * point.lateral_acceleration, rel=1e-9
    )
    assert point.yaw_rate / point.steer_angle == pytest.approx(
        float(bicycle.yaw_rate_gain(p, speed)), rel=1e-12
    )
    assert point.sideslip / point.steer_angle == pytest.approx(
        float(bicycle.sideslip_gain(p, speed)), rel=1e-12
    )
    # Kinematic limit: the COG velocity points b/R into the turn.
    slow = bicycle.steady_state(p, RADIUS, 1e-3)
    assert slow.sideslip == pytest.approx(p.cog_to_rear_axle / RADIUS, rel=1e-6)


def _independent_mode(p: VehicleParams, speed: float) -> tuple[float, float]:
    """w_n and zeta of the single track written out (Milliken ch. 5)."""
    c_f, c_r = bicycle.axle_cornering_stiffness(p)
    m, izz, u = p.mass, p.yaw_inertia, speed
    a, b, length = p.cog_to_front_axle, p.cog_to_rear_axle, p.wheelbase
    omega_sq = c_f * c_r * length**2 / (m * izz * u**2) + (b * c_r - a * c_f) / izz
    two_zeta_omega = (c_f + c_r) / (m * u) + (a**2 * c_f + b**2 * c_r) / (izz * u)
    omega = math.sqrt(omega_sq)
    return omega, two_zeta_omega / (2 * omega)


@pytest.mark.parametrize('speed', [10.0, 25.0, 40.0])
def test_transient_mode_matches_closed_form(passenger_car: VehicleParams, speed: float) -> None:
    omega, zeta = _independent_mode(passenger_car, speed)
    result = bicycle.bicycle_response(passenger_car, speed)
    assert result.natural_frequency == pytest.approx(omega, rel=1e-12)
    assert result.damping_ratio == pytest.approx(zeta, rel=1e-12)
    eigenvalues = np.sort_complex(
        np.linalg.eigvals(bicycle.state_space(passenger_car, speed).a).astype(complex)
    )
    roots = np.sort_complex(np.roots([1.0, 2 * zeta * omega, omega**2]).astype(complex))
    np.testing.assert_allclose(eigenvalues, roots, rtol=1e-9)
    assert np.all(eigenvalues.real < 0.0)


@pytest.mark.parametrize('car', ['passenger_car', 'oversteering_car'])
def test_state_space_steady_state_equals_the_gains(
    car: str, request: pytest.FixtureRequest
) -> None:
    p: VehicleParams = request.getfixturevalue(car)
    speed = 20.0
    ss = bicycle.state_space(p, speed)
    x = -np.linalg.solve(ss.a, ss.b[:, 0])  # response to delta = 1 rad
    y = ss.c @ x + ss.d[:, 0]
    assert x[1] == pytest.approx(float(bicycle.yaw_rate_gain(p, speed)), rel=1e-10)
    assert x[0] / speed == pytest.approx(float(bicycle.sideslip_gain(p, speed)), rel=1e-10)
    assert y[1] == pytest.approx(float(bicycle.lateral_acceleration_gain(p, speed)), rel=1e-10)


def test_step_response_settles_to_steady_state(passenger_car: VehicleParams) -> None:
    p = passenger_car
    speed, steer = 25.0, math.radians(1.0)
    result = bicycle.bicycle_response(p, speed)
    settle = 12.0 / (result.damping_ratio * result.natural_frequency)
    response = bicycle.steer_step_response(p, speed, steer, settle)
    assert response.time[0] == 0.0 and response.time[-1] == pytest.approx(settle)
    assert response.yaw_rate[0] == 0.0
    # The front axle force reacts at once: a_y(0+) = C_af delta / m.
    c_front, _ = bicycle.axle_cornering_stiffness(p)
    assert response.lateral_acceleration[0] == pytest.approx(c_front * steer / p.mass, rel=1e-12)
    assert response.yaw_rate[-1] == pytest.approx(result.yaw_rate_gain * steer, rel=1e-5)
    assert response.lateral_acceleration[-1] == pytest.approx(
        result.lateral_acceleration_gain * steer, rel=1e-5
    )
    assert response.lateral_velocity[-1] == pytest.approx(
        result.sideslip_gain * steer * speed, rel=1e-5
    )
    # ζ < 1 here: the yaw rate overshoots its final value.
    assert result.damping_ratio < 1.0
    assert response.yaw_rate.max() > response.yaw_rate[-1]


def test_invalid_inputs(passenger_car: VehicleParams) -> None:
    with pytest.raises(ValueError, match='radius'):
        bicycle.steer_angle(passenger_car, 0.0, 10.0)
    with pytest.raises(ValueError, match='speed'):
        bicycle.yaw_rate_gain(passenger_car, -1.0)
    with pytest.raises(ValueError, match='speed'):
        bicycle.state_space(passenger_car, 0.0)
    with pytest.raises(ValueError, match='duration'):
        bicycle.steer_step_response(passenger_car, 20.0, 0.01, 0.0)
