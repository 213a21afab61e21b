# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
A stopped lock-step session starts again without rebuilding the vehicle.

``vehicle/reset`` (std_srvs/Trigger) and ``initialpose`` (RViz's 2D Pose Estimate) put the
session back to t = 0, at the origin or at the pose given; the odometry says where the
car stands, its covariance marked unknown (REP 145) and its height the model's.
"""
from __future__ import annotations

import math

import pytest

from vdtest import wait_for

pytestmark = [pytest.mark.ros, pytest.mark.slow]


def test_reset_and_initial_pose_restart_a_stopped_session(ros_domain, sedan_master):
    from geometry_msgs.msg import PoseWithCovarianceStamped
    from nav_msgs.msg import Odometry
    import rclpy
    from rclpy.parameter import Parameter
    from std_srvs.srv import Trigger

    from vd_data_server.ros.qos import COMMANDS, STATES
    from vd_interfaces.msg import VehicleCommand
    from vd_solvers.nodes.vehicle import VehicleSolver

    solver = VehicleSolver(namespace='/car4', cli_args=['--ros-args', '-r',
                                                        '/clock:=/car4/clock'],
                           parameter_overrides=[Parameter('mode', value='lockstep'),
                                                Parameter('master', value=str(sedan_master)),
                                                Parameter('initial_speed', value=5.0),
                                                Parameter('start_timeout', value=600.0)])
    probe = rclpy.create_node('reset_probe')
    nodes = [solver, probe]
    odom: list = []
    try:
        probe.create_subscription(Odometry, '/car4/vehicle/odom', odom.append, STATES)
        pub = probe.create_publisher(VehicleCommand, '/car4/vehicle/command', COMMANDS)
        pose = probe.create_publisher(PoseWithCovarianceStamped, '/car4/initialpose', COMMANDS)
        client = probe.create_client(Trigger, '/car4/vehicle/reset')
        assert wait_for(nodes, lambda: pub.get_subscription_count() and client.service_is_ready()
                        and pose.get_subscription_count())
        session = solver.lockstep
        pub.publish(VehicleCommand())  # step 0
        assert wait_for(nodes, lambda: session.stepper.step == 1)
        bad = VehicleCommand(drive_torque=-1.0)
        bad.header.stamp.nanosec = 5_000_000
        pub.publish(bad)
        assert wait_for(nodes, lambda: not session.active)
        model = session.stepper.model
        future = client.call_async(Trigger.Request())
        assert wait_for(nodes, future.done)
        assert future.result().message == ('reset to t = 0 at x = 0 m, y = 0 m, yaw = 0 rad '
                                           '(1 steps run before)')
        assert session.active and session.stepper.step == 0
        assert solver.lockstep.stepper.model is model  # the same vehicle, not rebuilt
        pub.publish(VehicleCommand())  # step 0 again: taken
        assert wait_for(nodes, lambda: session.stepper.step == 1)
        # RViz's 2D Pose Estimate: 10 m, 5 m, heading +y
        msg = PoseWithCovarianceStamped()
        msg.pose.pose.position.x, msg.pose.pose.position.y = 10.0, 5.0
        msg.pose.pose.orientation.z = math.sin(math.pi / 4)
        msg.pose.pose.orientation.w = math.cos(math.pi / 4)
        pose.publish(msg)
        assert wait_for(nodes, lambda: odom[-1].header.stamp.sec == 0
                        and odom[-1].header.stamp.nanosec == 0
                        and odom[-1].pose.pose.position.x != 0.0)
    finally:
        for node in nodes:
            node.destroy_node()
    placed = odom[-1]
    assert (placed.pose.pose.position.x, placed.pose.pose.position.y) == (10.0, 5.0)
    o = placed.pose.pose.orientation
    assert math.atan2(2 * (o.w * o.z + o.x * o.y), 1 - 2 * (o.y**2 + o.z**2)) == \
        pytest.approx(math.pi / 2, abs=1e-9)
    assert placed.twist.twist.linear.x == pytest.approx(5.0, abs=0.05)  # along its heading
    # REP 145: not estimated; the body's height is the model's (on its tires, near design)
    assert placed.pose.covariance[0] == -1.0 and placed.twist.covariance[0] == -1.0
    assert placed.pose.pose.position.z != 0.0 and abs(placed.pose.pose.position.z) < 0.1


def test_the_vehicle_solver_is_a_managed_node(ros_domain, sedan_master):
    """Configure = build the vehicle, activate = start, deactivate = hold, cleanup = drop."""
    from lifecycle_msgs.msg import Transition
    from lifecycle_msgs.srv import ChangeState, GetState
    import rclpy
    from rclpy.parameter import Parameter

    from vd_data_server.ros.qos import COMMANDS
    from vd_interfaces.msg import VehicleCommand
    from vd_solvers.nodes.vehicle import VehicleSolver

    solver = VehicleSolver(namespace='/car5', cli_args=['--ros-args', '-r',
                                                        '/clock:=/car5/clock'],
                           parameter_overrides=[Parameter('mode', value='lockstep'),
                                                Parameter('autostart', value=False),
                                                Parameter('master', value=str(sedan_master)),
                                                Parameter('start_timeout', value=600.0)])
    probe = rclpy.create_node('lifecycle_probe')
    nodes = [solver, probe]
    try:
        change = probe.create_client(ChangeState, '/car5/vehicle_solver/change_state')
        get = probe.create_client(GetState, '/car5/vehicle_solver/get_state')
        assert wait_for(nodes, lambda: change.service_is_ready() and get.service_is_ready())

        def call(client, request):
            future = client.call_async(request)
            assert wait_for(nodes, future.done)
            return future.result()

        def transition(tid: int) -> bool:
            return call(change, ChangeState.Request(transition=Transition(id=tid))).success

        def state() -> str:
            return call(get, GetState.Request()).current_state.label

        assert state() == 'unconfigured' and solver.lockstep is None
        assert transition(Transition.TRANSITION_CONFIGURE) and state() == 'inactive'
        assert solver.lockstep is None  # built, not started: no /clock yet
        assert probe.count_publishers('/car5/clock') == 0
        assert transition(Transition.TRANSITION_ACTIVATE) and state() == 'active'
        session = solver.lockstep
        assert session is not None and session.active
        pub = probe.create_publisher(VehicleCommand, '/car5/vehicle/command', COMMANDS)
        assert wait_for(nodes, lambda: pub.get_subscription_count() > 0)
        pub.publish(VehicleCommand())
        assert wait_for(nodes, lambda: session.stepper.step == 1)
        assert transition(Transition.TRANSITION_DEACTIVATE) and state() == 'inactive'
        assert session.status == 'inactive at t = 0.005000 s'
        assert transition(Transition.TRANSITION_ACTIVATE)  # the session again, from t = 0
        assert session.active and session.stepper.step == 0
        assert transition(Transition.TRANSITION_DEACTIVATE)
        assert transition(Transition.TRANSITION_CLEANUP) and state() == 'unconfigured'
        assert solver.lockstep is None
        assert wait_for(nodes, lambda: probe.count_publishers('/car5/clock') == 0)
    finally:
        for node in nodes:
            node.destroy_node()
