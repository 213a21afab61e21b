# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
``ros2 run vd_solvers analytical_solver``: bicycle and two-track models.

Action ``steady_state/run_event`` (vd_interfaces/RunEvent); results on
``steady_state/result`` and ``steady_state/state``, relative to the node's namespace
(``/vd`` by default; see solver_node).

Cooperation with the K&C rung: the roll properties and the compliance of
both axles come from K&C results of the same configuration and data hash,
computed on demand in this process and cached by data hash
(``vd_solvers.kc.cache``), so a result does not depend on which K&C runs the
graph has seen before (``analytical/kc_link.py``).
"""
from __future__ import annotations

from vd_data_server.ros.node_main import spin_node
from vd_interfaces.msg import AnalyticalState
from vd_solvers.nodes.solver import SolverNode
from vd_solvers.solve import run_function

FAMILY = 'steady_state'


class AnalyticalSolver(SolverNode):
    """The analytical (bicycle, two-track) solver node."""

    STATE_TYPE = AnalyticalState

    def __init__(self, **kwargs) -> None:
        super().__init__('analytical_solver', FAMILY, run_function(FAMILY), **kwargs)


def main(args=None) -> None:
    """Entry point of ``ros2 run vd_solvers analytical_solver``."""
    spin_node(AnalyticalSolver, args)


if __name__ == '__main__':
    main()
