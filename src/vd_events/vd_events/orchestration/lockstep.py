# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
``vd launch --lockstep``: the lock-step vehicle and the example controller, closed loop.

Embedded (one process, one events executor, messages over DDS all the same): the
``vehicle_solver`` node in ``lockstep`` mode, the ``path_follower`` example controller
and, with a bag, a recorder of the co-simulation topics (``/clock``, state, odometry,
TF, the commands) whose log time is the message's simulation-time stamp, so Foxglove
plays the car along its path. Distributed: the two nodes as their own processes
(``ros2 run vd_solvers vehicle_solver --ros-args -p mode:=lockstep`` and
``ros2 run vd_events path_follower``), in the caller's ROS domain.

:func:`run_lockstep` returns the session's outcome: status, steps, wall time, steps per
second and where the time went (model step, message building and publishing, the rest:
DDS transport, executor and the controller).
"""
from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
import time

from nav_msgs.msg import Odometry
import rclpy
from rclpy.experimental import EventsExecutor
from rclpy.node import Node
from rclpy.parameter import Parameter
from rosgraph_msgs.msg import Clock
from std_msgs.msg import String

from tf2_msgs.msg import TFMessage
from vd_data_server.ros.qos import STATES, STATUS, profile_of
from vd_events.bags.bag import BagWriter, check_bag_path, offered_profiles
from vd_events.orchestration.path_follower import PathFollower
from vd_interfaces.msg import VehicleCommand, VehicleState
from vd_solvers.conversions import InPlaceMessage
from vd_solvers.nodes.lockstep import STATUS_TOPIC
from vd_solvers.nodes.vehicle import VehicleSolver


@dataclass
class LockstepOutcome:
    status: str
    steps: int
    simulated: float  # s
    wall: float  # s
    stale: int
    timings: dict[str, float] = field(default_factory=dict)  # s per part
    bag: Path | None = None
    path: list[tuple[float, float, float]] = field(default_factory=list)  # t, x, y

    @property
    def steps_per_second(self) -> float:
        return self.steps / self.wall if self.wall > 0 else float('nan')

    def to_json(self) -> dict:
        per = {k: v / self.steps * 1e6 if self.steps else float('nan')
               for k, v in self.timings.items()}
        return {'status': self.status, 'steps': self.steps, 'simulated_s': self.simulated,
                'wall_s': self.wall, 'steps_per_second': self.steps_per_second,
                'stale_commands': self.stale, 'us_per_step': per,
                'bag': str(self.bag) if self.bag else None}


#: topics a lock-step bag holds
RECORDED = ('/clock', '/vd/vehicle/state', '/vd/vehicle/odom', '/tf', '/vd/vehicle/command')


def run_lockstep(*, configuration: str = '', master: Path | None = None, duration: float = 20.0,
                 step: float = 0.005, radius: float = 40.0, speed: float = 12.0,
                 bag: Path | None = None, controller: bool = True, track: bool = True,
                 wall_limit: float = 600.0) -> LockstepOutcome:
    """
    Run the pair closed loop until the session finishes or fails (module doc).

    ``controller=False`` answers every state with a zero command from a minimal node
    (the transport's own cost, for the benchmark); ``track=False`` keeps no path (one
    subscriber less). ``wall_limit`` bounds the wall time.
    """
    if bag is not None:
        check_bag_path(Path(bag))
    own = not rclpy.ok()
    if own:
        rclpy.init()
    nodes: list[Node] = []
    writer = None
    try:
        params = [Parameter('mode', value='lockstep'),
                  Parameter('configuration', value=configuration),
                  Parameter('master', value=str(master) if master else ''),
                  Parameter('duration', value=float(duration)),
                  Parameter('step', value=float(step)),
                  Parameter('initial_speed', value=float(speed))]
        solver = VehicleSolver(parameter_overrides=params)
        nodes.append(solver)
        session = solver.lockstep
        assert session is not None  # mode lockstep
        if controller:
            nodes.append(PathFollower(parameter_overrides=[
                Parameter('radius', value=float(radius)), Parameter('speed', value=float(speed)),
                Parameter('wheelbase', value=float(
                    session.stepper.model.config.group('geometry').scalar('wheelbase'))),
                Parameter('steering_ratio', value=float(
                    session.stepper.model.maps.steering_ratio)),
                Parameter('use_sim_time', value=True)]))
        else:
            nodes.append(_zero_commander())
        watcher = rclpy.create_node('lockstep_watch')
        nodes.append(watcher)
        status: list[str] = []

        def on_status(msg: String) -> None:
            status.append(msg.data)

        watcher.create_subscription(String, '/vd/' + STATUS_TOPIC, on_status, STATUS)
        path: list[tuple[float, float, float]] = []
        if bag is not None:
            writer = BagWriter(Path(bag), {'vd.lockstep': configuration or 'first'})
            _record(watcher, writer, path)
        elif track:
            _track(watcher, path)
        executor = EventsExecutor()
        for node in nodes:
            executor.add_node(node)
        t0 = time.perf_counter()
        deadline = t0 + wall_limit
        while session.active and time.perf_counter() < deadline:
            executor.spin_once(timeout_sec=0.1)
        wall = time.perf_counter() - t0
        if session.active:
            session._stop(f'wall-time limit of {wall_limit:g} s reached')
        for _ in range(20):  # deliver the last messages to the recorder
            executor.spin_once(timeout_sec=0.02)
        result = LockstepOutcome(status=session.status, steps=session.stepper.step,
                                 simulated=session.stepper.time, wall=wall,
                                 stale=session.stale, timings=dict(session.timings),
                                 path=path)
        if writer is not None:
            if session.status.startswith('finished'):
                result.bag = writer.close()
            else:
                writer.abort()
            writer = None
        executor.shutdown(timeout_sec=0.0)
        return result
    finally:
        if writer is not None:
            writer.abort()
        for node in nodes:
            node.destroy_node()
        if own:
            rclpy.try_shutdown()


def _zero_commander():
    """Return a node answering every odometry message with a zero command of its stamp."""

    class ZeroCommander(Node):
        """
        Answer every odometry message with a zero command of its stamp, at least cost.

        The odometry is taken serialised (its stamp read out of the bytes) and the
        command is serialised once (its stamp rewritten): no message is built, so what
        the bench measures besides the session is the transport and the executor.
        """

        def __init__(self) -> None:
            super().__init__('zero_commander')
            self.pub = self.create_publisher(VehicleCommand, '/vd/vehicle/command', 10)
            self.create_subscription(Odometry, '/vd/vehicle/odom', self._answer, 10, raw=True)
            odom, self.command = InPlaceMessage(Odometry()), InPlaceMessage(VehicleCommand())
            self.stamp = [(odom.slots([f]), self.command.slots([f]))
                          for f in ('header.stamp.sec', 'header.stamp.nanosec')]

        def _answer(self, odom: bytes) -> None:
            for read, write in self.stamp:
                write.write(read.read(odom))
            self.pub.publish(self.command.data())
    return ZeroCommander()


def _types():

    return {'/clock': Clock, '/vd/vehicle/state': VehicleState, '/vd/vehicle/odom': Odometry,
            '/tf': TFMessage, '/vd/vehicle/command': VehicleCommand}


def _stamp(msg) -> int:
    if hasattr(msg, 'clock'):
        s = msg.clock
    elif hasattr(msg, 'transforms'):
        s = msg.transforms[0].header.stamp
    else:
        s = msg.header.stamp
    return s.sec * 1_000_000_000 + s.nanosec


def _record(node, writer, path) -> None:
    """Subscribe ``node`` to RECORDED and write each message at its stamp."""
    types = _types()
    last: dict[str, int] = {}
    offered: dict[str, list] = {}

    def writer_for(topic: str):
        def write(msg) -> None:
            ns = _stamp(msg)
            if topic != '/vd/vehicle/command' and last.get(topic) == ns:
                return  # a repeat of the step while its command was awaited
            last[topic] = ns
            if topic not in offered:  # a message came: its publisher is discovered
                offered[topic] = offered_profiles(node, topic, profile_of(topic))
            writer.write(topic, msg, ns, offered[topic])
            if topic == '/vd/vehicle/odom':
                path.append((ns * 1e-9, msg.pose.pose.position.x, msg.pose.pose.position.y))
        return write

    for topic in RECORDED:
        node.create_subscription(types[topic], topic, writer_for(topic), profile_of(topic))


def _track(node, path) -> None:


    def keep(msg) -> None:
        path.append((_stamp(msg) * 1e-9, msg.pose.pose.position.x, msg.pose.pose.position.y))
    node.create_subscription(Odometry, '/vd/vehicle/odom', keep, STATES)


__all__ = ['LockstepOutcome', 'run_lockstep', 'RECORDED']


def bench_lockstep(duration: float = 10.0) -> dict:
    """
    Measure lock-step steps per second over DDS (``vd bench``).

    Two closed loops of ``duration`` simulated seconds in one process on the events
    executor: the example path follower, and a minimal node answering each state with a
    zero command (the transport's and executor's own cost). Per step: the model step,
    building and publishing the messages, and the rest (DDS, executor, controller). A
    short loop runs first, untimed: the first step of a process loads the compiled
    model (numba's cache), a second or more that would be charged to the first loop.
    """
    run_lockstep(duration=0.05, controller=False, track=False)
    out = {}
    for name, controller in (('path_follower', True), ('zero_command', False)):
        r = run_lockstep(duration=duration, controller=controller, track=False)
        per = r.to_json()
        rest = r.wall - sum(r.timings.values())
        per['us_per_step']['rest'] = rest / r.steps * 1e6 if r.steps else float('nan')
        out[name] = per
    return out
