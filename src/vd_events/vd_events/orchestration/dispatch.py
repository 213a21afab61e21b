# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Many runs over many solver instances: discovery, one goal in flight each, retries.

The default instance of a family (node name = its executable, ``kc_solver``) serves the
family's action ``<ns>/kc/run_event``; every other instance, started under another node
name (``vd launch --solvers kc=2`` names them ``kc_solver_2``, ...; on another host, any
name), serves ``<ns>/kc/<node>/run_event`` (``vd_solvers.families.Family.action``).
Instances are found in the ROS graph: every action of type
``vd_interfaces/action/RunEvent`` of that form whose node is in the graph is one
instance of that family. No configuration file lists them; instances that appear during
a sweep join it.

The dispatcher keeps every instance busy with one goal at a time. A goal whose
instance died — its process ended (when this process started it) or its node left the
graph — is sent again to another instance, up to :data:`ATTEMPTS` times; the dead
instance gets no more goals. Nothing else counts as death, so a busy machine makes a
sweep slower, never lost: a goal request not answered is sent again to the same
instance at growing intervals (Fast DDS drops a response sent before discovery is
complete), and a goal silent (neither feedback nor result) for :data:`SILENCE` s has
its result asked for again. A goal the solver answers with an error is a failed run
(the data is wrong, another instance would say the same), not retried.
"""
from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
import os
import subprocess
import tempfile
import time
from typing import IO, Any

from action_msgs.msg import GoalStatus
import rclpy
from rclpy.action import ActionClient
from rclpy.action.graph import get_action_names_and_types
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node

from vd_events.errors import RunError
from vd_events.orchestration import graph
from vd_events.orchestration.graph import instance_names
from vd_events.orchestration.runner import (
    ACCEPT_TIMEOUT,
    DISCOVERY_GRACE,
    EventClient,
    RunRequest,
    _claim_domain,
    _ros_args,
    _spin_until,
    check_result,
    stop_processes,
)
from vd_interfaces.action import RunEvent
from vd_solvers.conversions import outcome_from_msg
from vd_solvers.families import FAMILIES as SOLVER_FAMILIES
from vd_solvers.results import EventOutcome

ACTION_TYPE = 'vd_interfaces/action/RunEvent'
#: s without feedback or result before a goal's result is asked for again
SILENCE = 30.0
#: times a goal is sent before its run counts as failed (instances died under it)
ATTEMPTS = 3
#: s to wait for the first instance of a family the runs need, when no process started
#: here can bring one (instances attached from the graph, other hosts); the instances
#: this process starts are awaited as long as their processes run
DISCOVERY_TIMEOUT = 90.0
#: s between two looks at the graph
DISCOVERY_PERIOD = 0.5
#: s a family's first goals wait, once one of its instances is ready, for the others the
#: sweep expects (``Dispatcher.expect``) before the runs start on the ones found
EXPECT_WAIT = 30.0

Done = Callable[[RunRequest, EventOutcome | None, str | None, str], None]


def parse_instance(action: str, nodes: set[str]) -> tuple[str, str] | None:
    """
    Return (node, family) of an instance's action, or None.

    ``/vd/kc/run_event`` -> (``/vd/kc_solver``, ``kc``); ``/vd/kc/kc_solver_2/run_event``
    -> (``/vd/kc_solver_2``, ``kc``); only when that node is in ``nodes``.
    """
    head, sep, tail = action.rpartition('/')
    if not sep or tail != 'run_event':
        return None
    rest, _, last = head.rpartition('/')
    if last in SOLVER_FAMILIES:  # the family's default instance
        node, family = f'{rest}/{SOLVER_FAMILIES[last].executable}', last
    else:
        namespace, _, family = rest.rpartition('/')
        node = f'{namespace}/{last}'
    if family not in SOLVER_FAMILIES or node not in nodes:
        return None
    return node, family


@dataclass
class _Job:
    request: RunRequest
    attempts: int = 0  # instances it was sent to
    resends: int = 0  # goal requests sent again to the current one (no answer)
    results: list = field(default_factory=list)  # result requests (asked again if silent)
    send: Any = None  # rclpy futures and goal handles
    handle: Any = None
    result: Any = None
    last_news: float = 0.0


@dataclass
class Instance:
    action: str
    node: str
    family: str
    client: Any  # rclpy.action.ActionClient
    ready_since: float | None = None
    job: _Job | None = None
    dead: str = ''  # why it gets no more goals
    runs: int = 0


@dataclass
class Dispatcher:
    """
    Spread runs over the instances found in the graph of ``node`` (spun by ``executor``).

    ``alive(node_name)`` says whether an instance's process runs (True/False: this
    process started it, and its exit is the one sign of its death; None: not a child,
    so the node leaving the graph is). ``expect`` (family
    -> count) holds a family's first goals until that many of its instances are ready, at
    most EXPECT_WAIT s after the first one is (a late instance joins once it is
    discovered; waiting for all makes the first goals spread over all of them).
    """

    node: Any  # rclpy.node.Node
    executor: Any  # rclpy.executors.Executor
    alive: Callable[[str], bool | None] | None = None
    silence: float = SILENCE
    instances: dict[str, Instance] = field(default_factory=dict)
    log: Callable[[str], None] | None = None
    expect: Mapping[str, int] = field(default_factory=dict)
    expect_wait: float = EXPECT_WAIT
    #: family -> whether a solver process this process started for it still runs (None:
    #: none started here). While one runs, its instance is awaited without a time limit:
    #: a loaded machine starts it late, its exit is the sign it never will
    starting: Callable[[str], bool | None] | None = None

    def discover(self) -> None:


        nodes = {(ns.rstrip('/') + '/' + name) for name, ns in
                 self.node.get_node_names_and_namespaces()}
        # a loaded machine's graph query can come back empty or partial: a look that
        # misses this very node says nothing about the others
        trusted = self.node.get_fully_qualified_name() in nodes
        for action, types in get_action_names_and_types(self.node):
            if ACTION_TYPE not in types or action in self.instances:
                continue
            parsed = parse_instance(action, nodes)
            if parsed is None:
                continue
            client = ActionClient(self.node, RunEvent, action)
            self.instances[action] = Instance(action, parsed[0], parsed[1], client)
        now = time.monotonic()
        for inst in self.instances.values():
            if inst.dead:
                continue
            running = (self.alive(inst.node.rsplit('/', 1)[-1]) if self.alive is not None
                       else None)
            if running is False:
                self._kill(inst, 'its process ended')
                continue
            if running is None and trusted and inst.node not in nodes:
                self._kill(inst, 'its node left the ROS graph')
                continue
            if inst.ready_since is None and inst.client.server_is_ready():
                inst.ready_since = now

    def _kill(self, inst: Instance, why: str) -> None:
        inst.dead = why
        if self.log is not None:
            self.log(f'solver instance {inst.node} lost ({why})'
                     + (f'; {inst.job.request.label} goes to another instance' if inst.job
                        else ''))

    def live(self, family: str) -> list[Instance]:
        return [i for i in self.instances.values() if i.family == family and not i.dead]

    def run(self, requests: Sequence[RunRequest], done: Done) -> None:
        """Compute every request; ``done`` is called once per request, as each finishes."""
        goal_of = EventClient.goal
        pending = [_Job(r) for r in requests]
        active: list[Instance] = []
        waiting_since = {f: time.monotonic() for f in {r.family for r in requests}}
        started: set[str] = set()  # families whose goals go out (expected instances found)
        last_look = 0.0
        while pending or active:
            now = time.monotonic()
            if now - last_look >= DISCOVERY_PERIOD:
                last_look = now
                self.discover()
                for inst in list(active):
                    if inst.dead:
                        active.remove(inst)
                        self._retry(inst.job, pending, done, inst.dead)
                        inst.job = None
            families = {j.request.family for j in pending}
            for family in families:
                idle = [i for i in self.live(family) if i.job is None and i.ready_since
                        is not None and now - i.ready_since >= DISCOVERY_GRACE]
                if family not in started and not self._complete(family, idle, now):
                    idle = []
                else:
                    started.add(family)
                own = self.starting(family) if self.starting is not None else None
                if self.live(family) or own:
                    waiting_since[family] = now
                elif own is False or now - waiting_since[family] > DISCOVERY_TIMEOUT:
                    for lost in [j for j in pending if j.request.family == family]:
                        pending.remove(lost)
                        done(lost.request, None, f'{lost.request.label}: no {family} solver '
                             f'instance in the ROS graph (start one: vd launch --solvers '
                             f'{family}=1, or {SOLVER_FAMILIES[family].executable} '
                             'on another host)', '')
                    continue
                for inst in sorted(idle, key=lambda i: i.runs):
                    queued = next((j for j in pending if j.request.family == family), None)
                    if queued is None:
                        break
                    pending.remove(queued)
                    self._send(inst, queued, goal_of)
                    active.append(inst)
            self.executor.spin_once(timeout_sec=0.01)
            now = time.monotonic()
            for inst in list(active):
                job = inst.job
                assert job is not None  # an active instance runs a job (_send)
                if job.handle is None and not job.send.done():
                    if now - job.last_news > ACCEPT_TIMEOUT * 2 ** job.resends:
                        # Fast DDS drops a goal response sent before the server has
                        # discovered this client's response reader: ask again, later
                        job.resends += 1
                        self._send(inst, job, goal_of, again=True)
                    continue
                if job.handle is None and job.send.done():
                    job.handle = job.send.result()
                    if not job.handle.accepted:
                        active.remove(inst)
                        inst.job = None
                        self._kill(inst, 'it rejected a goal')
                        self._retry(job, pending, done, 'goal rejected')
                        continue
                    job.result = job.handle.get_result_async()
                    job.results = [job.result]
                    job.last_news = now
                answered = next((f for f in job.results if f.done()), None)
                if answered is not None:
                    job.result = answered
                    active.remove(inst)
                    inst.job = None
                    inst.runs += 1
                    answer = job.result.result()
                    res = answer.result
                    if answer.status == GoalStatus.STATUS_SUCCEEDED and res.success:
                        try:
                            check_result(job.request, res.result)
                            done(job.request, outcome_from_msg(res.result), None, inst.node)
                        except RunError as err:
                            done(job.request, None, str(err), inst.node)
                    else:
                        done(job.request, None, res.message or f'{job.request.label}: goal '
                             f'ended with status {answer.status}', inst.node)
                elif job.result is not None and now - job.last_news > self.silence:
                    # silent: the result may have been sent and lost; the instance lives
                    job.results.append(job.handle.get_result_async())
                    job.last_news = now

    def _complete(self, family: str, ready: list[Instance], now: float) -> bool:
        """Say whether a family's goals may start on the ``ready`` instances (``expect``)."""
        want = self.expect.get(family, 1)
        if not ready:
            return False
        if len(ready) >= want:
            return True
        first = min(i.ready_since for i in ready if i.ready_since is not None)
        if now - first < self.expect_wait:
            return False
        if self.log is not None:
            self.log(f'{len(ready)} of the {want} expected {family} solver instances found '
                     f'after {self.expect_wait:.0f} s; the runs start on those (a later one '
                     'joins once it is discovered)')
        return True

    def _send(self, inst: Instance, job: _Job, goal_of, again: bool = False) -> None:
        """Send ``job`` to ``inst``; ``again``: the same instance, its answer never came."""
        if not again:
            job.attempts += 1
            job.resends = 0
        job.handle = job.result = None
        job.results = []
        job.last_news = time.monotonic()

        def on_feedback(_msg, job=job) -> None:
            job.last_news = time.monotonic()

        job.send = inst.client.send_goal_async(goal_of(job.request),
                                               feedback_callback=on_feedback)
        inst.job = job

    def _retry(self, job: _Job | None, pending: list[_Job], done: Done, why: str) -> None:
        if job is None:
            return
        if job.attempts >= ATTEMPTS:
            done(job.request, None, f'{job.request.label}: {job.attempts} solver instances '
                 f'died under this run (last: {why}); not retried', '')
        else:
            pending.insert(0, job)

    def cancel(self) -> None:
        """Ask every instance to drop the goal in progress (Ctrl-C)."""
        for inst in self.instances.values():
            if inst.job is not None and inst.job.handle is not None:
                future = inst.job.handle.cancel_goal_async()
                _spin_until(self.executor, future.done, 2.0)


