# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The launch arguments of the data server, shared by every launch file that starts it.

``data_server.launch.py`` (this package) and ``vd_events``' ``vd.launch.py`` declare the
same arguments and turn them into the data server's parameters here, once.
"""
from __future__ import annotations

from collections.abc import Callable

from launch.actions import DeclareLaunchArgument

from vd_data_server.ros.names import DEFAULT_NAMESPACE

#: (name, default, description) of each argument
ARGUMENTS = (
    ('namespace', DEFAULT_NAMESPACE, 'namespace of the nodes and their names'),
    ('master_file', '', 'master file (default: the bundled sedan study)'),
    ('allow_edits', 'false', 'accept set_override requests'),
    ('watch_period', '0.5', 'seconds between checks of the data files (0: off)'),
)


def declare() -> list:
    """Return the ``DeclareLaunchArgument`` actions of :data:`ARGUMENTS`."""
    return [DeclareLaunchArgument(name, default_value=default, description=text)
            for name, default, text in ARGUMENTS]


def data_server_settings(arg: Callable[[str], str]) -> dict:
    """
    Return the data server's settings from the performed arguments (``arg(name)``).

    ``master`` (None: the node's default study), ``watch_period`` (s) and
    ``allow_edits``, as ``vd_events.orchestration.graph.data_server`` takes them.
    """
    return {'master': arg('master_file') or None,
            'watch_period': float(arg('watch_period')),
            'allow_edits': arg('allow_edits').lower() == 'true'}
