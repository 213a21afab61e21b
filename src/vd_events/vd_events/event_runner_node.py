"""
``ros2 run vd_events event_runner``: runs a study plan against a running graph.

Parameter ``plan``: a study plan (see study_plan.py). The node sends each run
as a RunEvent goal to the solver that serves its model (``/vd/steady_state/
run_event``, ``/vd/kc/run_event``), logs each result or error, and exits when
the plan is done. Recording is the recorder node's job (start it first).
"""
from __future__ import annotations

from pathlib import Path
import sys

from rcl_interfaces.msg import ParameterDescriptor
import rclpy
from rclpy.executors import ExternalShutdownException, SingleThreadedExecutor
from rclpy.node import Node

from vd_data_server.errors import DataError
from vd_data_server.study import load_study

from .runner import RunError, _Client, _send, validate
from .study_plan import expand, load_plan


class EventRunner(Node):
    def __init__(self, **kwargs) -> None:
        super().__init__('event_runner', **kwargs)
        self.declare_parameter('plan', '', ParameterDescriptor(
            description='study plan YAML to run', read_only=True))
        self.client = _Client(self)


def main(args=None) -> None:
    rclpy.init(args=args)
    node = None
    failures = 0
    try:
        node = EventRunner()
        plan_path = node.get_parameter('plan').value
        if not plan_path:
            node.get_logger().error("parameter 'plan' is required")
            raise SystemExit(2)
        plan = load_plan(Path(plan_path))
        study = load_study(plan.master)
        requests = [r for r in expand(plan, study.configuration_names, Path('.'))]
        requests = [type(r)(**{**r.__dict__, 'bag': None}) for r in requests]
        requests = [validate(study, request) for request in requests]
        executor = SingleThreadedExecutor()
        executor.add_node(node)
        for request in requests:
            try:
                ok, message, result = _send(executor, node.client, request, lambda p, s: None)
            except RunError as err:
                ok, message = False, str(err)
            if ok:
                node.get_logger().info(message)
            else:
                failures += 1
                node.get_logger().error(message)
    except (DataError, RunError) as err:
        print(f'event_runner: {err}', file=sys.stderr)
        failures += 1
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    finally:
        if node is not None:
            node.destroy_node()
        rclpy.try_shutdown()
    raise SystemExit(1 if failures else 0)


if __name__ == '__main__':
    main()
