# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Lock-step co-simulation of the full vehicle on the ROS graph.

``vehicle_solver`` in mode ``lockstep`` or ``free``.

At each step k (simulation time t_k = k h) the session publishes ``/clock`` (t_k) and the
state at t_k: ``/vd/vehicle/state`` (VehicleState with the four wheels and tires),
``/vd/vehicle/odom`` (nav_msgs/Odometry, odom -> base_link) and ``/tf``, all stamped t_k.
It then waits for the command of step k, applies it over [t_k, t_k + h] and publishes
step k + 1. A command is one of

* ``vd_interfaces/VehicleCommand`` on ``/vd/vehicle/command`` (steering-wheel angle,
  wheel torques), applied as it is;
* ``ackermann_msgs/AckermannDriveStamped`` on ``/vd/ackermann_cmd`` (tire angle, speed,
  acceleration) or ``geometry_msgs/Twist`` on ``/vd/cmd_vel`` (speed, yaw rate), turned
  into the step's steering-wheel angle and torques by the actuator model
  (:mod:`vd_solvers.vehicle.actuators`).

A VehicleCommand or a stamped Ackermann command must be stamped t_k; a Twist (which has
no stamp) and an Ackermann command stamped 0 apply to the step the session waits for,
the step named by ``/clock``. Nothing is extrapolated:

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

from ackermann_msgs.msg import AckermannDriveStamped
from builtin_interfaces.msg import Time
from geometry_msgs.msg import PoseWithCovarianceStamped, TransformStamped, Twist
from nav_msgs.msg import Odometry
import numpy as np
from rclpy.node import Node
from rclpy.publisher import Publisher
from rclpy.service import Service
from rclpy.subscription import Subscription
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import JointState
from std_msgs.msg import String
from std_srvs.srv import Trigger

from tf2_msgs.msg import TFMessage
from vd_data_server.ros.names import BODY_FRAME, ODOM_FRAME
from vd_data_server.ros.qos import CLOCK, COMMANDS, STATES, STATUS, TF_STATIC
from vd_interfaces.msg import VehicleCommand, VehicleState, VehicleWheel
from vd_solvers.conversions import (
    WHEEL_FIELDS,
    InPlaceMessage,
    covariance_unknown,
    quaternion,
)
from vd_solvers.errors import SolverError
from vd_solvers.vehicle.actuators import Actuators, Setpoint, check_setpoint, twist_setpoint
from vd_solvers.vehicle.cosim import STATE_KEYS, Command, CommandError, Stepper, check_command
from vd_solvers.vehicle.description import Description, joint_positions
from vd_solvers.vehicle.description import transform as joint_transform
from vd_solvers.vehicle.maps import WHEELS
from vd_solvers.vehicle.simulation import WHEEL_ROW

#: relative: in the node's namespace (/vd/vehicle/command by default)
COMMAND_TOPIC = 'vehicle/command'
#: the standard drive commands, relative (/vd/ackermann_cmd, /vd/cmd_vel by default)
ACKERMANN_TOPIC = 'ackermann_cmd'
TWIST_TOPIC = 'cmd_vel'
#: VehicleState fields filled from the Stepper state
STATE_FIELDS = ('time', 'x', 'y', 'yaw', 'roll', 'pitch', 'yaw_rate', 'speed', 'sideslip',
                'lateral_acceleration', 'longitudinal_acceleration', 'steering_wheel_angle',
                'wheel_torque')
#: Odometry fields filled from the Stepper state (:func:`odometry_values`)
ODOMETRY_FIELDS = ('pose.pose.position.x', 'pose.pose.position.y', 'pose.pose.position.z',
                   'pose.pose.orientation.x', 'pose.pose.orientation.y',
                   'pose.pose.orientation.z', 'pose.pose.orientation.w',
                   'twist.twist.linear.x', 'twist.twist.linear.y', 'twist.twist.angular.z')
