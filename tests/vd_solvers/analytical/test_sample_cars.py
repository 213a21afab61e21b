# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The sample cars behave like cars: understeer budget, geometry, loaded alignment, preload.

Ranges are those of production saloons (Gillespie, "Fundamentals of Vehicle
Dynamics", ch. 6: understeer gradients of a few deg/g; characteristic speeds
of 65-100 km/h); the geometry ranges are the issue's: scrub radius -10...+40
mm, steering ratio 14-17, the rear roll centre above the front, the front's
share of the roll stiffness above its share of the weight.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from conftest import SAMPLE_DATA
from vd_data_server.study import load_study
from vd_data_server.units import ureg
from vd_solvers.analytical.budget import RANGE_TERMS, TERMS
from vd_solvers.analytical.events import run_event
from vd_solvers.constants import STANDARD_GRAVITY as G
from vd_solvers.kc import cache
from vd_solvers.kc.channels import wheel_angles
from vd_solvers.kc.events import KCModel
from vd_solvers.kc.from_config import run_kc_event, suspension_input
from vd_solvers.kc.metrics import derived_metrics
from vd_solvers.kc.solver import solve_static
from vd_solvers.kc.system import LoadCase
from vd_solvers.vehicle_data import static_wheel_loads

STUDIES = {name: load_study(SAMPLE_DATA / 'studies' / f'{name}.yaml')
           for name in ('sedan', 'hmmwv')}
CONFIGS = [(study, name) for study, s in STUDIES.items() for name in s.configurations]


@pytest.fixture(scope='module')
def sedan_bicycle():
    return run_event(STUDIES['sedan'].configurations['baseline'], 'steady_state_circular',
                     'bicycle', ['steps=3'])


def kc(config, axle: str, event: str) -> dict[str, float]:
    """Return the derived metrics of one K&C event (default parameters, cached by hash)."""
    results = {event: cache.kc_result(config, axle, event)}
    return {k: v for k, (v, _) in derived_metrics(
        results, cache.kc_model(config, axle).inp.tire_vertical_stiffness,
        wheelbase=config.group('geometry').scalar('wheelbase')).items()}


def test_sedan_understeers_like_a_saloon(sedan_bicycle) -> None:
    m = sedan_bicycle.metrics
    assert m['understeer_gradient'].unit == 'rad/(m/s^2)'
    assert 1.5 <= math.degrees(m['understeer_gradient'].value) * G <= 4.0  # deg/g
    assert m['characteristic_speed'].unit == 'm/s'
    assert 60.0 <= m['characteristic_speed'].value * 3.6 <= 110.0  # km/h


def test_sedan_budget_sums_to_its_understeer_gradient_and_names_its_sources(sedan_bicycle) -> None:
    m = sedan_bicycle.metrics
    linear = sum(m[f'understeer_budget_{t}'].value for t in TERMS if t not in RANGE_TERMS)
    assert linear == pytest.approx(m['understeer_gradient'].value, abs=1e-12)
    total = sum(m[f'understeer_budget_{t}'].value for t in TERMS)
    assert total == pytest.approx(m['understeer_budget_total'].value, abs=1e-12)
    for term in RANGE_TERMS:  # from the two-track model over the linear range
        assert m[f'understeer_budget_{term}'].source.startswith('two-track wheel by wheel')
    data_hash = STUDIES['sedan'].configurations['baseline'].data_hash
    for term in ('roll_steer', 'lateral_compliance_steer', 'aligning_torque', 'camber'):
        source = m[f'understeer_budget_{term}'].source
        assert 'K&C front' in source and 'K&C rear' in source and data_hash in source
    assert m['understeer_budget_tire'].source.startswith('front: tires/Sedan_Pac02Tire.tir')
    assert m['understeer_gradient'].source.startswith('effective axle cornering')


def test_sedan_budget_terms_are_the_k_and_c_metrics_of_the_same_data(sedan_bicycle) -> None:
    # lateral compliance steer alone, from the K&C lateral-force run's own metric:
    # (-c_f N_f/2 + c_r N_r/2) / g, c in rad/N (converted from the metric's own unit)
    config = STUDIES['sedan'].configurations['baseline']
    fz_f, fz_r = static_wheel_loads(config)
    # the K&C run as `vd run lateral_force --axle ...` reports it
    c_f, c_r = (
        _rad_per_newton(run_kc_event(config, 'lateral_force', axle)
                        .metrics['lateral_compliance_steer']) for axle in ('front', 'rear'))
    expected = (-c_f * fz_f + c_r * fz_r) / G
    term = sedan_bicycle.metrics['understeer_budget_lateral_compliance_steer']
    assert term.unit == 'rad/(m/s^2)'
    assert term.value == pytest.approx(expected, rel=1e-12)


def _rad_per_newton(metric) -> float:
    return float(ureg().Quantity(metric.value, metric.unit).to('rad/N').magnitude)


