# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The product driven as a ROS user drives it: the real ``ros2`` command line and ``ros2 launch``.

``ros2`` and ``ros2 launch`` are not on PyPI: tools/setup.sh installs them from
``../shared/ros-tools`` (upstream sources) when that folder is present. Without it these
tests are skipped and say why. One graph per module (``ros2 launch vd_events
vd.launch.py`` in a namespace, with parameters) serves most tests; every other shipped
launch file and ``ros2 run`` of every executable get their own short check. Everything is
checked from outside the graph, with ``ros2`` commands, in a private domain.
"""
from __future__ import annotations

from collections.abc import Sequence
import os
from pathlib import Path
import shutil
import signal
import subprocess
import time

import pytest

from vdtest import HANG_GUARD

REPO = Path(__file__).resolve().parents[2]
ROS_TOOLS = REPO.parent / 'shared' / 'ros-tools'

pytestmark = [pytest.mark.ros, pytest.mark.slow]


def _missing_tools() -> str | None:
    """Return why the ``ros2`` tests cannot run here, or None."""
    if shutil.which('ros2') is None:
        if not ROS_TOOLS.is_dir():
            return (f'{ROS_TOOLS} is absent: the ros2 CLI and ros2 launch are not installed '
                    '(tools/setup.sh installs them from there; a ROS install provides them)')
        return 'ros2 is not on PATH: run make setup (it installs ../shared/ros-tools)'
    return None


if _missing_tools():
    if ROS_TOOLS.is_dir():  # setup installs them from there: their absence is a defect
        pytest.fail(_missing_tools(), pytrace=False)
    pytest.skip(_missing_tools(), allow_module_level=True)


@pytest.fixture(scope='module')
def env():
    """Yield the environment of a private domain for this module's graphs."""
    from vd_events.orchestration.domain import claim_domain

    claim = claim_domain()
    environment = dict(os.environ, ROS_DOMAIN_ID=str(claim.domain),
                       ROS_AUTOMATIC_DISCOVERY_RANGE='LOCALHOST')
    yield environment
    subprocess.run(['ros2', 'daemon', 'stop'], env=environment, capture_output=True,
                   timeout=30)
    claim.release()


def ros2(env, *args: str, timeout: float = 0.0, check: bool = True):
    """
    Run ``ros2 ARGS``; return the completed process (stdout and stderr joined).

    ``ros2 param`` looks the node up in the graph itself (``--no-daemon``): the daemon's
    graph can lag behind a node that ``ros2 node list --no-daemon`` already shows, and one
    look of a few seconds may still miss a node on a loaded machine, so a ``Node not
    found`` is asked again (a node that is really absent stays absent).
    """
    param = args[0] == 'param'
    if param and '--no-daemon' not in args:
        args = (*args[:2], '--no-daemon', '--spin-time', '3', *args[2:])
    for _ in range(4 if param else 1):
        done = subprocess.run(['ros2', *args], env=env, stdout=subprocess.PIPE,
                              stderr=subprocess.STDOUT, text=True,
                              timeout=timeout or HANG_GUARD)
        if not done.stdout.startswith('Node not found'):
            break
    if check:
        assert done.returncode == 0, f"ros2 {' '.join(args)}:\n{done.stdout}"
    return done


def start(env, *args: str) -> subprocess.Popen:
    """Start ``ros2 ARGS`` in a session of its own (so SIGINT reaches it, see README)."""
    return subprocess.Popen(['setsid', 'ros2', *args], env=env, stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, text=True)


def stop(proc: subprocess.Popen, twice: bool = False) -> str:
    """SIGINT the process group (twice: as a terminal's Ctrl-C does); return its output."""
    if proc.poll() is None:
        os.killpg(proc.pid, signal.SIGINT)
        if twice:
            time.sleep(0.05)
            try:
                os.killpg(proc.pid, signal.SIGINT)
            except ProcessLookupError:
                pass
    try:
        out, _ = proc.communicate(timeout=HANG_GUARD)
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)
        out, _ = proc.communicate()
    return out


