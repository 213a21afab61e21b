# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The ladder as a tested property: every configuration of both sample studies.

The two-track model (wheel by wheel) and the full vehicle agree within 5 % on the
steady-state understeer gradient, roll gradient and yaw-rate gain; the bicycle's budget
within 10 %; the full vehicle's linear-range step response within 10 % of the single
track of its own axles (``vd_solvers/vehicle/ladder.py``). Every difference is a named
term, and the named terms add up to the differences.
"""
from __future__ import annotations

import math
from pathlib import Path

import pytest

from vd_data_server.study import load_study
from vd_solvers.vehicle.ladder import ladder

STUDIES = Path(__file__).resolve().parents[3] / 'src' / 'vd_data_server' / 'data' / 'studies'
CONFIGURATIONS = [('sedan', 'baseline'), ('sedan', 'stiff_rear'), ('sedan', 'sport'),
                  ('hmmwv', 'baseline'), ('hmmwv', 'bushings')]
DOCS = Path(__file__).resolve().parents[3] / 'docs' / 'ladder.md'


@pytest.fixture(scope='module')
def ladders():
    cache = {}

    def get(study: str, name: str):
        if (study, name) not in cache:
            config = load_study(STUDIES / f'{study}.yaml').configurations[name]
            cache[study, name] = ladder(config)
        return cache[study, name]

    return get


@pytest.mark.parametrize('study, name', CONFIGURATIONS)
def test_two_track_and_full_vehicle_understeer_gradients_agree(ladders, study, name):
    result = ladders(study, name)
    assert result.two_track.understeer_gradient == pytest.approx(
        result.vehicle.understeer_gradient, rel=0.05)


@pytest.mark.parametrize('study, name', CONFIGURATIONS)
def test_two_track_and_full_vehicle_roll_gradients_and_yaw_rate_gains_agree(ladders, study,
                                                                             name):
    result = ladders(study, name)
    assert result.two_track.roll_gradient == pytest.approx(result.vehicle.roll_gradient,
                                                           rel=0.05)
    assert result.two_track.yaw_rate_gain == pytest.approx(result.vehicle.yaw_rate_gain,
                                                           rel=0.05)


@pytest.mark.parametrize('study, name', CONFIGURATIONS)
def test_the_bicycle_budget_agrees_with_the_full_vehicle(ladders, study, name):
    result = ladders(study, name)
    assert result.bicycle.understeer_gradient == pytest.approx(
        result.vehicle.understeer_gradient, rel=0.10)
    assert result.bicycle.yaw_rate_gain == pytest.approx(result.vehicle.yaw_rate_gain,
                                                         rel=0.10)


@pytest.mark.parametrize('study, name', CONFIGURATIONS)
def test_the_named_terms_add_up(ladders, study, name):
    """The budget's terms are its total; the remaining terms are the rungs' differences."""
    result = ladders(study, name)
    assert math.fsum(t.value for t in result.budget) == pytest.approx(
        result.bicycle.understeer_gradient, rel=1e-12)
    remaining = {t.name: t.value for t in result.remaining}
    assert remaining['vehicle_minus_two_track'] == pytest.approx(
        result.vehicle.understeer_gradient - result.two_track.understeer_gradient, abs=1e-15)
    assert remaining['two_track_minus_budget'] == pytest.approx(
        result.two_track.understeer_gradient - result.bicycle.understeer_gradient, abs=1e-15)
    # each two-track effect moves the gradient the way its physics says: the aligning
    # moments put the axle forces behind the axles (understeer), the load transfer
    # softens the axles (understeer on both cars)
    effects = {t.name: t.value for t in result.two_track_effects}
    assert effects['aligning_moment'] > 0.0
    assert effects['load_transfer'] > 0.0


@pytest.mark.parametrize('study, name', CONFIGURATIONS)
def test_the_step_response_is_that_of_the_single_track_of_its_own_axles(ladders, study, name):
    """
    Check the full vehicle's linear-range step response against its axles' single track.

    Natural frequency and damping ratio (both identified by the same second-order fit)
    within 10 %; the yaw-rate overshoot within 10 % of the reference's, or 1 point where
    the overshoot itself is a few percent (the HMMWV's, about 2 %).
    """
    result = ladders(study, name)
    full, reference = result.vehicle, result.single_track
    assert full.natural_frequency == pytest.approx(reference.natural_frequency, rel=0.10)
    assert full.damping_ratio == pytest.approx(reference.damping_ratio, rel=0.10)
    assert abs(full.overshoot - reference.overshoot) <= max(0.1 * reference.overshoot, 1.0)


def _documented() -> dict[tuple[str, str], dict[str, object]]:
    """Read the tables of docs/ladder.md: per (study, configuration), data hash and rows."""
    out: dict[tuple[str, str], dict[str, object]] = {}
    key = None
    for line in DOCS.read_text(encoding='utf-8').splitlines():
        if line.startswith('## '):
            study, name, _, _, digest = line[3:].split()
            key = (study, name)
            out[key] = {'hash': digest.rstrip(')')}
        elif key is not None and line.startswith(('two-track ', 'full vehicle ')) and (
                ':' not in line):
            label = 'two_track' if line.startswith('two-track') else 'vehicle'
            values = line[36:].split()
            out[key][label] = [float(v) for v in values[:3]]
    return out


@pytest.mark.parametrize('study, name', CONFIGURATIONS)
def test_the_documented_ladder_is_the_computed_one(ladders, study, name):
    """docs/ladder.md's gradients (deg/g) and gains are this code's on this data."""
    documented = _documented()[study, name]
    result = ladders(study, name)
    assert documented['hash'] == result.data_hash
    for label in ('two_track', 'vehicle'):
        rung = getattr(result, label)
        k, roll, gain = documented[label]
        assert k == pytest.approx(math.degrees(rung.understeer_gradient * 9.80665), abs=2e-3)
        assert roll == pytest.approx(math.degrees(rung.roll_gradient * 9.80665), abs=2e-3)
        assert gain == pytest.approx(rung.yaw_rate_gain, abs=2e-4)
