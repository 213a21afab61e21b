# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
``vd launch [--distributed] [--namespace NS] [--solvers kc=2,...]``: start the graph.

The nodes are those of ``graph.graph()`` (the one definition the launch files use too):
the data server and the three solvers, in ``NS`` (``/vd`` by default). Unlike ``vd run``
this uses the caller's ROS graph (ROS_DOMAIN_ID as set), so other tools (a recorder,
Foxglove, ``ros2 run vd_events event_runner``, the ``ros2`` CLI) can use the nodes. It
is the path that needs no ``ros2 launch``; where that is installed, ``ros2 launch
vd_events vd.launch.py`` starts the same graph. Ctrl-C stops everything cleanly.
"""
from __future__ import annotations

import os
from pathlib import Path
import signal
import subprocess
import time

import rclpy
from rclpy.executors import ExternalShutdownException
from rclpy.parameter import Parameter

from vd_data_server.paths import default_master
from vd_data_server.ros import names
from vd_data_server.ros.node_main import make_executor, quiet_teardown, spin_guarded
from vd_data_server.study import load_study
from vd_events.orchestration import graph
from vd_events.orchestration.dispatch import parse_solvers
from vd_events.orchestration.domain import claim_launch_domain
from vd_events.orchestration.runner import stop_processes


def launch(master: Path | None, *, distributed: bool,
           namespace: str = names.DEFAULT_NAMESPACE, allow_edits: bool = False,
           solvers: str = '') -> int:
    """Start the graph (validated first: bad data starts nothing); return the exit code."""
    # instances per family (vd_events.orchestration.dispatch); default 1
    counts = parse_solvers(solvers)
    master = master or default_master()
    load_study(master)  # refuse bad data before anything starts
    specs = graph.graph(master, allow_edits=allow_edits or None, instances=counts)
    claim = claim_launch_domain()  # held while the nodes run: no vd run lands among them
    try:
        if distributed:
            return _distributed(specs, master, namespace)
        return _embedded(specs, master, namespace)
    finally:
        claim.release()


def _embedded(specs, master: Path, namespace: str) -> int:


    rclpy.init()
    nodes = [graph.node_class(spec)(
        namespace=namespace,
        parameter_overrides=[Parameter(k, value=v) for k, v in spec.parameters.items()],
        **({'node_name': spec.name} if spec.name else {})) for spec in specs]
    executor = make_executor(threads=2)
    for node in nodes:
        executor.add_node(node)
    print(f'vd nodes running in one process in {namespace} ({master}); Ctrl-C stops them',
          flush=True)
    try:
        spin_guarded(executor, nodes[0])
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    finally:
        quiet_teardown(nodes)
    return 0


def _distributed(specs, master: Path, namespace: str) -> int:

    commands = [graph.command(spec, namespace) for spec in specs]

    def stop(signum, frame):  # SIGTERM (and SIGINT where a shell ignores it) end the launch
        raise KeyboardInterrupt

    signal.signal(signal.SIGTERM, stop)
    # the nodes end with the launch, even after kill -9 (node_main.die_with_parent)
    env = dict(os.environ, VD_PARENT_PID=str(os.getpid()))
    procs = [subprocess.Popen(cmd, env=env) for cmd in commands]
    print(f'vd nodes running as {len(procs)} processes in {namespace} ({master}); Ctrl-C '
          'stops them', flush=True)
    try:
        while all(p.poll() is None for p in procs):
            time.sleep(0.5)
    except KeyboardInterrupt:
        pass
    finally:
        stop_processes(procs)
    failed = [p for p in procs if p.returncode not in (0, -signal.SIGINT, None)]
    return 1 if failed else 0
