# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""The data_server node in a private ROS domain: latched topics, services, file watching."""
from __future__ import annotations

from pathlib import Path
import time

import pytest

from vdtest import wait_for

pytestmark = pytest.mark.ros


@pytest.fixture
def server(ros_domain, sedan_master: Path):
    from rclpy.parameter import Parameter

    from vd_data_server.nodes.data_server import DataServer

    node = DataServer(parameter_overrides=[
        Parameter('master_file', value=str(sedan_master)),
        Parameter('watch_period', value=0.2),
    ])
    yield node
    node.destroy_node()


def _listener(name: str):
    from rclpy.node import Node

    from vd_data_server.ros.qos import CONFIGURATIONS, LATEST
    from vd_interfaces.msg import Configuration, DataStatus

    node = Node(name)
    node.configs = {}
    node.statuses = []
    node.create_subscription(Configuration, '/vd/configuration',
                             lambda m: node.configs.__setitem__(m.name, m),
                             CONFIGURATIONS)
    node.create_subscription(DataStatus, '/vd/data_status', node.statuses.append, LATEST)
    return node


def test_late_subscriber_receives_every_configuration(server):
    from vdtest import spin_until, wait_for

    spin_until([server], lambda: False, timeout=0.3)  # the server has published by now
    listener = _listener('late_listener')
    try:
        assert wait_for([server, listener], lambda: len(listener.configs) == 3 and
                          listener.statuses)
        assert set(listener.configs) == {'baseline', 'stiff_rear', 'sport'}
        status = listener.statuses[-1]
        modified = {(s.configuration, s.group) for s in status.status if s.state == s.MODIFIED}
        assert modified == {('sport', 'front_hardpoints'), ('sport', 'front_damper'),
                            ('sport', 'front_alignment')}
    finally:
        listener.destroy_node()


def test_configuration_message_round_trips_losslessly(server):
    from vd_data_server.conversions import configuration_from_msg

    listener = _listener('roundtrip_listener')

    try:
        assert wait_for([server, listener], lambda: len(listener.configs) == 3)
        for name, original in server.service.study.configurations.items():
            assert configuration_from_msg(listener.configs[name]) == original
            assert listener.configs[name].data_hash == original.data_hash
    finally:
        listener.destroy_node()


def test_editing_a_data_file_republishes_new_values_and_feedback(server, sample_root: Path):

    listener = _listener('edit_listener')
    try:
        assert wait_for([server, listener], lambda: len(listener.configs) == 3)
        old_hash = listener.configs['baseline'].data_hash
        spring = sample_root / 'sedan' / 'front_spring' / 'X.yaml'
        time.sleep(0.01)
        spring.write_text(spring.read_text().replace('rate: 30.0', 'rate: 33.0'))

        def updated() -> bool:
            msg = listener.configs.get('baseline')
            return msg is not None and msg.data_hash != old_hash

        assert wait_for([server, listener], updated)
        group = next(g for g in listener.configs['baseline'].groups if g.name == 'front_spring')
        rate = next(s for s in group.scalars if s.name == 'rate')
        assert rate.value == pytest.approx(33000.0)
        # X changed for every configuration that uses it; sport uses Y: front_spring now
        # differs between... it already did (Y). front_alignment of sport stays MODIFIED.
        status = listener.statuses[-1]
        spring_rows = [s for s in status.status if s.group == 'front_spring']
        assert all(s.state == s.UNCHANGED for s in spring_rows)
        assert {s.consistency for s in spring_rows} == {spring_rows[0].DIFFERS}
    finally:
        listener.destroy_node()


def test_master_override_edit_flips_feedback_to_modified(server, sedan_master: Path):

    listener = _listener('master_listener')
    try:
        assert wait_for([server, listener], lambda: listener.statuses)
        text = sedan_master.read_text().replace(
            '  baseline:\n    description: Reference car, all shared data unchanged.\n',
            '  baseline:\n    description: Reference car.\n    overrides:\n'
            '      rear_alignment.toe: 0.25 deg\n')
        time.sleep(0.01)
        sedan_master.write_text(text)

        def flipped() -> bool:
            return any(s.configuration == 'baseline' and s.group == 'rear_alignment'
                       and s.state == s.MODIFIED for s in listener.statuses[-1].status)

        assert wait_for([server, listener], flipped)
        row = next(s for s in listener.statuses[-1].status
                   if s.configuration == 'baseline' and s.group == 'rear_alignment')
        assert [(k.key, k.data_value, k.master_value, k.unit) for k in row.modified_keys] == [
            ('toe', '0.15', '0.25', 'deg')]
    finally:
        listener.destroy_node()


