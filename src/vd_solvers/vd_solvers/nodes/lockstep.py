# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Lock-step co-simulation of the full vehicle on the ROS graph.

``vehicle_solver`` in mode ``lockstep`` or ``free``.

At each step k (simulation time t_k = k h) the session publishes ``/clock`` (t_k) and the
state at t_k: ``/vd/vehicle/state`` (VehicleState with the four wheels and tires),
``/vd/vehicle/odom`` (nav_msgs/Odometry, odom -> base_link) and ``/tf``, all stamped t_k.
It then waits for a ``vd_interfaces/VehicleCommand`` on ``/vd/vehicle/command`` stamped
t_k, applies it over [t_k, t_k + h] and publishes step k + 1. Nothing is extrapolated:

* a command stamped **before** t_k (an answer to an earlier step, e.g. the repeat
  below) is dropped and counted;
* a command stamped **after** t_k (a controller ahead of the clock), a **non-finite**
  value, a negative torque, an angle beyond the steering lock or steering by torque
  stops the session with the error on ``/vd/vehicle/lockstep_status`` and in the log;
  the state stays at t_k;
* while it waits, the session repeats step k's messages every REPEAT_PERIOD s of wall
  time (a controller that connects late gets the state it must answer); with no valid
  command within ``command_timeout`` s (``start_timeout`` for the first step) it stops
  with a timeout error;
* a second publisher on the command topic (two controllers answering the same steps)
  stops the session with an error naming the publishing nodes (looked at every
  REPEAT_PERIOD s).