class SolverGraph:
    """
    The ROS graph a sweep runs on: its own, or the caller's (``attach``).

    Its own: a private domain with a data server and ``counts`` solver processes per
    family, children of this process. ``attach``: the caller's domain, where ``vd
    launch`` or other hosts run the nodes.
    """

    def __init__(self, master, counts: Mapping[str, int], *, attach: bool = False,
                 log: Callable[[str], None] | None = None) -> None:
        self.master, self.counts, self.attach, self.log = master, dict(counts), attach, log
        self.procs: dict[str, subprocess.Popen] = {}
        self.claim: Any = None
        self.context: Any = None
        self.executor: Any = None
        self.node: Any = None
        self._logs: IO[str] | None = None

    def __enter__(self) -> Dispatcher:


        try:
            if self.attach:
                domain = int(os.environ.get('ROS_DOMAIN_ID', '0') or 0)
            else:
                self.claim = _claim_domain()
                domain = self.claim.domain
                self._start_processes(domain)
            self.context = rclpy.Context()
            rclpy.init(args=_ros_args(), context=self.context, domain_id=domain,
                       signal_handler_options=None)
            self.executor = SingleThreadedExecutor(context=self.context)
            self.node = Node('sweep_runner', context=self.context)
            self.executor.add_node(self.node)
        except BaseException:
            self.__exit__(None, None, None)
            raise
        alive = None if self.attach else (
            lambda name: self.procs[name].poll() is None if name in self.procs else None)
        starting = None if self.attach else self._starting
        return Dispatcher(self.node, self.executor, alive=alive, log=self.log,
                          expect=self.counts, starting=starting)

    def _starting(self, family: str) -> bool | None:
        """Whether a process started here for ``family`` runs (None: none was started)."""
        procs = [self.procs[n] for n in instance_names(family, self.counts.get(family, 0))
                 if n in self.procs]
        return any(p.poll() is None for p in procs) if procs else None

    def _start_processes(self, domain: int) -> None:
        env = dict(os.environ, ROS_DOMAIN_ID=str(domain), VD_PARENT_PID=str(os.getpid()),
                   ROS_AUTOMATIC_DISCOVERY_RANGE=os.environ.get(
                       'ROS_AUTOMATIC_DISCOVERY_RANGE', 'LOCALHOST'))
        self._logs = tempfile.TemporaryFile(mode='w+')

        def start(name: str, command: list[str]) -> None:
            self.procs[name] = subprocess.Popen(command, env=env, stdout=self._logs,
                                                stderr=subprocess.STDOUT,
                                                stdin=subprocess.DEVNULL,
                                                start_new_session=True)

        start('data_server', graph.command(graph.data_server(self.master, watch_period=0.0),
                                           ros_args=('--log-level', 'warn')))
        for family, count in self.counts.items():
            for name in instance_names(family, count):
                start(name, solver_command(family, name))

    def __exit__(self, *exc) -> None:

        if self.node is not None:
            self.executor.remove_node(self.node)
            self.node.destroy_node()
            self.executor.shutdown()
            self.node = None
        if self.context is not None:
            rclpy.try_shutdown(context=self.context)
            self.context = None
        stop_processes(list(self.procs.values()))
        if self.claim is not None:
            self.claim.release()
            self.claim = None

    def kill(self, name: str) -> None:
        """End one solver process at once (SIGKILL): the fault a sweep must survive."""
        self.procs[name].kill()


