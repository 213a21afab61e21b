# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The lock-step vehicle driven by the standard command inputs.

A controller answers each step with a ``geometry_msgs/Twist`` on ``/vd/cmd_vel`` or an
``ackermann_msgs/AckermannDriveStamped`` on ``/vd/ackermann_cmd``: the car reaches the
commanded speed and turns the way REP 103 says (``angular.z`` > 0 and a positive tire
angle turn left: positive yaw rate, the path bends towards +y).
"""
from __future__ import annotations

import time

import pytest

from vdtest import HANG_GUARD

pytestmark = [pytest.mark.ros, pytest.mark.slow]

STEP, DURATION = 0.005, 8.0
START_SPEED, SPEED = 6.0, 9.0


def _drive(master, answer, **params):
    """Run a lock-step session, every step answered by ``answer``; return status, last state."""
    from nav_msgs.msg import Odometry
    import rclpy
    from rclpy.executors import SingleThreadedExecutor
    from rclpy.parameter import Parameter

    from vd_data_server.ros.qos import STATES
    from vd_solvers.nodes.vehicle import VehicleSolver

    values = {'mode': 'lockstep', 'master': str(master), 'step': STEP,
              'initial_speed': START_SPEED, 'duration': DURATION, **params}
    solver = VehicleSolver(parameter_overrides=[Parameter(k, value=v)
                                                for k, v in values.items()])
    node = rclpy.create_node('input_controller')
    answered: set[int] = set()
    pub = answer.publisher(node)

    def on_odom(odom) -> None:
        ns = odom.header.stamp.sec * 10**9 + odom.header.stamp.nanosec
        if ns in answered:
            return  # a repeat of a step already answered
        answered.add(ns)
        pub.publish(answer.message(odom))

    node.create_subscription(Odometry, '/vd/vehicle/odom', on_odom, STATES)
    executor = SingleThreadedExecutor()
    executor.add_node(solver)
    executor.add_node(node)
    session = solver.lockstep
    try:
        deadline = time.monotonic() + HANG_GUARD
        while session.active and time.monotonic() < deadline:
            executor.spin_once(timeout_sec=0.1)
        return session.status, session.stepper.state()
    finally:
        executor.shutdown(timeout_sec=0.0)
        solver.destroy_node()
        node.destroy_node()


class _Twist:
    def __init__(self, yaw_rate: float) -> None:
        self.yaw_rate = yaw_rate

    def publisher(self, node):
        from geometry_msgs.msg import Twist

        return node.create_publisher(Twist, '/vd/cmd_vel', 10)  # rclpy's default QoS

    def message(self, odom):
        from geometry_msgs.msg import Twist

        msg = Twist()
        msg.linear.x, msg.angular.z = SPEED, self.yaw_rate
        return msg


class _Ackermann:
    def __init__(self, angle: float) -> None:
        self.angle = angle

    def publisher(self, node):
        from ackermann_msgs.msg import AckermannDriveStamped

        return node.create_publisher(AckermannDriveStamped, '/vd/ackermann_cmd', 10)

    def message(self, odom):
        from ackermann_msgs.msg import AckermannDriveStamped

        msg = AckermannDriveStamped()
        msg.header.stamp = odom.header.stamp  # the step it answers
        msg.drive.steering_angle, msg.drive.speed = self.angle, SPEED
        msg.drive.acceleration = 2.0
        return msg


@pytest.mark.parametrize('answer, sign', [(_Twist(0.15), 1.0), (_Twist(-0.15), -1.0),
                                          (_Ackermann(0.03), 1.0), (_Ackermann(-0.03), -1.0)],
                         ids=['twist_left', 'twist_right', 'ackermann_left', 'ackermann_right'])
def test_a_standard_command_drives_the_lockstep_vehicle(ros_domain, sedan_master, answer,
                                                        sign):
    steps = int(round(DURATION / STEP))
    status, last = _drive(sedan_master, answer)
    assert status == f'finished at t = {DURATION:.6f} s ({steps} steps)', status
    assert last['speed'] == pytest.approx(SPEED, abs=0.3)
    # REP 103: a left command (positive) turns left: positive yaw rate, heading and y
    assert sign * last['yaw_rate'] > 0.05
    assert sign * last['yaw'] > 0.1 and sign * last['y'] > 1.0
    if isinstance(answer, _Twist):
        # at this low lateral acceleration the car holds about the commanded yaw rate
        assert last['yaw_rate'] == pytest.approx(answer.yaw_rate, rel=0.25)


def test_an_ackermann_command_ahead_of_the_clock_stops_the_session(ros_domain, sedan_master):
    class Ahead(_Ackermann):
        def message(self, odom):
            msg = super().message(odom)
            msg.header.stamp.sec += 1
            return msg

    status, _ = _drive(sedan_master, Ahead(0.0))
    assert status == ('error at t = 0.000000 s: command stamped 1.000000 s for the step at '
                      '0.000000 s: ahead of the simulation clock')


def test_a_reverse_twist_is_refused_with_its_reason(ros_domain, sedan_master):
    class Reverse(_Twist):
        def message(self, odom):
            msg = super().message(odom)
            msg.linear.x = -1.0
            return msg

    status, _ = _drive(sedan_master, Reverse(0.0))
    assert status == ('error at t = 0.000000 s: command for t = 0.000000 s refused: speed -1 '
                      'm/s: reverse is not available (the driveline model has no reverse gear)')
