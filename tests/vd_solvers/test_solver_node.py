# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""A solver node answers a failing goal with an error and keeps serving."""
from __future__ import annotations

import pytest

from vdtest import HANG_GUARD, spin_until, wait_for

pytestmark = pytest.mark.ros


def _goal(client_node, solver, server, **fields):
    from rclpy.action import ActionClient

    from vd_interfaces.action import RunEvent

    client = ActionClient(client_node, RunEvent, '/vd/steady_state/run_event')
    nodes = [server, solver, client_node]
    assert wait_for(nodes, client.server_is_ready)
    send = client.send_goal_async(RunEvent.Goal(**fields))
    # one thread: the acceptance reaches the client only after the goal has run (the
    # first analytical goal computes its K&C inputs, several seconds on a busy machine)
    assert wait_for(nodes, send.done)
    result = send.result().get_result_async()
    assert wait_for(nodes, result.done)
    return result.result().result


def test_solver_error_names_configuration_and_event_and_node_keeps_serving(ros_domain,
                                                                          sedan_master):
    from rclpy.node import Node
    from rclpy.parameter import Parameter

    from vd_data_server.nodes.data_server import DataServer
    from vd_solvers.nodes.analytical import AnalyticalSolver

    server = DataServer(parameter_overrides=[Parameter('master_file', value=str(sedan_master)),
                                             Parameter('watch_period', value=0.0)])
    solver = AnalyticalSolver()
    client_node = Node('goal_client')
    try:
        assert wait_for([server, solver], lambda: len(solver.configurations) == 3)
        bad = _goal(client_node, solver, server, event='handling_diagram',
                    configuration='baseline', model='two_track',
                    overrides=['mass.sprung_cog.z=20000 mm'])
        assert not bad.success
        # a 20 m centre of gravity is refused at the boundary (plausibility bound)
        assert bad.message == ("configuration 'baseline', event 'handling_diagram': overrides: "
                               "mass.sprung_cog.z: '20000 mm' is implausible: every coordinate "
                               "must be within 8 m of the origin (plausibility bound)")
        good = _goal(client_node, solver, server, event='handling_diagram',
                     configuration='baseline', model='two_track', parameters=['steps=5'])
        assert good.success, good.message
        assert len(next(c for c in good.result.channels
                        if c.name == 'lateral_acceleration').values) == 5
    finally:
        for node in (client_node, solver, server):
            node.destroy_node()


@pytest.mark.parametrize(('fields', 'reason'), [
    ({'event': 'lateral_force', 'model': 'kc'},
     "K&C events need axle front or rear (found '')"),
    ({'event': 'lateral_force', 'model': 'kc', 'axle': 'front', 'fidelity': 'stiff'},
     "unknown fidelity 'stiff' (rigid, flexible)"),
    ({'event': 'handling_diagram', 'model': 'kc', 'axle': 'front'},
     "event 'handling_diagram' does not run on model 'kc' (its events: parallel_wheel_travel"),
    ({'event': 'lateral_force', 'model': 'two_track', 'axle': 'front'},
     "model 'two_track' is not served here (models: kc)"),
    ({'event': 'lateral_force', 'model': 'kc', 'axle': 'front', 'parameters': ['steps=x']},
     'event lateral_force: steps:'),
    ({'event': 'lateral_force', 'model': 'kc', 'axle': 'front', 'overrides': ['camber']},
     "overrides: expected GROUP.KEY=VALUE, found 'camber'"),
    ({'event': 'lateral_force', 'model': 'kc', 'axle': 'front', 'configuration': 'nope'},
     "configuration 'nope' is not published (known: baseline, sport, stiff_rear)"),
])
def test_invalid_goals_are_rejected_with_the_reason_logged(ros_domain, sedan_master, capfd,
                                                          fields, reason):
    from rclpy.action import ActionClient
    from rclpy.node import Node
    from rclpy.parameter import Parameter

    from vd_data_server.nodes.data_server import DataServer
    from vd_interfaces.action import RunEvent
    from vd_solvers.nodes.kc import KCSolver

    server = DataServer(parameter_overrides=[Parameter('master_file', value=str(sedan_master)),
                                             Parameter('watch_period', value=0.0)])
    solver = KCSolver()
    client_node = Node('reject_client')
    nodes = [server, solver, client_node]
    try:
        assert wait_for(nodes, lambda: solver.status is not None and
                          len(solver.configurations) == 3)
        client = ActionClient(client_node, RunEvent, '/vd/kc/run_event')
        assert wait_for(nodes, client.server_is_ready)
        send = client.send_goal_async(RunEvent.Goal(**{'configuration': 'baseline', **fields}))
        assert wait_for(nodes, send.done)
        assert not send.result().accepted
        err = capfd.readouterr().err
        label = f"configuration '{fields.get('configuration', 'baseline')}', event " \
                f"'{fields['event']}'"
        assert f'goal rejected: {label}: {reason}' in err
    finally:
        for node in reversed(nodes):
            node.destroy_node()


