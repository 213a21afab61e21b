# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
An example external controller for the lock-step vehicle (``ros2 run vd_events path_follower``).

An ordinary rclpy node that knows nothing of the vehicle model: it subscribes to
``nav_msgs/Odometry`` (``vehicle/odom``) and, with ``use_sim_time``, to ``/clock``,
and answers every odometry message with a ``vd_interfaces/VehicleCommand`` on
``vehicle/command`` stamped with the odometry's stamp (the step it applies to); names
relative to its namespace (``/vd`` by default), as the vehicle solver's.

Path: the constant radius turn's left circle of ``radius`` through the origin, heading +x
(centre (0, radius)). Steering: pure pursuit on the odometry pose -- the point of the
circle ``lookahead_time`` * speed (at least ``min_lookahead``) ahead, curvature
2 y_target / d^2 in the vehicle frame, road-wheel angle atan(wheelbase * curvature),
steering-wheel angle through ``steering_ratio``. Speed: PI control of the total wheel
torque to ``speed``, positive as drive torque, negative as brake torque. When the
vehicle has turned ``laps`` full circles it logs ``lap complete`` and holds the command.
"""
from __future__ import annotations

import math

from nav_msgs.msg import Odometry
from rcl_interfaces.msg import ParameterDescriptor
from rclpy.node import Node
from rclpy.qos import HistoryPolicy, QoSProfile, ReliabilityPolicy

from vd_data_server.ros import names
from vd_interfaces.msg import VehicleCommand
from vd_solvers.families import ODOMETRY_TOPIC
from vd_solvers.nodes.lockstep import COMMAND_TOPIC

QOS = QoSProfile(history=HistoryPolicy.KEEP_LAST, depth=10,
                 reliability=ReliabilityPolicy.RELIABLE)
PARAMS = {
    'radius': (40.0, 'circle radius, m'),
    'speed': (12.0, 'target speed, m/s'),
    'wheelbase': (2.7, 'wheelbase, m'),
    'steering_ratio': (15.8, 'steering-wheel angle / road-wheel angle'),
    'lookahead_time': (0.8, 'pure-pursuit look-ahead, s of travel'),
    'min_lookahead': (6.0, 'shortest look-ahead, m'),
    'speed_gain': (600.0, 'proportional gain, N*m per m/s'),
    'speed_integral': (300.0, 'integral gain, N*m per m'),
    'max_steering_wheel_angle': (8.0, 'steering-wheel angle limit, rad'),
    'laps': (1.0, 'full circles to drive'),
}


class PathFollower(Node):
    """Pure pursuit on a circle and PI speed control (module doc)."""

    def __init__(self, **kwargs) -> None:
        kwargs.setdefault('namespace', names.DEFAULT_NAMESPACE)
        super().__init__('path_follower', **kwargs)
        self.p = {}
        for name, (default, doc) in PARAMS.items():
            self.declare_parameter(name, default, ParameterDescriptor(description=doc))
            self.p[name] = float(self.get_parameter(name).value)
        self.frame = names.frame_prefix(self.get_namespace()) + names.BODY_FRAME
        self.pub = self.create_publisher(VehicleCommand, COMMAND_TOPIC, QOS)
        self.create_subscription(Odometry, ODOMETRY_TOPIC, self._on_odometry, QOS)
        self._integral = 0.0
        self._last_ns: int | None = None
        self._turned = 0.0
        self._last_angle: float | None = None
        self.done = False
        self.commands = 0

    def _on_odometry(self, odom: Odometry) -> None:
        ns = odom.header.stamp.sec * 1_000_000_000 + odom.header.stamp.nanosec
        if self._last_ns is not None and ns <= self._last_ns:
            return  # a repeat of a state already answered
        dt = 0.0 if self._last_ns is None else (ns - self._last_ns) * 1e-9
        self._last_ns = ns
        p = self.p
        x, y = odom.pose.pose.position.x, odom.pose.pose.position.y
        q = odom.pose.pose.orientation
        yaw = math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))
        speed = math.hypot(odom.twist.twist.linear.x, odom.twist.twist.linear.y)
        radius = p['radius']
        # angle travelled around the centre (0, radius), counter-clockwise
        angle = math.atan2(x, radius - y)
        if self._last_angle is not None:
            self._turned += (angle - self._last_angle + math.pi) % (2 * math.pi) - math.pi
        self._last_angle = angle
        if not self.done and self._turned >= 2 * math.pi * p['laps']:
            self.done = True
            self.get_logger().info(f'lap complete at t = {ns * 1e-9:.3f} s')
        lookahead = max(p['lookahead_time'] * speed, p['min_lookahead'])
        target = angle + lookahead / radius
        tx, ty = radius * math.sin(target), radius - radius * math.cos(target)
        dx, dy = tx - x, ty - y
        local_y = -math.sin(yaw) * dx + math.cos(yaw) * dy
        curvature = 2.0 * local_y / max(dx * dx + dy * dy, 1e-6)
        swa = math.atan(p['wheelbase'] * curvature) * p['steering_ratio']
        limit = p['max_steering_wheel_angle']
        swa = max(-limit, min(limit, swa))
        error = p['speed'] - speed
        self._integral += error * dt
        torque = p['speed_gain'] * error + p['speed_integral'] * self._integral
        cmd = VehicleCommand()
        cmd.header.stamp = odom.header.stamp
        cmd.header.frame_id = self.frame
        cmd.steering_mode = VehicleCommand.STEERING_ANGLE
        cmd.steering_wheel_angle = swa
        cmd.drive_torque = max(torque, 0.0)
        cmd.brake_torque = max(-torque, 0.0)
        self.pub.publish(cmd)
        self.commands += 1
