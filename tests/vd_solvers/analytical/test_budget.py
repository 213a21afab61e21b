# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The understeer-gradient budget and the effective axle cornering stiffness.

References: every term in isolation against its closed form written out here
(Gillespie, "Fundamentals of Vehicle Dynamics", ch. 6; Milliken & Milliken,
"Race Car Vehicle Dynamics", ch. 5), with the roll gradient from thesis eq. 3
written out for a car without unsprung masses; the two-track model, which
applies the same compliance per wheel along its own path, as a second
implementation; and the bare-tire formulas of thesis eq. 2.
"""
from __future__ import annotations

from dataclasses import replace
import math

import numpy as np
import pytest

from vd_solvers.analytical import bicycle, two_track
from vd_solvers.analytical.budget import (
    PITCH_TERMS,
    RANGE_TERMS,
    SHIFT_TERMS,
    TERMS,
    effective_axle_cornering_stiffness,
    understeer_budget,
)
from vd_solvers.analytical.params import AxleCompliance, VehicleParams
from vd_solvers.errors import SolverError

from .conftest import CarFactory

DEG = 180.0 / math.pi
RADIUS = 100.0


def deg_per_g(k: float, p: VehicleParams) -> float:
    return k * DEG * p.g


@pytest.fixture
def rigid_car(make_car: CarFactory) -> VehicleParams:
    """Return the fixture car without unsprung masses, so eq. 3 is the thesis' own."""
    return make_car(unsprung_mass_front=0.0, unsprung_mass_rear=0.0)


def roll_gradient_eq3(p: VehicleParams) -> float:
    """Thesis eq. 3 per unit a_y: m h1 / (K_phi - m g h1), roll axis at the COG."""
    axis = (
        p.roll_centre_height_front
        + (p.roll_centre_height_rear - p.roll_centre_height_front)
        * p.cog_to_front_axle
        / p.wheelbase
    )
    h1 = p.cog_height - axis
    return p.mass * h1 / (p.roll_stiffness - p.mass * p.g * h1)


def wheel_stiffness(p: VehicleParams, axle: str) -> float:
    tire, load = ((p.tire_front, p.axle_load_front) if axle == 'front'
                  else (p.tire_rear, p.axle_load_rear))
    return float(tire.cornering_stiffness(load / 2.0))


def with_compliance(p: VehicleParams, axle: str, **values: float) -> VehicleParams:
    return replace(p, **{f'compliance_{axle}': AxleCompliance(**values)})


def only_term(p: VehicleParams, name: str, also: tuple[str, ...] = ()) -> float:
    """Return the one nonzero compliance term, checking that all others are exactly zero."""
    budget = understeer_budget(p)
    for term in budget.terms:
        if term.name not in ('tire', name, *also):
            assert term.value == 0.0, term.name
    return budget.term(name).value


# --- each term against its closed form ------------------------------------------------


@pytest.mark.parametrize('axle, sign', [('front', -1.0), ('rear', 1.0)])
def test_lateral_compliance_steer_term(rigid_car: VehicleParams, axle: str, sign: float) -> None:
    # c deg/kN of steer towards the force, per wheel: the wheel load N/2 per g
    # steers it by c N/2 / 1000 deg per g, understeer at the rear, oversteer at the front
    c = 0.12  # deg/kN
    p = with_compliance(rigid_car, axle, lateral_compliance_steer=c / DEG / 1e3)
    load = p.axle_load_front if axle == 'front' else p.axle_load_rear
    expected = sign * c * (load / 2.0) / 1000.0  # deg/g
    assert deg_per_g(only_term(p, 'lateral_compliance_steer'), p) == pytest.approx(
        expected, rel=1e-12
    )
    change = deg_per_g(bicycle.understeer_gradient(p) - bicycle.understeer_gradient(rigid_car), p)
    assert change == pytest.approx(expected, rel=1e-9)


@pytest.mark.parametrize('axle, sign', [('front', -1.0), ('rear', 1.0)])
def test_roll_steer_term(rigid_car: VehicleParams, axle: str, sign: float) -> None:
    epsilon = -0.08  # rad of steer (left) per rad of roll: front steers out of the turn
    p = with_compliance(rigid_car, axle, roll_steer=epsilon)
    expected = sign * epsilon * roll_gradient_eq3(p)  # rad/(m/s^2)
    assert only_term(p, 'roll_steer') == pytest.approx(expected, rel=1e-12)
    assert understeer_budget(p).roll_gradient == pytest.approx(roll_gradient_eq3(p), rel=1e-12)


