"""Runs events through the ROS graph: embedded (one process) or distributed.

Embedded: the data server, the solver nodes, a recorder per run and the event
runner's action client share one executor in this process. Distributed: each
node is its own process (the executables ``ros2 run`` starts), talking DDS on
loopback in a private domain; this process only sends the goals.

Everything a run needs is validated before anything starts, so bad input
leaves nothing behind.
"""
from __future__ import annotations

import os
import random
import shutil
import signal
import subprocess
import tempfile
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path

from vd_data_server.errors import DataError
from vd_data_server.master import parse_set, with_overrides
from vd_data_server.study import Study
from vd_solvers.analytical.events import EVENT_MODELS as ANALYTICAL_EVENTS
from vd_solvers.analytical.events import EVENT_PARAMS as ANALYTICAL_PARAMS
from vd_solvers.event_params import parse_params
from vd_solvers.kc.from_config import EVENT_PARAMS as KC_PARAMS
from vd_solvers.results import EventOutcome
from vd_solvers.vehicle.events import EVENT_PARAMS as VEHICLE_PARAMS

from .bag import BagError, check_bag_path

#: model -> (solver family, events it runs)
FAMILIES = {"bicycle": "steady_state", "two_track": "steady_state", "kc": "kc",
            "vehicle": "vehicle"}
ALL_EVENTS = ("steady_state_circular", "handling_diagram", "parallel_wheel_travel",
              "opposite_wheel_travel", "lateral_force", "longitudinal_force", "steering",
              "aligning_torque", "constant_radius_turn", "sine_with_dwell", "step_steer")
MODELS = ("bicycle", "two_track", "kc", "vehicle")
GOAL_TIMEOUT = 60.0  # s: a solver that does not answer by then has died or hung
SERVER_TIMEOUT = 20.0  # s: for the action server (a process) to appear
ACCEPT_TIMEOUT = 10.0  # s: for a goal to be accepted before it is sent again
GOAL_ATTEMPTS = 3
DISCOVERY_GRACE = 0.5  # s


class RunError(Exception):
    """A run could not start or did not finish (message names configuration and event)."""


@dataclass(frozen=True)
class RunRequest:
    event: str
    configuration: str
    model: str
    fidelity: str = "rigid"
    axle: str = ""
    overrides: tuple[str, ...] = ()
    parameters: tuple[str, ...] = ()
    bag: Path | None = None

    @property
    def family(self) -> str:
        return FAMILIES[self.model]

    @property
    def label(self) -> str:
        return f"configuration '{self.configuration}', event '{self.event}', model '{self.model}'"


@dataclass
class RunOutcome:
    request: RunRequest
    outcome: EventOutcome | None
    bag: Path | None
    error: str | None = None
    timings: dict[str, float] = field(default_factory=dict)


def events_for(model: str) -> tuple[str, ...]:
    if model in ("bicycle", "two_track"):
        return tuple(e for e, models in ANALYTICAL_EVENTS.items() if model in models)
    if model == "kc":
        return tuple(KC_PARAMS)
    if model == "vehicle":
        return tuple(VEHICLE_PARAMS)
    return ()


def event_params(model: str, event: str):
    if model == "kc":
        return KC_PARAMS[event]
    if model == "vehicle":
        return VEHICLE_PARAMS[event]
    return ANALYTICAL_PARAMS[event]


