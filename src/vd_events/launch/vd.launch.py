# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
``ros2 launch vd_events vd.launch.py``: the graph ``vd launch`` starts.

The data server and one solver per family, from ``vd_events.graph.graph()`` (the one
definition of the graph, shared with ``vd launch`` and ``vd run --distributed``).
Arguments: ``namespace`` (default ``/vd``), ``master_file`` (default: the bundled sedan
study), ``allow_edits`` (default ``false``), ``watch_period`` (s, default ``0.5``).
"""
from launch.actions import DeclareLaunchArgument, OpaqueFunction
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node

from launch import LaunchDescription
from vd_data_server.names import DEFAULT_NAMESPACE
from vd_events.graph import graph


def _nodes(context):
    """Return the graph's nodes with the arguments as the data server's parameters."""
    def arg(name: str) -> str:
        return LaunchConfiguration(name).perform(context)

    specs = graph(arg('master_file') or None, watch_period=float(arg('watch_period')),
                  allow_edits=arg('allow_edits').lower() == 'true')
    return [Node(package=spec.package, executable=spec.executable, namespace=arg('namespace'),
                 parameters=[dict(spec.parameters)] if spec.parameters else [],
                 output='screen') for spec in specs]


def generate_launch_description() -> LaunchDescription:
    """Describe the vd graph launch."""
    return LaunchDescription([
        DeclareLaunchArgument('namespace', default_value=DEFAULT_NAMESPACE,
                              description='namespace of the nodes and their names'),
        DeclareLaunchArgument('master_file', default_value='',
                              description='master file (default: the bundled sedan study)'),
        DeclareLaunchArgument('allow_edits', default_value='false',
                              description='accept set_override requests'),
        DeclareLaunchArgument('watch_period', default_value='0.5',
                              description='seconds between checks of the data files (0: off)'),
        OpaqueFunction(function=_nodes),
    ])
