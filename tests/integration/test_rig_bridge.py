# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The rig_bridge process: a rig's live sensor_msgs/JointState into a vd bag.

The bag reads like an imported or simulated one; bad parameters are refused with exit 2.
"""
from __future__ import annotations

import math
import os
import re
import subprocess
import time

from numpy.testing import assert_allclose
import pytest

from vdtest import HANG_GUARD, spin_until, wait_for

pytestmark = [pytest.mark.ros, pytest.mark.slow]

RIG_MAP = """kind: kc
event: parallel_wheel_travel
axle: front
rig: live test rig
vehicle: baseline
columns:
  post_left.position: {channel: wheel_travel, side: left}
  post_left.effort: {channel: pad_force, side: left}
  wheel_left.position: {channel: toe, side: left, unit: deg, sign: -1}
"""


def _exe() -> str:
    from ament_index_python.packages import get_package_prefix

    return os.path.join(get_package_prefix('vd_events'), 'lib', 'vd_events', 'rig_bridge')


@pytest.mark.parametrize('publisher_qos', ['default', 'sensor_data', 'latched'])
def test_joint_states_recorded_as_a_rig_measurement(ros_domain, tmp_path, publisher_qos):
    """
    Every profile a rig may publish JointState with is taken.

    ``ros2 topic pub`` and joint_state_broadcaster use the default QoS, drivers the
    sensor-data QoS.
    """
    from rclpy.node import Node
    from rclpy.qos import QoSPresetProfiles
    from sensor_msgs.msg import JointState
    from std_msgs.msg import UInt32
    from std_srvs.srv import Trigger

    from vd_data_server.ros.qos import LATEST, latched
    from vd_events.measured.compare import load_outcomes

    cmap = tmp_path / 'rig.yaml'
    cmap.write_text(RIG_MAP)
    bag = tmp_path / 'bag'
    proc = subprocess.Popen([_exe(), '--ros-args', '-p', f'map:={cmap}', '-p', f'bag:={bag}'],
                            env=dict(os.environ, ROS_DOMAIN_ID=str(ros_domain)),
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    node = Node('rig_publisher')
    try:
        # depth 10 alone is rclpy's default profile: reliable, volatile
        qos = {'default': 10, 'sensor_data': QoSPresetProfiles.SENSOR_DATA.value,
               'latched': latched(10)}[publisher_qos]
        pub = node.create_publisher(JointState, '/rig/joint_states', qos)
        received = [0]
        node.create_subscription(UInt32, '/rig_bridge/received',
                                 lambda m: received.__setitem__(0, m.data), LATEST)
        assert wait_for([node], lambda: pub.get_subscription_count() >= 1)
        # best effort drops what is sent before the bridge has matched the publisher:
        # messages without a mapped joint until the bridge says it takes them
        other = JointState(name=['other'], position=[1.0], velocity=[], effort=[0.0])
        deadline = time.monotonic() + HANG_GUARD
        while received[0] == 0 and proc.poll() is None and time.monotonic() < deadline:
            pub.publish(other)
            spin_until([node], lambda: received[0] > 0, timeout=1.0)
        assert received[0] > 0
        travel = [-0.02, -0.01, 0.0, 0.01, 0.02]
        for k, z in enumerate(travel):
            msg = JointState(name=['post_left', 'wheel_left', 'other'],
                             position=[z, 0.5 * k, 9.0], velocity=[],
                             effort=[3000.0 + k, 0.0, 0.0])
            msg.header.stamp = node.get_clock().now().to_msg()
            pub.publish(msg)
        # a message without a mapped joint is left out, not recorded half
        pub.publish(other)
        # a warm-up message still in flight may arrive after the count was read
        sent = received[0] + len(travel) + 1
        assert wait_for([node], lambda: received[0] >= sent)
        client = node.create_client(Trigger, '/rig_bridge/finish')
        assert wait_for([node], client.service_is_ready)
        future = client.call_async(Trigger.Request())
        assert wait_for([node], future.done)
        answer = future.result()
    finally:
        node.destroy_node()
        proc.terminate()
        out, _ = proc.communicate(timeout=HANG_GUARD)
    assert (answer.success, answer.message) == (True, str(bag)), out
    (outcome,) = load_outcomes(bag)
    assert (outcome.model, outcome.fidelity, outcome.axle) == ('rig', 'measured', 'front')
    assert_allclose(outcome.channels['wheel_travel_left'].values, travel)
    assert_allclose(outcome.channels['pad_force_left'].values, [3000, 3001, 3002, 3003, 3004])
    assert_allclose(outcome.channels['toe_left'].values,
                    [-math.radians(0.5 * k) for k in range(5)])
    assert any(re.fullmatch(r'[1-9]\d* message\(s\) without every mapped joint left out', n)
               for n in outcome.notes), outcome.notes


def test_rig_bridge_refuses_a_bad_map(ros_domain, tmp_path):
    cmap = tmp_path / 'rig.yaml'
    cmap.write_text(RIG_MAP.replace('post_left.effort', 'post_left.force'))
    done = subprocess.run([_exe(), '--ros-args', '-p', f'map:={cmap}', '-p',
                           f'bag:={tmp_path / "bag"}'], capture_output=True, text=True,
                          timeout=HANG_GUARD, env=dict(os.environ, ROS_DOMAIN_ID=str(ros_domain)))
    assert done.returncode == 2
    assert done.stderr.strip().splitlines()[-1] == (
        f'{cmap}: columns.post_left.force: a rig column is JOINT.position, JOINT.velocity '
        'or JOINT.effort')
    assert sorted(p.name for p in tmp_path.iterdir()) == ['rig.yaml']
