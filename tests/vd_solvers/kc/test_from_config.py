# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""The K&C input built from a resolved configuration, and K&C events on the sample vehicles."""
from __future__ import annotations

from dataclasses import replace
import math

from numpy.testing import assert_allclose
import pytest

from vd_data_server.master import with_overrides
from vd_data_server.study import load_study
from vd_solvers.analytical.events import run_event
from vd_solvers.errors import SolverError
from vd_solvers.kc.from_config import run_kc_event, suspension_input
from vd_solvers.vehicle_data import static_wheel_loads

G = 9.80665
EVENTS = ('parallel_wheel_travel', 'opposite_wheel_travel', 'lateral_force',
          'longitudinal_force', 'steering', 'aligning_torque')


@pytest.fixture(scope='module')
def sedan():
    from conftest import SAMPLE_DATA

    return load_study(SAMPLE_DATA / 'studies' / 'sedan.yaml')


@pytest.fixture(scope='module')
def hmmwv():
    from conftest import SAMPLE_DATA

    return load_study(SAMPLE_DATA / 'studies' / 'hmmwv.yaml')


def test_input_carries_the_data_in_si(sedan):
    inp = suspension_input(sedan.configurations['baseline'], 'front')
    assert inp.template == 'macpherson'
    # front_hardpoints/X.yaml writes lca_outer as [18.4, 706.0, 181.0] mm
    assert_allclose(inp.hardpoints['lca_outer'], [0.0184, 0.706, 0.181], atol=1e-12)
    assert inp.spring.rate == pytest.approx(30.0e3)  # 30 N/mm
    assert inp.spring.preload == pytest.approx(4535.0)  # sedan/front_spring/X.yaml
    assert inp.tire_vertical_stiffness == pytest.approx(280835.2941)  # Sedan_Pac02Tire.tir
    assert inp.tire_radius == pytest.approx(0.329)  # design wheel-centre height
    assert inp.camber == pytest.approx(math.radians(-0.5))
    assert inp.toe == pytest.approx(math.radians(0.05))
    # stabilizer from bar geometry: G pi r^4 / (2 L), r = 12 mm, L = 800 mm, G = 79300 N/mm^2
    assert inp.stabilizer.torsional_stiffness == pytest.approx(
        79300e6 * math.pi * 0.012 ** 4 / 2.0 / 0.8)
    # bushing rates: 8000 N/mm and 4000 N*mm/deg
    lca = inp.bushings['lca_front']
    assert lca.stiffness[0] == pytest.approx(8.0e6)
    assert lca.stiffness[3] == pytest.approx(4000e-3 * 180.0 / math.pi)
    assert inp.steering.rack_ratio == pytest.approx(0.078 / (2.0 * math.pi))
    assert suspension_input(sedan.configurations['baseline'], 'rear').steering is None


def test_corner_loads_add_up_to_the_vehicle_weight(sedan):
    front, rear = static_wheel_loads(sedan.configurations['baseline'])
    mass = 1550.0 + 2 * 45.0 + 2 * 40.0  # sedan/mass/X.yaml
    assert 2.0 * (front + rear) == pytest.approx(mass * G, rel=1e-12)


def test_damping_scale_override_scales_the_damper_curve(sedan):
    base = suspension_input(sedan.configurations['baseline'], 'front').damper.curve
    sport = suspension_input(sedan.configurations['sport'], 'front').damper.curve
    assert_allclose(sport.y, 1.2 * base.y)  # sport: front_damper.scale 120 %


@pytest.mark.parametrize('study_name', ['sedan', 'hmmwv'])
def test_every_event_runs_on_every_configuration_within_tolerance(request, study_name):
    study = request.getfixturevalue(study_name)
    for config in study.configurations.values():
        for axle in ('front', 'rear'):
            for event in EVENTS:
                if event == 'steering' and axle == 'rear':
                    continue
                out = run_kc_event(config, event, axle, ['steps=11'])
                assert out.metrics['max_constraint_residual'].value <= 1e-9
                assert out.metrics['max_force_residual'].value <= 1e-6
                assert out.n_steps == 11


def test_parallel_travel_is_left_right_symmetric(sedan):
    out = run_kc_event(sedan.configurations['sport'], 'parallel_wheel_travel', 'front',
                       ['steps=21'])
    ch = out.channels
    assert_allclose(ch['toe_left'].values, ch['toe_right'].values, atol=1e-9)
    assert_allclose(ch['camber_left'].values, ch['camber_right'].values, atol=1e-9)
    assert_allclose(ch['contact_point_y_left'].values, -ch['contact_point_y_right'].values,
                    atol=1e-9)


def test_design_alignment_reproduced_with_ideal_joints(hmmwv):
    """HMMWV baseline has no bushings: zero travel gives the data's camber and toe exactly."""
    config = with_overrides(hmmwv.configurations['baseline'],
                            {'front_alignment.camber': '-0.75 deg',
                             'front_alignment.toe': '0.1 deg'})
    out = run_kc_event(config, 'parallel_wheel_travel', 'front', ['steps=11'])
    assert out.metrics['camber'].value == pytest.approx(math.radians(-0.75), abs=1e-11)
    assert out.metrics['toe'].value == pytest.approx(math.radians(0.1), abs=1e-11)


