# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""An edit made in the workbench reaches a running data server node (it watches the files)."""
from __future__ import annotations

from pathlib import Path

import pytest

pytestmark = pytest.mark.ros


def test_a_workbench_edit_is_republished_by_the_data_server(ros_domain,
                                                            sedan_master: Path) -> None:
    from rclpy.node import Node
    from rclpy.parameter import Parameter

    from vd_data_server.nodes.data_server import DataServer, latched
    from vd_data_server.workbench.server import Workbench
    from vd_interfaces.msg import DataStatus
    from vdtest import wait_for

    node = DataServer(parameter_overrides=[Parameter('master_file', value=str(sedan_master)),
                                           Parameter('watch_period', value=0.2)])
    listener = Node('workbench_listener')
    statuses: list = []
    listener.create_subscription(DataStatus, '/vd/data_status', statuses.append, latched(1))
    bench = Workbench(sedan_master, edits=True)

    def modified() -> set:
        return {(s.configuration, s.group) for s in statuses[-1].status
                if s.state == s.MODIFIED} if statuses else set()

    try:
        assert wait_for([node, listener], lambda: bool(statuses))
        assert ('baseline', 'front_alignment') not in modified()
        assert bench.edit({'op': 'override', 'configuration': 'baseline',
                           'key': 'front_alignment.camber', 'value': '-1.2 deg'}) == (
            'baseline: front_alignment.camber = -1.2 deg')
        assert wait_for([node, listener],
                          lambda: ('baseline', 'front_alignment') in modified())
    finally:
        bench.stop()
        listener.destroy_node()
        node.destroy_node()
