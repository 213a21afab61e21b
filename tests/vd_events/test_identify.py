# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
``vd identify``: parameters recovered from logs whose true parameters are known.

The logs are simulated by vd's own models on the sample sedan with known overrides (front
and rear cornering-stiffness scales LKY), sensor noise added with a fixed seed, written
to bags as ``vd import`` writes them; the fit starts from the base configuration. The
fitted values must lie within three of their own standard errors of the truth, and the
standard errors must be small enough for that to mean something. A steady-state log at
one speed determines only the understeer combination of the two scales: the pair must be
reported as not identifiable apart.
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import yaml

import vbox_logs as vb
from vd_data_server.errors import DataError
from vd_data_server.paths import default_master
from vd_data_server.study import load_study
from vd_events.bags.outcomes import write_outcomes
from vd_events.cli.main import main
from vd_events.errors import InputError
from vd_events.measured.identify import (
    SETTLE,
    Predictor,
    identify,
    load_identify_plan,
    write_identified,
)
from vd_events.reports.identify import write_identify_page
from vd_solvers.results import Channel, EventOutcome

DEG = math.pi / 180.0
FRONT = 'front_tire.tir.SCALING_COEFFICIENTS.LKY'
REAR = 'rear_tire.tir.SCALING_COEFFICIENTS.LKY'
TRUTH = {FRONT: 0.85, REAR: 1.15}
RATE = 50.0  # Hz
#: sensor noise (standard deviations), the gyro and the accelerometer of a test car
NOISE = {'yaw_rate': 0.2 * DEG, 'lateral_acceleration': 0.05, 'steering_wheel_angle': 0.3 * DEG}


@pytest.fixture(scope='module')
def predictor() -> Predictor:
    """Return the bicycle of the sample sedan (its K&C once for the module)."""
    return Predictor(load_study(default_master()).configurations['baseline'], 'bicycle')


def _log(predictor: Predictor, seed: int, frequency: float = 0.6,
         gap: tuple[float, float] | None = None) -> EventOutcome:
    """Return a sine steer at 90 km/h through the truth, noise added (seeded), maybe a gap."""
    t = np.arange(0.0, 4.0, 1.0 / RATE)
    swa = 30.0 * DEG * np.sin(2.0 * np.pi * frequency * np.clip(t - 0.5, 0.0, None))
    speed = np.full(t.size, 25.0)
    inputs = EventOutcome('vehicle_test', 'car', 'test', 'measured', '', '', {}, {
        'time': Channel('s', t), 'steering_wheel_angle': Channel('rad', swa),
        'speed': Channel('m/s', speed)})
    truth = predictor.predict(predictor.configuration({k: f'{v}' for k, v in TRUTH.items()}),
                              inputs)
    rng = np.random.default_rng(seed)
    channels = {'time': t, 'steering_wheel_angle': swa, 'speed': speed,
                'yaw_rate': truth['yaw_rate'] + rng.normal(0.0, NOISE['yaw_rate'], t.size),
                'lateral_acceleration': truth['lateral_acceleration']
                + rng.normal(0.0, NOISE['lateral_acceleration'], t.size)}
    if gap is not None:
        keep = (t < gap[0]) | (t >= gap[0] + gap[1])
        channels = {k: v[keep] for k, v in channels.items()}
    units = {'time': 's', 'steering_wheel_angle': 'rad', 'speed': 'm/s', 'yaw_rate': 'rad/s',
             'lateral_acceleration': 'm/s^2'}
    return EventOutcome('vehicle_test', 'car', 'test', 'measured', '', f'log{seed:04d}' * 4, {},
                        {k: Channel(units[k], v) for k, v in channels.items()},
                        notes=(f'source: run{seed}.csv',))


def _bag(tmp_path: Path, log: EventOutcome, name: str) -> str:
    return str(write_outcomes(tmp_path / name, [(log, 1_700_000_000 * 10**9)],
                              {'vd.kind': 'measured'}))