def wait_for_nodes(env, names: set[str], procs: Sequence[subprocess.Popen] = (),
                   kind: str = 'node') -> set[str]:
    """
    Poll ``ros2 node list`` (or ``topic``) until ``names`` are all there; return the list.

    No deadline on a loaded machine's slow start: a process of ``procs`` that exits ends
    the wait (its output in the failure), and only a hang meets HANG_GUARD.
    """
    deadline = time.monotonic() + HANG_GUARD
    seen: set[str] = set()
    while time.monotonic() < deadline:
        done = ros2(env, kind, 'list', '--no-daemon', '--spin-time', '2', check=False)
        seen = set(done.stdout.split())
        if names <= seen:
            return seen
        for proc in procs:
            if proc.poll() is not None:
                pytest.fail(f'{proc.args} exited with {proc.returncode} before '
                            f'{sorted(names - seen)} appeared:\n{stop(proc)}')
    return seen


@pytest.fixture(scope='module')
def graph(env, tmp_path_factory):
    """``ros2 launch vd_events vd.launch.py`` in ``/cli``, edits on, a copy of the study."""
    root = tmp_path_factory.mktemp('cli') / 'data'
    shutil.copytree(REPO / 'src' / 'vd_data_server' / 'data', root)
    master = root / 'studies' / 'sedan.yaml'
    proc = start(env, 'launch', 'vd_events', 'vd.launch.py', 'namespace:=/cli',
                 f'master_file:={master}', 'allow_edits:=true', 'watch_period:=0.0')
    nodes = {'/cli/data_server', '/cli/kc_solver', '/cli/analytical_solver',
             '/cli/vehicle_solver'}
    seen = wait_for_nodes(env, nodes, [proc])
    if not nodes <= seen:
        pytest.fail(f'the launch did not start its nodes (seen: {sorted(seen)}):\n'
                    f'{stop(proc)}')
    yield {'master': master, 'proc': proc}
    out = stop(proc, twice=True)
    assert 'Traceback' not in out, out
    assert proc.returncode == 0, out


def test_launch_file_starts_the_graph_in_its_namespace(env, graph):
    wanted = {'/cli/configuration', '/cli/data_status', '/cli/kc/result', '/cli/kc/state',
              '/cli/provenance', '/cli/vehicle/odom'}
    topics = wait_for_nodes(env, wanted, kind='topic')
    assert wanted <= topics
    assert not [t for t in topics if t.startswith('/vd/')]
    params = ros2(env, 'param', 'get', '/cli/data_server', 'master_file').stdout
    assert str(graph['master']) in params


def test_latched_topics_reach_a_late_echo(env, graph):
    status = ros2(env, 'topic', 'echo', '--once', '/cli/data_status',
                  'vd_interfaces/msg/DataStatus', '--qos-durability', 'transient_local',
                  '--qos-reliability', 'reliable').stdout
    assert f'master_file: {graph["master"]}' in status
    config = ros2(env, 'topic', 'echo', '--once', '--field', 'name', '/cli/configuration',
                  'vd_interfaces/msg/Configuration', '--qos-durability', 'transient_local',
                  '--qos-reliability', 'reliable').stdout
    assert config.split()[0] in {'baseline', 'stiff_rear', 'sport'}


def test_services_answer_over_the_cli(env, graph):
    got = ros2(env, 'service', 'call', '/cli/get_configuration',
               'vd_interfaces/srv/GetConfiguration', '{name: nope}').stdout
    assert "configuration 'nope' does not exist (available: baseline, stiff_rear, sport)" in got
    edit = ros2(env, 'service', 'call', '/cli/set_override', 'vd_interfaces/srv/SetOverride',
                "{configuration: sport, key: front_alignment.camber, value: '-1.5 deg'}").stdout
    assert 'success=True' in edit and 'sport: front_alignment.camber = -1.5 deg' in edit
    reload = ros2(env, 'service', 'call', '/cli/reload', 'vd_interfaces/srv/Reload').stdout
    assert "message='reloaded'" in reload


