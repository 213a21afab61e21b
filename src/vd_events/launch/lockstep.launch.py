# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
``ros2 launch vd_events lockstep.launch.py``: the lock-step vehicle and the example controller.

Starts ``vehicle_solver`` in ``lockstep`` mode (the sample study's first configuration,
5 ms steps) and ``path_follower`` (pure pursuit on the 40 m constant radius circle at
12 m/s), the controller with ``use_sim_time``. Arguments: ``namespace`` (default ``/vd``; outside
it the frames carry the namespace: ``car2/odom``), ``master`` (default: the bundled
study), ``configuration``, ``mode`` (lockstep | free), ``duration`` (simulated s),
``radius``, ``speed``, ``real_time_factor`` (free mode), ``command_timeout`` (wall s the
vehicle waits for a step's command, default 2; more on a loaded machine), ``clock_topic``
(default ``/clock``: the simulation clock both nodes use; one owner per ROS domain, so a
second vehicle in the domain needs its own, e.g. ``clock_topic:=/car2/clock``).
``vd launch --lockstep`` starts the same pair where the launch tools are not installed.
"""
from launch.actions import DeclareLaunchArgument
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node
from launch_ros.parameter_descriptions import ParameterValue

from launch import LaunchDescription
from vd_data_server.ros.names import DEFAULT_NAMESPACE


def generate_launch_description() -> LaunchDescription:
    """Declare the arguments and the two nodes."""
    args = {'namespace': DEFAULT_NAMESPACE, 'master': '', 'configuration': '',
            'mode': 'lockstep', 'duration': '30.0', 'radius': '40.0', 'speed': '12.0',
            'real_time_factor': '1.0', 'command_timeout': '2.0', 'clock_topic': '/clock'}
    declared = [DeclareLaunchArgument(k, default_value=v) for k, v in args.items()]

    def value(name, kind=float):
        return ParameterValue(LaunchConfiguration(name), value_type=kind)

    namespace = LaunchConfiguration('namespace')
    clock = [('/clock', LaunchConfiguration('clock_topic'))]
    solver = Node(package='vd_solvers', executable='vehicle_solver', output='screen',
                  namespace=namespace, remappings=clock,
                  parameters=[{'mode': value('mode', str),
                               'master': value('master', str),
                               'configuration': value('configuration', str),
                               'duration': value('duration'),
                               'initial_speed': value('speed'),
                               'real_time_factor': value('real_time_factor'),
                               'command_timeout': value('command_timeout'),
                               'use_sim_time': False}])
    follower = Node(package='vd_events', executable='path_follower', output='screen',
                    namespace=namespace, remappings=clock,
                    parameters=[{'radius': value('radius'), 'speed': value('speed'),
                                 'use_sim_time': True}])
    return LaunchDescription([*declared, solver, follower])