@pytest.mark.parametrize('axle, sign', [('front', 1.0), ('rear', -1.0)])
def test_aligning_torque_term(rigid_car: VehicleParams, axle: str, sign: float) -> None:
    # Mz = -t F_y turns each wheel by -c_Mz t F_y: out of the turn
    c_mz, trail = 3.0 / DEG / 1e3, 0.03  # rad/(N*m), m
    p = with_compliance(
        rigid_car, axle, aligning_torque_compliance_steer=c_mz, pneumatic_trail=trail
    )
    load = p.axle_load_front if axle == 'front' else p.axle_load_rear
    expected = sign * c_mz * trail * load / 2.0  # rad per g
    # the same trail puts the axle's force behind it: the aligning_moment term
    assert only_term(p, 'aligning_torque', also=('aligning_moment',)) * p.g == pytest.approx(
        expected, rel=1e-12)


def _single_track_with_moments(p: VehicleParams, moment: float) -> float:
    """
    Return K of a single track whose yaw balance holds the tires' aligning moments.

    Written out: F_f + F_r = m a_y, a F_f - b F_r - t_f F_f - t_r F_r + moment a_y = 0,
    the bare axles' slips F / C, K = d(alpha_f - alpha_r) / d a_y.
    """
    t_f, t_r = p.compliance_front.pneumatic_trail, p.compliance_rear.pneumatic_trail
    a, b = p.cog_to_front_axle, p.cog_to_rear_axle
    matrix = np.array([[1.0, 1.0], [a - t_f, -(b + t_r)]])
    f_front, f_rear = np.linalg.solve(matrix, [p.mass, -moment])
    c_f, c_r = 2.0 * wheel_stiffness(p, 'front'), 2.0 * wheel_stiffness(p, 'rear')
    return f_front / c_f - f_rear / c_r


def test_aligning_moment_term(rigid_car: VehicleParams) -> None:
    """The tires' aligning moments -t F_y in the single track's yaw balance, written out."""
    p = replace(rigid_car, compliance_front=AxleCompliance(pneumatic_trail=0.04),
                compliance_rear=AxleCompliance(pneumatic_trail=0.03))
    expected = _single_track_with_moments(p, 0.0) - _single_track_with_moments(rigid_car, 0.0)
    assert expected > 0.0  # the forces act behind the axles: more front force, understeer
    assert only_term(p, 'aligning_moment') == pytest.approx(expected, rel=1e-9)
    change = bicycle.understeer_gradient(p) - bicycle.understeer_gradient(rigid_car)
    assert change == pytest.approx(expected, rel=1e-9)


def test_rolling_resistance_term(rigid_car: VehicleParams) -> None:
    """
    The outer wheels' larger rolling resistance turns the car out of the turn.

    Yaw moment -sum t_i rho_rr,i dF_zi per m/s^2 with the load transfer of eq. 4
    written out for a car without unsprung masses.
    """
    rho_rr = 0.012
    p = replace(rigid_car, compliance_front=AxleCompliance(rolling_resistance=rho_rr),
                compliance_rear=AxleCompliance(rolling_resistance=rho_rr))
    phi = roll_gradient_eq3(p)
    sprung_f = p.mass * p.cog_to_rear_axle / p.wheelbase
    transfer_f = ((sprung_f * p.roll_centre_height_front + p.roll_stiffness_front * phi)
                  / p.track_front)
    transfer_r = ((p.mass - sprung_f) * p.roll_centre_height_rear
                  + p.roll_stiffness_rear * phi) / p.track_rear
    moment = -rho_rr * (p.track_front * transfer_f + p.track_rear * transfer_r)
    expected = _single_track_with_moments(p, moment) - _single_track_with_moments(p, 0.0)
    assert expected > 0.0
    assert only_term(p, 'rolling_resistance') == pytest.approx(expected, rel=1e-9)