def validate(study: Study, request: RunRequest) -> None:
    """Every check that can be made before starting: raises DataError / RunError / BagError."""
    if request.event not in ALL_EVENTS:
        raise RunError(f"unknown event '{request.event}' (events: {', '.join(ALL_EVENTS)})")
    if request.model not in MODELS:
        raise RunError(f"unknown model '{request.model}' (models: {', '.join(MODELS)})")
    if request.model not in FAMILIES:
        raise RunError(f"model '{request.model}' is not available yet (available: "
                       f"{', '.join(FAMILIES)})")
    if request.event not in events_for(request.model):
        raise RunError(f"event '{request.event}' does not run on model '{request.model}' "
                       f"(its events: {', '.join(events_for(request.model))})")
    if request.fidelity not in ("rigid", "flexible"):
        raise RunError(f"unknown fidelity '{request.fidelity}' (rigid, flexible)")
    # the K&C model has flexible components; the full vehicle passes the fidelity to its
    # K&C maps (flexible K&C results when the configuration has flex data)
    if request.fidelity == "flexible" and request.model not in ("kc", "vehicle"):
        raise RunError(f"fidelity 'flexible' is available for models 'kc' and 'vehicle' only "
                       f"(model '{request.model}' has no flexible components)")
    if request.model == "kc" and request.axle not in ("front", "rear"):
        raise RunError(f"K&C events need --axle front or rear (found '{request.axle}')")
    if request.model != "kc" and request.axle:
        raise RunError(f"model '{request.model}' is a whole-vehicle model: no --axle")
    if request.configuration not in study.configurations:
        raise DataError(f"configuration '{request.configuration}' does not exist (available: "
                        f"{', '.join(study.configuration_names)})", file=str(study.master.path))
    config = with_overrides(study.configurations[request.configuration],
                            parse_set(request.overrides))
    if request.model == "kc" and request.event == "steering" and (
            request.axle != "front" or "steering" not in config.groups):
        raise RunError(f"event 'steering' needs a steered axle: the {request.axle} axle of "
                       f"'{request.configuration}' has no steering")
    if request.fidelity == "flexible":
        for axle in ([request.axle] if request.model == "kc" else ["front", "rear"]):
            if f"{axle}_flex" not in config.groups:
                raise RunError(f"configuration '{request.configuration}' has no flexible "
                               f"components on the {axle} axle (no {axle}_flex group in the "
                               "master file)")
    parse_params(request.event, event_params(request.model, request.event), request.parameters)
    if request.bag is not None:
        check_bag_path(request.bag)


def _ros_args() -> list[str]:
    """Node log level for in-process runs: the CLI reports errors itself, so the nodes
    stay quiet unless VD_VERBOSE is set."""
    return [] if os.environ.get("VD_VERBOSE") else ["--ros-args", "--log-level", "fatal"]


def _private_domain() -> int:
    return int(os.environ.get("VD_DOMAIN_ID", random.randint(101, 215)))


class _Client:
    """The event runner's action clients (one per solver family) on a node."""

    def __init__(self, node) -> None:
        from rclpy.action import ActionClient
        from vd_interfaces.action import RunEvent

        self.node = node
        self.warm: set[str] = set()
        self.clients = {family: ActionClient(node, RunEvent, f"/vd/{family}/run_event")
                        for family in set(FAMILIES.values())}

    def goal(self, request: RunRequest):
        from vd_interfaces.action import RunEvent

        return RunEvent.Goal(event=request.event, configuration=request.configuration,
                             model=request.model, fidelity=request.fidelity, axle=request.axle,
                             overrides=list(request.overrides),
                             parameters=list(request.parameters))


def _spin_until(executor, predicate: Callable[[], bool], timeout: float) -> bool:
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if predicate():
            return True
        executor.spin_once(timeout_sec=0.02)
    return predicate()


def _send(executor, client: _Client, request: RunRequest, progress: Callable[[float, str], None]):
    """Send one goal and wait for its result; returns (success, message, EventResult)."""
    action = client.clients[request.family]
    if not _spin_until(executor, action.server_is_ready, SERVER_TIMEOUT):
        raise RunError(f"{request.label}: no solver answers on /vd/{request.family}/run_event")
    if request.family not in client.warm:
        # Fast DDS drops a service response sent before the server has discovered the
        # client's response reader ("failed to send response"): give discovery a moment.
        _spin_until(executor, lambda: False, DISCOVERY_GRACE)
        client.warm.add(request.family)
    for _attempt in range(GOAL_ATTEMPTS):
        send = action.send_goal_async(client.goal(request),
                                      feedback_callback=lambda fb: progress(
                                          fb.feedback.progress, fb.feedback.stage))
        if _spin_until(executor, send.done, ACCEPT_TIMEOUT):
            break
    else:
        raise RunError(f"{request.label}: the solver did not accept the goal in time")
    handle = send.result()
    if not handle.accepted:
        raise RunError(f"{request.label}: goal rejected")
    result_future = handle.get_result_async()
    if not _spin_until(executor, result_future.done, GOAL_TIMEOUT):
        raise RunError(f"{request.label}: no result after {GOAL_TIMEOUT:.0f} s (solver died?)")
    result = result_future.result().result
    return result.success, result.message, result.result


def _run_goal(executor, client: _Client, request: RunRequest,
              progress: Callable[[RunRequest, float, str], None] | None) -> EventOutcome:
    """One goal to its solver; the result as an EventOutcome, or RunError."""
    from vd_solvers.conversions import outcome_from_msg

    ok, message, result = _send(executor, client, request,
                                lambda p, s: progress(request, p, s) if progress else None)
    if not ok:
        raise RunError(message)
    return outcome_from_msg(result)