STATUS_TOPIC = 'vehicle/lockstep_status'
#: the robot description of the vehicle (URDF, latched) and its joints, relative
ROBOT_DESCRIPTION_TOPIC = 'robot_description'
JOINT_STATES_TOPIC = 'joint_states'
#: start the session again (std_srvs/Trigger) / at a pose (RViz's 2D Pose Estimate), relative
RESET_SERVICE = 'vehicle/reset'
INITIAL_POSE_TOPIC = 'initialpose'
#: tf2's static frames (global, as /tf)
TF_STATIC_TOPIC = '/tf_static'
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
                 configuration: str, state_pub, odom_pub, tf_pub, actuators: Actuators,
                 description: Description | None = None, frame_prefix: str = '') -> None:
        self.node = node
        self.stepper = stepper
        self.actuators = actuators
        self.mode = mode
        self.h_ns = int(round(stepper.h * 1e9))
        self.duration = duration
        self.command_timeout = command_timeout
        self.start_timeout = start_timeout
        self.configuration = configuration
        self.frame_prefix = frame_prefix  # outside /vd: car2/odom -> car2/base_link
        self.state_pub, self.odom_pub, self.tf_pub = state_pub, odom_pub, tf_pub
        self._entities: list = []  # what the session created on the node (close())
        self.clock_pub = self._own(node.create_publisher(Clock, claim_clock(node), CLOCK))
        self.status_pub = self._own(node.create_publisher(String, STATUS_TOPIC, STATUS))
        self.stale = 0  # commands dropped as answers to an earlier step
        #: seconds spent in the model step and in building + publishing the messages
        self.timings = {'model': 0.0, 'publish': 0.0}
        self.status = 'running'
        self.held = Command()
        self.held_setpoint: Setpoint | None = None  # free mode: the newest setpoint, if any
        inputs = (node.create_subscription(VehicleCommand, COMMAND_TOPIC, self._on_command,
                                           COMMANDS),
                  node.create_subscription(AckermannDriveStamped, ACKERMANN_TOPIC,
                                           self._on_ackermann, COMMANDS),
                  node.create_subscription(Twist, TWIST_TOPIC, self._on_twist, COMMANDS))
        self.command_topics = tuple(sub.topic_name for sub in inputs)
        for entity in (
                *inputs,
                node.create_service(Trigger, RESET_SERVICE, self._on_reset),
                node.create_subscription(PoseWithCovarianceStamped, INITIAL_POSE_TOPIC,
                                         self._on_initial_pose, COMMANDS)):
            self._own(entity)
        self._messages()
        self._tf_msg = TFMessage(transforms=[TransformStamped()])
        self._tf_readers = 0  # /tf subscriptions matched when /tf was last published
        self.description = description
        if description is not None:
            self._describe(description)
        self._published_at = time.monotonic()
        self._waiting_since = self._published_at
        self.started = time.monotonic()
        self._publish_status('running')
        self._publish()
        if mode == 'free':
            self.timer = self._own(node.create_timer(stepper.h / real_time_factor,
                                                     self._free_step))
        else:
            self.timer = self._own(node.create_timer(REPEAT_PERIOD, self._watchdog))
        self.controllers = self._own(node.create_timer(REPEAT_PERIOD, self._check_controllers))

    def _messages(self) -> None:
        """
        Serialise the per-step messages once; each step rewrites their numbers in place.

        /clock, the state and the odometry are published every step: built from message
        objects field by field, converted and serialised by rclpy, they cost about as
        much as the model step (docs/ros-api.md, timing). Their strings and frames are set
        here; a wheel field the model does not give is NaN. The row and wheel indices map
        the Stepper's arrays to the fields.
        """
        odom_frame = self.frame_prefix + ODOM_FRAME
        self._clock = InPlaceMessage(Clock())
        state = VehicleState(event='lockstep', configuration=self.configuration,
                             model='vehicle')
        state.header.frame_id = odom_frame
        wheel_fields, wheel_index = [], []
        for w, wheel in enumerate(WHEELS):
            msg = VehicleWheel()
            for f, (channel, _) in WHEEL_FIELDS.items():
                if channel in WHEEL_ROW:
                    wheel_fields.append(f'{wheel}.{f}')
                    wheel_index.append(WHEEL_ROW[channel] * len(WHEELS) + w)
                else:
                    setattr(msg, f, math.nan)
            setattr(state, wheel, msg)
        self._state = InPlaceMessage(state)
        self._state_body = self._state.slots(STATE_FIELDS)
        self._state_wheels = self._state.slots(wheel_fields)
        self._state_step = self._state.slots(['step'])
        self._row_index = np.array([STATE_KEYS.index(f) for f in STATE_FIELDS])
        self._wheel_index = np.array(wheel_index)
        self._odom_msg = odometry(self.stepper.state(), Time(), None, self.frame_prefix)
        self._odom = InPlaceMessage(self._odom_msg)
        self._odom_slots = self._odom.slots(ODOMETRY_FIELDS)
        self._stamps = [(m.slots([f'{at}.sec']), m.slots([f'{at}.nanosec']))
                        for m, at in ((self._clock, 'clock'), (self._state, 'header.stamp'),
                                      (self._odom, 'header.stamp'))]

    def _own(self, entity):
        self._entities.append(entity)
        return entity

    def hold(self) -> None:
        """Stop stepping (a deactivated node); ``reset`` starts the session again."""
        if self.active:
            self.status = f'inactive at t = {self.now_ns * 1e-9:.6f} s'
            self.node.get_logger().info(f'lock-step {self.status}')
            self._publish_status(self.status)

    def close(self) -> None:
        """Remove what the session created from the node (a cleaned-up node)."""
        self.hold()
        for entity in reversed(self._entities):
            if isinstance(entity, Publisher):
                self.node.destroy_publisher(entity)
            elif isinstance(entity, Subscription):
                self.node.destroy_subscription(entity)
            elif isinstance(entity, Service):
                self.node.destroy_service(entity)
            else:
                self.node.destroy_timer(entity)
        self._entities.clear()

    # --- reset -------------------------------------------------------------------------

    def reset(self, x: float = 0.0, y: float = 0.0, yaw: float = 0.0) -> str:
        """
        Start the session again at t = 0 from the initial state, placed at x, y, yaw.

        The vehicle (its maps) is kept: a reset costs a step, not the model build.
        Return what was done (SolverError if the pose is unusable: nothing changes).
        """
        old = self.stepper
        stepper = Stepper(old.model, old.h, old.initial_speed, old.drive_front,
                          old.brake_front)
        stepper.place(x, y, yaw)
        ran = old.step
        self.stepper = stepper
        self.actuators = Actuators(self.actuators.p, speed=old.initial_speed)
        self.held, self.held_setpoint = Command(), None
        self.stale = 0
        self.status = 'running'
        self._publish_status(self.status)
        self._publish()
        self._waiting_since = self._published_at
        text = (f'reset to t = 0 at x = {x:g} m, y = {y:g} m, yaw = {yaw:g} rad ({ran} steps '
                'run before)')
        self.node.get_logger().info(f'lock-step {text}')
        return text

    def _on_reset(self, request, response):
        response.success, response.message = True, self.reset()
        return response

    def _on_initial_pose(self, msg: PoseWithCovarianceStamped) -> None:
        p, o = msg.pose.pose.position, msg.pose.pose.orientation
        yaw = math.atan2(2.0 * (o.w * o.z + o.x * o.y), 1.0 - 2.0 * (o.y * o.y + o.z * o.z))
        try:
            self.reset(float(p.x), float(p.y), yaw)
        except SolverError as err:
            self.node.get_logger().error(f'initial pose refused: {err}')

    def _describe(self, description: Description) -> None:
        """Publish the robot description and the static frames; prepare the joint states."""
        prefix = self.frame_prefix
        self.description_pub = self._own(self.node.create_publisher(
            String, ROBOT_DESCRIPTION_TOPIC, TF_STATIC))
        self.description_pub.publish(String(data=description.urdf()))
        static = TFMessage()
        for joint in description.fixed:
            t = TransformStamped()
            t.header.frame_id, t.child_frame_id = prefix + joint.parent, prefix + joint.child
            (t.transform.translation.x, t.transform.translation.y,
             t.transform.translation.z), (t.transform.rotation.x, t.transform.rotation.y,
                                          t.transform.rotation.z,
                                          t.transform.rotation.w) = joint_transform(joint, 0.0)
            static.transforms.append(t)
        self.static_pub = self._own(self.node.create_publisher(TFMessage, TF_STATIC_TOPIC,
                                                               TF_STATIC))
        self.static_pub.publish(static)
        self.joint_pub = self._own(self.node.create_publisher(JointState, JOINT_STATES_TOPIC,
                                                              STATES))
        self._joint_msg = JointState(name=[j.name for j in description.moving])
        for joint in description.moving:
            t = TransformStamped()
            t.header.frame_id, t.child_frame_id = prefix + joint.parent, prefix + joint.child
            self._tf_msg.transforms.append(t)

    @property
    def now_ns(self) -> int:
        """Simulation time of the current step, ns."""
        return self.stepper.step * self.h_ns

    @property
    def active(self) -> bool:
        return self.status == 'running'

    @property
    def running(self) -> bool:
        """Active, and rclpy not shut down (a SIGINT ends the context under a timer)."""
        return self.active and self.node.context.ok()

    # --- lock-step --------------------------------------------------------------------

    def _on_command(self, msg: VehicleCommand) -> None:
        self._take(stamp_ns(msg.header.stamp), command=msg)

    def _on_ackermann(self, msg: AckermannDriveStamped) -> None:
        stamp = stamp_ns(msg.header.stamp)
        self._take(stamp or None, setpoint=msg.drive)

    def _on_twist(self, msg: Twist) -> None:
        self._take(None, setpoint=msg)

    def _setpoint(self, msg) -> Setpoint:
        """Return the setpoint of an AckermannDrive or a Twist (CommandError if unusable)."""
        if isinstance(msg, Twist):
            return twist_setpoint(float(msg.linear.x), float(msg.angular.z),
                                  self.actuators.p.wheelbase)
        setpoint = Setpoint(steering_angle=float(msg.steering_angle), speed=float(msg.speed),
                            acceleration=abs(float(msg.acceleration)),
                            steering_angle_velocity=abs(float(msg.steering_angle_velocity)))
        check_setpoint(setpoint)
        return setpoint

    def _take(self, stamp: int | None, *, command=None, setpoint=None) -> None:
        """
        Take a command (VehicleCommand) or a setpoint (AckermannDrive, Twist).

        ``stamp`` None: for the step the session waits for (module doc).
        """
        if not self.running:
            return
        if self.mode == 'free':
            try:
                if setpoint is not None:
                    self.held_setpoint = self._setpoint(setpoint)
                else:
                    held = command_from_msg(command)
                    check_command(held, self.stepper.max_angle)
                    self.held, self.held_setpoint = held, None
            except CommandError as err:
                self.node.get_logger().error(f'command refused, the previous one is held: {err}')
            return
        now = self.now_ns
        if stamp is not None and stamp < now:
            self.stale += 1
            return
        if stamp is not None and stamp > now:
            self._stop(f'command stamped {stamp * 1e-9:.6f} s for the step at '
                       f'{now * 1e-9:.6f} s: ahead of the simulation clock')
            return
        c0 = time.perf_counter()
        try:
            if setpoint is not None:
                self._advance_to(self._setpoint(setpoint))
            else:
                applied = command_from_msg(command)
                self.stepper.advance(applied)
                self.actuators.follow(applied)
        except (CommandError, SolverError) as err:
            self._stop(f'command for t = {now * 1e-9:.6f} s refused: {err}')
            return
        self.timings['model'] += time.perf_counter() - c0
        self._after_step()

    def _advance_to(self, setpoint: Setpoint) -> None:
        """Advance one step with the actuators' command for ``setpoint``."""
        speed = self.stepper.state()['speed']
        self.stepper.advance(self.actuators.command(setpoint, speed, self.stepper.h))

    def _after_step(self) -> None:
        if self.duration > 0.0 and self.now_ns >= int(round(self.duration * 1e9)):
            self._publish()
            self._finish()
            return
        self._publish()
        self._waiting_since = self._published_at

    def _watchdog(self) -> None:
        if not self.running:
            return
        waited = time.monotonic() - self._waiting_since
        limit = self.start_timeout if self.stepper.step == 0 else self.command_timeout
        if waited > limit:
            self._stop(f'no command for the step at t = {self.now_ns * 1e-9:.6f} s within '
                       f'{limit:g} s')
            return
        if time.monotonic() - self._published_at >= REPEAT_PERIOD:
            self._publish(repeat=True)

    def _check_controllers(self) -> None:
        """Stop when a second controller publishes commands (any input): one is answered."""
        if not self.active:
            return
        found = [(topic, info) for topic in self.command_topics
                 for info in self.node.get_publishers_info_by_topic(topic)]
        if len(found) > 1:
            topics = sorted({topic for topic, _ in found})
            names = sorted({f"{i.node_namespace.rstrip('/')}/{i.node_name}" for _, i in found})
            self._stop(f"{len(found)} publishers on {', '.join(topics)} "
                       f"({', '.join(names)}): lock-step takes the commands of one "
                       'controller; stop the others')

    # --- free running -----------------------------------------------------------------

    def _free_step(self) -> None:
        if not self.running:
            return
        try:
            if self.held_setpoint is not None:
                self._advance_to(self.held_setpoint)
            else:
                self.stepper.advance(self.held)
        except (CommandError, SolverError) as err:
            self._stop(str(err))
            return
        self._after_step()

    # --- output -----------------------------------------------------------------------

    def _publish(self, repeat: bool = False) -> None:
        """
        Publish the current step; a ``repeat`` (while its command is awaited) leaves /tf out.

        tf2 refuses a transform stamped like one it holds (TF_REPEATED_DATA): a repeat
        carries /tf only when a reader joined since it was published (a late joiner).
        """
        c0 = time.perf_counter()
        stepper = self.stepper
        sec, nanosec = divmod(self.now_ns, 1_000_000_000)
        for sec_slot, nanosec_slot in self._stamps:
            sec_slot.write(sec)
            nanosec_slot.write(nanosec)
        self._state_step.write(stepper.step)
        self._state_body.write(stepper.row[self._row_index])
        self._state_wheels.write(stepper.wheel_rows.ravel()[self._wheel_index])
        s = stepper.state()
        z = float(stepper.q[2])
        self._odom_slots.write(odometry_values(s, z))
        self.clock_pub.publish(self._clock.data())
        self.state_pub.publish(self._state.data())
        self.odom_pub.publish(self._odom.data())
        # the joints and wheel frames only for whom listens (building them costs a step's
        # share); a reader that joins gets the next step, or the repeat below
        tf_readers = self.tf_pub.get_subscription_count()
        tf_due = tf_readers > 0 and (not repeat or tf_readers > self._tf_readers)
        joints_due = self.description is not None and self.joint_pub.get_subscription_count() > 0
        if tf_due or joints_due:
            stamp = to_stamp(self.now_ns)
            odom = odometry(s, stamp, self._odom_msg, self.frame_prefix, z)
            tf = transform(odom, self._tf_msg)
            positions = (joint_positions(self.description, stepper.q,
                                         stepper.wheels()['wheel_steer'])
                         if self.description is not None else [])
            if joints_due:
                joints = self._joint_msg
                joints.header.stamp = stamp
                joints.position = positions
                self.joint_pub.publish(joints)
            if tf_due:
                for t, joint, value in zip(tf.transforms[1:], self.description.moving
                                           if self.description is not None else (), positions):
                    t.header.stamp = stamp
                    (t.transform.translation.x, t.transform.translation.y,
                     t.transform.translation.z), r = joint_transform(joint, value)
                    (t.transform.rotation.x, t.transform.rotation.y, t.transform.rotation.z,
                     t.transform.rotation.w) = r
                self.tf_pub.publish(tf)
        self._tf_readers = tf_readers
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