def _plan(tmp_path: Path, master: Path, logs: list[str], **extra) -> Path:
    plan = {'name': 'lateral', 'master': str(master), 'configuration': 'baseline',
            'model': 'bicycle', 'logs': logs,
            'parameters': {'front_scale': {'key': FRONT, 'range': [0.5, 1.5]},
                           'rear_scale': {'key': REAR, 'range': [0.5, 1.5]}},
            'channels': {'yaw_rate': {'scale': '0.2 deg/s'},
                         'lateral_acceleration': {'scale': '0.05 m/s^2'}},
            'output': {'configuration': 'baseline_fitted'}, **extra}
    path = tmp_path / 'plan.yaml'
    path.write_text(yaml.safe_dump(plan))
    return path


def _assert_recovered(result) -> None:
    names = [f.key for f in result.plan.parameters]
    for key, fit, se in zip(names, result.fitted, result.standard_errors):
        assert 0.0 < se < 0.05, (key, se)
        assert abs(fit - TRUTH[key]) < 3.0 * se, (key, fit, se)
    assert result.identifiable and result.rank == 2 and not result.pairs
    assert result.cost_fitted < 0.1 * result.cost_start
    # the residuals are the noise the logs were given: sigma ~ 1 in units of the scales
    assert result.sigma == pytest.approx(1.0, rel=0.15)


def test_recovers_known_parameters_writes_them_and_cross_validates(
        tmp_path: Path, sedan_master: Path, predictor: Predictor) -> None:
    fit_bag = _bag(tmp_path, _log(predictor, 1), 'fit')
    check_bag = _bag(tmp_path, _log(predictor, 2, frequency=0.4), 'check')
    plan = load_identify_plan(_plan(tmp_path, sedan_master, [fit_bag], validate=[check_bag],
                                    force=True))
    result = identify(plan, predictor=predictor)
    _assert_recovered(result)
    # cross-validation: the other log predicted before and after, by ISO 22140's bands
    assert set(result.correlations) == {'identification before', 'identification after',
                                        'validation before', 'validation after'}
    assert result.correlations['validation after'].verdict == 'PASS'
    assert result.correlations['validation after'].manoeuvres[0].forced
    before, after = result.rms['validation'][0]['yaw_rate']
    assert after < before
    master = write_identified(result)
    study = load_study(master)
    config = study.configurations['baseline_fitted']
    for f, value in zip(plan.parameters, result.fitted):
        group, _, key = f.key.partition('.')
        assert config.groups[group].values[key].number() == pytest.approx(value, rel=1e-9)
    assert _log(predictor, 1).data_hash in config.description
    page = write_identify_page(result, tmp_path / 'page')
    text = page.read_text()
    assert 'front_scale' in text and 'validation after' in text and 'baseline_fitted' in text
    assert (tmp_path / 'page' / 'correlation' / 'correlate.html').is_file()
    with pytest.raises(DataError, match="'baseline_fitted' already exists"):
        identify(plan, predictor=predictor)


def test_recovers_known_parameters_across_a_gap(tmp_path: Path, sedan_master: Path,
                                                predictor: Predictor) -> None:
    bag = _bag(tmp_path, _log(predictor, 3, gap=(2.0, 0.6)), 'gap')
    plan = load_identify_plan(_plan(tmp_path, sedan_master, [bag]))
    result = identify(plan, predictor=predictor)
    _assert_recovered(result)
    # the samples of the gap and of the SETTLE s after it are not compared
    assert result.points == 2 * round((4.0 - 0.6 - SETTLE) * RATE)


