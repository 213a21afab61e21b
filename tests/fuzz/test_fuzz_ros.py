# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Fuzzed service requests and action goals to live nodes: every request gets an answer.

An answer is a success, a clean message or a rejected goal, and the node keeps serving:
never a dead node (issue 10).
"""
from __future__ import annotations

from pathlib import Path
import shutil

from hypothesis import given, settings
from hypothesis import strategies as st
import pytest

from fuzzing import QUANTITIES
from vdtest import wait_for

pytestmark = pytest.mark.ros

SAMPLE = Path(__file__).resolve().parents[2] / 'src' / 'vd_data_server' / 'data'
#: a fifth of the profile's examples: each one is a round trip through DDS
FEW = max(5, settings.default.max_examples // 5)
TEXTS = st.one_of(st.text(max_size=40), QUANTITIES)


@pytest.fixture(scope='module')
def graph(ros_domain, tmp_path_factory):
    from rclpy.node import Node
    from rclpy.parameter import Parameter

    from vd_data_server.nodes.data_server import DataServer
    from vd_solvers.nodes.analytical import AnalyticalSolver

    root = tmp_path_factory.mktemp('fuzz_ros') / 'data'
    shutil.copytree(SAMPLE, root)
    server = DataServer(parameter_overrides=[
        Parameter('master_file', value=str(root / 'studies' / 'sedan.yaml')),
        Parameter('watch_period', value=0.0), Parameter('allow_edits', value=True)])
    solver = AnalyticalSolver()
    client = Node('fuzz_client')
    nodes = [server, solver, client]
    assert wait_for(nodes, lambda: len(solver.configurations) == 3)
    yield nodes
    for node in nodes:
        node.destroy_node()


def _call(nodes, srv_type, name, request):
    client = nodes[2].create_client(srv_type, name)
    try:
        assert wait_for(nodes, client.service_is_ready)
        future = client.call_async(request)
        assert wait_for(nodes, future.done), f'{name}: no answer'
        return future.result()
    finally:
        nodes[2].destroy_client(client)


def _alive(nodes) -> None:
    from vd_interfaces.srv import GetConfiguration

    answer = _call(nodes, GetConfiguration, '/vd/get_configuration',
                   GetConfiguration.Request(name='baseline'))
    assert answer.success


@settings(max_examples=FEW)
@given(configuration=st.one_of(st.sampled_from(['baseline', 'sport']), st.text(max_size=20)),
       key=st.one_of(st.sampled_from(['front_spring.rate', 'mass.sprung_mass',
                                      'front_tire.tir.LATERAL_COEFFICIENTS.PKY2']),
                     st.text(max_size=30)),
       value=TEXTS)
def test_set_override_requests(graph, configuration, key, value):
    from vd_interfaces.srv import SetOverride

    answer = _call(graph, SetOverride, '/vd/set_override',
                   SetOverride.Request(configuration=configuration, key=key, value=value))
    assert answer.message
    assert 'Traceback' not in answer.message
    _alive(graph)


@settings(max_examples=FEW)
@given(event=st.one_of(st.sampled_from(['handling_diagram', 'steady_state_circular',
                                        'step_steer']), st.text(max_size=20)),
       configuration=st.one_of(st.just('baseline'), st.text(max_size=10)),
       model=st.sampled_from(['two_track', 'bicycle', '', 'kc', 'x']),
       overrides=st.lists(st.builds(lambda k, v: f'{k}={v}', st.sampled_from(
           ['front_spring.rate', 'mass.sprung_mass', 'targets.roll_stiffness_front', 'x']),
           TEXTS), max_size=2),
       parameters=st.lists(st.builds(lambda k, v: f'{k}={v}', st.sampled_from(
           ['radius', 'steps', 'speed', 'x']), TEXTS), max_size=2))
def test_run_event_goals(graph, event, configuration, model, overrides, parameters):
    from rclpy.action import ActionClient

    from vd_interfaces.action import RunEvent

    action = ActionClient(graph[2], RunEvent, '/vd/steady_state/run_event')
    try:
        assert wait_for(graph, action.server_is_ready)
        send = action.send_goal_async(RunEvent.Goal(
            event=event, configuration=configuration, model=model, overrides=overrides,
            parameters=parameters))
        assert wait_for(graph, send.done)
        if send.result().accepted:  # else rejected in the goal callback: an answer too
            result = send.result().get_result_async()
            assert wait_for(graph, result.done), 'no answer to the goal'
            answer = result.result().result
            assert answer.message and 'Traceback' not in answer.message
    finally:
        action.destroy()
    _alive(graph)