def clock_owners(node: Node, topic: str) -> list[str]:
    """Return the full names of the other nodes publishing on ``topic`` (as discovered)."""
    own = (node.get_name(), node.get_namespace())
    return sorted({f"{i.node_namespace.rstrip('/')}/{i.node_name}"
                   for i in node.get_publishers_info_by_topic(topic)
                   if (i.node_name, i.node_namespace) != own})


def claim_clock(node: Node) -> str:
    """
    Return the resolved clock topic of ``node``'s session, or ValueError if it is owned.

    One ``/clock`` owner per ROS domain: two sessions publishing one clock would send
    every ``use_sim_time`` node back and forth in time. A session started where another
    node already publishes the (remapped) clock refuses, naming that node and its
    namespace; a session with a clock of its own (``--ros-args -r /clock:=/car2/clock``,
    ``lockstep.launch.py clock_topic:=/car2/clock``) runs beside it.
    """
    topic = node.resolve_topic_name('/clock')
    owners = clock_owners(node, topic)
    if owners:
        namespaces = ', '.join(sorted({o.rsplit('/', 1)[0] or '/' for o in owners}))
        here = node.get_namespace().rstrip('/')
        raise ValueError(
            f'{topic} is already published by {", ".join(owners)} (namespace {namespaces}): '
            f'one {topic} owner per ROS domain. Give this session a clock of its own '
            f'(--ros-args -r /clock:={here}/clock, or lockstep.launch.py '
            f'clock_topic:={here}/clock, and the same remapping for its controller) or '
            'another ROS_DOMAIN_ID')
    return topic