def run_embedded(master: Path, requests: Sequence[RunRequest],
                 progress: Callable[[RunRequest, float, str], None] | None = None,
                 ) -> list[RunOutcome]:
    """All nodes in this process on one executor; a recorder node per run with a bag."""
    import rclpy
    from rclpy.executors import SingleThreadedExecutor
    from rclpy.node import Node
    from rclpy.parameter import Parameter

    from vd_data_server.data_server_node import DataServer
    from vd_solvers.analytical_node import AnalyticalSolver
    from vd_solvers.kc_node import KCSolver
    from vd_solvers.vehicle_node import VehicleSolver

    from .recorder_node import Recorder

    os.environ.setdefault("ROS_AUTOMATIC_DISCOVERY_RANGE", "LOCALHOST")
    context = rclpy.Context()
    rclpy.init(args=_ros_args(), context=context, domain_id=_private_domain(),
               signal_handler_options=None)
    executor = SingleThreadedExecutor(context=context)
    nodes = [DataServer(context=context, parameter_overrides=[
                 Parameter("master_file", value=str(master)), Parameter("watch_period",
                                                                        value=0.0)]),
             AnalyticalSolver(context=context), KCSolver(context=context),
             VehicleSolver(context=context)]
    client_node = Node("event_runner", context=context)
    nodes.append(client_node)
    for node in nodes:
        executor.add_node(node)
    client = _Client(client_node)
    solvers = nodes[1:4]
    outcomes: list[RunOutcome] = []
    try:
        # a single-threaded executor: every solver must hold the configurations before
        # a goal arrives (a solver waiting inside a goal would block the executor)
        _spin_until(executor, lambda: all(len(n.configurations) > 0 and n.status is not None
                                          for n in solvers), SERVER_TIMEOUT)
        for request in requests:
            recorder = None
            if request.bag is not None:
                recorder = Recorder(context=context, bag=str(request.bag),
                                    parameter_overrides=[Parameter(
                                        "configurations", value=[request.configuration])])
                executor.add_node(recorder)
                # let the recorder's latched subscriptions catch up before the run
                _spin_until(executor, lambda: recorder.counts["/vd/configuration"] > 0, 5.0)
            t0 = time.perf_counter()
            try:
                outcome = _run_goal(executor, client, request, progress)
                bag = None
                if recorder is not None:
                    if not _spin_until(executor, lambda: recorder.complete >= 1, 10.0):
                        raise RunError(f"{request.label}: the recorder did not record the "
                                       "result")
                    bag = recorder.stop()
                outcomes.append(RunOutcome(request, outcome, bag,
                                           timings={"run": time.perf_counter() - t0}))
            except RunError as err:
                if recorder is not None:
                    recorder.abort()
                outcomes.append(RunOutcome(request, None, None, str(err)))
            finally:
                if recorder is not None:
                    executor.remove_node(recorder)
                    recorder.destroy_node()
    finally:
        for node in nodes:
            executor.remove_node(node)
            node.destroy_node()
        executor.shutdown()
        rclpy.try_shutdown(context=context)
    return outcomes


def _executable(package: str, name: str) -> str:
    from ament_index_python.packages import get_package_prefix

    path = Path(get_package_prefix(package)) / "lib" / package / name
    if not path.exists():
        raise RunError(f"executable {path} not found (is the workspace built?)")
    return str(path)