def test_allow_edits_is_fixed_at_start(env, graph):
    done = ros2(env, 'param', 'set', '/cli/data_server', 'allow_edits', 'false', check=False)
    assert 'Setting parameter failed: Trying to set a read-only parameter: allow_edits.' \
        in done.stdout
    assert ros2(env, 'param', 'get', '/cli/data_server', 'allow_edits').stdout.strip() == \
        'Boolean value is: True'


def test_action_goal_with_feedback_and_an_invalid_goal_rejected(env, graph):
    goal = ("{event: parallel_wheel_travel, configuration: baseline, model: kc, axle: front, "
            "parameters: ['steps=21']}")
    done = ros2(env, 'action', 'send_goal', '--feedback', '/cli/kc/run_event',
                'vd_interfaces/action/RunEvent', goal).stdout
    assert 'Feedback:' in done and 'progress: 1.0' in done
    assert "message: 'configuration ''baseline'', event ''parallel_wheel_travel'': 21 steps'" \
        in done
    assert 'Goal finished with status: SUCCEEDED' in done
    bad = ros2(env, 'action', 'send_goal', '/cli/kc/run_event', 'vd_interfaces/action/RunEvent',
               '{event: parallel_wheel_travel, configuration: baseline, model: kc}',
               check=False).stdout
    assert 'Goal was rejected.' in bad


def test_ros2_run_of_every_executable(env, tmp_path, graph):
    """``ros2 run`` the graph's executables in ``/run``, drive a plan and record a bag."""
    from vd_events.bags.bag import read_bag

    master = graph['master']
    procs = [start(env, 'run', 'vd_data_server', 'data_server', '--ros-args', '-r',
                   '__ns:=/run', '-p', f'master_file:={master}', '-p', 'watch_period:=0.0')]
    procs += [start(env, 'run', 'vd_solvers', exe, '--ros-args', '-r', '__ns:=/run')
              for exe in ('analytical_solver', 'kc_solver', 'vehicle_solver')]
    bag = tmp_path / 'bag'
    recorder = start(env, 'run', 'vd_events', 'recorder', '--ros-args', '-r', '__ns:=/run',
                     '-p', f'bag:={bag}')
    try:
        wanted = {'/run/data_server', '/run/analytical_solver', '/run/kc_solver',
                  '/run/vehicle_solver', '/run/recorder'}
        assert wanted <= wait_for_nodes(env, wanted, [*procs, recorder])
        plan = tmp_path / 'plan.yaml'
        plan.write_text(f'name: cli\nmaster: {master}\nruns:\n  - event: handling_diagram\n'
                        '    models: [two_track]\n    configurations: [baseline]\n'
                        '    parameters: [steps=5]\n')
        runner = ros2(env, 'run', 'vd_events', 'event_runner', '--ros-args', '-r',
                      '__ns:=/run', '-p', f'plan:={plan}')
        assert "configuration 'baseline', event 'handling_diagram': 5 steps" in runner.stdout
        finish = ros2(env, 'service', 'call', '/run/recorder/finish',
                      'std_srvs/srv/Trigger').stdout
        assert f"message='{bag}'" in finish
        recorder.communicate(timeout=HANG_GUARD)
        topics = [m.topic for m in read_bag(bag)]
        assert topics.count('/run/steady_state/result') == 1
        assert topics.count('/run/steady_state/state') == 5
    finally:
        outs = [stop(p, twice=True) for p in [*procs, recorder]]
    for out, proc in zip(outs, procs):
        assert 'Traceback' not in out, out
        assert proc.returncode == 0, out


