"""
``ros2 run vd_solvers vehicle_solver``: the full-vehicle dynamics solver.

Names relative to the node's namespace (``/vd`` by default). Action ``vehicle/run_event``
(vd_interfaces/RunEvent; events constant_radius_turn and step_steer, goal.fidelity
rigid|flexible passed to the K&C maps); results on ``vehicle/result``, one
``VehicleState`` per recorded step on ``vehicle/state`` (named fields, four
``VehicleWheel``s) with header stamps on the simulation-time axis (run start + simulated
time), and the body pose as ``nav_msgs/Odometry`` on ``vehicle/odom`` (frame ``odom``,
child ``base_link``, REP 105) and as TF on the global ``/tf`` (``tf2_msgs/TFMessage``),
stamped alike. Outside the default namespace the frames carry the parameter
``frame_prefix`` (default: the namespace, ``car2/odom`` -> ``car2/base_link``), so
several vehicles share one TF tree.
"""
from __future__ import annotations

from nav_msgs.msg import Odometry
from rcl_interfaces.msg import ParameterDescriptor

from tf2_msgs.msg import TFMessage
from vd_data_server.model import Configuration
from vd_data_server.names import frame_prefix
from vd_data_server.node_main import spin_node
from vd_data_server.qos import STATES
from vd_interfaces.msg import VehicleState
from vd_solvers.conversions import outcome_odometry, outcome_transforms, outcome_vehicle_states
from vd_solvers.families import ODOMETRY_TOPIC, TF_TOPIC
from vd_solvers.results import EventOutcome
from vd_solvers.solver_node import SolverNode
from vd_solvers.vehicle.events import run_vehicle_event

FAMILY = 'vehicle'


def _run(config: Configuration, goal, progress) -> EventOutcome:
    return run_vehicle_event(config, goal.event, list(goal.parameters), goal.fidelity or 'rigid',
                             progress)


class VehicleSolver(SolverNode):
    """The full-vehicle solver; the body pose also as odometry and TF."""

    STATE_TYPE = VehicleState

    def __init__(self, **kwargs) -> None:
        super().__init__('vehicle_solver', FAMILY, _run, **kwargs)
        self.frame_prefix = self.declare_parameter(
            'frame_prefix', frame_prefix(self.get_namespace()), ParameterDescriptor(
                description='prefix of the frames odom and base_link (several vehicles '
                'on one TF tree)', read_only=True)).value
        self.odom_pub = self.create_publisher(Odometry, ODOMETRY_TOPIC, STATES)
        # the moving frame for RViz and Foxglove (TF: odom -> base_link, REP 105)
        self.tf_pub = self.create_publisher(TFMessage, TF_TOPIC, STATES)

    def publish_outcome(self, outcome: EventOutcome, config: Configuration, changes: list) -> None:
        stamp = self.get_clock().now().to_msg()
        # odometry and TF first: a recorder stops once the result and its samples are in
        for msg in outcome_transforms(outcome, stamp):
            for t in msg.transforms:
                self._prefix(t)
            self.tf_pub.publish(msg)
        for msg in outcome_odometry(outcome, stamp):
            self.odom_pub.publish(self._prefix(msg))
        super().publish_outcome(outcome, config, changes, stamp=stamp)


    def _prefix(self, msg):
        """Give ``msg``'s frames this graph's prefix (none in the default namespace)."""
        if self.frame_prefix:
            msg.header.frame_id = self.frame_prefix + msg.header.frame_id
            msg.child_frame_id = self.frame_prefix + msg.child_frame_id
        return msg

    def state_messages(self, outcome: EventOutcome, stamp) -> list:
        states = outcome_vehicle_states(outcome, stamp)
        if self.frame_prefix:
            for state in states:
                state.header.frame_id = self.frame_prefix + state.header.frame_id
        return states


def main(args=None) -> None:
    """Entry point of ``ros2 run vd_solvers vehicle_solver``."""
    spin_node(VehicleSolver, args)


if __name__ == '__main__':
    main()
