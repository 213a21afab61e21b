"""
``ros2 run vd_solvers vehicle_solver``: the full-vehicle dynamics solver.

Action ``/vd/vehicle/run_event`` (vd_interfaces/RunEvent; events constant_radius_turn and
step_steer, goal.fidelity rigid|flexible passed to the K&C maps); results on
``/vd/vehicle/result``, one ``VehicleState`` per recorded step on ``/vd/vehicle/state``
(named fields, four ``VehicleWheel``s) with header stamps on the simulation-time axis
(run start + simulated time), and the body
pose as ``nav_msgs/Odometry`` on ``/vd/vehicle/odom`` (frame ``odom``, child
``base_link``, REP 105) and as TF on ``/tf`` (``tf2_msgs/TFMessage``), stamped alike.
"""
from __future__ import annotations

from nav_msgs.msg import Odometry

from tf2_msgs.msg import TFMessage
from vd_data_server.model import Configuration
from vd_data_server.node_main import spin_node
from vd_interfaces.msg import VehicleState
from vd_solvers.conversions import outcome_odometry, outcome_transforms
from vd_solvers.results import EventOutcome
from vd_solvers.solver_node import SAMPLES, SolverNode
from vd_solvers.vehicle.events import run_vehicle_event

FAMILY = 'vehicle'


def _run(config: Configuration, goal, progress) -> EventOutcome:
    return run_vehicle_event(config, goal.event, list(goal.parameters), goal.fidelity or 'rigid',
                             progress)


class VehicleSolver(SolverNode):
    STATE_TYPE = VehicleState

    def __init__(self, **kwargs) -> None:
        super().__init__('vehicle_solver', FAMILY, _run, **kwargs)
        self.odom_pub = self.create_publisher(Odometry, f'/vd/{FAMILY}/odom', SAMPLES)
        # the moving frame for RViz and Foxglove (TF: odom -> base_link, REP 105)
        self.tf_pub = self.create_publisher(TFMessage, '/tf', SAMPLES)

    def publish_outcome(self, outcome: EventOutcome, config: Configuration, changes: list) -> None:
        stamp = self.run_stamp(outcome)
        # odometry and TF first: a recorder stops once the result and its samples are in
        for msg in outcome_transforms(outcome, stamp):
            self.tf_pub.publish(msg)
        for msg in outcome_odometry(outcome, stamp):
            self.odom_pub.publish(msg)
        super().publish_outcome(outcome, config, changes, stamp=stamp)


def main(args=None) -> None:
    spin_node(VehicleSolver, args)


if __name__ == '__main__':
    main()
