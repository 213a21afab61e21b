# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""End-to-end runs through the ROS graph: embedded and distributed, bags, report."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from vdtest import tree_snapshot

pytestmark = [pytest.mark.ros, pytest.mark.slow]

G = 9.80665


def _vd(capsys, *argv: str) -> tuple[int, str, str]:
    from vd_events.cli.main import main

    rc = main(list(argv))
    out, err = capsys.readouterr()
    return rc, out, err


def _bag_topics(bag: Path) -> dict[str, int]:
    from vd_events.bags.bag import read_bag

    counts: dict[str, int] = {}
    for item in read_bag(bag):
        counts[item.topic] = counts.get(item.topic, 0) + 1
    return counts


def test_embedded_run_writes_a_bag_mcap_and_rosbags_can_read(capsys, tmp_path, sedan_master):
    bag = tmp_path / 'hd'
    rc, out, err = _vd(capsys, 'run', 'handling_diagram', '--config', 'stiff_rear', '--model',
                       'two_track', '--master', str(sedan_master), '--bag', str(bag),
                       '--param', 'steps=21', '--json')
    assert rc == 0, err
    result = json.loads(out)
    assert result['bag'] == str(bag)
    assert set(result) >= {'event', 'configuration', 'model', 'fidelity', 'axle', 'metrics',
                           'channels', 'bag'}
    assert len(result['channels']['lateral_acceleration']['values']) == 21
    # rosbags: expected topics and counts
    counts = _bag_topics(bag)
    assert counts['/vd/steady_state/result'] == 1
    assert counts['/vd/steady_state/state'] == 21
    assert counts['/vd/provenance'] == 1
    assert counts['/vd/configuration'] == 1  # only the run's configuration
    assert counts['/vd/data_status'] == 1
    # the mcap library reads the same file, with the message definitions embedded
    from mcap.reader import make_reader

    (mcap_file,) = bag.glob('*.mcap')
    with mcap_file.open('rb') as stream:
        reader = make_reader(stream)
        summary = reader.get_summary()
        schemas = {s.name: s for s in summary.schemas.values()}
        assert 'vd_interfaces/msg/EventResult' in schemas
        assert b'NamedScalar[] metrics' in schemas['vd_interfaces/msg/EventResult'].data
        assert sum(summary.statistics.channel_message_counts.values()) == sum(counts.values())
    # provenance in the bag metadata
    from vd_events.bags.bag import custom_data

    meta = custom_data(bag)
    assert meta['vd.configuration'] == 'stiff_rear'
    assert meta['vd.model'] == 'two_track'
    assert meta['vd.data_hash'] == result['data_hash']
    assert not (tmp_path / 'hd.partial').exists()


def test_set_override_changes_result_and_is_recorded_as_modified(capsys, tmp_path, sedan_master):
    base_rc, base_out, _ = _vd(capsys, 'run', 'handling_diagram', '--master', str(sedan_master),
                               '--param', 'steps=5', '--json')
    bag = tmp_path / 'set'
    rc, out, err = _vd(capsys, 'run', 'handling_diagram', '--master', str(sedan_master),
                       '--param', 'steps=5', '--set', 'rear_stabilizer.bar_radius=11 mm',
                       '--bag', str(bag), '--json')
    assert base_rc == rc == 0, err
    base, changed = json.loads(base_out), json.loads(out)
    assert changed['data_hash'] != base['data_hash']
    # a stiffer rear on a front-limited car raises the limit (thesis 4.1, trend a)
    assert (changed['metrics']['max_lateral_acceleration']['value']
            > base['metrics']['max_lateral_acceleration']['value'])
    from vd_events.bags.bag import custom_data

    assert 'rear_stabilizer.bar_radius=' in custom_data(bag)['vd.modified']