def test_broken_data_file_keeps_previous_data_and_reports(server, sample_root: Path):
    from vdtest import line_no

    listener = _listener('broken_listener')
    try:
        assert wait_for([server, listener], lambda: len(listener.configs) == 3
                          and listener.statuses)
        before = {n: m.data_hash for n, m in listener.configs.items()}
        spring = sample_root / 'sedan' / 'front_spring' / 'X.yaml'
        time.sleep(0.01)
        spring.write_text(spring.read_text().replace('rate: 30.0', 'rate: -30.0'))
        assert wait_for([server, listener], lambda: listener.statuses[-1].errors)
        assert listener.statuses[-1].errors == [
            "sedan/front_spring/X.yaml: rate: must be positive, found -30.0 "
            f"(line {line_no(spring, '  rate:')})"]
        assert {n: m.data_hash for n, m in listener.configs.items()} == before
    finally:
        listener.destroy_node()


def _call(server, client_node, srv_type, name, request):

    client = client_node.create_client(srv_type, name)
    assert wait_for([server, client_node], client.service_is_ready)
    future = client.call_async(request)
    assert wait_for([server, client_node], future.done)
    return future.result()


def test_set_override_refused_without_allow_edits(server):
    from rclpy.node import Node

    from vd_interfaces.srv import SetOverride

    client_node = Node('override_client')
    try:
        before = server.service.study.configurations['baseline'].data_hash
        result = _call(server, client_node, SetOverride, '/vd/set_override',
                       SetOverride.Request(configuration='baseline',
                                           key='front_alignment.camber', value='-2 deg'))
        assert not result.success
        assert result.message == ('edits are disabled (start the data server with parameter '
                                  'allow_edits:=true)')
        assert server.service.study.configurations['baseline'].data_hash == before
    finally:
        client_node.destroy_node()


def test_allow_edits_cannot_be_switched_on_over_ros(server):
    """Any participant on the domain may call set_parameters: allow_edits is read-only."""
    from rclpy.parameter import Parameter

    (result,) = server.set_parameters([Parameter('allow_edits', value=True)])
    assert not result.successful
    assert result.reason == 'Trying to set a read-only parameter: allow_edits.'
    assert server.get_parameter('allow_edits').value is False


@pytest.fixture
def editable_server(ros_domain, sedan_master: Path):
    from rclpy.parameter import Parameter

    from vd_data_server.nodes.data_server import DataServer

    node = DataServer(parameter_overrides=[
        Parameter('master_file', value=str(sedan_master)),
        Parameter('watch_period', value=0.2), Parameter('allow_edits', value=True)])
    yield node
    node.destroy_node()


def test_set_override_with_allow_edits_validates_and_applies(editable_server):
    from rclpy.node import Node

    from vd_interfaces.srv import SetOverride

    server = editable_server
    client_node = Node('override_client2')
    try:
        bad = _call(server, client_node, SetOverride, '/vd/set_override',
                    SetOverride.Request(configuration='baseline',
                                        key='front_alignment.camber', value='-2 kg'))
        assert not bad.success
        assert bad.message == ("ROS edit /vd/set_override: front_alignment.camber: unit 'kg' is "
                               "not an angle unit (expected e.g. 'rad')")
        good = _call(server, client_node, SetOverride, '/vd/set_override',
                     SetOverride.Request(configuration='baseline',
                                         key='front_alignment.camber', value='-2 deg'))
        assert good.success, good.message
        camber = server.service.study.configurations['baseline'].group(
            'front_alignment').scalar('camber')
        assert camber == pytest.approx(-2.0 * 3.141592653589793 / 180.0)
        assert server.service.study.status_of('baseline', 'front_alignment').state == 'MODIFIED'
        value = server.service.study.configurations['baseline'].group(
            'front_alignment').values['camber']
        assert value.source == 'ROS edit /vd/set_override front_alignment.camber'
    finally:
        client_node.destroy_node()


def test_get_configuration_service(server):
    from rclpy.node import Node

    from vd_interfaces.srv import GetConfiguration

    client_node = Node('get_client')
    try:
        ok = _call(server, client_node, GetConfiguration, '/vd/get_configuration',
                   GetConfiguration.Request(name='sport'))
        assert ok.success and ok.configuration.name == 'sport'
        missing = _call(server, client_node, GetConfiguration, '/vd/get_configuration',
                        GetConfiguration.Request(name='nope'))
        assert not missing.success
        assert missing.message == ("configuration 'nope' does not exist (available: baseline, "
                                   "stiff_rear, sport)")
    finally:
        client_node.destroy_node()


