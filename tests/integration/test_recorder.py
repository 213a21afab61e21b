# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The recorder process: a bag becomes final only when its owner says so.

The owner says the recording is complete with ``/vd/recorder/finish``; SIGTERM and SIGINT
remove the partial bag and say so.
"""
from __future__ import annotations

import os
import signal
import subprocess

import pytest

from vdtest import HANG_GUARD, wait_for

pytestmark = [pytest.mark.ros, pytest.mark.slow]


def _record_three_samples(ros_domain, bag, stop) -> tuple[subprocess.Popen, str, int]:
    """
    Start a recorder, publish one run of three steps to it, then ``stop(node, proc)``.

    A run reaches the recorder as its provenance and its EventResult; the recorder writes
    the per-step states from the result. As a run's owner does
    (vd_events.orchestration.runner), the stop comes once the recorder's latched
    ``recorder/recorded`` count says the run is written.
    """
    from ament_index_python.packages import get_package_prefix
    from rclpy.node import Node
    from std_msgs.msg import UInt32

    from vd_data_server.ros.qos import LATEST, RESULTS
    from vd_interfaces.msg import Channel, EventResult, Provenance
    from vd_solvers.conversions import time_msg

    exe = os.path.join(get_package_prefix('vd_events'), 'lib', 'vd_events', 'recorder')
    env = dict(os.environ, ROS_DOMAIN_ID=str(ros_domain))
    proc = subprocess.Popen([exe, '--ros-args', '-p', f'bag:={bag}'], env=env,
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    node = Node('sample_publisher')
    try:
        provenance_pub = node.create_publisher(Provenance, '/vd/provenance', RESULTS)
        result_pub = node.create_publisher(EventResult, '/vd/kc/result', RESULTS)
        recorded: list[int] = []
        node.create_subscription(UInt32, '/vd/recorder/recorded',
                                 lambda m: recorded.append(m.data), LATEST)
        assert wait_for([node], lambda: provenance_pub.get_subscription_count() >= 1
                          and result_pub.get_subscription_count() >= 1)
        now = node.get_clock().now().nanoseconds
        provenance_pub.publish(Provenance(stamp=time_msg(now), event='e', configuration='c',
                                          model='kc'))
        # three quasi-static steps: 1 ms of pseudo-time apart, the result at the last one
        result_pub.publish(EventResult(
            stamp=time_msg(now + 2_000_000), event='e', configuration='c', model='kc',
            channels=[Channel(name='track', unit='m', values=[0.0, 1.0, 2.0])]))
        assert wait_for([node], lambda: recorded and recorded[-1] == 1)
        stop(node, proc)
        out, _ = proc.communicate(timeout=HANG_GUARD)
    finally:
        node.destroy_node()
        if proc.poll() is None:
            proc.kill()
    return proc, out, now


def test_finish_closes_the_bag_under_its_final_name(ros_domain, tmp_path):
    from std_srvs.srv import Trigger

    from vd_events.bags.bag import read_bag

    bag = tmp_path / 'bag'
    answers = []

    def finish(node, proc) -> None:
        client = node.create_client(Trigger, '/vd/recorder/finish')
        assert wait_for([node], client.service_is_ready)
        future = client.call_async(Trigger.Request())
        assert wait_for([node], future.done)
        answers.append(future.result())

    proc, out, start = _record_three_samples(ros_domain, bag, finish)
    assert (answers[0].success, answers[0].message) == (True, str(bag))
    assert proc.returncode == 0, out
    assert (bag / 'metadata.yaml').is_file()
    assert not (tmp_path / 'bag.partial').exists()
    messages = list(read_bag(bag))
    states = [m for m in messages if m.topic == '/vd/kc/state']
    # the states a K&C solver publishes for this result, written from the result alone
    assert [(s.msg.step, s.msg.track, s.msg.event, s.msg.configuration) for s in states] == [
        (0, 0.0, 'e', 'c'), (1, 1.0, 'e', 'c'), (2, 2.0, 'e', 'c')]
    assert [s.timestamp for s in states] == [start, start + 1_000_000, start + 2_000_000]
    assert [m.msg.event for m in messages if m.topic == '/vd/kc/result'] == ['e']


@pytest.mark.parametrize('sig', [signal.SIGTERM, signal.SIGINT])
def test_a_signal_removes_the_partial_bag_and_says_so(ros_domain, tmp_path, sig):
    bag = tmp_path / 'bag'
    proc, out, _ = _record_three_samples(ros_domain, bag,
                                         lambda node, p: p.send_signal(sig))
    assert proc.returncode == 1, out
    assert out.splitlines()[-1] == (f'recorder: interrupted before the recording was complete: '
                                    f'no bag written ({bag}.partial removed)')
    assert sorted(p.name for p in tmp_path.iterdir()) == []


def test_recorder_refuses_an_existing_bag(ros_domain, tmp_path):
    from ament_index_python.packages import get_package_prefix

    exe = os.path.join(get_package_prefix('vd_events'), 'lib', 'vd_events', 'recorder')
    bag = tmp_path / 'bag'
    bag.mkdir()
    done = subprocess.run([exe, '--ros-args', '-p', f'bag:={bag}'], capture_output=True,
                          text=True, timeout=HANG_GUARD,
                          env=dict(os.environ, ROS_DOMAIN_ID=str(ros_domain)))
    assert done.returncode == 2
    assert f'recorder: {bag}: bag path already exists (choose another --bag)' in done.stdout
    assert list(bag.iterdir()) == []