def odometry(state, stamp, msg: Odometry | None = None, prefix: str = '',
             z: float = 0.0) -> Odometry:
    """
    Return the nav_msgs/Odometry of a Stepper state (filled into ``msg`` if given).

    Frames ``odom`` -> ``base_link`` (REP 105), with ``prefix`` outside ``/vd``; ``z`` the
    height of the body frame's origin (the model's free-flyer position: 0 at design,
    negative as the body sinks). The covariance is marked unknown (REP 145).
    """
    if msg is None:
        msg = covariance_unknown(Odometry())
    msg.header.stamp = stamp
    msg.header.frame_id = prefix + ODOM_FRAME
    msg.child_frame_id = prefix + BODY_FRAME
    pose, twist = msg.pose.pose, msg.twist.twist
    (pose.position.x, pose.position.y, pose.position.z, pose.orientation.x,
     pose.orientation.y, pose.orientation.z, pose.orientation.w, twist.linear.x,
     twist.linear.y, twist.angular.z) = odometry_values(state, z)
    return msg


def odometry_values(state, z: float = 0.0) -> tuple[float, ...]:
    """
    Return the ODOMETRY_FIELDS of a Stepper state (:func:`odometry`), SI.

    The twist is in the child frame (REP 105): the CoG's horizontal velocity in yaw axes.
    """
    speed, beta = float(state['speed']), float(state['sideslip'])
    return (float(state['x']), float(state['y']), z,
            *quaternion(float(state['roll']), float(state['pitch']), float(state['yaw'])),
            speed * math.cos(beta), speed * math.sin(beta), float(state['yaw_rate']))


def transform(odom: Odometry, msg: TFMessage | None = None) -> TFMessage:
    """Return the TF odom -> base_link of an Odometry (filled into ``msg`` if given)."""
    if msg is None or not msg.transforms:
        msg = TFMessage(transforms=[TransformStamped()])
    t = msg.transforms[0]
    t.header = odom.header
    t.child_frame_id = odom.child_frame_id
    p = odom.pose.pose.position
    t.transform.translation.x, t.transform.translation.y, t.transform.translation.z = p.x, p.y, p.z
    t.transform.rotation = odom.pose.pose.orientation
    return msg


__all__ = ['LockstepSession', 'ACKERMANN_TOPIC', 'COMMAND_TOPIC', 'TWIST_TOPIC', 'STATUS_TOPIC',
           'claim_clock', 'clock_owners', 'command_from_msg', 'odometry', 'odometry_values',
           'stamp_ns',
           'to_stamp']