def solver_command(family: str, name: str) -> list[str]:
    """Return the command line of one solver instance named ``name``."""
    return graph.command(graph.solver(family, name), ros_args=('--log-level', 'warn'))


def parse_solvers(text: str) -> dict[str, int]:
    """``kc=2,steady_state=1`` (or a bare ``2``: that many of each needed family)."""
    out: dict[str, int] = {}
    aliases = {'analytical': 'steady_state', 'kc': 'kc', 'steady_state': 'steady_state',
               'vehicle': 'vehicle'}
    for item in filter(None, (p.strip() for p in text.split(','))):
        name, sep, count = item.partition('=')
        if not sep or name.strip() not in aliases:
            raise RunError(f'--solvers: expected FAMILY=N with FAMILY one of kc, analytical, '
                           f'vehicle, found {item!r}')
        try:
            n = int(count)
        except ValueError:
            n = 0
        if n < 1:
            raise RunError(f'--solvers: expected a positive number of instances, found {item!r}')
        out[aliases[name.strip()]] = n
    return out


def counts_for(requests: Sequence[RunRequest], solvers: int | Mapping[str, int]
               ) -> dict[str, int]:
    """Instances to start per family the requests need (``solvers`` each, or per family)."""
    families = sorted({r.family for r in requests})
    if isinstance(solvers, int):
        return dict.fromkeys(families, solvers)
    return {f: int(solvers.get(f, 1)) for f in families}


__all__ = ['Dispatcher', 'SolverGraph', 'Instance', 'instance_names', 'parse_instance',
           'solver_command', 'parse_solvers', 'counts_for']
