# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The bags of ``vd run`` as a ROS tool sees them.

* decoded with the independent ``mcap_ros2`` decoder, every channel of the run is a named
  field of the typed state (``/vd/kc/state/left/toe``), equal to the result's channel;
* stamps strictly increase on a simulation-time axis (simulated time in a step steer,
  the documented pseudo-time in a K&C sweep) and each message's log time is its stamp;
* chunks are compressed, ``ros_distro`` is ``jazzy`` and every topic records the QoS
  its publishers offered, so a player publishing with the recorded QoS (as ``ros2 bag
  play`` does) reaches the transient_local subscribers of vd, and one publishing
  volatile (what a bag without the QoS gives) does not.
"""
from __future__ import annotations

import contextlib
import io
import json
from pathlib import Path

import pytest
import yaml

from vdtest import spin_until

pytestmark = [pytest.mark.ros, pytest.mark.slow]


def _vd(capsys, *argv: str) -> tuple[int, str, str]:
    from vd_events.cli.main import main

    rc = main(list(argv))
    out, err = capsys.readouterr()
    return rc, out, err


def _decoded(bag: Path) -> dict[str, list]:
    """Topic -> [(log_time, decoded)] read with mcap + mcap_ros2 (not rosbags)."""
    from mcap.reader import make_reader
    from mcap_ros2.decoder import DecoderFactory

    (mcap_file,) = bag.glob('*.mcap')
    out: dict[str, list] = {}
    with mcap_file.open('rb') as stream:
        reader = make_reader(stream, decoder_factories=[DecoderFactory()])
        for _, channel, message, decoded in reader.iter_decoded_messages(log_time_order=False):
            out.setdefault(channel.topic, []).append((message.log_time, decoded))
    return out


def _stamp(msg) -> int:
    stamp = msg.header.stamp if hasattr(msg, 'header') else msg.stamp
    return stamp.sec * 1_000_000_000 + stamp.nanosec


def _field(state, channel: str) -> float:
    """Look up the value of ``channel`` by field name, as a plotting tool would."""
    from vd_solvers.conversions import KC_BUSHING_FIELDS, XYZ

    if channel.startswith('bushing_'):
        prefix, name, rest = channel.split('.')
        comp, side = rest.rsplit('_', 1)
        bushing = next(b for b in getattr(state, side).bushings if b.name == name)
        for field, (p, comps, _) in KC_BUSHING_FIELDS.items():
            if p == prefix and comp in comps:
                return getattr(getattr(bushing, field), XYZ[comps.index(comp)])
    if hasattr(state, channel):
        return getattr(state, channel)
    stem, side = channel.rsplit('_', 1)
    wheel = getattr(state, side)
    if hasattr(wheel, stem):
        return getattr(wheel, stem)
    stem, comp = stem.rsplit('_', 1)
    return getattr(getattr(wheel, stem), comp)


def _check_time_axis(messages: dict[str, list]) -> None:
    """Every stamped message is logged at its stamp; stamps strictly increase per topic."""
    for topic in ('/vd/provenance', '/vd/kc/state', '/vd/kc/result', '/vd/steady_state/state',
                  '/vd/steady_state/result'):
        stamps = [_stamp(msg) for _, msg in messages.get(topic, [])]
        assert [t for t, _ in messages.get(topic, [])] == stamps, topic
        assert all(b > a for a, b in zip(stamps, stamps[1:])), topic


def _metadata(bag: Path) -> dict:
    return yaml.safe_load((bag / 'metadata.yaml').read_text())['rosbag2_bagfile_information']


@pytest.fixture(scope='module')
def kc_bag(tmp_path_factory):
    from vd_data_server.paths import default_master
    from vd_events.cli.main import main

    bag = tmp_path_factory.mktemp('kc') / 'pwt'
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        rc = main(['run', 'parallel_wheel_travel', '--axle', 'front', '--master',
                   str(default_master()), '--param', 'steps=11', '--bag', str(bag), '--json'])
    assert rc == 0, out.getvalue()
    return bag, json.loads(out.getvalue())


def test_kc_bag_has_every_channel_as_a_named_field_on_a_pseudo_time_axis(kc_bag):
    from vd_solvers.conversions import PSEUDO_STEP

    bag, result = kc_bag
    messages = _decoded(bag)
    states = [msg for _, msg in messages['/vd/kc/state']]
    assert len(states) == 11
    assert len(result['channels']) > 100
    for name, channel in result['channels'].items():
        values = [_field(s, name) for s in states]
        assert values == pytest.approx(channel['values'], nan_ok=True), name
    _check_time_axis(messages)
    stamps = [_stamp(s) for s in states]
    assert {b - a for a, b in zip(stamps, stamps[1:])} == {int(PSEUDO_STEP * 1e9)}
    (result_msg,) = [msg for _, msg in messages['/vd/kc/result']]
    assert _stamp(result_msg) == stamps[-1]  # the result closes the run on the axis
    (provenance,) = [msg for _, msg in messages['/vd/provenance']]
    assert _stamp(provenance) == stamps[0]
    # XY plots: the swept quantity is a field
    assert [s.left.wheel_travel for s in states] == pytest.approx(
        result['channels']['wheel_travel_left']['values'])
    # the wheels move on /tf: base_link -> front_left_wheel, front_right_wheel at each
    # state's stamp, at the wheel centre (RViz / Foxglove 3D panels)
    tfs = [msg for _, msg in messages['/tf']]
    assert len(tfs) == len(states)
    assert [t for t, _ in messages['/tf']] == [_stamp(tf.transforms[0]) for tf in tfs]
    for tf, state in zip(tfs, states):
        assert [(t.header.frame_id, t.child_frame_id) for t in tf.transforms] == [
            ('base_link', 'front_left_wheel'), ('base_link', 'front_right_wheel')]
        for t, wheel in zip(tf.transforms, (state.left, state.right)):
            assert _stamp(t) == _stamp(state)
            tr, centre = t.transform.translation, wheel.wheel_centre
            assert (tr.x, tr.y, tr.z) == (centre.x, centre.y, centre.z)


def test_step_steer_bag_is_on_the_simulated_time_axis(capsys, tmp_path, sedan_master):
    bag = tmp_path / 'ss'
    rc, out, err = _vd(capsys, 'run', 'step_steer', '--model', 'bicycle', '--master',
                       str(sedan_master), '--param', 'steps=51', '--bag', str(bag), '--json')
    assert rc == 0, err
    result = json.loads(out)
    messages = _decoded(bag)
    states = [msg for _, msg in messages['/vd/steady_state/state']]
    time = result['channels']['time']['values']
    assert len(states) == len(time) == 51
    offsets = [(_stamp(s) - _stamp(states[0])) * 1e-9 for s in states]
    assert offsets == pytest.approx(time, abs=1e-9)
    for name, channel in result['channels'].items():
        assert [getattr(s, name) for s in states] == pytest.approx(channel['values']), name
    _check_time_axis(messages)


def test_bag_metadata_says_jazzy_compressed_chunks_and_the_offered_qos(kc_bag):
    from mcap.reader import make_reader
    from rosbags.rosbag2 import Reader

    bag, _ = kc_bag
    meta = _metadata(bag)
    assert meta['ros_distro'] == 'jazzy'
    topics = {t['topic_metadata']['name']: t['topic_metadata']
              for t in meta['topics_with_message_count']}
    assert set(topics) >= {'/vd/configuration', '/vd/data_status', '/vd/provenance',
                           '/vd/kc/state', '/vd/kc/result', '/tf'}
    # what the ROS tools expect: data and results latched, per-step streams and /tf
    # volatile (tf2's broadcaster), so a late subscriber never replays a finished run
    durability = {'/vd/configuration': 'transient_local', '/vd/data_status': 'transient_local',
                  '/vd/provenance': 'transient_local', '/vd/kc/result': 'transient_local',
                  '/vd/kc/state': 'volatile', '/tf': 'volatile'}
    for name, topic in topics.items():
        profiles = topic['offered_qos_profiles']  # one per publisher (three for provenance)
        assert profiles, name
        for qos in profiles:
            assert (qos['reliability'], qos['durability'], qos['history']) == (
                'reliable', durability[name], 'keep_last'), name
            assert qos['depth'] > 0, name
    assert topics['/tf']['offered_qos_profiles'][0]['depth'] == 100  # tf2_ros's depth
    # one per solver of the graph (an embedded run starts the solvers its runs need)
    assert len(topics['/vd/provenance']['offered_qos_profiles']) >= 1
    (mcap_file,) = bag.glob('*.mcap')
    with mcap_file.open('rb') as stream:
        summary = make_reader(stream).get_summary()
    assert summary.chunk_indexes
    assert {c.compression for c in summary.chunk_indexes} == {'zstd'}
    assert all(c.compressed_size < c.uncompressed_size for c in summary.chunk_indexes)
    with Reader(bag) as reader:  # rosbags opens the compressed chunks too
        assert reader.ros_distro == 'jazzy'
        assert sum(1 for _ in reader.messages()) == meta['message_count']


def _replay(node, bag: Path, durability):
    """
    Publish every message of the bag's /vd/configuration topic once, as ``ros2 bag play``.

    With the recorded offered QoS, or with its durability replaced.
    """
    from rclpy.qos import QoSProfile
    from rclpy.serialization import deserialize_message
    from rosbags.rosbag2 import Reader

    from vd_events.bags.bag import offered_qos
    from vd_interfaces.msg import Configuration

    (recorded,) = offered_qos(bag)['/vd/configuration']  # the data server's
    qos = QoSProfile(history=recorded.history, depth=recorded.depth,
                     reliability=recorded.reliability,
                     durability=recorded.durability if durability is None else durability)
    pub = node.create_publisher(Configuration, '/vd/configuration', qos)
    with Reader(bag) as reader:
        conns = [c for c in reader.connections if c.topic == '/vd/configuration']
        for _, _, raw in reader.messages(connections=conns):
            pub.publish(deserialize_message(bytes(raw), Configuration))
    return pub


@pytest.mark.parametrize('durability, expected', [(None, 1), ('volatile', 0)])
def test_replay_with_the_recorded_qos_reaches_a_late_transient_local_subscriber(
        ros_domain, kc_bag, durability, expected):
    from rclpy.node import Node
    from rclpy.qos import DurabilityPolicy

    from vd_data_server.ros.qos import CONFIGURATIONS as LATCHED  # as a solver subscribes
    from vd_interfaces.msg import Configuration

    bag, result = kc_bag
    player = Node('bag_player_stand_in')
    listener = Node('late_solver_stand_in')
    received: list = []
    try:
        _replay(player, bag, None if durability is None else DurabilityPolicy.VOLATILE)
        # a vd subscriber started after the replay (a solver subscribes latched)
        listener.create_subscription(Configuration, '/vd/configuration', received.append,
                                     LATCHED)
        spin_until([player, listener], lambda: len(received) >= 1, timeout=5.0)
    finally:
        player.destroy_node()
        listener.destroy_node()
    assert len(received) == expected
    if expected:
        assert received[0].name == result['configuration']
