# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Lock-step co-simulation on the ROS graph.

The example controller closes the loop around a constant radius turn, recorded to a
bag whose TF moves the car around the circle; every bad command and a timeout stop
the session with its message, and the state stays where it was.
"""
from __future__ import annotations

import math
from pathlib import Path
import time

import pytest

from vdtest import HANG_GUARD

pytestmark = [pytest.mark.ros, pytest.mark.slow]

RADIUS, SPEED, STEP = 30.0, 12.0, 0.008
LAP = 2.0 * math.pi * RADIUS / SPEED  # 15.7 s
DURATION, STEPS = 17.0, 2125  # a lap, the entry and a margin; 17 s / 8 ms


def test_the_example_controller_drives_a_full_constant_radius_turn(ros_domain, tmp_path,
                                                                   sedan_master):
    from vd_events.bags.bag import read_bag
    from vd_events.orchestration.lockstep import run_lockstep

    bag = tmp_path / 'lockstep'
    out = run_lockstep(master=sedan_master, duration=DURATION, step=STEP, radius=RADIUS,
                       speed=SPEED, bag=bag)
    assert out.status == f'finished at t = {DURATION:.6f} s ({STEPS} steps)', out.status
    steps = STEPS
    assert out.steps == steps and out.bag == bag and (bag / 'metadata.yaml').is_file()
    tf, clock, states, commands = [], [], [], []
    for item in read_bag(bag):
        {'/tf': tf, '/clock': clock, '/vd/vehicle/state': states,
         '/vd/vehicle/command': commands}.get(item.topic, []).append(item)
    # one message per step (the initial state and each step's result), log time = stamp
    assert len(tf) == len(clock) == len(states) == steps + 1
    assert len(commands) >= steps
    for item in tf:
        t, *wheels = item.msg.transforms  # the body, then the wheel frames
        assert len(wheels) == 10  # travel x 4, steer x 2, spin x 4
        assert item.timestamp == t.header.stamp.sec * 10**9 + t.header.stamp.nanosec
        assert (t.header.frame_id, t.child_frame_id) == ('odom', 'base_link')
    assert [c.timestamp for c in clock] == [k * int(STEP * 1e9) for k in range(steps + 1)]
    # the car goes once around the circle: its angle about the centre passes 2 pi, and
    # after the entry transient it keeps to the radius
    turned, last, errors = 0.0, 0.0, []
    for item in tf:
        p = item.msg.transforms[0].transform.translation
        angle = math.atan2(p.x, RADIUS - p.y)
        turned += (angle - last + math.pi) % (2 * math.pi) - math.pi
        last = angle
        if item.timestamp > 3e9:
            errors.append(math.hypot(p.x, p.y - RADIUS) - RADIUS)
    assert turned >= 2.0 * math.pi
    assert max(abs(e) for e in errors) < 1.0
    speeds = [s.msg.speed for s in states if s.timestamp > 3e9]
    assert min(speeds) == pytest.approx(SPEED, abs=0.5) and max(speeds) < SPEED + 0.5


class _Harness:
    """A lock-step solver and a test publisher on one executor."""

    def __init__(self, master: Path, **params) -> None:
        import rclpy
        from rclpy.executors import SingleThreadedExecutor
        from rclpy.parameter import Parameter
        from std_msgs.msg import String

        from vd_data_server.ros.qos import COMMANDS, STATUS
        from vd_interfaces.msg import VehicleCommand
        from vd_solvers.nodes.lockstep import STATUS_TOPIC
        from vd_solvers.nodes.vehicle import VehicleSolver

        values = {'mode': 'lockstep', 'master': str(master), 'step': 0.005,
                  'initial_speed': 10.0, **params}
        self.solver = VehicleSolver(parameter_overrides=[Parameter(k, value=v)
                                                         for k, v in values.items()])
        self.node = rclpy.create_node('lockstep_test')
        self.pub = self.node.create_publisher(VehicleCommand, '/vd/vehicle/command', COMMANDS)
        self.status: list[str] = []
        self.node.create_subscription(String, '/vd/' + STATUS_TOPIC,
                                      lambda m: self.status.append(m.data), STATUS)
        self.executor = SingleThreadedExecutor()
        self.executor.add_node(self.solver)
        self.executor.add_node(self.node)
        self.session = self.solver.lockstep

    def command(self, t: float, **fields) -> None:
        from vd_interfaces.msg import VehicleCommand

        msg = VehicleCommand(**fields)
        ns = int(round(t * 1e9))
        msg.header.stamp.sec, msg.header.stamp.nanosec = ns // 10**9, ns % 10**9
        self.pub.publish(msg)

    def spin_until(self, done, timeout: float = 10.0) -> None:
        deadline = time.monotonic() + timeout
        while not done() and time.monotonic() < deadline:
            self.executor.spin_once(timeout_sec=0.05)

    def close(self) -> None:
        self.executor.shutdown(timeout_sec=0.0)
        self.solver.destroy_node()
        self.node.destroy_node()


@pytest.fixture
def harness(ros_domain, sedan_master):
    made = []

    def make(**params):
        h = _Harness(sedan_master, **params)
        made.append(h)
        h.spin_until(lambda: h.pub.get_subscription_count() > 0, 5.0)
        return h
    yield make
    for h in made:
        h.close()


def _state(h):
    return h.session.stepper.step, h.session.stepper.q.copy()


def test_a_command_for_the_current_step_advances_one_step_and_a_stale_one_is_dropped(harness):
    h = harness()
    h.command(0.0, steering_wheel_angle=0.1)
    h.spin_until(lambda: h.session.stepper.step == 1)
    assert h.session.stepper.step == 1
    h.command(0.0, steering_wheel_angle=0.1)  # answers step 0 again: dropped
    h.spin_until(lambda: h.session.stale == 1, 3.0)
    assert h.session.stale == 1 and h.session.stepper.step == 1 and h.session.active
    h.command(0.005)
    h.spin_until(lambda: h.session.stepper.step == 2)
    assert h.session.stepper.step == 2 and h.session.active


def _leaves(msg, prefix: str = '') -> dict:
    """Return every leaf field of a message by its dotted path (arrays as lists)."""
    out = {}
    for name in msg.get_fields_and_field_types():
        value = getattr(msg, name)
        if hasattr(value, 'get_fields_and_field_types'):
            out.update(_leaves(value, f'{prefix}{name}.'))
        else:
            out[prefix + name] = value.tolist() if hasattr(value, 'tolist') else value
    return out


def _assert_same_fields(got, want, rel: float = 0.0) -> None:
    """Every field equal (NaN to NaN), floats to ``rel``."""
    a, b = _leaves(got), _leaves(want)
    assert a.keys() == b.keys()
    for key, value in b.items():
        if isinstance(value, float):
            assert (math.isnan(a[key]) and math.isnan(value)) or \
                math.isclose(a[key], value, rel_tol=rel, abs_tol=1e-300), (key, a[key], value)
        else:
            assert a[key] == value, (key, a[key], value)


def _fresh(session):
    """
    Build the session's current /clock, state and odometry as message objects, field by field.

    The reference for the messages the session rewrites in place: the state from the
    Stepper's named values, the odometry's quaternion from scipy's z-y-x Euler rotation.
    """
    from builtin_interfaces.msg import Time
    from nav_msgs.msg import Odometry
    from rosgraph_msgs.msg import Clock
    from scipy.spatial.transform import Rotation

    from vd_interfaces.msg import VehicleState, VehicleWheel
    from vd_solvers.conversions import VEHICLE_WHEELS, WHEEL_FIELDS
    from vd_solvers.nodes.lockstep import STATE_FIELDS

    stepper = session.stepper
    s, wheels = stepper.state(), stepper.wheels()
    ns = stepper.step * session.h_ns
    stamp = Time(sec=ns // 10**9, nanosec=ns % 10**9)
    state = VehicleState(event='lockstep', configuration=session.configuration,
                         model='vehicle', step=stepper.step)
    state.header.stamp, state.header.frame_id = stamp, 'odom'
    for name in STATE_FIELDS:
        setattr(state, name, s[name])
    for w, wheel in enumerate(VEHICLE_WHEELS):
        setattr(state, wheel, VehicleWheel(**{
            f: float(wheels[c][w]) if c in wheels else math.nan
            for f, (c, _) in WHEEL_FIELDS.items()}))
    odom = Odometry(child_frame_id='base_link')
    odom.header.stamp, odom.header.frame_id = stamp, 'odom'
    odom.pose.covariance[0] = odom.twist.covariance[0] = -1.0  # unknown (REP 145)
    p, o = odom.pose.pose.position, odom.pose.pose.orientation
    p.x, p.y, p.z = s['x'], s['y'], float(stepper.q[2])
    o.x, o.y, o.z, o.w = Rotation.from_euler(
        'ZYX', [s['yaw'], s['pitch'], s['roll']]).as_quat().tolist()
    t = odom.twist.twist
    t.linear.x = s['speed'] * math.cos(s['sideslip'])
    t.linear.y = s['speed'] * math.sin(s['sideslip'])
    t.angular.z = s['yaw_rate']
    return Clock(clock=stamp), state, odom


def test_the_messages_rewritten_in_place_equal_messages_built_fresh_at_every_step(harness):
    """
    /clock, the state and the odometry of each step, as a subscriber in the process gets them.

    The session reuses one serialised message per topic; every message received is kept
    until the end, so a later step's rewrite showing through an earlier message (the
    publisher's buffer aliased by the subscriber) would fail the comparison.
    """
    from nav_msgs.msg import Odometry
    from rosgraph_msgs.msg import Clock

    from vd_data_server.ros.qos import CLOCK, STATES
    from vd_interfaces.msg import VehicleState

    h = harness()
    got: dict[str, list] = {'clock': [], 'state': [], 'odom': []}
    for key, kind, topic, qos in (('clock', Clock, '/clock', CLOCK),
                                  ('state', VehicleState, '/vd/vehicle/state', STATES),
                                  ('odom', Odometry, '/vd/vehicle/odom', STATES)):
        h.node.create_subscription(kind, topic, got[key].append, qos)

    def received(k: int) -> bool:
        ns = k * h.session.h_ns
        return (any(m.step == k for m in got['state'])
                and any(m.header.stamp.sec * 10**9 + m.header.stamp.nanosec == ns
                        for m in got['odom'])
                and any(m.clock.sec * 10**9 + m.clock.nanosec == ns for m in got['clock']))

    h.session.reset()  # step 0 again, now that the subscriptions are there
    steps, expected = 8, []
    for k in range(steps + 1):
        h.spin_until(lambda: received(k))
        assert received(k), k
        expected.append(_fresh(h.session))
        if k < steps:
            h.command(k * 0.005, steering_wheel_angle=0.04 * k, drive_torque=150.0 * (k % 3),
                      brake_torque=100.0 * (k == 5))
    for k, (clock, state, odom) in enumerate(expected):
        ns = k * h.session.h_ns
        for m in got['state']:
            if m.step == k:
                _assert_same_fields(m, state)
        for m in got['odom']:
            if m.header.stamp.sec * 10**9 + m.header.stamp.nanosec == ns:
                _assert_same_fields(m, odom, rel=1e-12)
        assert [m for m in got['clock'] if m.clock == clock.clock]
    assert len({m.step for m in got['state']}) >= steps + 1


@pytest.mark.parametrize('fields, t, message', [
    ({'steering_wheel_angle': math.nan}, 0.0,
     'command for t = 0.000000 s refused: steering_wheel_angle is not finite (nan)'),
    ({'drive_torque': -10.0}, 0.0,
     'command for t = 0.000000 s refused: drive_torque must be >= 0 N*m, got -10'),
    ({'steering_mode': 1, 'steering_wheel_torque': 3.0}, 0.0,
     'command for t = 0.000000 s refused: steering by torque is not available: the vehicle '
     'model has no steering-system inertia; command the steering-wheel angle '
     '(steering_mode 0)'),
    ({}, 1.0, 'command stamped 1.000000 s for the step at 0.000000 s: ahead of the '
     'simulation clock'),
])
def test_a_bad_command_stops_the_session_with_its_message(harness, fields, t, message):
    h = harness()
    before = _state(h)
    h.command(t, **fields)
    h.spin_until(lambda: not h.session.active)
    assert h.session.status == f'error at t = 0.000000 s: {message}'
    h.spin_until(lambda: h.status and h.status[-1] == h.session.status, 3.0)
    assert h.status[-1] == h.session.status
    step, q = _state(h)
    assert step == before[0] == 0 and (q == before[1]).all()
    # a good command afterwards does not restart it
    h.command(0.0)
    h.spin_until(lambda: False, 0.3)
    assert h.session.stepper.step == 0


def test_no_command_within_the_timeout_is_an_error_not_an_extrapolation(harness):
    h = harness(start_timeout=0.6)
    h.spin_until(lambda: not h.session.active, 5.0)
    assert h.session.status == ('error at t = 0.000000 s: no command for the step at '
                                't = 0.000000 s within 0.6 s')
    assert h.session.stepper.step == 0


@pytest.mark.parametrize('params, message', [
    ({'mode': 'bogus'}, "parameter 'mode' must be one of events, lockstep, free, got 'bogus'"),
    ({'configuration': 'nope'}, "configuration 'nope' is not in the study (configurations: "
     'baseline, stiff_rear, sport)'),
    ({'command_timeout': -1.0}, "parameter 'command_timeout' must be a positive number of "
     'seconds (or factor), got -1.0'),
])
def test_unusable_lockstep_parameters_are_refused_with_their_name(ros_domain, sedan_master,
                                                                  params, message):
    with pytest.raises(ValueError) as err:
        _Harness(sedan_master, **params)
    assert str(err.value) == message


@pytest.mark.parametrize('argv, message', [
    (['--speed', '0'], '--speed 0 is outside [0.5, 60]'),
    (['--config', 'nope'], "configuration 'nope' is not in the study"),
])
def test_vd_launch_lockstep_refuses_bad_arguments_and_writes_nothing(capsys, tmp_path,
                                                                     sedan_master, argv,
                                                                     message):
    from vd_events.cli.main import main

    bag = tmp_path / 'b'
    rc = main(['launch', '--lockstep', '--master', str(sedan_master), '--bag', str(bag), *argv])
    _, err = capsys.readouterr()
    assert rc == 2 and message in err
    assert sorted(e.name for e in tmp_path.iterdir()) == ['data']  # no bag, no partial bag


def test_free_mode_runs_on_its_own_and_holds_the_newest_command(harness):
    """Mode free: steps without waiting; the newest good command is held, a bad one refused."""
    h = harness(mode='free', real_time_factor=1.0, duration=0.5)
    h.command(123.0, steering_wheel_angle=0.1)  # free mode does not check the stamp
    h.spin_until(lambda: h.session.held.steering_wheel_angle == 0.1, 3.0)
    h.command(0.0, steering_wheel_angle=math.nan)  # refused: the previous command is held
    h.spin_until(lambda: not h.session.active, 10.0)
    assert h.session.status == 'finished at t = 0.500000 s (100 steps)'
    assert h.session.held.steering_wheel_angle == 0.1
    assert h.session.stepper.state()['steering_wheel_angle'] == 0.1


def test_a_second_controller_on_the_command_topic_stops_the_session(harness):
    import rclpy

    from vd_data_server.ros.qos import COMMANDS
    from vd_interfaces.msg import VehicleCommand

    h = harness()
    other = rclpy.create_node('second_controller')
    try:
        other.create_publisher(VehicleCommand, '/vd/vehicle/command', COMMANDS)
        h.executor.add_node(other)
        h.spin_until(lambda: not h.session.active, HANG_GUARD)
        assert h.session.status == (
            'error at t = 0.000000 s: 2 publishers on /vd/vehicle/command (/lockstep_test, '
            '/second_controller): lock-step takes the commands of one controller; stop the '
            'others')
        assert h.session.stepper.step == 0
    finally:
        h.executor.remove_node(other)
        other.destroy_node()
