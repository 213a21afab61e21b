# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
``ros2 run vd_events event_runner``: runs a study plan against a running graph.

Parameter ``plan``: a study plan (see study_plan.py). The node sends each run as a
RunEvent goal to the solver that serves its model (``steady_state/run_event``,
``kc/run_event``, ``vehicle/run_event``, relative to its namespace: ``/vd`` by default,
``__ns:=/car2`` drives the graph in ``/car2``), logs each result or error, and exits
when the plan is done. Recording is the recorder node's job (start it first).
"""
from __future__ import annotations

from pathlib import Path
import sys

from rcl_interfaces.msg import ParameterDescriptor
from rclpy.node import Node

from vd_data_server.errors import DataError
from vd_data_server.ros import names
from vd_data_server.ros.node_main import run_node
from vd_data_server.study import load_study
from vd_events.errors import RunError
from vd_events.orchestration.runner import EventClient, send_goal, validate
from vd_events.studies.plan import expand, load_plan

#: exit code when Ctrl-C or SIGTERM stopped the plan (as a shell reports SIGINT)
INTERRUPTED = 130


class EventRunner(Node):
    """The event runner: the runner's action clients on a node with a ``plan``."""

    def __init__(self, **kwargs) -> None:
        kwargs.setdefault('namespace', names.DEFAULT_NAMESPACE)
        super().__init__('event_runner', **kwargs)
        self.declare_parameter('plan', '', ParameterDescriptor(
            description='study plan YAML to run', read_only=True))
        self.client = EventClient(self)


def run_plan(executor, node: EventRunner) -> int:
    """Run the node's plan; return the exit code (0 all runs succeeded, 1 else, 2 no plan)."""
    plan_path = node.get_parameter('plan').value
    if not plan_path:
        node.get_logger().error("parameter 'plan' is required")
        return 2
    failures = 0
    try:
        plan = load_plan(Path(plan_path))
        study = load_study(plan.master)
        requests = [type(r)(**{**r.__dict__, 'bag': None})
                    for r in expand(plan, study, Path('.'))]
        requests = [validate(study, request) for request in requests]
    except (DataError, RunError) as err:
        print(f'event_runner: {err}', file=sys.stderr)
        return 1
    for request in requests:
        try:
            ok, message, _ = send_goal(executor, node.client, request, lambda p, s: None)
        except RunError as err:
            ok, message = False, str(err)
        if ok:
            node.get_logger().info(message)
        else:
            failures += 1
            node.get_logger().error(message)
    return 1 if failures else 0


def main(args=None) -> None:
    """Entry point of ``ros2 run vd_events event_runner``."""
    code = run_node(EventRunner, run_plan, args)
    raise SystemExit(INTERRUPTED if code is None else code)


if __name__ == '__main__':
    main()
