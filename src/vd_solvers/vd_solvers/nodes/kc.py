# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
``ros2 run vd_solvers kc_solver``: the rigid and flexible kinematics & compliance solver.

Goal fidelity 'rigid' or 'flexible'; empty: the configuration's ``flexible`` switch.

Action ``kc/run_event`` (vd_interfaces/RunEvent, goal.axle front|rear); results on
``kc/result`` and per step on ``kc/state``, relative to the node's namespace (``/vd`` by
default; see solver_node); per step the two wheels' frames on the global ``/tf``
(``base_link`` -> ``front_left_wheel`` ..., stamped like the states, with the
parameter ``frame_prefix`` outside ``/vd``), so RViz and Foxglove show the wheels move.
"""
from __future__ import annotations

from tf2_msgs.msg import TFMessage
from vd_data_server.ros.node_main import spin_node
from vd_data_server.ros.qos import TF
from vd_interfaces.msg import KcState
from vd_solvers.families import TF_TOPIC
from vd_solvers.nodes.solver import SolverNode
from vd_solvers.solve import run_function

FAMILY = 'kc'


class KCSolver(SolverNode):
    """The K&C solver node."""

    STATE_TYPE = KcState

    def __init__(self, **kwargs) -> None:
        super().__init__('kc_solver', FAMILY, run_function(FAMILY), **kwargs)
        # the wheels move on the rig: base_link -> <axle>_<side>_wheel per step
        self.publishers_by_topic[TF_TOPIC] = self.create_publisher(TFMessage, TF_TOPIC, TF)


def main(args=None) -> None:
    """Entry point of ``ros2 run vd_solvers kc_solver``."""
    spin_node(KCSolver, args)


if __name__ == '__main__':
    main()
