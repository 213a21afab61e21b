# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
``ros2 launch vd_data_server data_server.launch.py``: the data server alone.

Arguments: ``namespace`` (default ``/vd``), ``master_file`` (default: the bundled sedan
study), ``allow_edits`` (default ``false``), ``watch_period`` (s, default ``0.5``).
"""
from launch.actions import DeclareLaunchArgument, OpaqueFunction
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node

from launch import LaunchDescription
from vd_data_server.names import DEFAULT_NAMESPACE


def _nodes(context):
    """Return the data server node with the arguments as its parameters."""
    def arg(name: str) -> str:
        return LaunchConfiguration(name).perform(context)

    params = {'allow_edits': arg('allow_edits').lower() == 'true',
              'watch_period': float(arg('watch_period'))}
    if arg('master_file'):
        params['master_file'] = arg('master_file')
    return [Node(package='vd_data_server', executable='data_server',
                 namespace=arg('namespace'), parameters=[params], output='screen')]


def generate_launch_description() -> LaunchDescription:
    """Describe the data server launch."""
    return LaunchDescription([
        DeclareLaunchArgument('namespace', default_value=DEFAULT_NAMESPACE,
                              description='namespace of the node and its names'),
        DeclareLaunchArgument('master_file', default_value='',
                              description='master file (default: the bundled sedan study)'),
        DeclareLaunchArgument('allow_edits', default_value='false',
                              description='accept set_override requests'),
        DeclareLaunchArgument('watch_period', default_value='0.5',
                              description='seconds between checks of the data files (0: off)'),
        OpaqueFunction(function=_nodes),
    ])
