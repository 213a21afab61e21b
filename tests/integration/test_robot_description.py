# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The lock-step vehicle as RViz and Foxglove see it.

A late subscriber gets the URDF on ``robot_description`` and the static frames on
``/tf_static`` (latched); every step puts the wheel frames on ``/tf`` and the joints on
``joint_states``; while a step's command is awaited, its odometry is repeated but its
``/tf`` is not (tf2 refuses a repeated stamp).
"""
from __future__ import annotations

import pytest

from vdtest import spin_until, wait_for

pytestmark = [pytest.mark.ros, pytest.mark.slow]


def test_the_vehicle_publishes_its_description_joints_and_frames(ros_domain, sedan_master):
    from nav_msgs.msg import Odometry
    import pinocchio as pin
    import rclpy
    from rclpy.parameter import Parameter
    from sensor_msgs.msg import JointState
    from std_msgs.msg import String

    from tf2_msgs.msg import TFMessage
    from vd_data_server.ros.qos import COMMANDS, STATES, TF, TF_STATIC
    from vd_interfaces.msg import VehicleCommand
    from vd_solvers.nodes.lockstep import REPEAT_PERIOD
    from vd_solvers.nodes.vehicle import VehicleSolver

    solver = VehicleSolver(namespace='/car3', cli_args=['--ros-args', '-r',
                                                        '/clock:=/car3/clock'],
                           parameter_overrides=[Parameter('mode', value='lockstep'),
                                                Parameter('master', value=str(sedan_master)),
                                                Parameter('start_timeout', value=600.0)])
    probe = rclpy.create_node('description_probe')
    nodes = [solver, probe]
    got: dict[str, list] = {'urdf': [], 'static': [], 'tf': [], 'joints': [], 'odom': []}
    try:
        # subscribed after the vehicle published: the latched topics still arrive
        probe.create_subscription(String, '/car3/robot_description', got['urdf'].append,
                                  TF_STATIC)
        probe.create_subscription(TFMessage, '/tf_static', got['static'].append, TF_STATIC)
        probe.create_subscription(TFMessage, '/tf', got['tf'].append, TF)
        probe.create_subscription(JointState, '/car3/joint_states', got['joints'].append,
                                  STATES)
        probe.create_subscription(Odometry, '/car3/vehicle/odom', got['odom'].append, STATES)
        pub = probe.create_publisher(VehicleCommand, '/car3/vehicle/command', COMMANDS)
        assert wait_for(nodes, lambda: got['urdf'] and got['static']
                        and pub.get_subscription_count())
        for k in range(2):
            msg = VehicleCommand(steering_wheel_angle=0.5, drive_torque=200.0)
            msg.header.stamp.nanosec = k * 5_000_000
            pub.publish(msg)
            assert wait_for(nodes, lambda k=k: solver.lockstep.stepper.step == k + 1)
        assert wait_for(nodes, lambda: any(
            m.header.stamp.nanosec == 10_000_000 for m in got['joints']))
        # no command for step 2: its odometry repeats, its /tf does not
        spin_until(nodes, lambda: False, 3 * REPEAT_PERIOD)
    finally:
        for node in nodes:
            node.destroy_node()
    model = pin.buildModelFromXML(got['urdf'][-1].data)
    assert model.existFrame('front_left_wheel') and model.existFrame('chassis')
    (static,) = got['static']
    assert [(t.header.frame_id, t.child_frame_id) for t in static.transforms] == [
        ('car3/base_link', 'car3/chassis')]
    last = [m for m in got['tf'] if m.transforms[0].header.stamp.nanosec == 10_000_000]
    assert len(last) == 1  # step 2 once, though its odometry was repeated
    assert sum(1 for m in got['odom'] if m.header.stamp.nanosec == 10_000_000) >= 2
    frames = {(t.header.frame_id, t.child_frame_id) for t in last[0].transforms}
    assert ('car3/odom', 'car3/base_link') in frames
    assert ('car3/base_link', 'car3/front_left_carrier') in frames
    assert ('car3/front_left_carrier', 'car3/front_left_knuckle') in frames
    assert ('car3/front_left_knuckle', 'car3/front_left_wheel') in frames
    assert ('car3/rear_right_carrier', 'car3/rear_right_wheel') in frames
    joints = got['joints'][-1]
    assert len(joints.name) == len(joints.position) == 10
    steer = dict(zip(joints.name, joints.position))
    assert steer['front_left_steer'] > 0.0 and steer['front_right_steer'] > 0.0  # + left


def test_the_shipped_rviz_and_foxglove_views_name_the_vehicle_topics():
    import json
    from pathlib import Path

    import yaml

    from vd_solvers.families import ODOMETRY_TOPIC
    from vd_solvers.nodes.lockstep import JOINT_STATES_TOPIC, ROBOT_DESCRIPTION_TOPIC

    launch = Path(__file__).resolve().parents[2] / 'src' / 'vd_events' / 'launch'
    rviz = yaml.safe_load((launch / 'vehicle.rviz').read_text())
    displays = {d['Class']: d for d in rviz['Visualization Manager']['Displays']}
    assert displays['rviz_default_plugins/RobotModel']['Description Topic']['Value'] == \
        f'/vd/{ROBOT_DESCRIPTION_TOPIC}'
    assert displays['rviz_default_plugins/RobotModel']['Description Topic'][
        'Durability Policy'] == 'Transient Local'  # the description is latched
    assert displays['rviz_default_plugins/Odometry']['Topic']['Value'] == \
        f'/vd/{ODOMETRY_TOPIC}'
    assert rviz['Visualization Manager']['Global Options']['Fixed Frame'] == 'odom'
    layout = json.loads((launch / 'vehicle.foxglove.json').read_text())
    topics = set(layout['configById']['3D!vehicle']['topics'])
    assert topics == {f'/vd/{ROBOT_DESCRIPTION_TOPIC}', f'/vd/{ODOMETRY_TOPIC}'}
    paths = [p['value'] for c in layout['configById'].values() for p in c.get('paths', [])]
    assert any(p.startswith(f'/vd/{JOINT_STATES_TOPIC}.') for p in paths)
