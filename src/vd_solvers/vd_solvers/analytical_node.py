"""``ros2 run vd_solvers analytical_solver``: bicycle and two-track models.

Action ``/vd/steady_state/run_event`` (vd_interfaces/RunEvent); results on
``/vd/steady_state/result`` and ``/vd/steady_state/state`` (see solver_node).
"""
from __future__ import annotations

from vd_data_server.model import Configuration
from vd_solvers.analytical.events import run_event
from vd_solvers.results import EventOutcome
from vd_solvers.solver_node import SolverNode, spin_node

FAMILY = "steady_state"


def _run(config: Configuration, goal) -> EventOutcome:
    return run_event(config, goal.event, goal.model or "two_track", list(goal.parameters))


class AnalyticalSolver(SolverNode):
    def __init__(self, **kwargs) -> None:
        super().__init__("analytical_solver", FAMILY, _run, **kwargs)


def main(args=None) -> None:
    spin_node(AnalyticalSolver, args)


if __name__ == "__main__":
    main()
