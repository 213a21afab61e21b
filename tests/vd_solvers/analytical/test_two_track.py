# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""Two-track steady state: eqs. 3-9, equilibrium, limits and the thesis' 4.1 trends."""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace
import math

import numpy as np
import numpy.testing as npt
import pytest

from vd_solvers.analytical import bicycle, two_track
from vd_solvers.analytical.params import VehicleParams
from vd_solvers.errors import BeyondLimitError, SolverError

RADIUS = 50.0  # m
FORCE_RESIDUAL = 1e-6  # N and N*m

CarFactory = Callable[..., VehicleParams]  # the conftest make_car fixture


def _thesis_car(p: VehicleParams) -> VehicleParams:
    """Return the car without unsprung masses: the thesis' eqs. 3-4 literally."""
    return replace(p, unsprung_mass_front=0.0, unsprung_mass_rear=0.0)


def test_roll_and_load_transfer_are_eqs_3_and_4(passenger_car: VehicleParams) -> None:
    p = _thesis_car(passenger_car)
    a_y = 6.0
    m, g, h = p.mass, p.g, p.cog_height
    b = p.wheelbase - p.cog_to_front_axle
    h_axis = p.roll_centre_height_front + (
        p.roll_centre_height_rear - p.roll_centre_height_front
    ) * (p.cog_to_front_axle / p.wheelbase)
    h1 = h - h_axis
    k_phi = p.roll_stiffness_front + p.roll_stiffness_rear
    phi = m * a_y * h1 / (k_phi - m * g * h1)  # eq. 3 with V^2/R = a_y
    m_f, m_r = m * b / p.wheelbase, m * p.cog_to_front_axle / p.wheelbase
    d_front = (
        m_f * a_y * p.roll_centre_height_front / p.track_front
        + p.roll_stiffness_front * m * a_y * h1 / (p.track_front * (k_phi - m * g * h1))
    )
    d_rear = (
        m_r * a_y * p.roll_centre_height_rear / p.track_rear
        + p.roll_stiffness_rear * m * a_y * h1 / (p.track_rear * (k_phi - m * g * h1))
    )
    assert two_track.roll_angle(p, a_y) == pytest.approx(phi, rel=1e-12)
    np.testing.assert_allclose(two_track.load_transfer(p, a_y), [d_front, d_rear], rtol=1e-12)
    n_f, n_r = m * g * b / p.wheelbase, m * g * p.cog_to_front_axle / p.wheelbase
    np.testing.assert_allclose(
        two_track.wheel_loads(p, a_y),
        [n_f / 2 - d_front, n_f / 2 + d_front, n_r / 2 - d_rear, n_r / 2 + d_rear],
    )


