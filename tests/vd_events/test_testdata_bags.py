# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Imported measurements in bags, simulation vs test, replay and the study report.

The sample files are vd's own model output with sensor noise (src/vd_events/samples):
an import must give back what went in (units, signs, time axis), the comparison of the
model that made a sample with it must pass, and one with a sign convention left out of
the column map must fail on the gradient.
"""
from __future__ import annotations

import hashlib
import math
from pathlib import Path

from numpy.testing import assert_allclose
import pytest

from vd_events.bags.bag import custom_data, read_bag
from vd_events.measured.columns import load_map
from vd_events.measured.compare import compare, compare_bags, load_outcomes
from vd_events.measured.importer import import_files
from vd_events.measured.vbo import read_vbo
from vd_events.reports.compare import write_compare_page

REPO = Path(__file__).resolve().parents[2]
SAMPLES = REPO / 'src' / 'vd_events' / 'samples'
DEG = math.pi / 180.0

pytestmark = pytest.mark.ros


@pytest.fixture(scope='module')
def baseline():
    from vd_data_server.paths import default_master
    from vd_data_server.study import load_study

    return load_study(default_master()).configurations['baseline']


@pytest.fixture(scope='module')
def vbox_bag(tmp_path_factory) -> Path:
    bag = tmp_path_factory.mktemp('vbox') / 'vbox'
    import_files([SAMPLES / 'vbox_sine_steer.vbo'], SAMPLES / 'vbox_sine_steer.map.yaml', bag)
    return bag


@pytest.fixture(scope='module')
def sim_bounce(baseline, tmp_path_factory) -> Path:
    from vd_events.bags.outcomes import write_outcomes
    from vd_solvers.kc.from_config import run_kc_event

    outcome = run_kc_event(baseline, 'parallel_wheel_travel', 'front', ['steps=41'])
    bag = tmp_path_factory.mktemp('sim') / 'sim_bounce'
    return write_outcomes(bag, [(outcome, 1_700_000_000_000_000_000)], {'vd.kind': 'test'})


def test_vbo_bag_holds_the_log_and_its_provenance(vbox_bag: Path) -> None:
    source = SAMPLES / 'vbox_sine_steer.vbo'
    (outcome,) = load_outcomes(vbox_bag)
    direct = read_vbo(source, load_map(SAMPLES / 'vbox_sine_steer.map.yaml'))
    assert (outcome.model, outcome.fidelity, outcome.event) == ('test', 'measured',
                                                                 'vehicle_test')
    for name, values in direct.channels.items():
        assert_allclose(outcome.channels[name].values, values, rtol=0, atol=0)
    digest = hashlib.sha256(source.read_bytes()).hexdigest()
    assert outcome.data_hash == digest
    meta = custom_data(vbox_bag)
    assert meta['vd.source_sha256'] == digest
    assert meta['vd.logger'] == 'VBOX 3i with IMU04 (synthetic test file)'
    assert 'Slip Angle: {channel: sideslip, sign: -1}' in meta['vd.column_map']
    assert f'source: {source}' in outcome.notes
    states = [m.msg for m in read_bag(vbox_bag, {'/vd/vehicle/state'})]
    odom = list(read_bag(vbox_bag, {'/vd/vehicle/odom'}))
    assert len(states) == len(odom) == 161
    assert_allclose([s.yaw_rate for s in states], outcome.channels['yaw_rate'].values)
    assert all(math.isnan(s.front_left.load) for s in states)  # not measured
    # the log's own time axis: log time = stamp = UTC start + time
    first, last = odom[0], odom[-1]
    assert (last.timestamp - first.timestamp) * 1e-9 == pytest.approx(8.0, abs=1e-6)


def test_log_of_the_model_matches_the_model_within_the_noise(vbox_bag: Path) -> None:
    """
    Check the imported log against itself: heading vs yaw rate, track vs speed.

    Heading, position and speed imported from degrees, minutes and km/h agree with each
    other within the sensor noise.
    """
    (log,) = load_outcomes(vbox_bag)
    ch = {k: c.values for k, c in log.channels.items()}
    # yaw from the heading vs the integral of the logged yaw rate (ISO sign of both)
    dt = ch['time'][1] - ch['time'][0]
    integral = ch['yaw'][0] + dt * (ch['yaw_rate'].cumsum() - 0.5 * ch['yaw_rate'][0]
                                    - 0.5 * ch['yaw_rate'])
    assert_allclose(ch['yaw'], integral, atol=0.3 * DEG)
    # speed from the lat/long track vs the logged velocity
    speed = ((ch['x'][2:] - ch['x'][:-2]) ** 2 + (ch['y'][2:] - ch['y'][:-2]) ** 2) ** 0.5 \
        / (2 * dt)
    assert_allclose(speed, ch['speed'][1:-1], atol=0.1)


def test_rig_measurement_passes_against_its_model(sim_bounce: Path, tmp_path: Path) -> None:
    rig = tmp_path / 'rig'
    import_files([SAMPLES / 'kc_spmm_bounce_front.csv'],
                 SAMPLES / 'kc_spmm_bounce_front.map.yaml', rig)
    (c,) = compare_bags(sim_bounce, rig)
    page = write_compare_page([c], tmp_path / 'cmp', [sim_bounce, rig])
    assert c.verdict == 'PASS'
    toe = next(e for e in c.errors if e.channel == 'toe_left')
    # the rig's noisy end point (-80.013 mm) lies beyond the simulated -80 mm: left out
    assert toe.points == 40
    assert '1 of 41 test points lie outside the simulated wheel_travel_left range and are ' \
        'left out' in c.notes
    assert toe.gradient_test == pytest.approx(toe.gradient_sim, rel=0.01)  # bump steer
    assert page.is_file() and 'toe_left' in page.read_text()


def test_rig_sign_convention_left_out_fails_on_the_gradient(sim_bounce: Path,
                                                            tmp_path: Path) -> None:
    cmap = tmp_path / 'nosign.yaml'
    cmap.write_text((SAMPLES / 'kc_spmm_bounce_front.map.yaml').read_text()
                    .replace(', sign: -1}', '}'))
    rig = tmp_path / 'rig'
    import_files([SAMPLES / 'kc_spmm_bounce_front.csv'], cmap, rig)
    (c,) = compare_bags(sim_bounce, rig)
    toe = next(e for e in c.errors if e.channel == 'toe_left')
    assert c.verdict == 'FAIL' and 'gradient' in toe.failures
    assert toe.gradient_test == pytest.approx(-toe.gradient_sim, rel=0.01)


def test_kc_compared_at_the_measured_points(baseline) -> None:
    """Lateral-force rig points (21) between the simulated ones (41): interpolated."""
    from vd_events.measured.importer import read_measurement, to_outcome
    from vd_solvers.kc.from_config import run_kc_event

    path = SAMPLES / 'kc_abd_lateral_front.txt'
    cmap = load_map(SAMPLES / 'kc_abd_lateral_front.map.yaml')
    test = to_outcome(path, *read_measurement(path, cmap), cmap)
    sim = run_kc_event(baseline, 'lateral_force', 'front', ['steps=41'])
    c = compare(sim, test)
    assert c.axis == 'applied_force' and c.verdict == 'PASS'
    assert {e.channel: e.points for e in c.errors}['toe_left'] <= 21
    assert any('interpolated linearly' in n for n in c.notes)


def test_replay_through_both_models(vbox_bag: Path, tmp_path: Path) -> None:
    """
    Replay the log through the full vehicle and the bicycle model.

    The log was made by the full vehicle: its replay reproduces yaw rate and lateral
    acceleration within the sensor noise, closer than the linear bicycle does.
    """
    from vd_events.measured.replay import replay_bag

    result = replay_bag(vbox_bag, ['bicycle', 'vehicle'], 'baseline', None,
                        tmp_path / 'replay')
    by_model = {c.sim.model: {e.channel: e for e in c.errors}
                for c in result['_comparisons']}
    vehicle, bicycle = by_model['vehicle'], by_model['bicycle']
    assert 'steering_wheel_angle' not in vehicle and 'speed' not in vehicle  # the inputs
    assert vehicle['yaw_rate'].rms < 0.2 * DEG
    assert vehicle['lateral_acceleration'].rms < 0.1
    # the log's longitudinal acceleration carries 0.05 m/s^2 of noise; the speed reference
    # is smoothed, so its slope fed forward does not follow the speed's noise
    assert vehicle['longitudinal_acceleration'].rms < 0.1
    assert bicycle['yaw_rate'].rms > vehicle['yaw_rate'].rms
    assert {o.model for o in load_outcomes(tmp_path / 'replay')} == {'bicycle', 'vehicle'}
    page = write_compare_page(result['_comparisons'], tmp_path / 'out',
                              [tmp_path / 'replay', vbox_bag])
    assert 'yaw_rate' in page.read_text()


def test_study_report_from_bags_alone(sim_bounce: Path, vbox_bag: Path, tmp_path: Path) -> None:
    from vd_events.reports.study import build_study_report

    rig = tmp_path / 'rig'
    import_files([SAMPLES / 'kc_spmm_bounce_front.csv'],
                 SAMPLES / 'kc_spmm_bounce_front.map.yaml', rig)
    path = build_study_report([sim_bounce, rig, vbox_bag], tmp_path / 'report')
    text = path.read_text()
    assert 'Simulation vs test — parallel_wheel_travel front' in text
    assert 'K&amp;C metrics' in text and 'bump_steer' in text
    assert 'Plotly.newPlot' in text  # interactive figures
    assert '<script src=' not in text  # self-contained: plotly.js inlined
    assert 'data:image/png;base64,' in text  # comparison PNGs embedded
    assert 'vd.source_sha256' in text  # provenance of the measurement


def test_import_and_compare_json(capsys, sim_bounce: Path, tmp_path: Path) -> None:
    import json

    from vd_events.cli.main import main

    rig = tmp_path / 'rig'
    rc = main(['import', str(SAMPLES / 'kc_spmm_bounce_front.csv'), '--map',
               str(SAMPLES / 'kc_spmm_bounce_front.map.yaml'), '--bag', str(rig), '--json'])
    out = json.loads(capsys.readouterr().out)
    assert rc == 0 and out['bag'] == str(rig)
    (result,) = out['results']
    assert (result['event'], result['model'], result['axle'], result['samples']) == (
        'parallel_wheel_travel', 'rig', 'front', 41)
    rc = main(['compare', str(sim_bounce), str(rig), '--out', str(tmp_path / 'cmp'), '--json'])
    out = json.loads(capsys.readouterr().out)
    assert rc == 0
    (c,) = out['comparisons']
    assert (c['axis'], c['verdict'], c['sim']['model'], c['test']['model']) == (
        'wheel_travel_left', 'PASS', 'kc', 'rig')
    toe = next(ch for ch in c['channels'] if ch['channel'] == 'toe_left')
    assert toe['unit'] == 'rad' and toe['gradient_unit'] == 'rad/m'


def test_compare_without_a_matching_simulation(capsys, vbox_bag: Path, sim_bounce: Path,
                                               tmp_path: Path) -> None:
    from vd_events.cli.main import main

    rc = main(['compare', str(sim_bounce), str(vbox_bag), '--out', str(tmp_path / 'cmp')])
    out, err = capsys.readouterr()
    assert (rc, out) == (2, '')
    assert err.strip() == (f'{sim_bounce}: no simulation of the measured events (vehicle_test);'
                           ' the bag has: parallel_wheel_travel front')
    assert not (tmp_path / 'cmp').exists()


def test_csv_vehicle_log_bag_has_states_but_no_pose(tmp_path: Path) -> None:
    """A log without position and heading: typed states, no odometry or TF."""
    bag = tmp_path / 'log'
    import_files([SAMPLES / 'vehicle_log.csv'], SAMPLES / 'vehicle_log.map.yaml', bag)
    topics = [m.topic for m in read_bag(bag)]
    assert topics.count('/vd/vehicle/state') == 81
    assert '/vd/vehicle/odom' not in topics and '/tf' not in topics
    (outcome,) = load_outcomes(bag)
    assert outcome.channels['speed'].unit == 'm/s'
    assert_allclose(outcome.channels['time'].values[:3], [0.0, 0.1, 0.2])
