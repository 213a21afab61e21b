# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""Solver instance names: what the dispatcher counts as one instance of a family."""
from __future__ import annotations

import pytest

from vd_events.errors import RunError
from vd_events.orchestration.dispatch import (
    instance_names,
    parse_instance,
    parse_solvers,
    solver_command,
)


def test_instance_names_keep_the_default_first():
    assert instance_names('kc', 3) == ['kc_solver', 'kc_solver_2', 'kc_solver_3']
    assert instance_names('steady_state', 1) == ['analytical_solver']


def test_parse_instance():
    """Check the two action forms of vd_solvers.families.Family.action, in any namespace."""
    nodes = {'/vd/kc_solver', '/vd/kc_solver_2', '/car2/kc_solver_b', '/vd/data_server'}
    # the default instance serves the family's action
    assert parse_instance('/vd/kc/run_event', nodes) == ('/vd/kc_solver', 'kc')
    # other instances serve <family>/<node>/run_event in their namespace
    assert parse_instance('/vd/kc/kc_solver_2/run_event', nodes) == ('/vd/kc_solver_2', 'kc')
    assert parse_instance('/car2/kc/kc_solver_b/run_event', nodes) == ('/car2/kc_solver_b', 'kc')
    # a node not in the graph (gone), an unknown family, another action
    assert parse_instance('/car2/kc/run_event', nodes) is None
    assert parse_instance('/vd/kc/kc_solver_9/run_event', nodes) is None
    assert parse_instance('/vd/tyre/kc_solver/run_event', nodes) is None
    assert parse_instance('/vd/kc/kc_solver/other', nodes) is None


def test_solver_command_renames_all_but_the_default():
    """Check that only the extra instances get a node name of their own."""
    assert not any(a.startswith('__node:=') for a in solver_command('kc', 'kc_solver'))
    command = solver_command('kc', 'kc_solver_2')
    assert command[command.index('__node:=kc_solver_2') - 1] == '-r'
    assert command[command.index('__ns:=/vd') - 1] == '-r'


def test_parse_solvers():
    assert parse_solvers('kc=2, analytical=1') == {'kc': 2, 'steady_state': 1}
    assert parse_solvers('') == {}
    with pytest.raises(RunError, match=r"--solvers: expected FAMILY=N with FAMILY one of kc, "
                       r"analytical, vehicle, found 'tires=2'"):
        parse_solvers('tires=2')


def test_first_goals_wait_for_the_expected_instances():
    """Start a family's runs at ``expect`` ready instances, or EXPECT_WAIT s after the first."""
    from vd_events.orchestration.dispatch import Dispatcher, Instance

    lines: list[str] = []
    dispatcher = Dispatcher(node=None, executor=None, expect={'kc': 2}, expect_wait=30.0,
                            log=lines.append)
    one = Instance('/vd/kc/run_event', '/vd/kc_solver', 'kc', client=None, ready_since=100.0)
    two = Instance('/vd/kc/kc_solver_2/run_event', '/vd/kc_solver_2', 'kc', client=None,
                   ready_since=105.0)
    assert not dispatcher._complete('kc', [], 200.0)
    assert not dispatcher._complete('kc', [one], 129.9)
    assert dispatcher._complete('kc', [one, two], 105.0)
    assert not lines
    # the second never came: the runs start on the first after the wait, and the log says so
    assert dispatcher._complete('kc', [one], 130.0)
    assert lines == ['1 of the 2 expected kc solver instances found after 30 s; the runs start '
                     'on those (a later one joins once it is discovered)']
    # a family not in expect waits for one instance only
    assert dispatcher._complete('vehicle', [Instance('/vd/vehicle/run_event', '/vd/vehicle_solver',
                                                     'vehicle', None, ready_since=1.0)], 1.0)


class _Future:
    def __init__(self, value=None, done=False):
        self.value, self._done = value, done

    def done(self):
        return self._done

    def result(self):
        return self.value


class _Client:
    """An action client whose first ``lost`` goal requests are never answered."""

    def __init__(self, lost: int, clock=None):
        import time

        self.lost, self.sent = lost, 0
        self.clock = clock or time.monotonic
        self.times: list[float] = []

    def send_goal_async(self, goal, feedback_callback=None):
        import time
        from types import SimpleNamespace

        from action_msgs.msg import GoalStatus

        self.sent += 1
        self.times.append(time.monotonic())
        if self.sent <= self.lost:
            return _Future()
        answer = SimpleNamespace(status=GoalStatus.STATUS_ABORTED, result=SimpleNamespace(
            success=False, message='solver says no'))
        handle = SimpleNamespace(accepted=True,
                                 get_result_async=lambda: _Future(answer, done=True))
        return _Future(handle, done=True)