def test_kc_goal_reports_progress_and_can_be_cancelled(ros_domain, sedan_master, tmp_path):
    """
    Run the real kc_solver process (multi-threaded, as ros2 run starts it).

    Feedback rises to 1 during a run, and a cancel request stops a long sweep between two
    steps.
    """
    import os
    import signal
    import subprocess

    from action_msgs.msg import GoalStatus
    from ament_index_python.packages import get_package_prefix
    from rclpy.action import ActionClient
    from rclpy.node import Node
    from rclpy.parameter import Parameter

    from vd_data_server.nodes.data_server import DataServer
    from vd_interfaces.action import RunEvent

    server = DataServer(parameter_overrides=[Parameter('master_file', value=str(sedan_master)),
                                             Parameter('watch_period', value=0.0)])
    exe = os.path.join(get_package_prefix('vd_solvers'), 'lib', 'vd_solvers', 'kc_solver')
    log = tmp_path / 'kc_solver.log'
    solver = subprocess.Popen([exe], env=dict(os.environ, ROS_DOMAIN_ID=str(ros_domain)),
                              stdout=log.open('w'), stderr=subprocess.STDOUT)
    client_node = Node('cancel_client')
    nodes = [server, client_node]
    try:
        client = ActionClient(client_node, RunEvent, '/vd/kc/run_event')
        assert wait_for(nodes, client.server_is_ready)
        spin_until(nodes, lambda: False, timeout=1.0)  # discovery of the response readers

        def accepted(goal):
            """Send ``goal``; return its answered request and the feedback of that goal."""
            # as vd_events.orchestration.runner.send_goal does: Fast DDS drops a goal response sent
            # before the server has discovered the client's reader, so ask again (a
            # list per request: an unanswered goal may still run and report)
            for _ in range(3):
                seen: list[float] = []
                send = client.send_goal_async(
                    goal, feedback_callback=lambda fb, seen=seen: seen.append(
                        fb.feedback.progress))
                if spin_until(nodes, send.done, timeout=10):
                    return send, seen
            raise AssertionError(f'no goal response; solver log:\n{log.read_text()}')

        send, seen = accepted(
            RunEvent.Goal(event='parallel_wheel_travel', configuration='baseline', model='kc',
                          axle='front', parameters=['steps=401']))
        done = send.result().get_result_async()
        assert wait_for(nodes, done.done)
        assert done.result().result.success
        # feedback is a topic, the result a service: the last feedback may come after it
        assert wait_for(nodes, lambda: seen and seen[-1] == 1.0)
        assert seen == sorted(seen) and len(seen) >= 3
        send, _ = accepted(
            RunEvent.Goal(event='parallel_wheel_travel', configuration='baseline', model='kc',
                          axle='front', parameters=['steps=2001']))
        handle = send.result()
        spin_until(nodes, lambda: False, timeout=0.3)
        cancel = handle.cancel_goal_async()
        assert wait_for(nodes, cancel.done)
        result = handle.get_result_async()
        assert wait_for(nodes, result.done)
        assert result.result().status == GoalStatus.STATUS_CANCELED
        assert result.result().result.message == ("configuration 'baseline', event "
                                                  "'parallel_wheel_travel': cancelled")
    finally:
        solver.send_signal(signal.SIGINT)
        solver.wait(timeout=HANG_GUARD)
        for node in reversed(nodes):
            node.destroy_node()


def test_numerical_warnings_are_part_of_the_error_they_explain(ros_domain, sedan_master,
                                                              monkeypatch, capfd):
    import numpy as np
    from rclpy.node import Node
    from rclpy.parameter import Parameter

    from vd_data_server.nodes.data_server import DataServer
    import vd_solvers.analytical.events as analytical_events
    from vd_solvers.errors import SolverError
    from vd_solvers.nodes.analytical import AnalyticalSolver

    real = analytical_events.run_event

    def overflowing(config, event, model, parameters):
        np.exp(np.array([1000.0]))  # RuntimeWarning: overflow encountered in exp
        if 'steps=3' in parameters:
            raise SolverError('the sweep diverged')
        return real(config, event, model, parameters)

    monkeypatch.setattr(analytical_events, 'run_event', overflowing)
    server = DataServer(parameter_overrides=[Parameter('master_file', value=str(sedan_master)),
                                             Parameter('watch_period', value=0.0)])
    solver = AnalyticalSolver()
    client_node = Node('warning_client')
    try:
        assert wait_for([server, solver], lambda: len(solver.configurations) == 3)
        capfd.readouterr()
        bad = _goal(client_node, solver, server, event='handling_diagram',
                    configuration='baseline', model='two_track', parameters=['steps=3'])
        assert not bad.success
        assert bad.message == ("configuration 'baseline', event 'handling_diagram': the sweep "
                               "diverged (numerical warnings: overflow encountered in exp)")
        good = _goal(client_node, solver, server, event='handling_diagram',
                     configuration='baseline', model='two_track', parameters=['steps=5'])
        assert good.success, good.message
        assert good.result.notes[-1] == ('numerical warnings during the run: overflow '
                                         'encountered in exp')
        assert 'RuntimeWarning' not in capfd.readouterr().err  # not printed on its own
    finally:
        for node in (client_node, solver, server):
            node.destroy_node()