def test_distributed_run_matches_embedded(capsys, tmp_path, sedan_master):
    args = ('run', 'handling_diagram', '--config', 'baseline', '--master', str(sedan_master),
            '--param', 'steps=11', '--json')
    rc_e, out_e, err_e = _vd(capsys, *args)
    bag = tmp_path / 'dist'
    rc_d, out_d, err_d = _vd(capsys, *args, '--distributed', '--bag', str(bag))
    assert rc_e == 0, err_e
    assert rc_d == 0, out_d + err_d
    emb, dist = json.loads(out_e), json.loads(out_d)
    assert dist['metrics'] == emb['metrics']
    assert dist['channels'] == emb['channels']
    counts = _bag_topics(bag)
    assert counts['/vd/steady_state/result'] == 1
    assert counts['/vd/steady_state/state'] == 11


@pytest.mark.parametrize('argv, message', [
    # every event of every model, model by model (bicycle, two_track, kc, vehicle)
    (('run', 'nope'), "unknown event 'nope' (events: steady_state_circular, handling_diagram, "
     "step_steer, parallel_wheel_travel, opposite_wheel_travel, lateral_force, "
     "longitudinal_force, steering, aligning_torque, constant_radius_turn, sine_with_dwell, "
     "straight_line_braking, brake_in_turn, power_off_in_turn, straight_line_acceleration, "
     "ride, bump, lane_change, lane_change_limit)"),
    (('run', 'handling_diagram', '--model', 'tricycle'),
     "unknown model 'tricycle' (models: bicycle, two_track, kc, vehicle)"),
    (('run', 'step_steer', '--model', 'two_track'),
     "event 'step_steer' does not run on model 'two_track' (its events: "
     "steady_state_circular, handling_diagram)"),
    (('run', 'handling_diagram', '--set', 'front_spring.stiffness=3 N/mm'),
     "--set: front_spring.stiffness: key 'stiffness' does not exist in group 'front_spring' "
     "(sedan/front_spring/X.yaml); keys: preload, rate"),
    (('run', 'handling_diagram', '--set', 'front_spring.rate=3 kg'),
     "--set: front_spring.rate: unit 'kg' is not a stiffness unit (expected e.g. 'N/m')"),
    (('run', 'handling_diagram', '--param', 'radius=-5 m'),
     'event handling_diagram: radius: -5 m is outside [1, inf] m'),
    (('run', 'handling_diagram', '--param', 'diameter=5 m'),
     "event handling_diagram: unknown parameter 'diameter' (parameters of handling_diagram: "
     "radius, steps, max_lateral_acceleration, speed)"),
    (('run', 'aligning_torque', '--axle', 'front', '--param', 'moment_max=-5 N*m'),
     'event aligning_torque: moment_max: -5 N*m is outside [0, inf] N*m'),
    (('run', 'aligning_torque', '--axle', 'front', '--param', 'moment_max=5 kg'),
     "event aligning_torque: moment_max: unit 'kg' is not a torque unit (expected e.g. 'N*m')"),
    (('run', 'aligning_torque', '--axle', 'front', '--param', 'force_max=5 N'),
     "event aligning_torque: unknown parameter 'force_max' (parameters of aligning_torque: "
     "moment_min, moment_max, steps)"),
])
def test_bad_run_input_exits_2_with_message_and_writes_nothing(capsys, tmp_path, sedan_master,
                                                               argv, message):
    bag = tmp_path / 'bag'
    before = tree_snapshot(sedan_master.parents[1])
    rc, out, err = _vd(capsys, *argv, '--master', str(sedan_master), '--bag', str(bag))
    assert rc == 2
    assert err.strip() == message
    assert not bag.exists() and not list(tmp_path.glob('bag*'))
    assert tree_snapshot(sedan_master.parents[1]) == before


def test_unknown_configuration_json_error(capsys, tmp_path, sedan_master):
    rc, out, err = _vd(capsys, 'run', 'handling_diagram', '--config', 'nope', '--master',
                       str(sedan_master), '--json')
    assert rc == 2
    assert json.loads(out) == {'error': f"{sedan_master}: configuration 'nope' does not exist "
                                        "(available: baseline, stiff_rear, sport)"}