Mode ``free`` runs without waiting, at ``real_time_factor`` times wall time, applying
the newest command and holding it until the next one arrives (a refused command is
logged and the previous one held). Status messages (std_msgs/String, latched):
``running``, ``finished at t = ... s (N steps)``, ``error at t = ... s: ...``.
"""
from __future__ import annotations

import math
import time

from builtin_interfaces.msg import Time
from geometry_msgs.msg import TransformStamped
from nav_msgs.msg import Odometry
from rclpy.node import Node
from rosgraph_msgs.msg import Clock
from std_msgs.msg import String

from tf2_msgs.msg import TFMessage
from vd_data_server.ros.names import BODY_FRAME, ODOM_FRAME
from vd_data_server.ros.qos import CLOCK, COMMANDS, STATUS
from vd_interfaces.msg import VehicleCommand, VehicleState, VehicleWheel
from vd_solvers.conversions import WHEEL_FIELDS, set_quaternion
from vd_solvers.errors import SolverError
from vd_solvers.vehicle.cosim import Command, CommandError, Stepper, check_command
from vd_solvers.vehicle.maps import WHEELS

#: relative: in the node's namespace (/vd/vehicle/command by default)
COMMAND_TOPIC = 'vehicle/command'
#: VehicleState fields filled from the Stepper state
STATE_FIELDS = ('time', 'x', 'y', 'yaw', 'roll', 'pitch', 'yaw_rate', 'speed', 'sideslip',
                'lateral_acceleration', 'longitudinal_acceleration', 'steering_wheel_angle',
                'wheel_torque')
STATUS_TOPIC = 'vehicle/lockstep_status'
#: wall seconds between repeats of a step's messages while its command is awaited
REPEAT_PERIOD = 0.25
def stamp_ns(stamp) -> int:
    """Nanoseconds of a builtin_interfaces/Time."""
    return int(stamp.sec) * 1_000_000_000 + int(stamp.nanosec)


def to_stamp(ns: int) -> Time:
    """Return the builtin_interfaces/Time of ``ns`` nanoseconds."""
    return Time(sec=ns // 1_000_000_000, nanosec=ns % 1_000_000_000)


def command_from_msg(msg: VehicleCommand) -> Command:
    """Return the ROS-free command of a VehicleCommand."""
    return Command(steering_wheel_angle=float(msg.steering_wheel_angle),
                   drive_torque=float(msg.drive_torque), brake_torque=float(msg.brake_torque),
                   steering_mode=int(msg.steering_mode),
                   steering_wheel_torque=float(msg.steering_wheel_torque))


class LockstepSession:
    """The lock-step (or free-running) vehicle of one configuration on ``node``."""

    def __init__(self, node: Node, stepper: Stepper, *, mode: str, duration: float,
                 command_timeout: float, start_timeout: float, real_time_factor: float,
                 configuration: str, state_pub, odom_pub, tf_pub,
                 frame_prefix: str = '') -> None:
        self.node = node
        self.stepper = stepper
        self.mode = mode
        self.h_ns = int(round(stepper.h * 1e9))
        self.duration = duration
        self.command_timeout = command_timeout
        self.start_timeout = start_timeout
        self.configuration = configuration
        self.frame_prefix = frame_prefix  # outside /vd: car2/odom -> car2/base_link
        self.state_pub, self.odom_pub, self.tf_pub = state_pub, odom_pub, tf_pub
        self.clock_pub = node.create_publisher(Clock, '/clock', CLOCK)
        self.status_pub = node.create_publisher(String, STATUS_TOPIC, STATUS)
        self.stale = 0  # commands dropped as answers to an earlier step
        #: seconds spent in the model step and in building + publishing the messages
        self.timings = {'model': 0.0, 'publish': 0.0}
        self.status = 'running'
        self.held = Command()
        sub = self.node.create_subscription(VehicleCommand, COMMAND_TOPIC, self._on_command,
                                            COMMANDS)
        self.command_topic = sub.topic_name
        self._state_msg = VehicleState(event='lockstep', configuration=configuration,
                                       model='vehicle')
        self._state_msg.header.frame_id = frame_prefix + ODOM_FRAME
        self._wheel_msgs = [VehicleWheel() for _ in WHEELS]
        for wheel, m in zip(WHEELS, self._wheel_msgs):
            setattr(self._state_msg, wheel, m)
        self._wheel_msgs = [getattr(self._state_msg, wheel) for wheel in WHEELS]
        self._odom_msg = Odometry()
        self._tf_msg = None
        self._published_at = time.monotonic()
        self._waiting_since = self._published_at
        self.started = time.monotonic()
        self._publish_status('running')
        self._publish()
        if mode == 'free':
            self.timer = node.create_timer(stepper.h / real_time_factor, self._free_step)
        else:
            self.timer = node.create_timer(REPEAT_PERIOD, self._watchdog)
        self.controllers = node.create_timer(REPEAT_PERIOD, self._check_controllers)

    @property
    def now_ns(self) -> int:
        """Simulation time of the current step, ns."""
        return self.stepper.step * self.h_ns

    @property
    def active(self) -> bool:
        return self.status == 'running'

    # --- lock-step --------------------------------------------------------------------

    def _on_command(self, msg: VehicleCommand) -> None:
        if not self.active:
            return
        if self.mode == 'free':
            try:
                command = command_from_msg(msg)
                check_command(command, self.stepper.max_angle)
                self.held = command
            except CommandError as err:
                self.node.get_logger().error(f'command refused, the previous one is held: {err}')
            return
        stamp = stamp_ns(msg.header.stamp)
        now = self.now_ns
        if stamp < now:
            self.stale += 1
            return
        if stamp > now:
            self._stop(f'command stamped {stamp * 1e-9:.6f} s for the step at '
                       f'{now * 1e-9:.6f} s: ahead of the simulation clock')
            return
        c0 = time.perf_counter()
        try:
            self.stepper.advance(command_from_msg(msg))
        except (CommandError, SolverError) as err:
            self._stop(f'command for t = {now * 1e-9:.6f} s refused: {err}')
            return
        self.timings['model'] += time.perf_counter() - c0
        self._after_step()

    def _after_step(self) -> None:
        if self.duration > 0.0 and self.now_ns >= int(round(self.duration * 1e9)):
            self._publish()
            self._finish()
            return
        self._publish()
        self._waiting_since = self._published_at

    def _watchdog(self) -> None:
        if not self.active:
            return
        waited = time.monotonic() - self._waiting_since
        limit = self.start_timeout if self.stepper.step == 0 else self.command_timeout
        if waited > limit:
            self._stop(f'no command for the step at t = {self.now_ns * 1e-9:.6f} s within '
                       f'{limit:g} s')
            return
        if time.monotonic() - self._published_at >= REPEAT_PERIOD:
            self._publish()

    def _check_controllers(self) -> None:
        """Stop when a second controller publishes commands: lock-step answers one."""
        if not self.active:
            return
        found = self.node.get_publishers_info_by_topic(self.command_topic)
        if len(found) > 1:
            names = sorted({f"{i.node_namespace.rstrip('/')}/{i.node_name}" for i in found})
            self._stop(f'{len(found)} publishers on {self.command_topic} '
                       f"({', '.join(names)}): lock-step takes the commands of one "
                       'controller; stop the others')

    # --- free running -----------------------------------------------------------------

    def _free_step(self) -> None:
        if not self.active:
            return
        try:
            self.stepper.advance(self.held)
        except (CommandError, SolverError) as err:
            self._stop(str(err))
            return
        self._after_step()

    # --- output -----------------------------------------------------------------------

    def _publish(self) -> None:
        c0 = time.perf_counter()
        stamp = to_stamp(self.now_ns)
        self.clock_pub.publish(Clock(clock=stamp))
        s = self.stepper.state()
        wheels = self.stepper.wheels()
        # one message object per topic, refilled each step (publish serialises at once)
        msg = self._state_msg
        msg.step = self.stepper.step
        msg.header.stamp = stamp
        for name in STATE_FIELDS:
            setattr(msg, name, float(s[name]))
        for w, wheel in enumerate(self._wheel_msgs):
            for f, (c, _) in WHEEL_FIELDS.items():  # a field the step lacks stays NaN
                setattr(wheel, f, float(wheels[c][w]) if c in wheels else math.nan)
        odom = odometry(s, stamp, self._odom_msg, self.frame_prefix)
        self.state_pub.publish(msg)
        self.odom_pub.publish(odom)
        self._tf_msg = transform(odom, self._tf_msg)
        self.tf_pub.publish(self._tf_msg)
        self._published_at = time.monotonic()
        self.timings['publish'] += time.perf_counter() - c0

    def _publish_status(self, text: str) -> None:
        self.status_pub.publish(String(data=text))

    def _finish(self) -> None:
        self.status = f'finished at t = {self.now_ns * 1e-9:.6f} s ({self.stepper.step} steps)'
        self.node.get_logger().info(f'lock-step {self.status}')
        self._publish_status(self.status)

    def _stop(self, reason: str) -> None:
        self.status = f'error at t = {self.now_ns * 1e-9:.6f} s: {reason}'
        self.node.get_logger().error(f'lock-step stopped: {self.status}')
        self._publish_status(self.status)


def odometry(state, stamp, msg: Odometry | None = None, prefix: str = '') -> Odometry:
    """
    Return the nav_msgs/Odometry of a Stepper state (filled into ``msg`` if given).

    Frames ``odom`` -> ``base_link`` (REP 105), with ``prefix`` outside ``/vd``.
    """
    msg = msg if msg is not None else Odometry()
    msg.header.stamp = stamp
    msg.header.frame_id = prefix + ODOM_FRAME
    msg.child_frame_id = prefix + BODY_FRAME
    msg.pose.pose.position.x = float(state['x'])
    msg.pose.pose.position.y = float(state['y'])
    set_quaternion(msg.pose.pose.orientation,
                   *(float(state[k]) for k in ('roll', 'pitch', 'yaw')))
    # twist in the child frame (REP 105): the CoG's horizontal velocity in yaw axes
    beta = float(state['sideslip'])
    msg.twist.twist.linear.x = float(state['speed']) * math.cos(beta)
    msg.twist.twist.linear.y = float(state['speed']) * math.sin(beta)
    msg.twist.twist.angular.z = float(state['yaw_rate'])
    return msg


def transform(odom: Odometry, msg: TFMessage | None = None) -> TFMessage:
    """Return the TF odom -> base_link of an Odometry (filled into ``msg`` if given)."""
    if msg is None or not msg.transforms:
        msg = TFMessage(transforms=[TransformStamped()])
    t = msg.transforms[0]
    t.header = odom.header
    t.child_frame_id = odom.child_frame_id
    p = odom.pose.pose.position
    t.transform.translation.x, t.transform.translation.y = p.x, p.y
    t.transform.rotation = odom.pose.pose.orientation
    return msg


__all__ = ['LockstepSession', 'COMMAND_TOPIC', 'STATUS_TOPIC', 'command_from_msg', 'odometry',
           'stamp_ns', 'to_stamp']
