# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Two graphs side by side in one ROS domain, under ``/car1`` and ``/car2``.

Each namespace has its own data server (two different studies) and solvers; the names
resolve in the namespace, so each runner reaches only its own graph and gets results of
its own data.
"""
from __future__ import annotations

import shutil

import pytest

from vdtest import replace_once

pytestmark = [pytest.mark.ros, pytest.mark.slow]


def _graph(namespace: str, master):
    """Return a data server, K&C and analytical solvers and a runner node in ``namespace``."""
    from rclpy.node import Node
    from rclpy.parameter import Parameter

    from vd_data_server.nodes.data_server import DataServer
    from vd_events.orchestration.runner import EventClient
    from vd_solvers.nodes.analytical import AnalyticalSolver
    from vd_solvers.nodes.kc import KCSolver

    server = DataServer(namespace=namespace, parameter_overrides=[
        Parameter('master_file', value=str(master)), Parameter('watch_period', value=0.0)])
    solvers = [KCSolver(namespace=namespace), AnalyticalSolver(namespace=namespace)]
    client_node = Node('event_runner', namespace=namespace)
    return [server, *solvers, client_node], EventClient(client_node)


def test_two_studies_run_side_by_side_in_two_namespaces(ros_domain, sample_root, tmp_path):
    from rclpy.executors import MultiThreadedExecutor

    from vd_data_server.study import load_study
    from vd_events.orchestration.runner import RunRequest, send_goal, validate

    second = tmp_path / 'data2'
    shutil.copytree(sample_root, second)
    replace_once(second / 'sedan' / 'front_spring' / 'X.yaml', 'rate: 30.0', 'rate: 36.0')
    masters = {'/car1': sample_root / 'studies' / 'sedan.yaml',
               '/car2': second / 'studies' / 'sedan.yaml'}
    graphs = {ns: _graph(ns, master) for ns, master in masters.items()}
    executor = MultiThreadedExecutor(num_threads=4)
    nodes = [n for nodes, _ in graphs.values() for n in nodes]
    # the one global TF tree: each graph's wheel frames under its own prefix
    from rclpy.node import Node

    from tf2_msgs.msg import TFMessage
    from vd_data_server.ros.qos import STATES

    frames: set[tuple[str, str]] = set()
    tf_node = Node('tf_listener')
    tf_node.create_subscription(TFMessage, '/tf', lambda m: frames.update(
        (t.header.frame_id, t.child_frame_id) for t in m.transforms), STATES)
    nodes.append(tf_node)
    for node in nodes:
        executor.add_node(node)
    try:
        solvers = [n for nodes, _ in graphs.values() for n in nodes[1:3]]
        assert _spin(executor, lambda: all(len(s.configurations) == 3 for s in solvers))
        topics = {name for name, _ in nodes[0].get_topic_names_and_types()}
        assert {'/car1/configuration', '/car2/configuration', '/car1/kc/result',
                '/car2/kc/result'} <= topics
        hashes, rates = {}, {}
        for ns, (_, client) in graphs.items():
            study = load_study(masters[ns])
            request = validate(study, RunRequest('parallel_wheel_travel', 'baseline', 'kc',
                                                 axle='front', parameters=('steps=5',)))
            ok, message, result = send_goal(executor, client, request, lambda p, s: None)
            assert ok, message
            assert result.data_hash == request.data_hash
            rates[ns] = next(m.value for m in result.metrics if m.name == 'wheel_rate')
            hashes[ns] = result.data_hash
        assert hashes['/car1'] != hashes['/car2']
        assert _spin(executor, lambda: len(frames) == 4)
        assert frames == {(f'{car}/base_link', f'{car}/front_{side}_wheel')
                          for car in ('car1', 'car2') for side in ('left', 'right')}
        # the second study's stiffer spring shows in its own graph's result only
        assert rates['/car2'] > rates['/car1']
    finally:
        for node in nodes:
            executor.remove_node(node)
            node.destroy_node()
        executor.shutdown()


def _spin(executor, predicate, timeout: float = 20.0) -> bool:
    """Spin ``executor`` until ``predicate()`` holds or ``timeout`` s pass."""
    import time

    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if predicate():
            return True
        executor.spin_once(timeout_sec=0.05)
    return predicate()