def run_distributed(master: Path, requests: Sequence[RunRequest],
                    progress: Callable[[RunRequest, float, str], None] | None = None,
                    ) -> list[RunOutcome]:
    """One process per node (as ``ros2 run`` starts them), DDS on loopback."""
    import rclpy
    from rclpy.executors import SingleThreadedExecutor
    from rclpy.node import Node

    from rclpy.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy
    from std_msgs.msg import UInt32

    from .bag import read_bag
    from .recorder_node import RECORDED_TOPIC

    domain = _private_domain()
    env = dict(os.environ, ROS_DOMAIN_ID=str(domain),
               ROS_AUTOMATIC_DISCOVERY_RANGE=os.environ.get("ROS_AUTOMATIC_DISCOVERY_RANGE",
                                                            "LOCALHOST"))
    # the nodes' output goes to one log file, shown when a run fails
    logs = tempfile.TemporaryFile(mode="w+")
    procs = [
        subprocess.Popen([_executable("vd_data_server", "data_server"), "--ros-args",
                          "--log-level", "warn", "-p",
                          f"master_file:={master}", "-p", "watch_period:=0.0"], env=env,
                         stdout=logs, stderr=subprocess.STDOUT),
        *(subprocess.Popen([_executable("vd_solvers", exe), "--ros-args", "--log-level",
                            "warn"], env=env, stdout=logs, stderr=subprocess.STDOUT)
          for exe in sorted({f"{'analytical' if f == 'steady_state' else f}_solver"
                             for f in {r.family for r in requests}})),
    ]
    context = rclpy.Context()
    rclpy.init(context=context, domain_id=domain, signal_handler_options=None)
    executor = SingleThreadedExecutor(context=context)
    node = Node("event_runner", context=context)
    executor.add_node(node)
    client = _Client(node)
    recorded = [0]  # results the current run's recorder says it has written

    def on_recorded(msg) -> None:
        recorded[0] = msg.data

    node.create_subscription(UInt32, RECORDED_TOPIC, on_recorded, QoSProfile(
        depth=1, reliability=ReliabilityPolicy.RELIABLE,
        durability=DurabilityPolicy.TRANSIENT_LOCAL))
    outcomes: list[RunOutcome] = []
    try:
        for request in requests:
            recorder = None
            recorded[0] = 0
            if request.bag is not None:
                recorder = subprocess.Popen(
                    [_executable("vd_events", "recorder"), "--ros-args", "-p",
                     f"bag:={request.bag}", "-p", f"configurations:=['{request.configuration}']"],
                    env=env, stdout=logs, stderr=subprocess.STDOUT)
            t0 = time.perf_counter()
            try:
                if recorder is not None:
                    # the recorder's subscriptions must be matched before the results flow
                    topics = (f"/vd/{request.family}/result", f"/vd/{request.family}/state")
                    if not _spin_until(executor, lambda: all(node.count_subscribers(t) >= 1
                                                             for t in topics), SERVER_TIMEOUT):
                        raise RunError(f"{request.label}: the recorder did not start")
                outcome = _run_goal(executor, client, request, progress)
                bag = None
                if recorder is not None:
                    if not _spin_until(executor, lambda: recorded[0] >= 1, 10.0):
                        raise RunError(f"{request.label}: the recorder did not record the result")
                    recorder.send_signal(signal.SIGINT)
                    recorder.wait(timeout=20)
                    recorder = None
                    topics = {m.topic for m in read_bag(request.bag)}
                    if f"/vd/{request.family}/result" not in topics:
                        raise RunError(f"{request.label}: the recorder missed the result")
                    bag = request.bag
                outcomes.append(RunOutcome(request, outcome, bag,
                                           timings={"run": time.perf_counter() - t0}))
            except RunError as err:
                logs.seek(0)
                tail = "".join(logs.readlines()[-5:]).strip()
                outcomes.append(RunOutcome(request, None, None,
                                           f"{err}" + (f"\nnode output:\n{tail}" if tail else "")))
                if recorder is not None:
                    recorder.send_signal(signal.SIGINT)
                    recorder.wait(timeout=20)
                    recorder = None
                if request.bag is not None:
                    # the run failed: no bag may look like a result (validate() made sure
                    # the path did not exist before, so this removes only our own files)
                    shutil.rmtree(request.bag, ignore_errors=True)
                    shutil.rmtree(request.bag.with_name(request.bag.name + ".partial"),
                                  ignore_errors=True)
            finally:
                if recorder is not None:
                    recorder.send_signal(signal.SIGINT)
                    recorder.wait(timeout=20)
    finally:
        executor.remove_node(node)
        node.destroy_node()
        executor.shutdown()
        rclpy.try_shutdown(context=context)
        stop_processes(procs)
    return outcomes


def stop_processes(procs: Sequence[subprocess.Popen], timeout: float = 10.0) -> None:
    """SIGINT (a node's clean shutdown) to every process still running, then wait;
    kill what does not stop in time."""
    for proc in procs:
        if proc.poll() is None:
            proc.send_signal(signal.SIGINT)
    for proc in procs:
        try:
            proc.wait(timeout=timeout)
        except subprocess.TimeoutExpired:
            proc.kill()


__all__ = ["RunRequest", "RunOutcome", "RunError", "BagError", "validate", "run_embedded",
           "run_distributed", "events_for", "stop_processes"]