def test_rolling_resistance_pitch_term(rigid_car: VehicleParams) -> None:
    """
    The rolling-resistance moments unload the front axle: understeer.

    Written out: each tire's M_y = -rho_rr F_z R_l about the wheel's axis, summed over
    the car, is a nose-up moment -rho_rr R_l m g; the pitch balance takes
    rho_rr R_l m g / L from the front axle to the rear, whose lateral forces (m a_y b / L,
    m a_y a / L) stay; the bare axles' slips F / C at the loads in motion.
    """
    rho_rr, radius = 0.012, 0.30
    p = replace(rigid_car,
                compliance_front=AxleCompliance(rolling_resistance=rho_rr, loaded_radius=radius),
                compliance_rear=AxleCompliance(rolling_resistance=rho_rr, loaded_radius=radius))
    weight = p.mass * p.g
    shift = rho_rr * radius * weight / p.wheelbase
    front_force = p.mass * p.cog_to_rear_axle / p.wheelbase  # N per m/s^2
    rear_force = p.mass * p.cog_to_front_axle / p.wheelbase

    def slip(force: float, tire, axle_load: float) -> float:
        return force / (2.0 * float(tire.cornering_stiffness(axle_load / 2.0)))

    moving = (slip(front_force, p.tire_front, p.axle_load_front - shift)
              - slip(rear_force, p.tire_rear, p.axle_load_rear + shift))
    static = (slip(front_force, p.tire_front, p.axle_load_front)
              - slip(rear_force, p.tire_rear, p.axle_load_rear))
    expected = moving - static
    assert expected > 0.0
    assert only_term(p, 'rolling_resistance_pitch', also=('rolling_resistance',)) == (
        pytest.approx(expected, rel=1e-9))
    # the bicycle's effective axles hold it: K moves by the term
    change = bicycle.understeer_gradient(p) - bicycle.understeer_gradient(
        replace(p, compliance_front=AxleCompliance(rolling_resistance=rho_rr),
                compliance_rear=AxleCompliance(rolling_resistance=rho_rr)))
    assert change == pytest.approx(expected, rel=1e-9)


@pytest.mark.parametrize('axle, sign', [('front', 1.0), ('rear', -1.0)])
def test_roll_camber_term(rigid_car: VehicleParams, axle: str, sign: float) -> None:
    # the wheels lean out of the turn by -0.8 rad per rad of roll; the camber
    # thrust C_gamma gamma then has to be made up by C_w of slip
    roll_camber, c_gamma = -0.8, 4000.0
    p = with_compliance(rigid_car, axle, roll_camber=roll_camber, camber_stiffness=c_gamma)
    expected = -sign * c_gamma / wheel_stiffness(p, axle) * roll_camber * roll_gradient_eq3(p)
    assert only_term(p, 'camber') == pytest.approx(expected, rel=1e-12)


def test_lateral_compliance_camber_term(rigid_car: VehicleParams) -> None:
    # top-outward camber per inward force: both wheels lean out of the turn
    cc, c_gamma = 0.05 / DEG / 1e3, 4000.0
    p = with_compliance(rigid_car, 'front', lateral_compliance_camber=cc, camber_stiffness=c_gamma)
    expected = c_gamma / wheel_stiffness(p, 'front') * cc * p.axle_load_front / 2.0  # rad per g
    assert only_term(p, 'camber') * p.g == pytest.approx(expected, rel=1e-12)


def test_tire_term_is_eq_2_and_load_transfer_vanishes(rigid_car: VehicleParams) -> None:
    budget = understeer_budget(rigid_car)
    c_f = 2.0 * wheel_stiffness(rigid_car, 'front')
    c_r = 2.0 * wheel_stiffness(rigid_car, 'rear')
    expected = (rigid_car.axle_load_front / c_f - rigid_car.axle_load_rear / c_r) / rigid_car.g
    assert budget.term('tire').value == pytest.approx(expected, rel=1e-13)
    assert budget.term('load_transfer').value == 0.0
    assert [t.name for t in budget.terms] == list(TERMS)


# --- the sum, and the bicycle and two-track models ------------------------------------


def all_terms(p: VehicleParams) -> VehicleParams:
    front = AxleCompliance(
        lateral_compliance_steer=-0.1 / DEG / 1e3,
        lateral_compliance_camber=0.02 / DEG / 1e3,
        roll_steer=-0.05,
        roll_camber=-0.8,
        aligning_torque_compliance_steer=3e-3 / DEG,
        pneumatic_trail=0.03,
        camber_stiffness=4000.0,
        rolling_resistance=0.01,
        loaded_radius=0.30,
    )
    rear = AxleCompliance(
        lateral_compliance_steer=0.09 / DEG / 1e3,
        lateral_compliance_camber=0.08 / DEG / 1e3,
        roll_steer=0.03,
        roll_camber=-0.45,
        aligning_torque_compliance_steer=0.26e-3 / DEG,
        pneumatic_trail=0.03,
        camber_stiffness=3500.0,
        rolling_resistance=0.01,
        loaded_radius=0.30,
    )
    return replace(p, compliance_front=front, compliance_rear=rear)


def test_terms_sum_to_the_bicycle_understeer_gradient(passenger_car: VehicleParams) -> None:
    p = all_terms(passenger_car)
    budget = understeer_budget(p)
    # the range terms come from the two-track model, not given here
    assert all((t.value == 0.0) == (t.name in RANGE_TERMS) for t in budget.terms)
    total = sum(deg_per_g(t.value, p) for t in budget.terms)
    assert total == pytest.approx(deg_per_g(bicycle.understeer_gradient(p), p), abs=1e-9)
    assert deg_per_g(budget.total, p) == pytest.approx(total, abs=1e-12)


