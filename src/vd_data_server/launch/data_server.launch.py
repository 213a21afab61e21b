# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
``ros2 launch vd_data_server data_server.launch.py``: the data server alone.

Arguments (``vd_data_server/launch_arguments.py``, shared with ``vd.launch.py``):
``namespace`` (default ``/vd``), ``master_file`` (default: the bundled sedan study),
``allow_edits`` (default ``false``), ``watch_period`` (s, default ``0.5``).
"""
from launch.actions import OpaqueFunction
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node

from launch import LaunchDescription
from vd_data_server.ros.launch_arguments import data_server_settings, declare


def _nodes(context):
    """Return the data server node with the arguments as its parameters."""
    def arg(name: str) -> str:
        return LaunchConfiguration(name).perform(context)

    settings = data_server_settings(arg)
    params = {'allow_edits': settings['allow_edits'], 'watch_period': settings['watch_period']}
    if settings['master'] is not None:
        params['master_file'] = settings['master']
    return [Node(package='vd_data_server', executable='data_server',
                 namespace=arg('namespace'), parameters=[params], output='screen')]


def generate_launch_description() -> LaunchDescription:
    """Describe the data server launch."""
    return LaunchDescription([*declare(), OpaqueFunction(function=_nodes)])
