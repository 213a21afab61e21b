# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""Full-vehicle outcome -> VehicleState and nav_msgs/Odometry messages (bare messages)."""
from __future__ import annotations

import math

from builtin_interfaces.msg import Time
import numpy as np
import pytest

from vd_solvers.conversions import WHEEL_FIELDS, outcome_odometry, outcome_vehicle_states
from vd_solvers.results import Channel, EventOutcome

WHEELS = ('front_left', 'front_right', 'rear_left', 'rear_right')


def _outcome() -> EventOutcome:
    t = np.array([0.0, 0.25])
    channels = {name: Channel('', np.array([0.1, 0.2]) + i)
                for i, name in enumerate(('x', 'y', 'roll', 'pitch', 'yaw_rate', 'speed',
                                          'lateral_acceleration', 'longitudinal_acceleration',
                                          'steering_wheel_angle', 'wheel_torque'))}
    channels['time'] = Channel('s', t)
    channels['yaw'] = Channel('rad', np.array([0.0, math.pi / 2]))
    channels['roll'] = Channel('rad', np.zeros(2))
    channels['pitch'] = Channel('rad', np.zeros(2))
    channels['sideslip'] = Channel('rad', np.array([0.0, 0.1]))
    for k, wheel in enumerate(WHEELS):
        for j, (channel, _) in enumerate(WHEEL_FIELDS.values()):
            channels[f'{channel}_{wheel}'] = Channel('', np.array([k, 10.0 * j + k]))
    return EventOutcome('step_steer', 'baseline', 'vehicle', 'rigid', '', 'abc', {}, channels)


def test_vehicle_states_carry_the_channels_as_named_fields_on_the_simulation_time_axis():
    states = outcome_vehicle_states(_outcome(), Time(sec=100, nanosec=900_000_000))
    assert [s.step for s in states] == [0, 1]
    assert (states[1].header.stamp.sec, states[1].header.stamp.nanosec) == (101, 150_000_000)
    assert states[1].speed == pytest.approx(5.2)
    assert states[1].rear_left.load == 2.0  # wheel 2, field 0
    assert states[1].front_right.aligning_moment == pytest.approx(91.0)  # wheel 1, field 9
    assert states[0].header.frame_id == 'odom' and states[0].configuration == 'baseline'


def test_odometry_is_odom_to_base_link_with_the_yaw_as_quaternion():
    odom = outcome_odometry(_outcome(), Time(sec=100, nanosec=0))
    last = odom[1]
    assert (last.header.frame_id, last.child_frame_id) == ('odom', 'base_link')
    q = last.pose.pose.orientation
    assert (q.w, q.x, q.y, q.z) == pytest.approx((math.cos(math.pi / 4), 0.0, 0.0,
                                                   math.sin(math.pi / 4)))
    assert last.twist.twist.linear.x == pytest.approx(5.2 * math.cos(0.1))
    assert last.twist.twist.linear.y == pytest.approx(5.2 * math.sin(0.1))
    assert last.header.stamp.nanosec == 250_000_000
