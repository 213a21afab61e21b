# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Sweeps over several solver processes: discovery, a solver killed mid-sweep, attach.

Small sweeps (a few short K&C runs) so the suite stays fast; the scaling figures are
``vd bench``'s job.
"""
from __future__ import annotations

import json
import os
from pathlib import Path
import random
import signal
import subprocess
import sys
import threading

from numpy.testing import assert_allclose
import pytest

from vd_data_server.master import parse_set, with_overrides
from vd_data_server.study import load_study
from vd_events.sweeps.plan import convert, load_plan
from vd_events.sweeps.sweep import load_records, sweep
from vd_solvers.kc.from_config import run_kc_event
from vdtest import HANG_GUARD

pytestmark = [pytest.mark.ros, pytest.mark.slow]

PLAN = """\
name: bars
master: {master}
configuration: baseline
factors:
  bar_radius: {{key: front_stabilizer.bar_radius, unit: mm, values: [{values}]}}
runs:
  - {{event: opposite_wheel_travel, axle: front, parameters: [steps=11]}}
responses:
  roll_stiffness: {{metric: roll_stiffness, event: opposite_wheel_travel, unit: N*m/deg}}
"""


def _plan(tmp_path: Path, master: Path, values: str) -> Path:
    path = tmp_path / 'bars.yaml'
    path.write_text(PLAN.format(master=master, values=values))
    return path


def _direct(study, radius: float) -> float:
    config = with_overrides(study.configurations['baseline'],
                            parse_set([f'front_stabilizer.bar_radius={radius} mm']))
    metric = run_kc_event(config, 'opposite_wheel_travel', 'front', ['steps=11']).metrics[
        'roll_stiffness']
    return convert(metric.value, metric.unit, 'N*m/deg')


def test_two_solver_processes_and_one_killed_mid_sweep(tmp_path, sedan_master):
    from vd_events.orchestration.dispatch import SolverGraph

    plan = load_plan(_plan(tmp_path, sedan_master, '11, 11.5, 12, 12.5, 13, 13.5'))
    study = load_study(plan.master)
    out = tmp_path / 'out'
    lines: list[str] = []
    killed: list[str] = []
    graph = SolverGraph(plan.master, {'kc': 2}, log=lines.append)
    with graph as dispatcher:
        def kill_when_busy(stop: threading.Event) -> None:
            # the first moment kc_solver_2 holds an accepted goal, its process is killed
            while not stop.is_set() and not killed:
                victim = next((i for i in list(dispatcher.instances.values())
                               if i.node == '/vd/kc_solver_2'), None)
                job = victim.job if victim is not None else None
                if job is not None and job.handle is not None:
                    graph.kill('kc_solver_2')
                    killed.append(job.request.overrides[0])
                stop.wait(0.01)

        def evaluator(requests, done):
            stop = threading.Event()
            watcher = threading.Thread(target=kill_when_busy, args=(stop,), daemon=True)
            watcher.start()
            try:
                dispatcher.run(requests, done)
            finally:
                stop.set()
                watcher.join()

        result = sweep(plan, study, evaluator, out, bags=False)
    assert killed, 'kc_solver_2 never held a goal'
    assert any(line.startswith('solver instance /vd/kc_solver_2 lost (its process ended)')
               for line in lines), lines
    # no run was lost: every point has its result, equal to the single run in this process
    assert not any(result.errors), result.errors
    assert result.computed == 6
    expected = [_direct(study, r) for r in (11, 11.5, 12, 12.5, 13, 13.5)]
    assert_allclose(result.responses[:, 0], expected, rtol=1e-9)
    # the run the killed instance was solving is recorded once: finished by the other
    # instance, or by the killed one when its result was on the wire as the kill came
    # (the log above says the instance was lost either way)
    records = load_records(out).values()
    retried = [r for r in records if r.data_hash == _hash(study, killed[0])]
    assert len(retried) == 1
    assert {r.instance for r in records} <= {'/vd/kc_solver', '/vd/kc_solver_2'}


def _hash(study, override: str) -> str:
    return with_overrides(study.configurations['baseline'], parse_set([override])).data_hash


def test_launch_solvers_and_sweep_attach(tmp_path, sedan_master, capsys):
    """`vd launch --distributed --solvers kc=2` serves a `vd sweep --attach`."""
    from vd_events.cli import main as cli

    domain = str(random.randint(216, 232))
    env = dict(os.environ, ROS_DOMAIN_ID=domain, ROS_AUTOMATIC_DISCOVERY_RANGE='LOCALHOST')
    launcher = subprocess.Popen([sys.executable, '-m', 'vd_events.cli.main', 'launch',
                                 '--distributed', '--solvers', 'kc=2', '--master',
                                 str(sedan_master)], env=env, stdout=subprocess.PIPE,
                                stderr=subprocess.STDOUT, text=True)
    plan = _plan(tmp_path, sedan_master, '11, 12, 13, 14')
    out = tmp_path / 'out'
    old = os.environ.get('ROS_DOMAIN_ID')
    os.environ['ROS_DOMAIN_ID'] = domain
    try:
        names = _action_names(int(domain), launcher)
        # --solvers kc=2 with --attach: the runs wait until the sweep has found both
        # instances, so both get goals (a late instance would join only once it appears)
        code = cli.main(['sweep', str(plan), '--attach', '--solvers', 'kc=2', '--out',
                         str(out), '--json'])
    finally:
        if old is None:
            os.environ.pop('ROS_DOMAIN_ID', None)
        else:
            os.environ['ROS_DOMAIN_ID'] = old
        launcher.send_signal(signal.SIGTERM)
        log, _ = launcher.communicate(timeout=HANG_GUARD)
    summary = json.loads(capsys.readouterr().out)
    assert code == 0, (summary['errors'], log)
    assert summary['computed'] == 4 and summary['failed'] == 0
    assert {r.instance for r in load_records(out).values()} == {'/vd/kc_solver', '/vd/kc_solver_2'}
    # the default instance serves the family's action; the second one of its own
    # (vd_solvers.families.Family.action)
    assert names == {'kc_solver': {'/vd/kc/run_event'},
                     'kc_solver_2': {'/vd/kc/kc_solver_2/run_event'}}
    assert launcher.returncode == 0, log
    assert (out / 'table.csv').is_file()


def _action_names(domain: int, launcher: subprocess.Popen) -> dict[str, set[str]]:
    """
    Return the RunEvent actions each kc solver node serves, once both are discovered.

    However long a loaded machine takes to start them; the launcher's exit ends the wait.
    """
    import time

    import rclpy
    from rclpy.action.graph import get_action_server_names_and_types_by_node
    from rclpy.node import Node

    context = rclpy.Context()
    rclpy.init(context=context, domain_id=domain, signal_handler_options=None)
    node = Node('probe', context=context)
    try:
        deadline = time.monotonic() + HANG_GUARD
        servers: dict[str, set[str]] = {}
        while time.monotonic() < deadline and launcher.poll() is None:
            try:
                servers = {name: {n for n, _ in get_action_server_names_and_types_by_node(
                    node, name, '/vd')} for name in ('kc_solver', 'kc_solver_2')}
            except Exception:  # noqa: BLE001 - RCLError until the node is discovered
                servers = {}
            if servers and all(servers.values()):
                break
            time.sleep(0.2)
        return servers
    finally:
        node.destroy_node()
        rclpy.try_shutdown(context=context)