def test_existing_bag_path_is_refused_and_left_alone(capsys, tmp_path, sedan_master):
    bag = tmp_path / 'existing'
    bag.mkdir()
    (bag / 'keep.txt').write_text('mine')
    rc, _, err = _vd(capsys, 'run', 'handling_diagram', '--master', str(sedan_master), '--bag',
                     str(bag))
    assert rc == 2
    assert err.strip() == f'{bag}: bag path already exists (choose another --bag)'
    assert (bag / 'keep.txt').read_text() == 'mine'


def test_unwritable_bag_path_is_refused(capsys, tmp_path, sedan_master):
    blocker = tmp_path / 'file'
    blocker.write_text('x')
    rc, _, err = _vd(capsys, 'run', 'handling_diagram', '--master', str(sedan_master), '--bag',
                     str(blocker / 'bag'))
    assert rc == 2
    assert err.strip() == f"{blocker / 'bag'}: cannot write under {blocker}"


def test_beyond_limit_answers_with_error_and_no_bag(capsys, tmp_path, sedan_master):
    """
    Check that a bicycle sweep beyond the critical speed is an error.

    The variant is oversteering; the error names configuration and event; no bag is
    left behind.
    """
    bag = tmp_path / 'beyond'
    rc, out, err = _vd(capsys, 'run', 'step_steer', '--model', 'bicycle', '--master',
                       str(sedan_master), '--set', 'mass.sprung_cog.x=-2500 mm',
                       '--param', 'speed=300 km/h', '--bag', str(bag))
    assert rc == 2
    assert err.startswith("configuration 'baseline', event 'step_steer', model 'bicycle': ")
    assert 'critical speed' in err
    assert not bag.exists() and not (tmp_path / 'beyond.partial').exists()


def test_study_plan_runs_and_reports(capsys, tmp_path, sedan_master):
    plan = tmp_path / 'plan.yaml'
    plan.write_text(f"""name: small
master: {sedan_master}
runs:
  - event: handling_diagram
    models: [two_track]
    configurations: all
    parameters: [steps=11]
  - event: steady_state_circular
    models: [bicycle]
    configurations: [baseline]
""")
    out = tmp_path / 'out'
    rc, stdout, err = _vd(capsys, 'study', str(plan), '--report', str(out), '--json')
    assert rc == 0, err
    summary = json.loads(stdout)
    assert [r['error'] for r in summary['runs']] == [None] * 4
    html = (out / 'report.html').read_text()
    assert 'stiff_rear' in html and 'MODIFIED' in html and 'UNCHANGED' in html
    # the understeer budget of every analytical run, each term with its source
    assert 'Understeer budget — baseline (bicycle)' in html
    assert '<td>lateral compliance steer</td>' in html and 'K&amp;C front lateral_force' in html
    assert (out / 'handling_diagram_analytical_0.png').stat().st_size > 10_000
    bags = sorted(p.name for p in (out / 'bags').iterdir())
    assert bags == ['handling_diagram_two_track_baseline', 'handling_diagram_two_track_sport',
                    'handling_diagram_two_track_stiff_rear',
                    'steady_state_circular_bicycle_baseline']
    # the report can be rebuilt from the bags alone
    rc, stdout, err = _vd(capsys, 'report', *[str(out / 'bags' / b) for b in bags], '--out',
                          str(tmp_path / 'again'))
    assert rc == 0, err
    assert (tmp_path / 'again' / 'report.html').exists()


def test_report_of_a_non_bag_is_an_error(capsys, tmp_path):
    rc, _, err = _vd(capsys, 'report', str(tmp_path), '--out', str(tmp_path / 'r'))
    assert rc == 2
    assert err.strip() == f'{tmp_path}: not a finished rosbag2 bag (no metadata.yaml)'
    assert not (tmp_path / 'r').exists()
