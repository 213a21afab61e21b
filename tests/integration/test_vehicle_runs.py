# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""Full-vehicle runs through the ROS graph: embedded and distributed, bags, odometry, report."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from vdtest import tree_snapshot

pytestmark = [pytest.mark.ros, pytest.mark.slow]


def _vd(capsys, *argv: str) -> tuple[int, str, str]:
    from vd_events.cli.main import main

    rc = main(list(argv))
    out, err = capsys.readouterr()
    return rc, out, err


def _messages(bag: Path) -> dict[str, list]:
    from vd_events.bags.bag import read_bag

    out: dict[str, list] = {}
    for item in read_bag(bag):
        out.setdefault(item.topic, []).append(item.msg)
    return out


def test_embedded_step_steer_records_states_odometry_and_result(capsys, tmp_path, sedan_master):
    bag = tmp_path / 'ss'
    rc, out, err = _vd(capsys, 'run', 'step_steer', '--model', 'vehicle', '--master',
                       str(sedan_master), '--param', 'duration=3 s', '--bag', str(bag), '--json')
    assert rc == 0, err
    result = json.loads(out)
    assert (result['model'], result['fidelity'], result['axle']) == ('vehicle', 'rigid', '')
    time = result['channels']['time']['values']
    assert result['channels']['time']['unit'] == 's' and time[-1] == pytest.approx(3.0)
    assert result['metrics']['steady_lateral_acceleration']['value'] == pytest.approx(4.0,
                                                                                     rel=0.02)
    msgs = _messages(bag)
    assert len(msgs['/vd/vehicle/result']) == 1
    states, odom = msgs['/vd/vehicle/state'], msgs['/vd/vehicle/odom']
    assert len(states) == len(odom) == len(time)
    # header stamps on the simulation-time axis: run start + simulated time
    t0 = states[0].header.stamp.sec + states[0].header.stamp.nanosec * 1e-9
    stamps = [s.header.stamp.sec + s.header.stamp.nanosec * 1e-9 - t0 for s in states]
    assert stamps == pytest.approx(time, abs=1e-6)
    last = odom[-1]
    assert (last.header.frame_id, last.child_frame_id) == ('odom', 'base_link')
    assert last.pose.pose.position.x == pytest.approx(result['channels']['x']['values'][-1])
    # TF (REP 105): the same pose as odom -> base_link, one transform per step
    tf = msgs['/tf']
    assert len(tf) == len(time)
    (moved,) = tf[-1].transforms
    assert (moved.header.frame_id, moved.child_frame_id) == ('odom', 'base_link')
    assert moved.transform.translation.y == pytest.approx(last.pose.pose.position.y)
    assert moved.transform.rotation.z == pytest.approx(last.pose.pose.orientation.z)
    assert last.twist.twist.angular.z == pytest.approx(
        result['channels']['yaw_rate']['values'][-1])
    # typed states: the channels as named fields, one VehicleWheel per wheel
    assert states[-1].yaw_rate == pytest.approx(result['channels']['yaw_rate']['values'][-1])
    assert [s.step for s in states] == list(range(len(time)))
    assert states[-1].front_right.load == pytest.approx(
        result['channels']['wheel_load_front_right']['values'][-1])
    assert states[-1].header.frame_id == 'odom'
    # the report draws the thesis' figures from the bag
    report = tmp_path / 'report'
    rc, _, err = _vd(capsys, 'report', str(bag), '--out', str(report))
    assert rc == 0, err
    assert len(list(report.glob('step_steer_vehicle_*.png'))) == 4


