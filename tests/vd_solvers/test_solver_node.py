"""A solver node answers a failing goal with an error and keeps serving."""
from __future__ import annotations

import pytest

from vdtest import spin_until

pytestmark = pytest.mark.ros


def _goal(client_node, solver, server, **fields):
    from rclpy.action import ActionClient
    from vd_interfaces.action import RunEvent

    client = ActionClient(client_node, RunEvent, "/vd/steady_state/run_event")
    nodes = [server, solver, client_node]
    assert spin_until(nodes, client.server_is_ready)
    send = client.send_goal_async(RunEvent.Goal(**fields))
    assert spin_until(nodes, send.done)
    result = send.result().get_result_async()
    assert spin_until(nodes, result.done)
    return result.result().result


def test_solver_error_names_configuration_and_event_and_node_keeps_serving(ros_domain,
                                                                          sedan_master):
    from rclpy.node import Node
    from rclpy.parameter import Parameter

    from vd_data_server.data_server_node import DataServer
    from vd_solvers.analytical_node import AnalyticalSolver

    server = DataServer(parameter_overrides=[Parameter("master_file", value=str(sedan_master)),
                                             Parameter("watch_period", value=0.0)])
    solver = AnalyticalSolver()
    client_node = Node("goal_client")
    try:
        assert spin_until([server, solver], lambda: len(solver.configurations) == 3)
        bad = _goal(client_node, solver, server, event="handling_diagram",
                    configuration="baseline", model="two_track",
                    overrides=["targets.roll_stiffness_front=1 N*m/rad",
                               "targets.roll_stiffness_rear=1 N*m/rad"])
        assert not bad.success
        assert bad.message.startswith(
            "configuration 'baseline', event 'handling_diagram', model 'two_track': ")
        assert "roll instability" in bad.message
        good = _goal(client_node, solver, server, event="handling_diagram",
                     configuration="baseline", model="two_track", parameters=["steps=5"])
        assert good.success, good.message
        assert len(next(c for c in good.result.channels
                        if c.name == "lateral_acceleration").values) == 5
    finally:
        for node in (client_node, solver, server):
            node.destroy_node()
