# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
``ros2 launch vd_events vd.launch.py``: the graph ``vd launch`` starts.

The data server and one solver per family, from ``vd_events.orchestration.graph.graph()`` (the one
definition of the graph, shared with ``vd launch`` and ``vd run --distributed``).
Arguments (the data server's, ``vd_data_server/launch_arguments.py``): ``namespace``
(default ``/vd``), ``master_file`` (default: the bundled sedan study), ``allow_edits``
(default ``false``), ``watch_period`` (s, default ``0.5``).
"""
from launch.actions import OpaqueFunction
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node

from launch import LaunchDescription
from vd_data_server.ros.launch_arguments import data_server_settings, declare
from vd_events.orchestration.graph import graph


def _nodes(context):
    """Return the graph's nodes with the arguments as the data server's parameters."""
    def arg(name: str) -> str:
        return LaunchConfiguration(name).perform(context)

    specs = graph(**data_server_settings(arg))
    return [Node(package=spec.package, executable=spec.executable, namespace=arg('namespace'),
                 parameters=[dict(spec.parameters)] if spec.parameters else [],
                 output='screen') for spec in specs]


def generate_launch_description() -> LaunchDescription:
    """Describe the vd graph launch."""
    return LaunchDescription([*declare(), OpaqueFunction(function=_nodes)])