def test_front_and_rear_scales_from_one_speed_steady_state_are_not_identifiable_apart(
        tmp_path: Path, sedan_master: Path, predictor: Predictor) -> None:
    """At one speed the steer over a_y sees the understeer combination of the two only."""
    steady = Predictor.__new__(Predictor)
    steady.__dict__.update(predictor.__dict__, model='two_track')
    n = 120
    speed = np.full(n, 20.0)
    ay = np.linspace(1.0, 5.0, n)
    log = EventOutcome('constant_radius_turn', 'car', 'test', 'measured', '', 'c' * 64, {}, {
        'time': Channel('s', np.arange(n) * 0.01), 'speed': Channel('m/s', speed),
        'yaw_rate': Channel('rad/s', ay / speed),
        'lateral_acceleration': Channel('m/s^2', ay)})
    truth = steady.predict(steady.configuration({k: f'{v}' for k, v in TRUTH.items()}), log)
    rng = np.random.default_rng(5)
    swa = truth['steering_wheel_angle'] + rng.normal(0.0, NOISE['steering_wheel_angle'], n)
    log = EventOutcome(log.event, 'car', 'test', 'measured', '', log.data_hash, {},
                       {**log.channels, 'steering_wheel_angle': Channel('rad', swa)},
                       notes=('source: circle.csv',))
    path = _plan(tmp_path, sedan_master, [_bag(tmp_path, log, 'circle')], model='two_track',
                 channels={'steering_wheel_angle': {'scale': '0.3 deg'}}, force=True)
    result = identify(load_identify_plan(path), predictor=steady)
    assert not result.identifiable
    ((a, b, corr),) = result.pairs
    assert {a, b} == {'front_scale', 'rear_scale'} and abs(corr) > 0.95
    assert result.condition > 100.0
    # the steady-state model's prediction, correlated by ISO 19364 over lateral acceleration
    after = result.correlations['identification after']
    assert after.method.method == 'iso19364' and after.verdict == 'PASS'
    assert {c.channel for c in after.manoeuvres[0].channels} == {'steering_wheel_angle'}


def test_logs_that_failed_the_import_checks_are_refused_by_name(
        tmp_path: Path, sedan_master: Path) -> None:
    glitchy, _, _ = vb.write(tmp_path / 'glitchy.vbo', vb.swd_truth(), vb.Log(glitches=[
        (1.5, 'Steering_Angle', 27899.0)]))
    empty = tmp_path / 'not_a_bag'
    empty.mkdir()
    cmap = vb.write_map(tmp_path / 'map.yaml', 'sine_with_dwell')
    plan = load_identify_plan(_plan(tmp_path, sedan_master, [str(glitchy), str(empty)],
                                    map=str(cmap)))
    with pytest.raises(InputError, match=r'2 log\(s\) failed the import checks.*glitchy.vbo.*'
                       r'glitch.*not_a_bag'):
        identify(plan)


@pytest.mark.parametrize(('change', 'message'), [
    ({'model': 'kc'}, "unknown model 'kc'"),
    ({'parameters': {'x': {'key': 'front_tire.nothing', 'range': [0, 1]}}},
     "key 'nothing' does not exist"),
    ({'channels': {'roll': {}}}, 'model bicycle predicts'),
    ({'logs': []}, 'expected a list of log files or bags'),
])
def test_bad_plans_are_refused(tmp_path: Path, sedan_master: Path, change: dict,
                               message: str) -> None:
    path = _plan(tmp_path, sedan_master, ['x'])
    plan = yaml.safe_load(path.read_text())
    plan.update(change)
    path.write_text(yaml.safe_dump(plan))
    with pytest.raises(DataError, match=message):
        load_identify_plan(path)


def test_cli_refuses_a_bad_plan_with_exit_2(tmp_path: Path, sedan_master: Path, capsys) -> None:
    path = _plan(tmp_path, sedan_master, ['x'], output={'configuration': 'sport'})
    before = sedan_master.read_bytes()
    assert main(['identify', str(path), '--out', str(tmp_path / 'out')]) == 2
    err = capsys.readouterr().err
    assert "configuration 'sport' already exists" in err and 'never overwritten' in err
    assert sedan_master.read_bytes() == before and not (tmp_path / 'out').exists()