def test_distributed_constant_radius_turn_on_the_hmmwv(capsys, tmp_path, sample_root):
    """The HMMWV (no anti-roll bars) over the ROS graph, one process per node, with a bag."""
    bag = tmp_path / 'crt'
    master = sample_root / 'studies' / 'hmmwv.yaml'
    rc, out, err = _vd(capsys, 'run', 'constant_radius_turn', '--model', 'vehicle',
                       '--master', str(master), '--param', 'start_lateral_acceleration=1 m/s^2',
                       '--param', 'max_lateral_acceleration=2 m/s^2', '--distributed',
                       '--bag', str(bag),
                       '--json')
    assert rc == 0, err
    result = json.loads(out)
    assert result['configuration'] == 'baseline'
    assert result['metrics']['roll_gradient']['value'] > 0.0
    assert any('anti_roll_bar: front: no anti-roll bar' in n for n in result['notes'])
    msgs = _messages(bag)
    assert len(msgs['/vd/vehicle/result']) == 1
    assert len(msgs['/vd/vehicle/state']) == len(result['channels']['time']['values'])


@pytest.mark.parametrize('argv, message', [
    (('run', 'step_steer', '--model', 'vehicle', '--axle', 'front'),
     "model 'vehicle' is a whole-vehicle model: no --axle"),
    (('run', 'constant_radius_turn', '--model', 'vehicle', '--param', 'radius=5 m'),
     'event constant_radius_turn: radius: 5 m is outside [10, 500] m'),
    (('run', 'constant_radius_turn', '--model', 'two_track'),
     "event 'constant_radius_turn' does not run on model 'two_track' (its events: "
     "steady_state_circular, handling_diagram)"),
])
def test_bad_vehicle_input_exits_2_and_writes_nothing(capsys, tmp_path, sedan_master, argv,
                                                       message):
    bag = tmp_path / 'bag'
    before = tree_snapshot(sedan_master.parents[1])
    rc, _, err = _vd(capsys, *argv, '--master', str(sedan_master), '--bag', str(bag))
    assert rc == 2
    assert err.strip() == message
    assert not list(tmp_path.glob('bag*'))
    assert tree_snapshot(sedan_master.parents[1]) == before


def test_flexible_fidelity_without_flex_data_is_refused_before_the_run(capsys, tmp_path,
                                                                     sedan_master):
    from vdtest import replace_once

    replace_once(sedan_master, '  rear_flex: X\n', '')
    bag = tmp_path / 'flex'
    rc, out, err = _vd(capsys, 'run', 'step_steer', '--model', 'vehicle', '--fidelity',
                       'flexible', '--master', str(sedan_master), '--bag', str(bag), '--json')
    assert rc == 2
    assert json.loads(out) == {'error': "configuration 'baseline' has no flexible components "
                                        "on the rear axle (no rear_flex group in the master "
                                        "file)"}
    assert not list(tmp_path.glob('flex*'))


def test_constant_radius_turn_defaults_to_the_vehicle_model(capsys, sedan_master):
    from vd_solvers.families import event_model

    assert event_model('constant_radius_turn') == 'vehicle'
    assert event_model('step_steer') == 'bicycle'


def test_vd_run_gives_the_vehicle_its_configurations_fidelity_unless_asked(capsys,
                                                                           sedan_master):
    """
    `vd run --model vehicle` on `sport` (flexible: true): flexible K&C maps by default.

    The default run is the run asked with --fidelity flexible, value for value; the run
    asked with --fidelity rigid differs.
    """
    results = {}
    for asked in ((), ('--fidelity', 'flexible'), ('--fidelity', 'rigid')):
        rc, out, err = _vd(capsys, 'run', 'step_steer', '--model', 'vehicle', '--config',
                           'sport', '--master', str(sedan_master), '--param', 'duration=3 s',
                           *asked, '--json')
        assert rc == 0, err
        results[asked[1] if asked else 'default'] = json.loads(out)
    default, flexible, rigid = results['default'], results['flexible'], results['rigid']
    assert (default['fidelity'], flexible['fidelity'], rigid['fidelity']) == (
        'flexible', 'flexible', 'rigid')
    assert default['metrics'] == flexible['metrics']
    assert default['channels']['yaw_rate'] == flexible['channels']['yaw_rate']
    assert rigid['metrics']['yaw_rate_gain']['value'] != pytest.approx(
        flexible['metrics']['yaw_rate_gain']['value'], rel=1e-3)