def test_any_failure_of_a_reload_keeps_the_last_good_data(server, monkeypatch):
    """
    Keep serving whatever a reload raises, not only data errors.

    Here a RecursionError, as from a pathological file: the node keeps serving and
    reports it on its status topic.
    """
    import vd_data_server.service as service

    def broken(*args, **kwargs):
        raise RecursionError('maximum recursion depth exceeded')

    listener = _listener('reload_listener')
    try:
        assert wait_for([server, listener], lambda: len(listener.configs) == 3
                          and listener.statuses)
        before = server.service.study
        monkeypatch.setattr(service, 'load_study', broken)
        server._publish_outcome(server.service.load())
        expected = [f'{server.service.master_file}: cannot load: RecursionError: maximum '
                    'recursion depth exceeded']
        assert wait_for([server, listener], lambda: listener.statuses[-1].errors == expected)
        assert server.service.study is before
        assert len(listener.statuses[-1].status) > 0  # the last good feedback is still served
    finally:
        listener.destroy_node()


def test_edit_that_used_to_crash_the_server_is_answered(editable_server):
    from rclpy.node import Node

    from vd_interfaces.srv import GetConfiguration, SetOverride

    server = editable_server
    client_node = Node('override_client3')
    try:
        before = server.service.study.configurations['baseline'].data_hash
        big = '9' * 400 + ' N/mm'
        for value, message in (('30 N/(mm*0)', "invalid unit 'N/(mm*0)'"),
                               ('', "expected a number with a unit, found ''"),
                               (big, f"value must be finite, found '{big}'")):
            answer = _call(server, client_node, SetOverride, '/vd/set_override',
                           SetOverride.Request(configuration='baseline',
                                               key='front_spring.rate', value=value))
            assert not answer.success
            assert answer.message == f'ROS edit /vd/set_override: front_spring.rate: {message}'
        alive = _call(server, client_node, GetConfiguration, '/vd/get_configuration',
                      GetConfiguration.Request(name='baseline'))
        assert alive.success and alive.configuration.data_hash == before
    finally:
        client_node.destroy_node()


def test_a_late_joiner_gets_exactly_the_current_version_of_every_configuration(
        server, sample_root: Path, sedan_master: Path):
    """After a data change and after a configuration was removed: no stale versions."""
    from rclpy.node import Node

    from vd_data_server.ros.qos import CONFIGURATIONS
    from vd_interfaces.msg import Configuration
    from vdtest import replace_once, spin_until

    def late_listener(name: str):
        node = Node(name)
        node.received = []
        node.create_subscription(Configuration, '/vd/configuration', node.received.append,
                                 CONFIGURATIONS)
        return node

    first = late_listener('before_listener')
    try:
        assert wait_for([server, first], lambda: len(first.received) == 3)
        old = {m.name: m.data_hash for m in first.received}
    finally:
        first.destroy_node()
    replace_once(sample_root / 'sedan' / 'front_spring' / 'X.yaml', 'rate: 30.0', 'rate: 33.0')
    assert wait_for([server], lambda: server.service.study.configurations[
        'baseline'].data_hash != old['baseline'])
    second = late_listener('after_edit_listener')
    try:
        spin_until([server, second], lambda: len(second.received) > 3, timeout=2.0)
        assert sorted(m.name for m in second.received) == ['baseline', 'sport', 'stiff_rear']
        current = server.service.study.configurations
        assert {m.name: m.data_hash for m in second.received} == {
            n: c.data_hash for n, c in current.items()}
        received = {m.name: m.data_hash for m in second.received}
        assert received['baseline'] != old['baseline']  # the new version, not the old
    finally:
        second.destroy_node()
    text = sedan_master.read_text(encoding='utf-8')
    start = text.index('  stiff_rear:')
    end = text.index('  sport:')
    sedan_master.write_text(text[:start] + text[end:], encoding='utf-8')
    assert wait_for([server], lambda: sorted(server.service.study.configurations) ==
                      ['baseline', 'sport'])
    third = late_listener('after_removal_listener')
    try:
        spin_until([server, third], lambda: len(third.received) > 2, timeout=2.0)
        assert sorted(m.name for m in third.received) == ['baseline', 'sport']
    finally:
        third.destroy_node()
