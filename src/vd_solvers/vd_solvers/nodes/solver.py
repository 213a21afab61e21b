# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The shell every solver node shares: configurations in, RunEvent action, results out.

Names are relative to the node's namespace (``/vd`` unless remapped with ``__ns:=``).
A solver node subscribes to the latched ``configuration`` and ``data_status``
topics, serves ``<family>/run_event`` (vd_interfaces/RunEvent, with progress
feedback, cancellable between stages; see ``families`` for other instances), and
publishes each result on ``<family>/result`` (EventResult), one typed state per step
on ``<family>/state`` (``STATE_TYPE``: KcState, AnalyticalState, VehicleState) and the
run's provenance on ``provenance``, stamped on the process's time axis
(``conversions.TIME_AXIS``). A goal that cannot
run (unknown event or model, bad axle, fidelity, parameter or override, a
configuration the data server does not publish) is rejected in the goal callback and
the reason logged; a failure during the run answers the goal with an error naming
the configuration and event. The node keeps serving.
"""
from __future__ import annotations

import time

from rcl_interfaces.msg import ParameterDescriptor
from rclpy.action import ActionServer, CancelResponse, GoalResponse
from rclpy.callback_groups import ReentrantCallbackGroup
from rclpy.node import Node

from vd_data_server.conversions import configuration_from_msg
from vd_data_server.errors import DataError
from vd_data_server.master import parse_set
from vd_data_server.model import Configuration
from vd_data_server.ros import names
from vd_data_server.ros.qos import CONFIGURATIONS, LATEST, RESULTS, STATES
from vd_interfaces.action import RunEvent
from vd_interfaces.msg import Configuration as ConfigurationMsg
from vd_interfaces.msg import DataStatus, EventResult, Provenance
from vd_solvers.conversions import (
    outcome_messages,
    outcome_to_msg,
    provenance_to_msg,
    run_stamp,
)
from vd_solvers.errors import SolverError
from vd_solvers.families import FAMILIES, check_request
from vd_solvers.results import EventOutcome
from vd_solvers.solve import (
    OVERRIDES_SOURCE,
    Cancelled,
    GoalFailed,
    RunFn,
    goal_label,
    provenance_groups,
    solve_goal,
    throttled,
)

#: seconds a goal waits for its configuration to arrive on /vd/configuration
CONFIGURATION_WAIT = 5.0


class SolverNode(Node):
    """A solver: the family's RunEvent action over a run function of the ROS-free core."""

    #: message type of the per-step states on <family>/state (set by each solver)
    STATE_TYPE: type

    def __init__(self, name: str, family: str, run: RunFn, **kwargs) -> None:
        spec = FAMILIES[family]
        kwargs.setdefault('namespace', names.DEFAULT_NAMESPACE)
        # ``node_name``: another instance of the family (it serves its own action)
        super().__init__(kwargs.pop('node_name', name), **kwargs)
        self.family = family
        self._run = run
        self.frame_prefix = self.declare_parameter(
            'frame_prefix', names.frame_prefix(self.get_namespace()), ParameterDescriptor(
                description='prefix of the frames it publishes (odom, base_link, the wheels: '
                'several vehicles on one TF tree)', read_only=True)).value
        self.configurations: dict[str, Configuration] = {}
        self.status: DataStatus | None = None
        group = ReentrantCallbackGroup()
        self.create_subscription(ConfigurationMsg, names.CONFIGURATION, self._on_configuration,
                                 CONFIGURATIONS, callback_group=group)
        self.create_subscription(DataStatus, names.DATA_STATUS, self._on_status, LATEST,
                                 callback_group=group)
        self.result_pub = self.create_publisher(EventResult, spec.result_topic, RESULTS)
        self.sample_pub = self.create_publisher(self.STATE_TYPE, spec.state_topic, STATES)
        self.provenance_pub = self.create_publisher(Provenance, names.PROVENANCE, RESULTS)
        #: topic -> publisher of a run's messages (conversions.outcome_messages); the K&C
        #: and vehicle solvers add TF and odometry
        self.publishers_by_topic = {spec.result_topic: self.result_pub,
                                    spec.state_topic: self.sample_pub}
        self.action = ActionServer(self, RunEvent, spec.action(self.get_name()), self._execute,
                                   goal_callback=self._check_goal,
                                   cancel_callback=lambda _: CancelResponse.ACCEPT,
                                   callback_group=group)

    def _check_goal(self, goal) -> GoalResponse:
        """Reject a goal that cannot run, and log why (the action protocol has no reason)."""
        try:
            check_request(self.family, goal.event, goal.model or FAMILIES[self.family].
                          default_model, goal.fidelity, goal.axle, goal.parameters)
            parse_set(goal.overrides, source=OVERRIDES_SOURCE)
            published = set(self.configurations) | set(
                self.status.configurations if self.status is not None else ())
            if self.status is not None and goal.configuration not in published:
                raise DataError(f"configuration '{goal.configuration}' is not published "
                                f"(known: {', '.join(sorted(published)) or 'none'})")
        except (DataError, SolverError) as err:
            self.get_logger().error(f"goal rejected: configuration '{goal.configuration}', "
                                    f"event '{goal.event}': {err}")
            return GoalResponse.REJECT
        return GoalResponse.ACCEPT

    def _wait_for_configuration(self, name: str) -> Configuration | None:
        """
        Wait a little for a configuration that has not arrived yet.

        A solver started together with the data server may get a goal before the
        latched configurations have arrived.
        """
        deadline = time.monotonic() + CONFIGURATION_WAIT
        while name not in self.configurations and time.monotonic() < deadline:
            time.sleep(0.05)
        return self.configurations.get(name)

    def _on_configuration(self, msg: ConfigurationMsg) -> None:
        self.configurations[msg.name] = configuration_from_msg(msg)

    def _on_status(self, msg: DataStatus) -> None:
        self.status = msg
        if not msg.errors and msg.configurations:
            # a reload that removed a configuration: it is no longer served
            for name in set(self.configurations) - set(msg.configurations):
                del self.configurations[name]

    def _execute(self, goal_handle):
        goal = goal_handle.request
        result = RunEvent.Result()
        feedback = RunEvent.Feedback()

        def publish(fraction: float, stage: str) -> None:
            feedback.progress, feedback.stage = float(fraction), stage
            goal_handle.publish_feedback(feedback)

        publish_throttled = throttled(publish)

        def progress(fraction: float, stage: str) -> None:
            if goal_handle.is_cancel_requested:
                raise Cancelled
            publish_throttled(fraction, stage)

        try:
            base = self._wait_for_configuration(goal.configuration)
            if base is None:
                raise GoalFailed(f"configuration '{goal.configuration}' is not published "
                                 f"(known: {', '.join(sorted(self.configurations)) or 'none'})")
            progress(0.0, 'solving')
            solved = solve_goal(self._run, base, goal, progress)
            if goal_handle.is_cancel_requested:
                raise Cancelled
        except Cancelled:
            goal_handle.canceled()
            result.success, result.message = False, f'{goal_label(goal)}: cancelled'
            return result
        except GoalFailed as err:
            self.get_logger().error(str(err))
            goal_handle.abort()
            result.success, result.message = False, str(err)
            return result
        outcome = solved.outcome
        self.publish_outcome(outcome, solved.config, solved.changes)
        publish(1.0, 'done')
        goal_handle.succeed()
        result.success = True
        result.message = f'{goal_label(goal)}: {outcome.n_steps} steps'
        result.result = outcome_to_msg(outcome, self.get_clock().now().to_msg())
        return result

    def publish_outcome(self, outcome: EventOutcome, config: Configuration,
                        changes: list, stamp=None) -> None:
        """
        Publish provenance (with this goal's ``--set`` changes), then the run's messages.

        Provenance is stamped ``stamp`` (default: :meth:`run_stamp`); the run's TF,
        odometry and states (conversions.outcome_messages) ``stamp`` + simulated time
        (time-domain events) or + step * PSEUDO_STEP (quasi-static ones), the result with
        the last state's stamp.
        """
        stamp = stamp if stamp is not None else self.run_stamp(outcome)
        groups = provenance_groups(self.status.status, config.name, changes) \
            if self.status is not None else []
        self.provenance_pub.publish(provenance_to_msg(outcome, stamp, config.master_file,
                                                      groups))
        for topic, msg in outcome_messages(outcome, stamp, self.frame_prefix):
            self.publishers_by_topic[topic].publish(msg)

    def run_stamp(self, outcome: EventOutcome):
        """Claim a run's stamp: now, or after the previous run's time axis if that is later."""
        return run_stamp(outcome, self.get_clock().now().nanoseconds)