@pytest.mark.parametrize('lost', [0, 2, 5])
def test_an_unanswered_goal_request_is_sent_again(monkeypatch, lost):
    """
    A lost goal response costs a resend to the same instance, never the instance.

    However many requests go unanswered (a loaded machine), the instance that lives keeps
    the run; the resends come at doubling intervals.
    """
    from types import SimpleNamespace

    import vd_events.orchestration.dispatch as dispatch
    from vd_events.orchestration.runner import RunRequest

    # the dispatcher's clock: 1 ms per spin, so the schedule is exact whatever the load
    clock = SimpleNamespace(now=0.0)
    monkeypatch.setattr(dispatch.time, 'monotonic', lambda: clock.now)

    def spin_once(timeout_sec):
        clock.now += 0.001

    monkeypatch.setattr(dispatch, 'ACCEPT_TIMEOUT', 0.01)
    monkeypatch.setattr(dispatch, 'DISCOVERY_GRACE', 0.0)
    client = _Client(lost, lambda: clock.now)
    lines: list[str] = []
    dispatcher = dispatch.Dispatcher(node=None, executor=SimpleNamespace(spin_once=spin_once),
                                     log=lines.append)
    dispatcher.instances['/vd/kc/run_event'] = dispatch.Instance(
        '/vd/kc/run_event', '/vd/kc_solver', 'kc', client, ready_since=0.0)
    monkeypatch.setattr(dispatcher, 'discover', lambda: None)  # the graph does not change
    results: list = []
    request = RunRequest('parallel_wheel_travel', 'baseline', 'kc', axle='front')
    dispatcher.run([request], lambda *args: results.append(args))
    assert [(r[0], r[1], r[2]) for r in results] == [(request, None, 'solver says no')]
    assert client.sent == lost + 1
    gaps = [b - a for a, b in zip(client.times, client.times[1:])]
    # each resend waits twice as long as the one before: 10, 20, 40 ... ms (to a spin)
    assert all(0.01 * 2 ** k - 1e-9 <= gap <= 0.01 * 2 ** k + 0.002
               for k, gap in enumerate(gaps)), gaps
    assert not lines and not dispatcher.instances['/vd/kc/run_event'].dead


def test_a_silent_goal_has_its_result_asked_for_again(monkeypatch):
    """A result response lost on a loaded machine is asked for again, the instance kept."""
    from types import SimpleNamespace

    from action_msgs.msg import GoalStatus

    import vd_events.orchestration.dispatch as dispatch
    from vd_events.orchestration.runner import RunRequest

    monkeypatch.setattr(dispatch, 'DISCOVERY_GRACE', 0.0)
    answer = SimpleNamespace(status=GoalStatus.STATUS_ABORTED, result=SimpleNamespace(
        success=False, message='solver says no'))
    asked: list = []

    def get_result_async():  # the first answer is lost, the second arrives
        asked.append(1)
        return _Future(answer, done=len(asked) > 1)

    handle = SimpleNamespace(accepted=True, get_result_async=get_result_async)
    client = SimpleNamespace(send_goal_async=lambda goal, feedback_callback=None: _Future(
        handle, done=True))
    lines: list[str] = []
    dispatcher = dispatch.Dispatcher(node=None, executor=SimpleNamespace(
        spin_once=lambda timeout_sec: None), log=lines.append, silence=0.05)
    dispatcher.instances['/vd/kc/run_event'] = dispatch.Instance(
        '/vd/kc/run_event', '/vd/kc_solver', 'kc', client, ready_since=0.0)
    monkeypatch.setattr(dispatcher, 'discover', lambda: None)
    results: list = []
    request = RunRequest('parallel_wheel_travel', 'baseline', 'kc', axle='front')
    dispatcher.run([request], lambda *args: results.append(args))
    assert [r[2] for r in results] == ['solver says no']
    assert len(asked) == 2
    assert not lines and not dispatcher.instances['/vd/kc/run_event'].dead


def test_a_graph_look_that_misses_this_node_kills_no_instance(monkeypatch):
    """
    An empty or partial graph query (a loaded machine) is not a node leaving the graph.

    A look that does not see the sweep's own node is not trusted; one that does and
    lacks an instance's node is.
    """
    from types import SimpleNamespace

    import vd_events.orchestration.dispatch as dispatch

    graph = {'nodes': []}
    node = SimpleNamespace(get_node_names_and_namespaces=lambda: graph['nodes'],
                           get_fully_qualified_name=lambda: '/sweep_runner')
    dispatcher = dispatch.Dispatcher(node=node, executor=None)
    inst = dispatch.Instance('/vd/kc/run_event', '/vd/kc_solver', 'kc',
                             SimpleNamespace(server_is_ready=lambda: True), ready_since=0.0)
    dispatcher.instances[inst.action] = inst
    monkeypatch.setattr(dispatch, 'get_action_names_and_types', lambda _node: [])
    dispatcher.discover()  # nothing seen at all
    assert not inst.dead
    graph['nodes'] = [('kc_solver', '/vd')]  # this node missing: partial
    dispatcher.discover()
    assert not inst.dead
    graph['nodes'] = [('sweep_runner', '/')]  # a trusted look without the instance
    dispatcher.discover()
    assert inst.dead == 'its node left the ROS graph'


@pytest.mark.ros
def test_a_starting_solver_process_is_awaited_as_long_as_it_runs(ros_domain, monkeypatch):
    """No clock on a solver this process started: only its exit ends the wait."""
    import rclpy
    from rclpy.executors import SingleThreadedExecutor

    from vd_events.orchestration import dispatch
    from vd_events.orchestration.runner import RunRequest

    monkeypatch.setattr(dispatch, 'DISCOVERY_TIMEOUT', 0.0)  # any clock would have ended it
    node = rclpy.create_node('dispatch_test', namespace='/nowhere')
    executor = SingleThreadedExecutor()
    executor.add_node(node)
    looks = []

    def starting(family: str) -> bool:
        looks.append(family)
        return len(looks) < 20  # the process runs for 20 looks, then exits unseen

    results = []
    try:
        runner = dispatch.Dispatcher(node, executor, starting=starting)
        runner.run([RunRequest('parallel_wheel_travel', 'baseline', 'kc', axle='front')],
                   lambda request, outcome, error, instance: results.append(error))
    finally:
        executor.shutdown()
        node.destroy_node()
    assert len(looks) >= 20 and set(looks) == {'kc'}
    assert results == ["configuration 'baseline', event 'parallel_wheel_travel', model 'kc': "
                       'no kc solver instance in the ROS graph (start one: vd launch '
                       '--solvers kc=1, or kc_solver on another host)']
