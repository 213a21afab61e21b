# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
``ros2 launch vd_solvers solvers.launch.py``: the solver nodes (no data server).

Arguments: ``namespace`` (default ``/vd``; the data server must serve the same one) and
``families`` (comma-separated, default every family: ``steady_state,kc,vehicle``).
"""
from launch.actions import DeclareLaunchArgument, OpaqueFunction
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node

from launch import LaunchDescription
from vd_data_server.ros.names import DEFAULT_NAMESPACE
from vd_solvers.families import FAMILIES


def _nodes(context):
    """Return a solver node per chosen family."""
    namespace = LaunchConfiguration('namespace').perform(context)
    chosen = [f.strip() for f in LaunchConfiguration('families').perform(context).split(',')
              if f.strip()]
    unknown = [f for f in chosen if f not in FAMILIES]
    if unknown:
        raise RuntimeError(f"families: unknown {', '.join(unknown)} (families: "
                           f"{', '.join(FAMILIES)})")
    return [Node(package='vd_solvers', executable=FAMILIES[f].executable, namespace=namespace,
                 output='screen') for f in chosen]


def generate_launch_description() -> LaunchDescription:
    """Describe the solvers launch."""
    return LaunchDescription([
        DeclareLaunchArgument('namespace', default_value=DEFAULT_NAMESPACE,
                              description='namespace of the nodes and their names'),
        DeclareLaunchArgument('families', default_value=','.join(FAMILIES),
                              description='solver families to start (comma-separated)'),
        OpaqueFunction(function=_nodes),
    ])