def test_result_does_not_depend_on_what_ran_before() -> None:
    # a fresh process (empty cache) and one that ran the K&C events first give
    # the same numbers: vd run on a fresh graph equals the value inside make demo
    config = STUDIES['sedan'].configurations['baseline']
    cache.clear()
    fresh = run_event(config, 'handling_diagram', 'two_track', ['steps=5'])
    run_kc_event(config, 'opposite_wheel_travel', 'rear', ['steps=21'])
    again = run_event(config, 'handling_diagram', 'two_track', ['steps=5'])
    assert ({k: v.value for k, v in fresh.metrics.items()}
            == {k: v.value for k, v in again.metrics.items()})


@pytest.mark.parametrize('name', ['baseline', 'sport'])
def test_sedan_geometry_is_credible(name: str) -> None:
    config = STUDIES['sedan'].configurations[name]
    front = kc(config, 'front', 'parallel_wheel_travel')
    rear = kc(config, 'rear', 'parallel_wheel_travel')
    assert -0.010 <= front['scrub_radius'] <= 0.040  # m
    assert 14.0 <= kc(config, 'front', 'steering')['steering_ratio'] <= 17.0
    assert rear['roll_centre_height_kinematic'] > front['roll_centre_height_kinematic']
    k_f = kc(config, 'front', 'opposite_wheel_travel')['roll_stiffness']
    k_r = kc(config, 'rear', 'opposite_wheel_travel')['roll_stiffness']
    fz_f, fz_r = static_wheel_loads(config)
    assert k_f / (k_f + k_r) > fz_f / (fz_f + fz_r)


def test_thesis_trend_a_on_the_sample_sedan() -> None:
    # the stiffer rear bar of stiff_rear raises the limit of the understeering car
    limits = {}
    for name in ('baseline', 'stiff_rear'):
        out = run_event(STUDIES['sedan'].configurations[name], 'handling_diagram', 'two_track',
                        ['steps=3'])
        assert out.metrics['limiting_axle_is_rear'].value == 0.0
        assert out.metrics['understeer_gradient_linear'].value > 0.0
        limits[name] = out.metrics['max_lateral_acceleration'].value
    assert limits['stiff_rear'] > limits['baseline'] + 0.01


@pytest.mark.parametrize('study, name', CONFIGS)
@pytest.mark.parametrize('axle', ['front', 'rear'])
def test_loaded_alignment_and_spring_preload(study: str, name: str, axle: str) -> None:
    # recomputed from the solved design state: toe and camber of both wheels are the
    # specified ones, and the pads carry the corner load from the mass data within 1 %
    config = STUDIES[study].configurations[name]
    inp = suspension_input(config, axle)
    model = KCModel(inp)
    state, _, _ = solve_static(model.system, LoadCase(), 'design', None)
    _, axis, _ = model.system.contact_points(state)
    angles = wheel_angles(axis)
    for key, spec in (('toe', inp.toe), ('camber', inp.camber)):
        assert np.degrees(np.abs(angles[key] - spec)).max() < 1e-4, (key, angles[key], spec)
    if not inp.bushings:
        assert (model.inp.toe, model.inp.camber) == (inp.toe, inp.camber)
    pad = -state.lam[model.system.outputs.pad_rows]
    np.testing.assert_allclose(pad, inp.corner_load, rtol=0.01)


def test_hmmwv_front_bushings_pivot_freely() -> None:
    # Chrono's bushing leaves the arm's pivot rotation free: the bushings change
    # the roll stiffness of ideal joints by a few per cent, not by a factor
    study = STUDIES['hmmwv']
    ideal, bushed = (kc(study.configurations[name], 'front', 'opposite_wheel_travel')
                     ['roll_stiffness'] for name in ('baseline', 'bushings'))
    assert math.isclose(bushed, ideal, rel_tol=0.05)


def test_without_a_k_and_c_model_the_result_says_bare_tire_and_design_target() -> None:
    from dataclasses import replace

    config = STUDIES['sedan'].configurations['baseline']
    groups = {k: v for k, v in config.groups.items() if k != 'rear_spring'}
    bare = replace(config, groups=groups)
    out = run_event(bare, 'steady_state_circular', 'bicycle', ['steps=3'])
    assert "bare tire and design targets: no K&C model ('rear_spring')" in out.notes
    m = out.metrics
    assert m['understeer_gradient'].source == 'bare tire: no K&C results'
    assert m['understeer_budget_roll_steer'].source == (
        'front: bare tire: no K&C results; rear: bare tire: no K&C results')
    # the bare-tire gradient is the tire term alone
    assert m['understeer_gradient'].value == m['understeer_budget_total'].value
    assert m['understeer_budget_tire'].value == pytest.approx(
        m['understeer_gradient'].value, rel=1e-12)
    two = run_event(bare, 'handling_diagram', 'two_track', ['steps=3'])
    assert two.metrics['roll_stiffness_front'].source == (
        'design target sedan/targets/X.yaml (variant X)')
