"""``ros2 run vd_solvers analytical_solver``: bicycle and two-track models.

Action ``/vd/steady_state/run_event`` (vd_interfaces/RunEvent); results on
``/vd/steady_state/result`` and ``/vd/steady_state/state`` (see solver_node).

Cooperation with the K&C rung: the node listens to ``/vd/kc/result``. When the
K&C solver has published, for the same configuration and data hash, the
opposite-wheel-travel (roll stiffness) and parallel-wheel-travel (roll-centre
height) results of both axles, the two-track model uses them instead of the
design targets, and says so in the parameter sources.
"""
from __future__ import annotations

import math

from vd_interfaces.msg import EventResult

from vd_data_server.model import Configuration
from vd_solvers.analytical.events import run_event
from vd_solvers.analytical.from_config import AxleSuspension
from vd_solvers.results import EventOutcome
from vd_data_server.node_main import spin_node
from vd_solvers.solver_node import RESULTS, SolverNode

FAMILY = "steady_state"
DEG = 180.0 / math.pi


class KCRollCache:
    """Roll stiffness and roll-centre height per (configuration, data hash, axle)."""

    def __init__(self) -> None:
        self.values: dict[tuple[str, str, str], dict[str, float]] = {}

    def add(self, msg: EventResult) -> None:
        metrics = {m.name: (m.value, m.unit) for m in msg.metrics}
        entry = self.values.setdefault((msg.configuration, msg.data_hash, msg.axle), {})
        if msg.event == "opposite_wheel_travel" and "roll_stiffness" in metrics:
            value, unit = metrics["roll_stiffness"]
            entry["roll_stiffness"] = value * DEG if unit == "N*m/deg" else value
        if msg.event == "parallel_wheel_travel" and "roll_centre_height_kinematic" in metrics:
            entry["roll_centre_height"] = metrics["roll_centre_height_kinematic"][0]

    def suspension(self, config: Configuration) -> dict[str, AxleSuspension] | None:
        out = {}
        for axle in ("front", "rear"):
            entry = self.values.get((config.name, config.data_hash, axle), {})
            if len(entry) < 2:
                return None
            out[axle] = AxleSuspension(entry["roll_stiffness"], entry["roll_centre_height"],
                                       f"K&C {axle} axle (opposite and parallel wheel travel, "
                                       f"data hash {config.data_hash})")
        return out


class AnalyticalSolver(SolverNode):
    def __init__(self, **kwargs) -> None:
        self.kc = KCRollCache()
        super().__init__("analytical_solver", FAMILY, self._solve, **kwargs)
        self.create_subscription(EventResult, "/vd/kc/result", self.kc.add, RESULTS)

    def _solve(self, config: Configuration, goal, progress) -> EventOutcome:
        return run_event(config, goal.event, goal.model or "two_track", list(goal.parameters),
                         suspension=self.kc.suspension(config))


def main(args=None) -> None:
    spin_node(AnalyticalSolver, args)


if __name__ == "__main__":
    main()