def test_package_launch_files_with_namespace_and_parameters(env, graph):
    """data_server.launch.xml, data_server.launch.py and solvers.launch.py."""
    xml = start(env, 'launch', 'vd_data_server', 'data_server.launch.xml', 'namespace:=/xml',
                f'master_file:={graph["master"]}', 'watch_period:=0.0')
    py = start(env, 'launch', 'vd_data_server', 'data_server.launch.py', 'namespace:=/py',
               'watch_period:=0.25')
    solvers = start(env, 'launch', 'vd_solvers', 'solvers.launch.py', 'namespace:=/xml',
                    'families:=steady_state')
    try:
        wanted = {'/xml/data_server', '/py/data_server', '/xml/analytical_solver'}
        assert wanted <= wait_for_nodes(env, wanted, [xml, py, solvers])
        assert ros2(env, 'param', 'get', '/py/data_server', 'watch_period').stdout.strip() == \
            'Double value is: 0.25'
        assert str(graph['master']) in ros2(env, 'param', 'get', '/xml/data_server',
                                            'master_file').stdout
        goal = ("{event: steady_state_circular, configuration: sport, model: bicycle, "
                "parameters: ['steps=5']}")
        done = ros2(env, 'action', 'send_goal', '/xml/steady_state/run_event',
                    'vd_interfaces/action/RunEvent', goal).stdout
        assert 'Goal finished with status: SUCCEEDED' in done
    finally:
        outs = [stop(p, twice=True) for p in (xml, py, solvers)]
    for out, proc in zip(outs, (xml, py, solvers)):
        assert 'Traceback' not in out, out
        assert proc.returncode == 0, out


def test_lockstep_launch_drives_the_vehicle_in_its_namespace(env):
    """lockstep.launch.py: the lock-step vehicle and the path follower, to the end."""
    # command_timeout: each ros2 command below takes a core for a second or two, and the
    # vehicle must not give up on a command the loaded controller answers late
    launch = start(env, 'launch', 'vd_events', 'lockstep.launch.py', 'namespace:=/ls',
                   'duration:=20.0', 'speed:=10.0', 'radius:=30.0', 'command_timeout:=30.0')
    # odometry is a per-step stream (volatile): a plain echo started with the launch gets a
    # step of the run; 20 s of steps (each answered over ROS by the controller) leave it
    # seconds to subscribe however fast the lock-step runs
    echo = start(env, 'topic', 'echo', '--once', '/ls/vehicle/odom', 'nav_msgs/msg/Odometry')
    try:
        wanted = {'/ls/vehicle_solver', '/ls/path_follower'}
        assert wanted <= wait_for_nodes(env, wanted, [launch])
        assert ros2(env, 'param', 'get', '/ls/path_follower', 'radius').stdout.strip() == \
            'Double value is: 30.0'
        assert ros2(env, 'param', 'get', '/ls/vehicle_solver', 'frame_prefix').stdout.strip() \
            == 'String value is: ls/'
        # 20 s of 5 ms steps, each one answered by the controller over ROS
        deadline, status = time.monotonic() + HANG_GUARD, ''
        while time.monotonic() < deadline and not status.startswith('data: finished'):
            status = ros2(env, 'topic', 'echo', '--once', '--qos-durability',
                          'transient_local', '--qos-reliability', 'reliable',
                          '/ls/vehicle/lockstep_status').stdout.strip()
            time.sleep(2.0)
        assert status.startswith('data: finished at t = 20.000000 s (4000 steps)'), status
        assert ros2(env, 'param', 'get', '/ls/vehicle_solver', 'command_timeout').stdout \
            .strip() == 'Double value is: 30.0'
        odom, _ = echo.communicate(timeout=HANG_GUARD)
        assert 'frame_id: ls/odom' in odom and 'child_frame_id: ls/base_link' in odom
    finally:
        out = stop(launch, twice=True)
        if echo.poll() is None:
            stop(echo)
    assert 'Traceback' not in out, out
    assert launch.returncode == 0, out
