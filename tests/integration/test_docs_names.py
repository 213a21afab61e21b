# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The names the docs quote are the names the code uses, both ways.

docs/ros-api.md, docs/sweeps.md and the README quote topics, services, actions, node
parameters, ``ros2 run`` executables and ``vd`` verbs with their flags. Each quoted name is
checked against the running nodes (a graph in ``/vd`` built in this process: the data
server, the three solvers, a second K&C instance, the recorder and the rig bridge), the
installed executables and the CLI's parser; and every name the running graph offers in
``/vd`` is quoted in docs/ros-api.md, so the reference cannot fall behind the code.
"""
from __future__ import annotations

import argparse
from pathlib import Path
import re

from ament_index_python.packages import get_package_prefix
import pytest

from vdtest import wait_for

pytestmark = [pytest.mark.ros]

REPO = Path(__file__).resolve().parents[2]
DOCS = [REPO / 'docs' / 'ros-api.md', REPO / 'docs' / 'sweeps.md', REPO / 'README.md']
API = REPO / 'docs' / 'ros-api.md'
#: a rig's column map (the rig bridge needs one to start)
RIG_MAP = """kind: kc
event: parallel_wheel_travel
axle: front
columns:
  post_left.position: {channel: wheel_travel, side: left}
"""
#: what rclpy adds to every node (not vd's API)
BUILTIN = ('/rosout', '/parameter_events', 'describe_parameters', 'get_parameters',
           'get_parameter_types', 'list_parameters', 'set_parameters',
           'set_parameters_atomically', 'get_type_description')


#: parameters rclpy declares on every node
RCLPY_PARAMETERS = {'use_sim_time', 'start_type_description_service'}


def _text() -> str:
    return '\n'.join(p.read_text(encoding='utf-8') for p in DOCS)


def _quoted() -> set[str]:
    """Every backticked name of a topic, service or action in the graph's default namespace."""
    return set(re.findall(r'`(/vd/[a-z0-9_/]+|/tf|/clock|/rig_bridge/[a-z_]+)`', _text()))


@pytest.fixture(scope='module')
def graph(ros_domain, tmp_path_factory):
    """Yield the names and nodes of the default graph in /vd, built in this process."""
    from rclpy.action import get_action_names_and_types
    from rclpy.node import Node
    from rclpy.parameter import Parameter

    from vd_data_server.nodes.data_server import DataServer
    from vd_events.bags.recorder import Recorder
    from vd_events.nodes.event_runner import EventRunner
    from vd_events.nodes.rig_bridge import RigBridge
    from vd_solvers.nodes.analytical import AnalyticalSolver
    from vd_solvers.nodes.kc import KCSolver
    from vd_solvers.nodes.vehicle import VehicleSolver

    tmp = tmp_path_factory.mktemp('docs')
    (tmp / 'rig.yaml').write_text(RIG_MAP)
    nodes = [DataServer(parameter_overrides=[Parameter('watch_period', value=0.0)]),
             AnalyticalSolver(), KCSolver(), KCSolver(node_name='kc_solver_2'),
             VehicleSolver(), Recorder(bag=str(tmp / 'bag')), EventRunner(),
             RigBridge(parameter_overrides=[Parameter('map', value=str(tmp / 'rig.yaml')),
                                            Parameter('bag', value=str(tmp / 'rig'))])]
    probe = Node('docs_probe')
    names: dict[str, set[str]] = {}

    def look() -> bool:
        names['topics'] = {n for n, _ in probe.get_topic_names_and_types()}
        names['services'] = {n for n, _ in probe.get_service_names_and_types()}
        names['actions'] = {n for n, _ in get_action_names_and_types(probe)}
        return {'/vd/kc/run_event', '/vd/kc/kc_solver_2/run_event',
                '/vd/recorder/finish'} <= names['actions'] | names['services'] and \
            '/vd/configuration' in names['topics']

    try:
        assert wait_for([*nodes, probe], look)
        yield names, nodes
    finally:
        for node in [*nodes, probe]:
            node.destroy_node()


def _ours(name: str) -> bool:
    return not any(name == b or name.endswith('/' + b) for b in BUILTIN) and \
        '/_action/' not in name


