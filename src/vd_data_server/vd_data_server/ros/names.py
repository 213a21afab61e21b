# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The names of the vd graph (a contract: tests and users rely on them).

Every topic, service and action name of a vd node is **relative**, so it resolves in the
node's namespace. The nodes' default namespace is ``/vd``: started as they are, the
graph has today's names (``/vd/configuration``, ``/vd/kc/run_event``, ...), and
``--ros-args -r __ns:=/car2`` (or ``ros2 launch ... namespace:=/car2``, ``vd run
--namespace /car2``) moves a node, with all its names, to ``/car2/configuration``, ...
Two studies, or two vehicles, share a ROS domain in two namespaces.

ROS-free (plain strings), so the CLI can check a namespace before anything starts.
"""
from __future__ import annotations

import re

from vd_data_server.errors import DataError

#: the namespace of every vd node unless the caller remaps it (``__ns:=``)
DEFAULT_NAMESPACE = '/vd'

# data server (topics, services), relative to the namespace
CONFIGURATION = 'configuration'
DATA_STATUS = 'data_status'
GET_CONFIGURATION = 'get_configuration'
SET_OVERRIDE = 'set_override'
RELOAD = 'reload'
# solvers: one provenance topic for all; per family see vd_solvers.families
PROVENANCE = 'provenance'

# ROS 2 name rules (rcl): absolute, tokens of letters, digits and '_' not starting with
# a digit, no '__', no trailing '/'
_TOKEN = re.compile(r'^[A-Za-z_][A-Za-z0-9_]*$')


def check_namespace(namespace: str, *, what: str = '--namespace') -> str:
    """
    ``namespace`` as an absolute ROS namespace (``car2`` -> ``/car2``), or DataError.

    ``/`` is the root namespace.
    """
    text = namespace.strip()
    if not text.startswith('/'):
        text = '/' + text
    if text == '/':
        return text
    tokens = text[1:].split('/')
    if any(not _TOKEN.match(t) or '__' in t for t in tokens):
        raise DataError(f"'{namespace}' is not a valid ROS namespace (tokens of letters, "
                        "digits and '_', not starting with a digit, separated by '/', "
                        "e.g. '/car2')", file=what)
    return text


def resolve(namespace: str, name: str) -> str:
    """Return the absolute name of the relative ``name`` in ``namespace``."""
    return f"{namespace.rstrip('/')}/{name}"


# REP 105 frames: the vehicle body and the world-fixed odometry frame. A graph outside
# the default namespace prefixes them (``car2/base_link``): the TF tree on /tf is global
# and shared by every vehicle on the domain.
BODY_FRAME = 'base_link'
ODOM_FRAME = 'odom'


def frame_prefix(namespace: str) -> str:
    """Return the frame prefix of a graph in ``namespace``: none in ``/vd``, else ``car2/``."""
    ns = namespace.strip('/')
    return '' if '/' + ns == DEFAULT_NAMESPACE or not ns else ns + '/'