def test_effective_stiffness_reproduces_each_axle_slip(passenger_car: VehicleParams) -> None:
    # N/C_eff = N/C + g e for each axle separately
    p = all_terms(passenger_car)
    budget = understeer_budget(p)
    c_f, c_r = effective_axle_cornering_stiffness(p)
    front = sum(t.front for t in budget.terms)
    rear = sum(t.rear for t in budget.terms)
    assert p.axle_load_front / c_f / p.g == pytest.approx(front, rel=1e-12)
    assert p.axle_load_rear / c_r / p.g == pytest.approx(rear, rel=1e-12)


def test_two_track_linear_gradient_equals_the_budget(passenger_car: VehicleParams) -> None:
    # the two-track model applies steer and camber thrust per wheel and solves the
    # tires itself: its linear-range slope must be the budget's total but for the
    # shift and pitch terms, which its equal-slip axles at their static loads do not
    # hold (the wheel-by-wheel model does)
    p = all_terms(passenger_car)
    budget = understeer_budget(p)
    k_two_track = two_track.understeer_gradient_linear(p)
    shifts = sum(budget.term(name).value for name in SHIFT_TERMS + PITCH_TERMS)
    assert k_two_track == pytest.approx(budget.total - shifts, rel=1e-3)
    point = two_track.steady_state(p, 3.0, RADIUS)
    # in force and moment equilibrium with the camber thrust in the wheel forces
    assert point.axle_force_front + point.axle_force_rear == pytest.approx(p.mass * 3.0, rel=1e-9)
    assert (p.cog_to_front_axle * point.axle_force_front
            - p.cog_to_rear_axle * point.axle_force_rear) == pytest.approx(0.0, abs=1e-6)
    # kinematic slip = tire slip - steer change (front: out of the turn, so larger)
    assert point.slip_angle_front > point.tire_slip_angle[0]


def test_bicycle_steady_state_uses_the_effective_stiffness(passenger_car: VehicleParams) -> None:
    p = all_terms(passenger_car)
    state = bicycle.steady_state(p, RADIUS, 20.0)
    k = bicycle.understeer_gradient(p)
    assert state.steer_angle == pytest.approx(
        p.wheelbase / RADIUS + k * state.lateral_acceleration, rel=1e-12
    )
    assert state.steer_angle == pytest.approx(
        p.wheelbase / RADIUS + state.slip_angle_front - state.slip_angle_rear, rel=1e-12)
    assert bicycle.characteristic_speed(p) == pytest.approx(math.sqrt(p.wheelbase / k), rel=1e-12)


# --- zero compliance is today's bare-tire model --------------------------------------


def test_zero_compliance_gives_the_bare_tire_values_exactly(passenger_car: VehicleParams) -> None:
    labelled = replace(
        passenger_car,
        compliance_front=AxleCompliance(sources={'roll_steer': 'K&C'}),
        compliance_rear=AxleCompliance(camber_stiffness=4000.0),
    )
    for p in (passenger_car, labelled):
        c_f = 2.0 * float(p.tire_front.cornering_stiffness(p.axle_load_front / 2.0))
        c_r = 2.0 * float(p.tire_rear.cornering_stiffness(p.axle_load_rear / 2.0))
        assert effective_axle_cornering_stiffness(p) == (c_f, c_r)
        assert (
            bicycle.understeer_gradient(p)
            == (p.axle_load_front / c_f - p.axle_load_rear / c_r) / p.g
        )
        assert understeer_budget(p).total == bicycle.understeer_gradient(p)
        ss = bicycle.state_space(p, 25.0)
        bare = bicycle.state_space(passenger_car, 25.0)
        np.testing.assert_array_equal(ss.a, bare.a)
        np.testing.assert_array_equal(ss.b, bare.b)
        assert two_track.understeer_gradient_linear(p) == two_track.understeer_gradient_linear(
            passenger_car
        )
        limit = two_track.max_lateral_acceleration(p, RADIUS)
        assert limit == two_track.max_lateral_acceleration(passenger_car, RADIUS)
    sources = {t.name: t.source for t in understeer_budget(passenger_car).terms}
    assert (
        sources['roll_steer']
        == 'front: bare tire: no K&C results; rear: bare tire: no K&C results'
    )


def test_compliance_that_cancels_the_tires_is_refused(passenger_car: VehicleParams) -> None:
    # steer towards the force large enough to need no tire slip at all
    p = with_compliance(passenger_car, 'front', lateral_compliance_steer=2.0 / DEG / 1e3)
    with pytest.raises(SolverError, match="front axle: the compliance slip .* cancels the tires' "
                                          ".* no positive effective cornering stiffness"):
        effective_axle_cornering_stiffness(p)