def test_every_quoted_name_exists(graph):
    from rosidl_runtime_py.utilities import get_message

    from vd_events.studies.capability import TOPIC as CAPABILITY_TOPIC
    from vd_solvers.nodes.lockstep import (
        ACKERMANN_TOPIC,
        COMMAND_TOPIC,
        INITIAL_POSE_TOPIC,
        JOINT_STATES_TOPIC,
        RESET_SERVICE,
        ROBOT_DESCRIPTION_TOPIC,
        STATUS_TOPIC,
        TF_STATIC_TOPIC,
        TWIST_TOPIC,
    )

    names, _ = graph
    live = names['topics'] | names['services'] | names['actions']
    # names of a mode not started here, checked against their one definition
    defined = {f'/vd/{COMMAND_TOPIC}', f'/vd/{STATUS_TOPIC}', f'/vd/{ACKERMANN_TOPIC}',
               f'/vd/{TWIST_TOPIC}', f'/vd/{INITIAL_POSE_TOPIC}', f'/vd/{RESET_SERVICE}',
               f'/vd/{ROBOT_DESCRIPTION_TOPIC}', f'/vd/{JOINT_STATES_TOPIC}', TF_STATIC_TOPIC,
               '/clock', CAPABILITY_TOPIC}
    types = {'/vd/kc/state': 'vd_interfaces/msg/KcState',
             '/vd/steady_state/state': 'vd_interfaces/msg/AnalyticalState',
             '/vd/vehicle/state': 'vd_interfaces/msg/VehicleState'}
    unknown = []
    for name in sorted(_quoted()):
        if name in live or name in defined:
            continue
        # a channel as PlotJuggler names it: a state topic and a field path of its message
        topic = next((t for t in types if name.startswith(t + '/')), None)
        if topic is not None:
            msg = get_message(types[topic])()
            try:
                for part in name[len(topic) + 1:].split('/'):
                    msg = getattr(msg, part)
                continue
            except AttributeError:
                pass
        unknown.append(name)
    assert unknown == []


def test_every_name_of_the_graph_is_documented(graph):
    names, _ = graph
    documented = set(re.findall(r'`(/vd/[a-z0-9_/]+|/tf)`', API.read_text(encoding='utf-8')))
    offered = {n for n in names['topics'] | names['services'] | names['actions']
               if (n.startswith('/vd/') or n == '/tf') and _ours(n)}
    assert sorted(offered - documented) == []


def test_documented_parameters_are_the_nodes_parameters(graph):
    """Every row of the parameter table names parameters its node declares, and vice versa."""
    _, nodes = graph
    declared = {n.get_name(): set(n.list_parameters([], 1).names) - RCLPY_PARAMETERS
                for n in nodes}
    section = API.read_text(encoding='utf-8').split('### Parameters', 1)[1].split('\n## ', 1)[0]
    documented: dict[str, set[str]] = {}
    for line in section.splitlines():
        cells = [c.strip() for c in line.strip().strip('|').split('|')]
        if len(cells) < 2 or not cells[0].startswith('`'):
            continue
        params = set(re.findall(r'`([a-z_]+)`', cells[1]))
        for node in re.findall(r'`([a-z_0-9]+)`', cells[0]):
            documented.setdefault(node, set()).update(params)
    for node, params in documented.items():
        have = declared.get(node, declared.get('kc_solver') if node.endswith('_solver') else None)
        assert have is not None, f'documented node {node} is not in the graph'
        assert params <= have, (node, params - have)
    vehicle = declared['vehicle_solver'] - {'mode', 'autostart', 'frame_prefix'}
    assert vehicle == set(), vehicle  # the lock-step parameters are declared in that mode only
    for node in ('data_server', 'recorder', 'kc_solver', 'analytical_solver'):
        assert declared[node] <= documented.get(node, set()), (node, declared[node])


def test_ros2_run_executables_exist():
    quoted = set(re.findall(r'ros2 run (vd_[a-z_]+) ([a-z_]+)', _text()))
    quoted |= set(re.findall(r'`(vd_[a-z_]+) ([a-z_]+)`', _text()))
    missing = []
    for package, exe in sorted(quoted):
        if exe.endswith('launch'):
            continue
        lib = Path(get_package_prefix(package)) / 'lib' / package
        if not (lib / exe).is_file():
            missing.append(f'{package} {exe}')
    assert missing == []


def test_vd_verbs_and_flags_exist():
    """``vd VERB ... --flag`` quoted in the docs: the verb exists and takes the flag."""
    from vd_events.cli.parsers import build_parser

    parser = build_parser()
    verbs = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    problems = []
    for quote in re.findall(r'`(vd [^`]+)`', _text()):
        words = quote.split()
        verb = words[1]
        if verb not in verbs.choices:
            if not verb.startswith(('-', '<', '[', '…')) and verb.isidentifier():
                problems.append(f'{quote}: no verb {verb!r}')
            continue
        sub = verbs.choices[verb]
        nested = next((a for a in sub._actions if isinstance(a, argparse._SubParsersAction)),
                      None)
        if nested is not None and len(words) > 2 and words[2] in nested.choices:
            sub = nested.choices[words[2]]
        flags = {o for a in sub._actions for o in a.option_strings}
        for word in words[2:]:
            flag = word.split('=')[0].rstrip(',.;:)]')
            if flag.startswith('--') and flag not in flags:
                problems.append(f'{quote}: {verb} has no {flag}')
    assert problems == []
