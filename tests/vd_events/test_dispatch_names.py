# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""Solver instance names: what the dispatcher counts as one instance of a family."""
from __future__ import annotations

import pytest

from vd_events.dispatch import instance_names, parse_instance, parse_solvers, solver_command
from vd_events.runner import RunError


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
    from vd_events.dispatch import Dispatcher, Instance

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

    def __init__(self, lost: int):
        self.lost, self.sent = lost, 0

    def send_goal_async(self, goal, feedback_callback=None):
        from types import SimpleNamespace

        from action_msgs.msg import GoalStatus

        self.sent += 1
        if self.sent <= self.lost:
            return _Future()
        answer = SimpleNamespace(status=GoalStatus.STATUS_ABORTED, result=SimpleNamespace(
            success=False, message='solver says no'))
        handle = SimpleNamespace(accepted=True,
                                 get_result_async=lambda: _Future(answer, done=True))
        return _Future(handle, done=True)


@pytest.mark.parametrize('lost, sent, error', [
    (2, 3, 'solver says no'),  # answered at the third request: the same instance keeps it
    (3, 3, "configuration 'baseline', event 'parallel_wheel_travel', model 'kc': 3 solver "
           'instances died under this run (last: no answer to 3 goal requests); not retried'),
])
def test_an_unanswered_goal_request_is_sent_again(monkeypatch, lost, sent, error):
    """A lost goal response costs a resend to the same instance, not the instance."""
    from types import SimpleNamespace

    import vd_events.dispatch as dispatch
    from vd_events.runner import RunRequest

    monkeypatch.setattr(dispatch, 'ACCEPT_TIMEOUT', 0.02)
    monkeypatch.setattr(dispatch, 'DISCOVERY_GRACE', 0.0)
    client = _Client(lost)
    lines: list[str] = []
    dispatcher = dispatch.Dispatcher(node=None, executor=SimpleNamespace(
        spin_once=lambda timeout_sec: None), log=lines.append)
    dispatcher.instances['/vd/kc/run_event'] = dispatch.Instance(
        '/vd/kc/run_event', '/vd/kc_solver', 'kc', client, ready_since=0.0)
    # the graph does not change; an instance that is lost stays lost
    monkeypatch.setattr(dispatcher, 'discover', lambda: None)
    if lost >= 3:  # three instances, each of which never answers
        for n in (2, 3):
            dispatcher.instances[f'/vd/kc/kc_solver_{n}/run_event'] = dispatch.Instance(
                f'/vd/kc/kc_solver_{n}/run_event', f'/vd/kc_solver_{n}', 'kc', _Client(3),
                ready_since=0.0)
    results: list = []
    request = RunRequest('parallel_wheel_travel', 'baseline', 'kc', axle='front')
    dispatcher.run([request], lambda *args: results.append(args))
    assert [(r[0], r[1], r[2]) for r in results] == [(request, None, error)]
    assert client.sent == sent
    if lost < 3:
        assert not lines and not dispatcher.instances['/vd/kc/run_event'].dead
    else:
        assert all(i.dead == 'no answer to 3 goal requests'
                   for i in dispatcher.instances.values())
