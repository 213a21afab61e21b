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

from collections.abc import Callable
import dataclasses
import time
import warnings

from rcl_interfaces.msg import ParameterDescriptor
from rclpy.action import ActionServer, CancelResponse, GoalResponse
from rclpy.callback_groups import ReentrantCallbackGroup
from rclpy.node import Node

from vd_data_server.conversions import configuration_from_msg
from vd_data_server.errors import DataError
from vd_data_server.master import parse_set, with_overrides
from vd_data_server.model import Configuration
from vd_data_server.ros import names
from vd_data_server.ros.qos import CONFIGURATIONS, LATEST, RESULTS, STATES
from vd_data_server.study import modified_keys
from vd_interfaces.action import RunEvent
from vd_interfaces.msg import Configuration as ConfigurationMsg
from vd_interfaces.msg import DataStatus, EventResult, ModifiedKey, Provenance
from vd_interfaces.msg import GroupStatus as GroupStatusMsg
from vd_solvers import __version__
from vd_solvers.conversions import outcome_messages, outcome_to_msg, run_stamp
from vd_solvers.errors import SolverError
from vd_solvers.families import FAMILIES, check_request
from vd_solvers.results import EventOutcome

#: seconds a goal waits for its configuration to arrive on /vd/configuration
CONFIGURATION_WAIT = 5.0

#: (configuration, goal, progress(fraction, stage)) -> outcome
RunFn = Callable[[Configuration, RunEvent.Goal, Callable[[float, str], None]], EventOutcome]
#: least interval between two feedback messages, s
FEEDBACK_PERIOD = 0.1
#: how a goal's overrides are named in messages
OVERRIDES_SOURCE = 'overrides'


class Cancelled(Exception):
    """The client cancelled the goal while it was being solved."""


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
        label = f"configuration '{goal.configuration}', event '{goal.event}'"
        feedback = RunEvent.Feedback()
        # numpy / LAPACK warnings (overflow, a singular matrix) are not printed on their
        # own: they become part of the error they explain, or a note of the result.
        # (catch_warnings is process-wide; goals of one runner come one at a time.)
        caught: list[warnings.WarningMessage] = []
        try:
            config = self._wait_for_configuration(goal.configuration)
            if config is None:
                raise DataError(f"configuration '{goal.configuration}' is not published "
                                f"(known: {', '.join(sorted(self.configurations)) or 'none'})")
            base = config
            config = with_overrides(config, parse_set(goal.overrides, OVERRIDES_SOURCE),
                                    OVERRIDES_SOURCE)
            last = [0.0]

            def progress(fraction: float, stage: str) -> None:
                if goal_handle.is_cancel_requested:
                    raise Cancelled
                now = time.monotonic()
                if now - last[0] >= FEEDBACK_PERIOD:
                    last[0] = now
                    feedback.progress, feedback.stage = float(fraction), stage
                    goal_handle.publish_feedback(feedback)

            progress(0.0, 'solving')
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter('always')
                outcome = self._run(config, goal, progress)
            if goal_handle.is_cancel_requested:
                raise Cancelled
        except Cancelled:
            goal_handle.canceled()
            result.success, result.message = False, f'{label}: cancelled'
            return result
        except (DataError, SolverError) as err:
            message = str(err) if goal.configuration in str(err) else f'{label}: {err}'
            message += _warnings_text(caught)
            self.get_logger().error(message)
            goal_handle.abort()
            result.success, result.message = False, message
            return result
        except Exception as err:  # noqa: BLE001 - a solver bug must not kill the node
            message = (f'{label}: internal solver error {type(err).__name__}: {err}'
                       f'{_warnings_text(caught)}')
            self.get_logger().error(message)
            goal_handle.abort()
            result.success, result.message = False, message
            return result
        if caught:
            outcome = dataclasses.replace(outcome, notes=(
                *outcome.notes, 'numerical warnings during the run: ' +
                '; '.join(_warning_messages(caught))))
        self.publish_outcome(outcome, config, set_changes(base, config))
        feedback.progress, feedback.stage = 1.0, 'done'
        goal_handle.publish_feedback(feedback)
        goal_handle.succeed()
        result.success = True
        result.message = f'{label}: {outcome.n_steps} steps'
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
        provenance = Provenance(stamp=stamp, configuration=config.name,
                                master_file=config.master_file, data_hash=config.data_hash,
                                model=outcome.model, fidelity=outcome.fidelity,
                                event=outcome.event, software_version=__version__)
        if self.status is not None:
            changed = {g.group: g for g in changes}
            provenance.groups = [changed.get(s.group, s) for s in self.status.status
                                 if s.configuration == config.name]
        self.provenance_pub.publish(provenance)
        for topic, msg in outcome_messages(outcome, stamp, self.frame_prefix):
            self.publishers_by_topic[topic].publish(msg)

    def run_stamp(self, outcome: EventOutcome):
        """Claim a run's stamp: now, or after the previous run's time axis if that is later."""
        return run_stamp(outcome, self.get_clock().now().nanoseconds)


def _warning_messages(caught) -> list[str]:
    """Return the caught warnings' messages, each once, at most five."""
    return list(dict.fromkeys(str(w.message) for w in caught or ()))[:5]


def _warnings_text(caught) -> str:
    """`` (numerical warnings: overflow encountered in exp; ...)``, or ""."""
    texts = _warning_messages(caught)
    return f" (numerical warnings: {'; '.join(texts)})" if texts else ''


def set_changes(base: Configuration, config: Configuration) -> list:
    """GroupStatus messages for the groups a run's ``--set`` overrides changed."""
    out = []
    for name, group in config.groups.items():
        keys = modified_keys(base.groups[name].values, group.values)
        if keys:
            out.append(GroupStatusMsg(configuration=config.name, group=name,
                                      variant=group.variant, state=GroupStatusMsg.MODIFIED,
                                      consistency=GroupStatusMsg.DIFFERS,
                                      modified_keys=[ModifiedKey(key=k.key,
                                                                 data_value=k.data_value,
                                                                 master_value=k.master_value,
                                                                 unit=k.unit) for k in keys]))
    return out
