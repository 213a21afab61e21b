# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The QoS profiles against what the ROS tools expect of them.

References: tf2_ros ``qos.hpp`` (DynamicBroadcasterQoS: depth 100, reliable, volatile;
StaticBroadcasterQoS: depth 1, reliable, transient_local), and the DDS request/offer
rule: a transient_local reader never matches a volatile writer (the rig bridge's
best-effort reader is tested against real publishers in tests/integration/test_rig_bridge.py).
"""
from __future__ import annotations

import pytest

pytestmark = pytest.mark.ros


def _kind(profile):
    return (profile.reliability.name, profile.durability.name, profile.depth)


@pytest.mark.parametrize('topic, expected', [
    ('/tf', ('RELIABLE', 'VOLATILE', 100)),
    ('/tf_static', ('RELIABLE', 'TRANSIENT_LOCAL', 1)),
    ('robot_description', ('RELIABLE', 'TRANSIENT_LOCAL', 1)),
    ('/vd/vehicle/state', ('RELIABLE', 'VOLATILE', 1000)),
    ('/vd/vehicle/odom', ('RELIABLE', 'VOLATILE', 1000)),
    ('/car2/vehicle/joint_states', ('RELIABLE', 'VOLATILE', 1000)),
    ('/vd/kc/result', ('RELIABLE', 'TRANSIENT_LOCAL', 100)),
    ('/vd/provenance', ('RELIABLE', 'TRANSIENT_LOCAL', 100)),
    ('/vd/data_status', ('RELIABLE', 'TRANSIENT_LOCAL', 1)),
    ('/vd/vehicle/lockstep_status', ('RELIABLE', 'TRANSIENT_LOCAL', 1)),
    ('/clock', ('RELIABLE', 'VOLATILE', 10)),
    ('/vd/cmd_vel', ('RELIABLE', 'VOLATILE', 10)),
])
def test_each_topic_is_offered_as_the_ros_tools_expect(topic, expected):
    from vd_data_server.ros.qos import profile_of

    assert _kind(profile_of(topic)) == expected

