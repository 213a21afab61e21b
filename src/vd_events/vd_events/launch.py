"""
``vd launch [--distributed]``: start the data server and the solvers and keep them up.

Unlike ``vd run`` this uses the caller's ROS graph (ROS_DOMAIN_ID as set), so
other tools (a recorder, Foxglove, ``ros2 run vd_events event_runner``) can use
the nodes. Ctrl-C stops everything cleanly.
"""
from __future__ import annotations

import os
from pathlib import Path
import signal
import subprocess
import time


def launch(master: Path | None, *, distributed: bool, solvers: str = '') -> int:
    from vd_data_server.paths import default_master
    from vd_data_server.study import load_study

    from .dispatch import parse_solvers

    counts = parse_solvers(solvers)  # instances per family (vd_events.dispatch); default 1
    master = master or default_master()
    load_study(master)  # refuse bad data before anything starts
    if distributed:
        return _distributed(master, counts)
    return _embedded(master, counts)


def _embedded(master: Path, counts: dict[str, int] | None = None) -> int:
    import rclpy
    from rclpy.executors import ExternalShutdownException, MultiThreadedExecutor
    from rclpy.parameter import Parameter

    from vd_data_server.data_server_node import DataServer
    from vd_data_server.node_main import spin_guarded
    from vd_solvers.analytical_node import AnalyticalSolver
    from vd_solvers.kc_node import KCSolver
    from vd_solvers.vehicle_node import VehicleSolver

    rclpy.init()
    nodes = [DataServer(parameter_overrides=[Parameter('master_file', value=str(master))]),
             AnalyticalSolver(), KCSolver(), VehicleSolver()]
    from .dispatch import instance_names

    kinds = {'steady_state': AnalyticalSolver, 'kc': KCSolver, 'vehicle': VehicleSolver}
    nodes += [kinds[family](cli_args=['--ros-args', '-r', f'__node:={name}'])
              for family, n in (counts or {}).items() for name in instance_names(family, n)[1:]]
    executor = MultiThreadedExecutor(num_threads=2)
    for node in nodes:
        executor.add_node(node)
    print(f'vd nodes running in one process ({master}); Ctrl-C stops them')
    try:
        spin_guarded(executor, nodes[0])
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    finally:
        for node in nodes:
            node.destroy_node()
        rclpy.try_shutdown()
    return 0


def _distributed(master: Path, counts: dict[str, int] | None = None) -> int:
    from .dispatch import instance_names, solver_command
    from .runner import _executable, stop_processes

    commands = [[_executable('vd_data_server', 'data_server'), '--ros-args', '-p',
                 f'master_file:={master}'],
                [_executable('vd_solvers', 'analytical_solver')],
                [_executable('vd_solvers', 'kc_solver')],
                [_executable('vd_solvers', 'vehicle_solver')]]
    # extra instances (--solvers kc=2): named kc_solver_2, ... (one action each)
    commands += [solver_command(family, name) for family, n in (counts or {}).items()
                 for name in instance_names(family, n)[1:]]
    def stop(signum, frame):  # SIGTERM (and SIGINT where a shell ignores it) end the launch
        raise KeyboardInterrupt

    signal.signal(signal.SIGTERM, stop)
    # the nodes end with the launch, even after kill -9 (node_main.die_with_parent)
    env = dict(os.environ, VD_PARENT_PID=str(os.getpid()))
    procs = [subprocess.Popen(cmd, env=env) for cmd in commands]
    print(f'vd nodes running as {len(procs)} processes ({master}); Ctrl-C stops them')
    try:
        while all(p.poll() is None for p in procs):
            time.sleep(0.5)
    except KeyboardInterrupt:
        pass
    finally:
        stop_processes(procs)
    failed = [p for p in procs if p.returncode not in (0, -signal.SIGINT, None)]
    return 1 if failed else 0