def test_bushings_make_the_axle_compliant(hmmwv):
    rigid = run_kc_event(hmmwv.configurations['baseline'], 'lateral_force', 'front',
                         ['steps=11'])
    bushed = run_kc_event(hmmwv.configurations['bushings'], 'lateral_force', 'front',
                          ['steps=11'])
    assert math.isinf(rigid.metrics['lateral_stiffness'].value)
    assert math.isfinite(bushed.metrics['lateral_stiffness'].value)


def test_stiffer_rear_bar_raises_rear_roll_stiffness_by_the_bar_change(sedan):
    base = run_kc_event(sedan.configurations['baseline'], 'opposite_wheel_travel', 'rear',
                        ['steps=21'])
    stiff = run_kc_event(sedan.configurations['stiff_rear'], 'opposite_wheel_travel', 'rear',
                         ['steps=21'])
    assert stiff.metrics['roll_stiffness_no_bar'].value == pytest.approx(
        base.metrics['roll_stiffness_no_bar'].value, rel=1e-9)
    # bar stiffness scales with r^4: 11 mm vs 9 mm bars (rear_stabilizer Y vs X)
    assert stiff.metrics['roll_stiffness_bar'].value == pytest.approx(
        base.metrics['roll_stiffness_bar'].value * (11.0 / 9.0) ** 4, rel=2e-3)


def test_steering_on_the_rear_axle_is_refused(sedan):
    with pytest.raises(SolverError) as err:
        run_kc_event(sedan.configurations['baseline'], 'steering', 'rear')
    assert str(err.value) == ("configuration 'baseline', event 'steering', axle 'rear': the "
                              "rear axle has no steering")


def test_unknown_event_and_axle_are_refused(sedan):
    config = sedan.configurations['baseline']
    with pytest.raises(SolverError) as err:
        run_kc_event(config, 'bounce', 'front')
    assert str(err.value).startswith("configuration 'baseline', event 'bounce', axle 'front': "
                                     "the K&C solver has no event 'bounce'")
    with pytest.raises(SolverError) as err:
        run_kc_event(config, 'lateral_force', 'middle')
    assert str(err.value) == ("configuration 'baseline', event 'lateral_force', axle 'middle': "
                              "K&C events need --axle front or rear")


def test_stabilizer_without_its_hard_points_is_refused(hmmwv, sedan):
    """A stabilizer group needs the bar's drop-link and pivot hard points."""
    config = hmmwv.configurations['baseline']
    groups = dict(config.groups)
    groups['front_stabilizer'] = sedan.configurations['baseline'].groups['front_stabilizer']
    with pytest.raises(SolverError) as err:
        suspension_input(replace(config, groups=groups), 'front')
    assert str(err.value) == ('front_stabilizer is given but hmmwv/front_hardpoints/X.yaml lacks '
                              'the anti-roll-bar hard points arb_link_lower, arb_link_upper, '
                              'arb_pivot')


def test_kc_roll_properties_feed_the_two_track_model_and_are_labelled(sedan):
    """
    Check that the two-track model takes the K&C roll properties, labelled.

    The two-track model computes the K&C roll properties on demand: the same
    numbers as a direct K&C run of the same configuration, labelled with the data
    hash; without K&C the parameters say 'design target'.
    """
    from vd_solvers.analytical.from_config import vehicle_params
    from vd_solvers.kc.events import KCModel
    from vd_solvers.kc.metrics import derived_metrics

    config = sedan.configurations['baseline']
    fed = run_event(config, 'handling_diagram', 'two_track', ['steps=5'])
    for axle in ('front', 'rear'):
        inp = suspension_input(config, axle)
        model = KCModel(inp)
        direct = derived_metrics({e: model.run(e) for e in ('opposite_wheel_travel',
                                                             'parallel_wheel_travel')},
                                 inp.tire_vertical_stiffness)
        stiffness = fed.metrics[f'roll_stiffness_{axle}']
        assert stiffness.value == pytest.approx(direct['roll_stiffness'][0], rel=1e-12)
        assert stiffness.source == (f'K&C {axle} axle (opposite and parallel wheel travel, '
                                    f'data hash {config.data_hash})')
        height = fed.metrics[f'roll_centre_height_{axle}'].value
        assert height == pytest.approx(direct['roll_centre_height_kinematic'][0], rel=1e-12)
    targets = vehicle_params(config)
    assert targets.sources['roll_stiffness_front'].startswith('design target sedan/targets/')


def test_the_tire_vertical_stiffness_follows_the_configurations_pressure():
    """C_z = VERTICAL_STIFFNESS (1 + PFZ1 dpi) at the configuration's pressure (MF 6.x, 4.E68)."""
    from conftest import SAMPLE_DATA

    study = load_study(SAMPLE_DATA / 'studies' / 'sedan_mf62.yaml')
    # tires/MF62_255_55R20.tir: VERTICAL_STIFFNESS 322913 N/m, PFZ1 0.8156607, NOMPRES 260000 Pa;
    # the study's mf62_low_pressure sets INFLPRES to 2.1 bar
    nominal = suspension_input(study.configurations['mf62'], 'front')
    low = suspension_input(study.configurations['mf62_low_pressure'], 'front')
    assert nominal.tire_vertical_stiffness == pytest.approx(322913.0, rel=1e-12)
    dpi = (210000.0 - 260000.0) / 260000.0
    assert low.tire_vertical_stiffness == pytest.approx(322913.0 * (1.0 + 0.8156607 * dpi),
                                                        rel=1e-9)
