# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Runs events through the ROS graph: embedded (one process) or distributed.

Embedded: the data server, the solver nodes, a recorder per run and the event
runner's action client share one executor in this process. Distributed: each
node is its own process (the executables ``ros2 run`` starts), talking DDS on
loopback in a private domain; this process only sends the goals.

Everything a run needs is validated before anything starts (requests.py), so bad
input leaves nothing behind. Each run claims its ROS domain (domain.py) for its whole
life, and every result is matched to its request (configuration, event, model,
axle and the data hash of the configuration validated here) before it counts. A
bag becomes final only once its result is confirmed; an interrupted or failed
run removes its partial bag and says so.
"""
from __future__ import annotations

from collections.abc import Callable, Sequence
import os
from pathlib import Path
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from typing import Any

import rclpy
from rclpy.action import ActionClient
from rclpy.executors import MultiThreadedExecutor, SingleThreadedExecutor
from rclpy.node import Node
from rclpy.parameter import Parameter
from std_msgs.msg import UInt32
from std_srvs.srv import Trigger

from vd_data_server.nodes.data_server import DataServer
from vd_data_server.ros import names
from vd_data_server.ros.qos import LATEST
from vd_data_server.study import Study
from vd_events.bags.bag import PARTIAL_SUFFIX, read_bag
from vd_events.bags.recorder import FINISH_SERVICE, RECORDED_TOPIC, Recorder
from vd_events.errors import BagError, DomainError, Interrupted, RunError
from vd_events.orchestration import graph
from vd_events.orchestration.domain import claim_domain
from vd_events.orchestration.graph import solver_class
from vd_events.orchestration.requests import (
    Phases,
    RunOutcome,
    RunRequest,
    check_result,
    interrupted,
    validate,
)
from vd_interfaces.action import RunEvent
from vd_solvers.conversions import outcome_from_msg
from vd_solvers.families import FAMILIES, events_for
from vd_solvers.results import EventOutcome

#: s of silence (no result, no feedback) after which the result is asked for again: a
#: response Fast DDS dropped is not a dead solver (a dead one is told by its process exit)
GOAL_TIMEOUT = 60.0
SERVER_TIMEOUT = 20.0  # s: for the in-process action server and recorder to match
ACCEPT_TIMEOUT = 10.0  # s: for a goal to be accepted before it is sent again (doubling)
DISCOVERY_GRACE = 0.5  # s
#: s: after the bag is final, for the recorder process to exit before it is stopped
RECORDER_EXIT_WAIT = 10.0
CANCEL_WAIT = 2.0  # s: for an interrupted goal to be cancelled before the nodes stop
#: s: how often a long wait says what it waits for (on a terminal and in a log alike)
NOTICE_PERIOD = 30.0
#: s: longest wait of one spin while nothing happens (events end it at once); each spin
#: rebuilds the wait set, which costs the solver's worker thread the GIL
SPIN_PERIOD = 0.1


def _ros_args() -> list[str]:
    """
    Return the node arguments of in-process runs: log level fatal unless VD_VERBOSE.

    The CLI reports errors itself, so the nodes stay quiet.
    """
    return [] if os.environ.get('VD_VERBOSE') else ['--ros-args', '--log-level', 'fatal']


def _claim_domain():
    try:
        return claim_domain()
    except DomainError as err:
        raise RunError(str(err)) from None


class EventClient:
    """
    The event runner's action clients (one per solver family) on a node.

    The action names are relative: they resolve in ``node``'s namespace. Before the
    first goal to each family it waits ``discovery_grace`` s (see DISCOVERY_GRACE); nodes
    of one process share one DDS participant, which matches its own endpoints at once.
    """

    def __init__(self, node, discovery_grace: float = DISCOVERY_GRACE) -> None:


        self.node = node
        self.discovery_grace = discovery_grace
        self.warm: set[str] = set()
        self.running: list = []  # goal handles accepted and not finished (to cancel)
        self.clients = {name: ActionClient(node, RunEvent, family.action())
                        for name, family in FAMILIES.items()}

    @staticmethod
    def goal(request: RunRequest):
        """Return the RunEvent goal of ``request``."""
        return RunEvent.Goal(event=request.event, configuration=request.configuration,
                             model=request.model, fidelity=request.fidelity, axle=request.axle,
                             overrides=list(request.overrides),
                             parameters=list(request.parameters))


def _spin_until(executor, predicate: Callable[[], bool], timeout: float) -> bool:
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if predicate():
            return True
        executor.spin_once(timeout_sec=SPIN_PERIOD)
    return predicate()


#: says whether the peers a wait depends on still live: None, or why they do not
Alive = Callable[[], 'str | None']


def _always() -> str | None:
    return None


def _wait_for(executor, done: Callable[[], bool], alive: Alive, what: str,
              notice: Callable[[str], None] | None = None) -> None:
    """
    Spin until ``done()``: no deadline, a busy machine only makes it slower.

    A dead peer ends the wait at once with RunError (``alive()`` says why); every
    NOTICE_PERIOD s ``notice`` (if given) hears what is still awaited.
    """
    since = last = time.monotonic()
    while not done():
        dead = alive()
        if dead is not None:
            raise RunError(f'{what}: {dead}')
        executor.spin_once(timeout_sec=SPIN_PERIOD)
        now = time.monotonic()
        if notice is not None and now - last >= NOTICE_PERIOD:
            last = now
            notice(f'still waiting ({now - since:.0f} s): {what}')


def send_goal(executor, client: EventClient, request: RunRequest,
              progress: Callable[[float, str], None], alive: Alive = _always,
              notice: Callable[[str], None] | None = None):
    """
    Send one goal and wait for its result; returns (success, message, EventResult).

    Nothing here waits on a clock for work that may take longer: the server's
    appearance, the acceptance (a request Fast DDS dropped is sent again, at growing
    intervals) and the result (asked for again after GOAL_TIMEOUT s of silence) are
    awaited while ``alive()`` says the solver lives.
    """
    action = client.clients[request.family]
    name = client.node.resolve_topic_name(FAMILIES[request.family].action())
    _wait_for(executor, action.server_is_ready, alive,
              f'{request.label}: no solver answers on {name}', notice)
    if request.family not in client.warm:
        # Fast DDS drops a service response sent before the server has discovered the
        # client's response reader ("failed to send response"): give discovery a moment.
        _spin_until(executor, lambda: False, client.discovery_grace)
        client.warm.add(request.family)
    last_news = [time.monotonic()]  # the latest feedback: a goal that reports is alive

    def on_feedback(fb) -> None:
        last_news[0] = time.monotonic()
        progress(fb.feedback.progress, fb.feedback.stage)

    interval = ACCEPT_TIMEOUT
    while True:
        send = action.send_goal_async(client.goal(request), feedback_callback=on_feedback)
        if _spin_until(executor, lambda: send.done() or alive() is not None, interval):
            break
        interval *= 2  # not accepted yet: sent again, waiting longer each time
    _wait_for(executor, send.done, alive, f'{request.label}: the goal was not accepted')
    handle = send.result()
    if not handle.accepted:
        raise RunError(f'{request.label}: goal rejected (the solver logs why)')
    futures = [handle.get_result_async()]
    client.running.append(handle)
    last_news[0] = time.monotonic()

    def answered() -> bool:
        if any(f.done() for f in futures):
            return True
        if time.monotonic() - last_news[0] > GOAL_TIMEOUT:
            # silent this long: ask again (the server keeps the result for a while)
            futures.append(handle.get_result_async())
            last_news[0] = time.monotonic()
        return False

    def solver_alive() -> str | None:
        return alive() or (None if action.server_is_ready()
                           else f'the solver left the graph ({name})')

    def silent_notice(text: str) -> None:  # a goal that reports progress needs no notice
        if notice is not None and time.monotonic() - last_news[0] >= NOTICE_PERIOD:
            notice(text)

    _wait_for(executor, answered, solver_alive,
              f'{request.label}: no result and no progress', silent_notice)
    client.running.remove(handle)
    result = next(f for f in futures if f.done()).result().result
    return result.success, result.message, result.result


def _notice(text: str) -> None:
    """Say on stderr what a long wait is waiting for (stdout stays the result's)."""
    print(text, file=sys.stderr, flush=True)


def _run_goal(executor, client: EventClient, request: RunRequest,
              progress: Callable[[RunRequest, float, str], None] | None,
              alive: Alive = _always) -> EventOutcome:
    """One goal to its solver; the result as an EventOutcome, or RunError."""
    ok, message, result = send_goal(executor, client, request,
                                     lambda p, s: progress(request, p, s) if progress else None,
                                     alive, _notice)
    if not ok:
        raise RunError(message)
    check_result(request, result)
    return outcome_from_msg(result)


def run_embedded(master: Path, requests: Sequence[RunRequest],
                 progress: Callable[[RunRequest, float, str], None] | None = None,
                 namespace: str = names.DEFAULT_NAMESPACE, timings: dict | None = None,
                 study: Study | None = None,
                 on_done: Callable[[RunOutcome], None] | None = None) -> list[RunOutcome]:
    """
    All nodes in this process, in ``namespace``; a recorder node per run with a bag.

    ``study``: ``master`` as the caller loaded and validated it (the data server serves
    it instead of loading the files again).
    Only the solvers the requests need are started. A multi-threaded executor: a
    solver's execute callback (a goal may take minutes) runs in a worker thread while
    this thread keeps spinning the accept and result futures, the feedback and the
    recorder. ``timings`` (if given) receives the seconds of each phase; ``on_done``
    (if given) hears each run's outcome as soon as it is complete.
    """
    clock = Phases(timings)


    families = sorted({r.family for r in requests})
    classes = [solver_class(f) for f in families]
    clock.lap('imports')
    os.environ.setdefault('ROS_AUTOMATIC_DISCOVERY_RANGE', 'LOCALHOST')
    claim = _claim_domain()
    context = rclpy.Context()
    rclpy.init(args=_ros_args(), context=context, domain_id=claim.domain,
               signal_handler_options=None)
    executor = MultiThreadedExecutor(num_threads=EMBEDDED_THREADS, context=context)
    # a private graph: no parameter services and no /rosout (fewer DDS endpoints to create
    # and discover, a smaller wait set for every spin)
    private: dict[str, Any] = {'context': context, 'namespace': namespace,
                               'start_parameter_services': False, 'enable_rosout': False}
    server = DataServer(**private, study=study, parameter_overrides=[
        Parameter('master_file', value=str(master)), Parameter('watch_period', value=0.0)])
    solvers = [cls(**private) for cls in classes]
    client_node = Node('event_runner', **private)
    nodes: list[Node] = [server, *solvers, client_node]
    for node in nodes:
        executor.add_node(node)
    client = EventClient(client_node, discovery_grace=0.0)
    outcomes: list[RunOutcome] = []
    clock.lap('graph_start')
    try:
        _wait_for(executor, lambda: all(len(n.configurations) > 0 and n.status is not None
                                        for n in solvers), _always,
                  'the solvers have not received the configurations', _notice)
        clock.lap('discovery')
        for request in requests:
            recorder = None
            try:
                if request.bag is not None:
                    recorder = Recorder(bag=str(request.bag), **private,
                                        parameter_overrides=[Parameter(
                                            'configurations', value=[request.configuration])])
                    executor.add_node(recorder)
                    # let the recorder's latched subscriptions catch up before the run
                    _spin_until(executor, lambda: recorder.counts[names.CONFIGURATION] > 0
                                or recorder.error is not None, 5.0)
                t0 = time.perf_counter()
                clock.lap('record')  # the recorder's start
                outcome = _run_goal(executor, client, request, progress)
                clock.lap('solve')
                bag = None
                if recorder is not None:
                    # one message (the result) brings the whole run: in this process
                    # it arrives, however busy the machine
                    _wait_for(executor, lambda: recorder.complete >= 1 or
                              recorder.error is not None, _always,
                              f'{request.label}: the recorder has not written the result',
                              _notice)
                    try:
                        bag = recorder.stop()
                    except BagError as err:
                        raise RunError(f'{request.label}: {err}') from None
                    clock.lap('record')
                outcomes.append(RunOutcome(request, outcome, bag,
                                           timings={'run': time.perf_counter() - t0}))
            except RunError as err:
                outcomes.append(RunOutcome(request, None, None, str(err)))
            except KeyboardInterrupt:
                _cancel_running(executor, client)
                raise Interrupted(interrupted(request)) from None
            finally:
                if recorder is not None:
                    recorder.abort()  # removes the partial bag unless stop() finished it
                    executor.remove_node(recorder)
                    recorder.destroy_node()
            if on_done is not None:
                on_done(outcomes[-1])
    finally:
        clock.lap('record')
        for node in nodes:
            executor.remove_node(node)
            node.destroy_node()
        executor.shutdown(timeout_sec=CANCEL_WAIT)
        rclpy.try_shutdown(context=context)
        claim.release()
        clock.lap('shutdown')
    return outcomes


#: worker threads of an embedded run: a goal's execute callback + everything else
EMBEDDED_THREADS = 4


def _cancel_running(executor, client: EventClient) -> None:
    """Ask the solver to drop the goal in progress (it stops at its next step)."""
    for handle in list(client.running):
        future = handle.cancel_goal_async()
        _spin_until(executor, future.done, CANCEL_WAIT)
    client.running.clear()


def run_distributed(master: Path, requests: Sequence[RunRequest],
                    progress: Callable[[RunRequest, float, str], None] | None = None,
                    namespace: str = names.DEFAULT_NAMESPACE,
                    on_done: Callable[[RunOutcome], None] | None = None) -> list[RunOutcome]:
    """
    One process per node (as ``ros2 run`` starts them), DDS on loopback, in ``namespace``.

    ``on_done`` (if given) hears each run's outcome as soon as it is complete.

    The nodes are this process's children in their own session (a Ctrl-C at the
    terminal reaches only this process, which stops them in order) and end with
    it however it ends (node_main.die_with_parent, also after ``kill -9``).
    """
    claim = _claim_domain()
    env = dict(os.environ, ROS_DOMAIN_ID=str(claim.domain), VD_PARENT_PID=str(os.getpid()),
               ROS_AUTOMATIC_DISCOVERY_RANGE=os.environ.get('ROS_AUTOMATIC_DISCOVERY_RANGE',
                                                            'LOCALHOST'))
    # the nodes' output goes to one log file, shown when a run fails
    logs = tempfile.TemporaryFile(mode='w+')

    def start(command: list[str]) -> subprocess.Popen:
        return subprocess.Popen(command, env=env, stdout=logs, stderr=subprocess.STDOUT,
                                stdin=subprocess.DEVNULL, start_new_session=True)

    procs: list[subprocess.Popen] = []
    context = None
    node = None
    executor = None
    client = None
    outcomes: list[RunOutcome] = []
    recorder = None
    request = None
    try:
        quiet = ('--log-level', 'warn')
        try:
            procs.extend(start(graph.command(spec, namespace, quiet)) for spec in graph.graph(
                master, watch_period=0.0, families={r.family for r in requests}))
        except FileNotFoundError as err:
            raise RunError(str(err)) from None
        context = rclpy.Context()
        rclpy.init(context=context, domain_id=claim.domain, signal_handler_options=None)
        executor = SingleThreadedExecutor(context=context)
        node = Node('event_runner', context=context, namespace=namespace)
        executor.add_node(node)
        client = EventClient(node)
        finish = node.create_client(Trigger, FINISH_SERVICE)
        recorded = [0]  # results the current run's recorder says it has written

        def on_recorded(msg) -> None:
            recorded[0] = msg.data

        node.create_subscription(UInt32, RECORDED_TOPIC, on_recorded, LATEST)

        def alive() -> str | None:
            """Say why the graph is dead: a node process that exited is the one signal."""
            for proc in [*procs, *([recorder] if recorder is not None else [])]:
                if proc.poll() is not None:
                    name = Path(str(proc.args[0] if isinstance(proc.args, list)
                                    else proc.args)).name
                    return f"the node process '{name}' exited with code {proc.returncode}"
            return None

        for request in requests:
            recorded[0] = 0
            family = FAMILIES[request.family]
            if request.bag is not None:
                recorder = start(graph.command(graph.NodeSpec('vd_events', 'recorder', {
                    'bag': str(request.bag), 'configurations': [request.configuration]}),
                    namespace))
            t0 = time.perf_counter()
            try:
                if recorder is not None:
                    # the recorder's subscriptions must be matched before the results flow
                    _wait_for(executor, lambda: node.count_subscribers(
                        family.result_topic) >= 1, alive,
                        f'{request.label}: the recorder has not started', _notice)
                outcome = _run_goal(executor, client, request, progress, alive)
                bag = None
                if recorder is not None:
                    _wait_for(executor, lambda: recorded[0] >= 1, alive,
                              f'{request.label}: the recorder has not written the result',
                              _notice)
                    bag = _finish_recording(executor, finish, recorder, request)
                    recorder = None
                    topics = {m.topic for m in read_bag(bag)}
                    if node.resolve_topic_name(family.result_topic) not in topics:
                        raise RunError(f'{request.label}: the recorder missed the result')
                outcomes.append(RunOutcome(request, outcome, bag,
                                           timings={'run': time.perf_counter() - t0}))
            except RunError as err:
                logs.seek(0)
                tail = ''.join(logs.readlines()[-5:]).strip()
                outcomes.append(RunOutcome(request, None, None,
                                           f'{err}' + (f'\nnode output:\n{tail}' if tail else '')))
                _drop_recording(recorder, request)
                recorder = None
            if on_done is not None:
                on_done(outcomes[-1])
        request = None
    except KeyboardInterrupt:
        if client is not None:
            _cancel_running(executor, client)
        raise Interrupted(interrupted(request) if request is not None
                          else 'interrupted') from None
    finally:
        if request is not None:
            _drop_recording(recorder, request)
        if node is not None and executor is not None:
            executor.remove_node(node)
            node.destroy_node()
            executor.shutdown()
        if context is not None:
            rclpy.try_shutdown(context=context)
        stop_processes(procs)
        claim.release()
    return outcomes


def _finish_recording(executor, finish, recorder: subprocess.Popen, request: RunRequest) -> Path:
    """
    Have the recorder close the bag under its final name (the result is confirmed).

    Waits on the events themselves: the service, then its answer or the recorder's exit
    (an answer Fast DDS dropped still leaves the final bag behind).
    """
    assert request.bag is not None

    def recorder_alive() -> str | None:
        return (None if recorder.poll() is None
                else f'the recorder exited with code {recorder.returncode}')

    _wait_for(executor, finish.service_is_ready, recorder_alive,
              f'{request.label}: the recorder does not answer', _notice)
    future = finish.call_async(Trigger.Request())
    _wait_for(executor, lambda: future.done() or recorder.poll() is not None, _always,
              f'{request.label}: the recorder has not finished the bag', _notice)
    if future.done() and not future.result().success:
        raise RunError(f'{request.label}: {future.result().message}')
    try:
        recorder.wait(timeout=RECORDER_EXIT_WAIT)
    except subprocess.TimeoutExpired:
        stop_processes([recorder])  # it lingers after finishing: the bag is closed
    if not (request.bag / 'metadata.yaml').is_file():
        raise RunError(f'{request.label}: the recorder did not finish the bag (exit code '
                       f'{recorder.returncode})')
    return request.bag


def _drop_recording(recorder: subprocess.Popen | None, request: RunRequest) -> None:
    """
    Clean up after a failed or interrupted run: nothing that looks like a result stays.

    Its recorder is stopped (which removes its partial bag); validate() made sure the
    paths did not exist before, so this removes only this run's files.
    """
    if recorder is not None:
        stop_processes([recorder])
    if request.bag is not None:
        shutil.rmtree(request.bag, ignore_errors=True)
        shutil.rmtree(request.bag.with_name(request.bag.name + PARTIAL_SUFFIX),
                      ignore_errors=True)


def stop_processes(procs: Sequence[subprocess.Popen], timeout: float = 10.0) -> None:
    """
    Send SIGINT (a node's clean shutdown) to every process still running, then wait.

    What does not stop in time is killed. A Ctrl-C during the wait does not cut it short.
    """
    for proc in procs:
        if proc.poll() is None:
            proc.send_signal(signal.SIGINT)
    for proc in procs:
        while True:
            try:
                proc.wait(timeout=timeout)
            except subprocess.TimeoutExpired:
                proc.kill()
                proc.wait()
            except KeyboardInterrupt:
                continue
            break


__all__ = ['RunRequest', 'RunOutcome', 'RunError', 'Interrupted', 'BagError', 'validate',
           'check_result', 'run_embedded', 'run_distributed', 'events_for', 'stop_processes']
