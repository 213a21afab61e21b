# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
``ros2 run vd_events rig_bridge``: records a rig's live topics into a vd bag.

Subscribes to ``topic`` (default ``/rig/joint_states``, ``sensor_msgs/JointState``: posts
and load cells as joints) and maps the joints to vd channels with the column map of
parameter ``map`` (docs/testdata.md: ``JOINT.position`` / ``.velocity`` / ``.effort``
keys). The subscription is best effort and volatile, so it matches every publisher:
default QoS (``ros2 topic pub``, ``joint_state_broadcaster``), sensor-data QoS and latched
ones. ``~/received`` (std_msgs/UInt32, latched) counts the messages taken so far, so a rig
(or a test) sees the bridge is listening. The service ``~/finish`` (std_srvs/Trigger)
writes what was received as one EventOutcome (model ``rig`` or ``test``, fidelity
``measured``) to the bag of parameter ``bag`` with the messages of a simulation
(:mod:`vd_events.bags.outcomes`) and answers its path; nothing is written before, and a
finish with fewer than two complete samples writes nothing and says so. The core is
:class:`vd_events.measured.rig.RigRecording`.
"""
from __future__ import annotations

from pathlib import Path
import sys
import time

from rcl_interfaces.msg import ParameterDescriptor
import rclpy
from rclpy.node import Node
from sensor_msgs.msg import JointState
from std_msgs.msg import UInt32
from std_srvs.srv import Trigger

from vd_data_server.errors import DataError
from vd_data_server.ros.node_main import spin_node
from vd_data_server.ros.qos import LATEST, RIG_INPUT
from vd_events.bags.bag import check_bag_path
from vd_events.bags.outcomes import write_outcomes
from vd_events.errors import BagError
from vd_events.measured.columns import load_map
from vd_events.measured.rig import RigRecording

DEFAULT_TOPIC = '/rig/joint_states'


class RigBridge(Node):
    def __init__(self, **kwargs) -> None:
        super().__init__('rig_bridge', **kwargs)
        for name, default, text in (
                ('map', '', 'column map YAML (JOINT.position/velocity/effort -> channel)'),
                ('bag', '', 'bag directory to create on ~/finish'),
                ('topic', DEFAULT_TOPIC, 'sensor_msgs/JointState topic of the rig')):
            self.declare_parameter(name, default, ParameterDescriptor(description=text,
                                                                      read_only=True))
        path = self.get_parameter('map').value
        self.bag = self.get_parameter('bag').value
        if not path or not self.bag:
            raise DataError("rig_bridge: parameters 'map' and 'bag' are required")
        check_bag_path(Path(self.bag))
        topic = self.get_parameter('topic').value
        self.recording = RigRecording(load_map(path), topic)
        self.written: str | None = None
        self.received = 0
        self.received_pub = self.create_publisher(UInt32, '~/received', LATEST)
        self.create_subscription(JointState, topic, self._on_state, RIG_INPUT)
        self.create_service(Trigger, '~/finish', self._finish)
        self.get_logger().info(f"recording {topic} ({', '.join(self.recording.channels)}) "
                               f'for {self.bag}')

    def _on_state(self, msg: JointState) -> None:
        stamp = msg.header.stamp.sec + 1e-9 * msg.header.stamp.nanosec
        self.recording.add(stamp, msg.name, msg.position, msg.velocity, msg.effort)
        self.received += 1
        self.received_pub.publish(UInt32(data=self.received))

    def finish(self) -> str:
        """Write the bag; return its path (DataError/BagError: nothing written)."""
        if self.written is not None:
            return self.written
        outcome = self.recording.outcome()
        path = write_outcomes(Path(self.bag), [(outcome, time.time_ns())], {
            'vd.kind': 'measurement (live rig)', 'vd.model': outcome.model,
            'vd.event': outcome.event, 'vd.source': self.recording.source,
            'vd.column_map': self.recording.cmap.text})
        self.written = str(path)
        return self.written

    def _finish(self, request, response):
        try:
            response.message = self.finish()
            response.success = True
        except (DataError, BagError, OSError) as err:
            response.success, response.message = False, str(err)
            self.get_logger().error(response.message)
        return response


def main(args=None) -> None:
    try:
        spin_node(RigBridge, args)
    except (DataError, BagError) as err:  # bad parameters or map: a message, exit 2
        print(err, file=sys.stderr)
        rclpy.try_shutdown()
        sys.exit(2)


if __name__ == '__main__':
    main()