@pytest.mark.parametrize('unsprung', [True, False])
def test_load_transfer_balances_the_overturning_moment(
    passenger_car: VehicleParams, unsprung: bool
) -> None:
    """
    Check that the sum of dF_z t is m a_y h + m_s g h1 phi.

    That is the inertia at the COG plus the rolled body's weight shift.
    """
    p = passenger_car if unsprung else _thesis_car(passenger_car)
    geometry = two_track.roll_geometry(p)
    a_y = np.linspace(-8.0, 8.0, 9)
    transfer = two_track.load_transfer(p, a_y)
    moment = transfer[:, 0] * p.track_front + transfer[:, 1] * p.track_rear
    phi = two_track.roll_angle(p, a_y)
    expected = p.mass * a_y * p.cog_height + geometry.sprung_mass * p.g * geometry.roll_arm * phi
    np.testing.assert_allclose(moment, expected, rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(two_track.wheel_loads(p, a_y).sum(axis=1), p.mass * p.g, rtol=1e-14)


def test_roll_is_outward_and_loads_the_outer_wheels(passenger_car: VehicleParams) -> None:
    # Left turn (ISO: a_y > 0): body rolls to the right (positive roll), right wheels carry more.
    assert two_track.roll_angle(passenger_car, 5.0) > 0.0
    fl, fr, rl, rr = two_track.wheel_loads(passenger_car, 5.0)
    assert fr > fl and rr > rl
    # A mid-range passenger-car roll gradient.
    gradient_deg_per_g = math.degrees(
        two_track.roll_geometry(passenger_car).roll_gradient * passenger_car.g
    )
    assert 3.0 < gradient_deg_per_g < 7.0


def test_two_track_tends_to_bicycle_at_small_lateral_acceleration(
    passenger_car: VehicleParams,
) -> None:
    p = passenger_car
    static = two_track.steady_state(p, 0.0, RADIUS)
    np.testing.assert_allclose(
        static.wheel_loads, [p.axle_load_front / 2] * 2 + [p.axle_load_rear / 2] * 2, rtol=1e-15
    )
    c_front, c_rear = bicycle.axle_cornering_stiffness(p)
    assert static.cornering_stiffness[:2].sum() == pytest.approx(c_front, rel=1e-14)
    assert static.cornering_stiffness[2:].sum() == pytest.approx(c_rear, rel=1e-14)
    assert two_track.understeer_gradient_linear(p) == pytest.approx(
        bicycle.understeer_gradient(p), rel=1e-3
    )


def test_linear_gradient_sign_follows_weight_distribution(oversteering_car: VehicleParams) -> None:
    gradient = two_track.understeer_gradient_linear(oversteering_car)
    assert gradient == pytest.approx(bicycle.understeer_gradient(oversteering_car), rel=1e-3)
    assert gradient < 0.0


@pytest.mark.parametrize('car', ['passenger_car', 'oversteering_car'])
def test_every_solved_point_is_in_equilibrium(car: str, request: pytest.FixtureRequest) -> None:
    p: VehicleParams = request.getfixturevalue(car)
    diagram = two_track.handling_diagram(p, RADIUS, n=25)
    a, b = p.cog_to_front_axle, p.cog_to_rear_axle
    front, rear = diagram.axle_force_front, diagram.axle_force_rear
    np.testing.assert_allclose(
        front + rear, p.mass * diagram.lateral_acceleration, rtol=0, atol=FORCE_RESIDUAL
    )
    np.testing.assert_allclose(a * front - b * rear, 0.0, rtol=0, atol=FORCE_RESIDUAL)
    np.testing.assert_allclose(
        diagram.wheel_loads.sum(axis=1), p.mass * p.g, rtol=0, atol=FORCE_RESIDUAL
    )
    # Each wheel's friction, stiffness and force come from its own load (eqs. 6-9).
    tires = [p.tire_front, p.tire_front, p.tire_rear, p.tire_rear]
    alphas = np.stack([diagram.slip_angle_front] * 2 + [diagram.slip_angle_rear] * 2, axis=1)
    for wheel, tire in enumerate(tires):
        fz = diagram.wheel_loads[:, wheel]
        np.testing.assert_allclose(diagram.friction[:, wheel], tire.friction(fz), rtol=1e-15)
        np.testing.assert_allclose(
            diagram.cornering_stiffness[:, wheel], tire.cornering_stiffness(fz), rtol=1e-15
        )
        force = tire.lateral_force(fz, alphas[:, wheel])
        np.testing.assert_allclose(diagram.lateral_force[:, wheel], force, rtol=1e-15)


def test_handling_diagram_shape_and_steer(passenger_car: VehicleParams) -> None:
    p = passenger_car
    diagram = two_track.handling_diagram(p, RADIUS, n=30)
    assert diagram.lateral_acceleration.shape == (30,)
    assert diagram.wheel_loads.shape == diagram.lateral_force.shape == (30, 4)
    assert diagram.lateral_acceleration[0] == 0.0
    assert diagram.lateral_acceleration[-1] == diagram.limit.lateral_acceleration
    np.testing.assert_allclose(diagram.speed**2 / RADIUS, diagram.lateral_acceleration, rtol=1e-14)
    np.testing.assert_allclose(
        diagram.steer_angle, p.wheelbase / RADIUS + diagram.slip_angle_difference, rtol=1e-15
    )
    assert np.all(np.diff(diagram.slip_angle_front) > 0.0) and np.all(
        np.diff(diagram.slip_angle_rear) > 0.0
    )
    # Understeer grows towards the front-limited end: the front slips ever more than the rear.
    assert np.all(np.diff(diagram.slip_angle_difference) > 0.0)
    assert np.all(np.diff(diagram.steer_angle) > 0.0)


def test_right_turn_mirrors_left_turn(passenger_car: VehicleParams) -> None:
    left = two_track.steady_state(passenger_car, 7.0, RADIUS)
    right = two_track.steady_state(passenger_car, -7.0, -RADIUS)
    assert right.speed == pytest.approx(left.speed)
    assert (
        right.slip_angle_front,
        right.slip_angle_rear,
        right.steer_angle,
        right.roll_angle,
    ) == pytest.approx(
        (-left.slip_angle_front, -left.slip_angle_rear, -left.steer_angle, -left.roll_angle),
        rel=1e-12,
    )
    np.testing.assert_allclose(right.wheel_loads, left.wheel_loads[[1, 0, 3, 2]], rtol=1e-14)
    np.testing.assert_allclose(right.lateral_force, -left.lateral_force[[1, 0, 3, 2]], rtol=1e-10)
    right_limit = two_track.max_lateral_acceleration(passenger_car, -RADIUS)
    left_limit = two_track.max_lateral_acceleration(passenger_car, RADIUS)
    assert right_limit.lateral_acceleration == -left_limit.lateral_acceleration
    assert right_limit.limiting_axle == left_limit.limiting_axle


def test_symmetric_car_is_neutral(make_car: CarFactory) -> None:
    """Equal axles, equal roll stiffness, roll centres and tracks: alpha_f = alpha_r throughout."""
    p = make_car(
        front_share=0.5,
        roll_stiffness_front=50000.0,
        roll_stiffness_rear=50000.0,
        roll_centre_height_rear=0.05,
        unsprung_mass_rear=80.0,
    )
    assert bicycle.understeer_gradient(p) == 0.0
    diagram = two_track.handling_diagram(p, RADIUS, n=20)
    np.testing.assert_allclose(
        diagram.slip_angle_front, diagram.slip_angle_rear, rtol=1e-9, atol=1e-15
    )
    np.testing.assert_allclose(diagram.steer_angle, p.wheelbase / RADIUS, rtol=1e-9)


def test_axle_peak_is_the_maximum_of_the_axle_force(passenger_car: VehicleParams) -> None:
    tire = passenger_car.tire_front
    loads = two_track.wheel_loads(passenger_car, 8.0)[:2]
    alpha_peak, force_peak = two_track.axle_peak(tire, loads)
    grid = np.linspace(0.0, 0.5, 50001)
    dense = two_track.axle_lateral_force(tire, loads, grid)
    assert force_peak >= dense.max()
    assert alpha_peak == pytest.approx(grid[np.argmax(dense)], abs=2e-5)
    # Between the two wheels' own peaks, the lighter wheel peaking first.
    inner_peak, outer_peak = two_track.tire_peak_slip(tire, loads)
    assert inner_peak < alpha_peak < outer_peak


def test_tire_peak_slip_is_where_the_force_peaks(passenger_car: VehicleParams) -> None:
    tire = passenger_car.tire_front
    for fz in (2000.0, 4000.0, 6000.0):
        alpha = float(two_track.tire_peak_slip(tire, fz))
        force = float(tire.lateral_force(fz, alpha))
        # sin(.) = 1 at the peak
        assert force == pytest.approx(float(tire.friction(fz)) * fz, rel=1e-12)
        assert tire.lateral_force(fz, alpha * 0.99) < force > tire.lateral_force(fz, alpha * 1.01)


def test_limit_is_solvable_and_just_beyond_it_is_not(passenger_car: VehicleParams) -> None:
    p = passenger_car
    limit = two_track.max_lateral_acceleration(p, RADIUS)
    assert limit.limiting_axle == 'front' and limit.cause == 'saturation'
    assert limit.behaviour == 'limit understeer'
    assert 0.85 * p.g < limit.lateral_acceleration < 1.0 * p.g
    assert limit.speed == pytest.approx(math.sqrt(limit.lateral_acceleration * RADIUS))
    two_track.steady_state(p, limit.lateral_acceleration, RADIUS)
    with pytest.raises(BeyondLimitError, match='front axle saturates'):
        two_track.steady_state(
            p, limit.lateral_acceleration + 2 * two_track.LIMIT_TOLERANCE, RADIUS
        )
    with pytest.raises(BeyondLimitError, match=r'front axle .* a_y = 10\.5'):
        two_track.steady_state(p, 10.5, RADIUS)


def test_oversteering_car_is_rear_limited(oversteering_car: VehicleParams) -> None:
    limit = two_track.max_lateral_acceleration(oversteering_car, RADIUS)
    assert limit.limiting_axle == 'rear' and limit.behaviour == 'limit oversteer'
    with pytest.raises(BeyondLimitError, match='rear axle saturates'):
        two_track.steady_state(
            oversteering_car, limit.lateral_acceleration + 2 * two_track.LIMIT_TOLERANCE, RADIUS
        )


def test_inner_wheel_lift_is_carried_to_the_axle_limit(make_car: CarFactory) -> None:
    # stiff front in roll, high COG: the inner front wheel lifts at 0.77 g, the
    # front axle saturates later, on its outer wheel alone
    car = make_car(cog_height=0.75, roll_stiffness_front=100000.0, roll_stiffness_rear=30000.0)
    axle, onset = two_track.wheel_lift_onset(car)
    assert axle == 'front'
    geo = two_track.roll_geometry(car)
    # eq. 4 with both wheels down reaches N_f/2 exactly at the onset
    transfer = (
        geo.sprung_mass_front * onset * car.roll_centre_height_front
        + car.roll_stiffness_front * geo.roll_gradient * onset
        + car.unsprung_mass_front * onset * car.unsprung_cog_height_front
    ) / car.track_front
    assert transfer == pytest.approx(car.axle_load_front / 2.0, rel=1e-12)
    limit = two_track.max_lateral_acceleration(car, RADIUS)
    assert (limit.limiting_axle, limit.cause) == ('front', 'saturation')
    assert limit.lateral_acceleration > onset + 0.5
    a_y = 0.5 * (onset + limit.lateral_acceleration)
    point = two_track.steady_state(car, a_y, RADIUS)
    loads = point.wheel_loads
    assert loads[0] == pytest.approx(0.0, abs=1e-9)
    assert loads[1] == pytest.approx(car.axle_load_front, rel=1e-12)
    assert point.lateral_force[0] == 0.0
    # equilibrium of the whole car, recomputed from the returned state
    phi = point.roll_angle
    d_front, d_rear = (loads[1] - loads[0]) / 2.0, (loads[3] - loads[2]) / 2.0
    overturning = car.mass * a_y * car.cog_height + geo.sprung_mass * car.g * geo.roll_arm * phi
    assert d_front * car.track_front + d_rear * car.track_rear == pytest.approx(
        overturning, rel=1e-12
    )
    assert point.axle_force_front + point.axle_force_rear == pytest.approx(
        car.mass * a_y, rel=1e-9
    )
    assert (car.cog_to_front_axle * point.axle_force_front
            - car.cog_to_rear_axle * point.axle_force_rear) == pytest.approx(0.0, abs=1e-6)
    # the body rolls against the rear alone: m_s h1 (a_y + g phi) = front moment at lift + K_r phi
    front_moment = (car.axle_load_front / 2.0 * car.track_front
                    - geo.sprung_mass_front * a_y * car.roll_centre_height_front
                    - car.unsprung_mass_front * a_y * car.unsprung_cog_height_front)
    body = geo.sprung_mass * geo.roll_arm * (a_y + car.g * phi)
    assert body == pytest.approx(front_moment + car.roll_stiffness_rear * phi, rel=1e-12)
    assert phi > geo.roll_gradient * a_y  # rolls more than eq. 3 once the front is lifted
    # continuous at the onset
    below, above = two_track.roll_angle(car, [onset * (1 - 1e-9), onset * (1 + 1e-9)])
    assert above == pytest.approx(below, rel=1e-6)


def test_rollover_when_both_inner_wheels_lift(make_car: CarFactory) -> None:
    tall = make_car(cog_height=0.9, roll_stiffness_front=80000.0, roll_stiffness_rear=20000.0)
    limit = two_track.max_lateral_acceleration(tall, RADIUS)
    assert (limit.limiting_axle, limit.cause, limit.behaviour) == ('front', 'rollover', 'rollover')
    loads = two_track.steady_state(tall, limit.lateral_acceleration, RADIUS).wheel_loads
    assert loads[0] == pytest.approx(0.0, abs=1e-9) and loads[2] > 0.0
    with pytest.raises(BeyondLimitError, match='rolls over'):
        two_track.steady_state(
            tall, limit.lateral_acceleration + 2 * two_track.LIMIT_TOLERANCE, RADIUS
        )


def test_roll_instability_is_a_solver_error(passenger_car: VehicleParams) -> None:
    soft = replace(passenger_car, roll_stiffness_front=2000.0, roll_stiffness_rear=2000.0)
    for call in (
        lambda: two_track.roll_angle(soft, 1.0),
        lambda: two_track.steady_state(soft, 1.0, RADIUS),
        lambda: two_track.max_lateral_acceleration(soft, RADIUS),
        lambda: two_track.handling_diagram(soft, RADIUS),
    ):
        with pytest.raises(SolverError, match='roll instability') as caught:
            call()
        assert not isinstance(caught.value, BeyondLimitError)


def test_invalid_operating_points(passenger_car: VehicleParams) -> None:
    with pytest.raises(ValueError, match='radius'):
        two_track.steady_state(passenger_car, 1.0, 0.0)
    with pytest.raises(ValueError, match='share the sign'):
        two_track.steady_state(passenger_car, -1.0, RADIUS)
    with pytest.raises(ValueError, match='n must'):
        two_track.handling_diagram(passenger_car, RADIUS, n=1)


# Thesis 4.1, trend (a): front-heavy cars differing only in roll stiffness
# (N*m/rad, front/rear): reference, stiffer rear, stiffer rear and softer front.
ROLL_STIFFNESS_VARIANTS = [(60000.0, 40000.0), (60000.0, 55000.0), (50000.0, 55000.0)]
# Thesis 4.1, trend (b): rear-heavy cars differing only in COG height, m.
COG_HEIGHT_VARIANTS = [0.45, 0.55, 0.65]


def _front_heavy(make_car: CarFactory, front: float, rear: float) -> VehicleParams:
    return make_car(front_share=0.60, roll_stiffness_front=front, roll_stiffness_rear=rear)


def _rear_heavy(make_car: CarFactory, height: float) -> VehicleParams:
    return make_car(
        front_share=0.40,
        cog_height=height,
        roll_stiffness_front=45000.0,
        roll_stiffness_rear=55000.0,
    )


def test_trend_a_rear_roll_stiffness_raises_the_understeer_limit(make_car: CarFactory) -> None:
    """
    Moving roll stiffness rearward unloads the front's load transfer.

    That gives more grip where it limits.
    """
    cars = [_front_heavy(make_car, front, rear) for front, rear in ROLL_STIFFNESS_VARIANTS]
    limits = [two_track.max_lateral_acceleration(car, RADIUS) for car in cars]
    assert [limit.behaviour for limit in limits] == ['limit understeer'] * 3
    assert all(two_track.understeer_gradient_linear(car) > 0.0 for car in cars)
    a_max = [limit.lateral_acceleration for limit in limits]
    assert a_max[0] < a_max[1] < a_max[2]
    # a real effect, not bisection noise
    assert a_max[2] - a_max[0] > 100 * two_track.LIMIT_TOLERANCE


def test_trend_b_higher_cog_lowers_the_oversteer_limit(make_car: CarFactory) -> None:
    """More load transfer on both axles costs grip through the friction load sensitivity."""
    cars = [_rear_heavy(make_car, height) for height in COG_HEIGHT_VARIANTS]
    limits = [two_track.max_lateral_acceleration(car, RADIUS) for car in cars]
    assert [limit.behaviour for limit in limits] == ['limit oversteer'] * 3
    assert all(two_track.understeer_gradient_linear(car) < 0.0 for car in cars)
    a_max = [limit.lateral_acceleration for limit in limits]
    assert a_max[0] > a_max[1] > a_max[2]
    assert a_max[0] - a_max[2] > 100 * two_track.LIMIT_TOLERANCE


@pytest.mark.parametrize('variants', ['roll_stiffness', 'cog_height'])
def test_trends_vanish_with_load_insensitive_tires(make_car: CarFactory, variants: str) -> None:
    """
    Control: with load-insensitive tires (mu1 = c1 = 0) both trends disappear.

    An axle's force is then mu0 N f(alpha) whatever the load transfer, so every car
    reaches mu0 g: the trends come from the tire physics.
    """
    insensitive = replace(make_car().tire_front, mu1=0.0, c1=0.0)
    if variants == 'roll_stiffness':
        cars = [_front_heavy(make_car, front, rear) for front, rear in ROLL_STIFFNESS_VARIANTS]
    else:
        cars = [_rear_heavy(make_car, height) for height in COG_HEIGHT_VARIANTS]
    for car in cars:
        car = replace(car, tire_front=insensitive, tire_rear=insensitive)
        limit = two_track.max_lateral_acceleration(car, RADIUS)
        assert limit.lateral_acceleration == pytest.approx(
            insensitive.mu0 * car.g, abs=2 * two_track.LIMIT_TOLERANCE
        )


def test_tire_vertical_compliance_rolls_the_axles_on_their_tires(make_car) -> None:
    """
    Check the roll with compliant tires against the three balances solved here.

    Unknowns: body roll phi and each axle's roll on its tires psi_i (K_ti = C_z t_i^2 / 2).
    Each axle's tires carry its load transfer, K_ti psi_i = M_geo,i + K_phi,i (phi - psi_i);
    the body balances m_s h1 (a_y + g phi) = sum K_phi,i (phi - psi_i). A 250 kN/m tire on
    this car adds a quarter to the rigid-tire roll gradient (the sedan's: 2.87 -> 3.69
    deg/g); the load transfer still balances the overturning moment.
    """
    c_z = 250e3
    rigid = make_car()
    p = replace(rigid, tire_vertical_stiffness_front=c_z, tire_vertical_stiffness_rear=c_z)
    geo = two_track.roll_geometry(p)
    a_y = 1.0
    m_geo = [geo.sprung_mass_front * p.roll_centre_height_front
             + p.unsprung_mass_front * p.unsprung_cog_height_front,
             geo.sprung_mass_rear * p.roll_centre_height_rear
             + p.unsprung_mass_rear * p.unsprung_cog_height_rear]
    k_phi = [p.roll_stiffness_front, p.roll_stiffness_rear]
    k_t = [c_z * p.track_front**2 / 2.0, c_z * p.track_rear**2 / 2.0]
    net = geo.sprung_mass * p.g * geo.roll_arm
    # rows: body, front tires, rear tires; columns: phi, psi_f, psi_r
    matrix = np.array([[sum(k_phi) - net, -k_phi[0], -k_phi[1]],
                       [-k_phi[0], k_t[0] + k_phi[0], 0.0],
                       [-k_phi[1], 0.0, k_t[1] + k_phi[1]]])
    phi, psi_f, psi_r = np.linalg.solve(
        matrix, [geo.sprung_mass * geo.roll_arm * a_y, m_geo[0] * a_y, m_geo[1] * a_y])
    assert geo.roll_gradient == pytest.approx(phi, rel=1e-12)
    roll, transfer, tilt = two_track.roll_state(p, a_y)
    assert roll == pytest.approx(phi, rel=1e-12)
    npt.assert_allclose(tilt, [psi_f, psi_r], rtol=1e-12)
    npt.assert_allclose(transfer, [k_t[0] * psi_f / p.track_front, k_t[1] * psi_r / p.track_rear],
                        rtol=1e-12)
    rigid_roll = two_track.roll_geometry(rigid).roll_gradient
    assert 1.1 * rigid_roll < phi < 1.5 * rigid_roll
    overturning = (p.mass * a_y * p.cog_height + net * phi)
    assert transfer @ [p.track_front, p.track_rear] == pytest.approx(overturning, rel=1e-12)


def test_the_spinning_wheels_gyroscopic_moment_rolls_the_body(make_car) -> None:
    """
    Check the gyroscopic roll moment: sum over the wheels of I_spin omega r.

    In a steady turn each wheel's spin momentum I_spin V / R (R its rolling radius) turns
    at the yaw rate V / R_turn: a roll moment (I_spin / R) a_y per wheel on the body,
    outward. Rigid tires: eq. 3 with m_s h1 a_y + sum (I_spin / R) a_y.
    """
    per_wheel = 1.2 / 0.31  # kg*m^2 over m
    rigid = make_car()
    p = replace(rigid, wheel_gyroscopic_front=per_wheel, wheel_gyroscopic_rear=per_wheel)
    geo = two_track.roll_geometry(p)
    net = p.roll_stiffness - geo.sprung_mass * p.g * geo.roll_arm
    expected = (geo.sprung_mass * geo.roll_arm + 4.0 * per_wheel) / net
    assert geo.roll_gradient == pytest.approx(expected, rel=1e-12)
    assert geo.roll_gradient > two_track.roll_geometry(rigid).roll_gradient
