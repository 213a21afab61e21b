# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
EventOutcome -> typed per-step states -> channels, lossless, and the bag's time axis.

Real outcomes of the K&C and analytical models go through the messages and back; every
channel must come back under its name with its unit and every value bit for bit.
"""
from __future__ import annotations

from builtin_interfaces.msg import Time
import numpy as np
import pytest

from vd_solvers.conversions import (
    ANALYTICAL_FIELDS,
    KC_WHEEL_FIELDS,
    PSEUDO_STEP,
    RUN_GAP,
    VEHICLE_FIELDS,
    VEHICLE_WHEELS,
    WHEEL_FIELDS,
    TimeAxis,
    outcome_from_msg,
    outcome_states,
    outcome_to_msg,
    stamp_ns,
    states_channels,
)
from vd_solvers.results import Channel, EventOutcome

START = Time(sec=1_700_000_000, nanosec=999_500_000)


@pytest.fixture(scope='module')
def sedan():
    from vd_data_server.paths import default_master
    from vd_data_server.study import load_study

    return load_study(default_master()).configurations['baseline']


def _kc(sedan, event: str, axle: str = 'front'):
    from vd_solvers.kc.from_config import run_kc_event

    return run_kc_event(sedan, event, axle, ['steps=7'])


def _assert_lossless(outcome: EventOutcome) -> None:
    states = outcome_states(outcome, START)
    assert len(states) == outcome.n_steps
    back = states_channels(states)
    assert set(back) == set(outcome.channels), (set(outcome.channels) ^ set(back))
    for name, channel in outcome.channels.items():
        assert back[name].unit == channel.unit, name
        np.testing.assert_array_equal(back[name].values, channel.values, err_msg=name)


@pytest.mark.parametrize('event', ['parallel_wheel_travel', 'opposite_wheel_travel',
                                   'lateral_force', 'longitudinal_force', 'steering'])
def test_kc_outcomes_survive_the_kc_state_messages(sedan, event):
    _assert_lossless(_kc(sedan, event))


def test_kc_state_fields_are_the_channels_by_name(sedan):
    outcome = _kc(sedan, 'lateral_force')
    states = outcome_states(outcome, START)
    ch = outcome.channels
    i = 3
    s = states[i]
    assert s.left.toe == ch['toe_left'].values[i]
    assert s.right.camber == ch['camber_right'].values[i]
    assert s.left.contact_point.y == ch['contact_point_y_left'].values[i]
    assert s.right.contact_force.y == ch['contact_force_y_right'].values[i]
    assert s.applied_force == ch['applied_force'].values[i]
    (name, *_) = [k.split('.')[1] for k in ch if k.startswith('bushing_force.')]
    bushing = next(b for b in s.left.bushings if b.name == name)
    assert bushing.force.x == ch[f'bushing_force.{name}.x_left'].values[i]
    assert bushing.torque.z == ch[f'bushing_force.{name}.rz_left'].values[i]
    assert bushing.rotation.y == ch[f'bushing_deflection.{name}.ry_left'].values[i]
    assert (s.axle, s.fidelity, s.header.frame_id) == ('front', 'rigid', 'base_link')
    assert set(KC_WHEEL_FIELDS) <= set(s.left.get_fields_and_field_types())


def test_quasi_static_steps_are_one_pseudo_step_apart(sedan):
    states = outcome_states(_kc(sedan, 'parallel_wheel_travel'), START)
    stamps = np.array([stamp_ns(s.header.stamp) for s in states])
    assert stamps[0] == stamp_ns(START)
    np.testing.assert_array_equal(np.diff(stamps), int(PSEUDO_STEP * 1e9))


@pytest.mark.parametrize('event, model', [('handling_diagram', 'two_track'),
                                          ('steady_state_circular', 'bicycle'),
                                          ('step_steer', 'bicycle')])
def test_analytical_outcomes_survive_the_analytical_state_messages(sedan, event, model):
    from vd_solvers.analytical.events import run_event

    outcome = run_event(sedan, event, model, ['steps=11'])
    _assert_lossless(outcome)
    states = outcome_states(outcome, START)
    offsets = np.array([stamp_ns(s.header.stamp) - stamp_ns(START) for s in states]) * 1e-9
    if event == 'step_steer':  # simulated time is the axis
        np.testing.assert_allclose(offsets, outcome.channels['time'].values, atol=1e-9)
    else:  # the swept quantity is a field; the stamps are the pseudo-time
        np.testing.assert_allclose(offsets, np.arange(11) * PSEUDO_STEP, atol=1e-9)
        assert [s.lateral_acceleration for s in states] == list(
            outcome.channels['lateral_acceleration'].values)
    assert set(outcome.channels) <= set(ANALYTICAL_FIELDS)


def test_vehicle_outcomes_survive_the_vehicle_state_messages():
    n = 4
    rng = np.random.default_rng(1)
    channels = {name: Channel(unit, rng.normal(size=n)) for name, unit in VEHICLE_FIELDS.items()}
    channels['time'] = Channel('s', np.arange(n) * 0.01)
    for field, (prefix, unit) in WHEEL_FIELDS.items():
        for wheel in VEHICLE_WHEELS:
            if field == 'steer_angle' and wheel.startswith('rear'):
                continue  # the vehicle model has no rear steering channel
            channels[f'{prefix}_{wheel}'] = Channel(unit, rng.normal(size=n))
    _assert_lossless(EventOutcome('step_steer', 'baseline', 'vehicle', 'rigid', '', 'abc', {},
                                  channels))


def test_event_result_round_trip_keeps_metrics_channels_and_notes(sedan):
    outcome = _kc(sedan, 'parallel_wheel_travel')
    back = outcome_from_msg(outcome_to_msg(outcome, START))
    assert back.metrics == outcome.metrics
    assert back.notes == outcome.notes
    assert set(back.channels) == set(outcome.channels)
    for name, channel in outcome.channels.items():
        np.testing.assert_array_equal(back.channels[name].values, channel.values)


def test_time_axis_never_lets_two_runs_overlap():
    axis = TimeAxis()
    now = 10 * 10**9
    first = axis.claim(now, 3.0)  # a 3 s step steer
    second = axis.claim(now + 1, 0.1)  # solved a nanosecond later
    third = axis.claim(now + 10 * 10**9, 0.0)  # well after both
    assert first == now
    assert second == first + 3 * 10**9 + int(RUN_GAP * 1e9)
    assert third == now + 10 * 10**9
    # every earlier run ends at or before end(): a recorder starting after end() sees
    # none of them (their stamps may lie ahead of the wall clock)
    assert axis.end() == third
    before = axis.end()
    assert axis.claim(now, 0.5) > before


def _rotation(q) -> np.ndarray:
    """Return the rotation matrix of a geometry_msgs quaternion (independent of conversions)."""
    w, x, y, z = q.w, q.x, q.y, q.z
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


@pytest.mark.parametrize('event', ['steering', 'lateral_force', 'opposite_wheel_travel'])
def test_kc_wheel_frames_put_the_contact_point_straight_below_the_wheel_centre(sedan, event):
    """
    Check the wheels' TF frames against the solver's own contact points.

    The contact point lies one loaded radius from the wheel centre along the road
    normal projected into the wheel plane (kc/channels.py); the wheel frame's x axis
    (heading) is level, so in the wheel frame the contact point is (0, 0, -r): a wrong
    toe or camber sign or a swapped side moves it off the z axis.
    """
    from vd_solvers.conversions import outcome_kc_transforms, step_offsets

    outcome = _kc(sedan, event)
    ch = outcome.channels
    tfs = outcome_kc_transforms(outcome, START)
    assert len(tfs) == outcome.n_steps
    states = outcome_states(outcome, START)
    toe_moved = 0.0
    for i, (msg, state) in enumerate(zip(tfs, states)):
        assert [t.child_frame_id for t in msg.transforms] == ['front_left_wheel',
                                                               'front_right_wheel']
        for t, side in zip(msg.transforms, ('left', 'right')):
            assert t.header.frame_id == 'base_link'
            assert t.header.stamp == state.header.stamp  # the same time axis as the states
            r = _rotation(t.transform.rotation)
            np.testing.assert_allclose(r.T @ r, np.eye(3), atol=1e-12)
            centre = np.array([ch[f'wheel_centre_{c}_{side}'].values[i] for c in 'xyz'])
            tr = t.transform.translation
            np.testing.assert_array_equal([tr.x, tr.y, tr.z], centre)
            contact = np.array([ch[f'contact_point_{c}_{side}'].values[i] for c in 'xyz'])
            local = r.T @ (contact - centre)
            np.testing.assert_allclose(local[:2], 0.0, atol=1e-9, err_msg=f'{side} {i}')
            assert 0.25 < -local[2] < 0.40  # the sedan's loaded radius, m
            toe_moved = max(toe_moved, abs(ch[f'toe_{side}'].values[i]))
    assert toe_moved > 1e-4  # the events do turn the wheels
    np.testing.assert_allclose(np.diff(step_offsets(outcome)), PSEUDO_STEP)


def test_kc_wheel_frames_mirror_in_parallel_travel_and_carry_the_prefix(sedan):
    from vd_solvers.conversions import outcome_kc_transforms

    outcome = _kc(sedan, 'parallel_wheel_travel', 'rear')
    for msg in outcome_kc_transforms(outcome, START, prefix='car2/'):
        left, right = msg.transforms
        assert (left.header.frame_id, left.child_frame_id) == ('car2/base_link',
                                                               'car2/rear_left_wheel')
        assert right.child_frame_id == 'car2/rear_right_wheel'
        a, b = left.transform, right.transform
        np.testing.assert_allclose([a.translation.x, a.translation.y, a.translation.z],
                                   [b.translation.x, -b.translation.y, b.translation.z],
                                   atol=1e-9)
        # mirrored in the x-z plane: yaw and roll change sign
        np.testing.assert_allclose([a.rotation.w, a.rotation.x, a.rotation.y, a.rotation.z],
                                   [b.rotation.w, -b.rotation.x, b.rotation.y, -b.rotation.z],
                                   atol=1e-9)


def test_kc_outcome_without_wheel_centres_has_no_frames(sedan):
    """A measured rig file without wheel centres: no TF (and the recorder expects none)."""
    import dataclasses

    from vd_solvers.conversions import has_wheel_frames, outcome_kc_transforms

    outcome = _kc(sedan, 'parallel_wheel_travel')
    assert has_wheel_frames({k: c.values for k, c in outcome.channels.items()})
    partial = dataclasses.replace(outcome, channels={
        k: c for k, c in outcome.channels.items() if k != 'wheel_centre_z_right'})
    assert outcome_kc_transforms(partial, START) == []
    gap = dict(outcome.channels)
    values = gap['wheel_centre_x_left'].values.copy()
    values[2] = np.nan
    gap['wheel_centre_x_left'] = Channel('m', values)
    assert not has_wheel_frames({k: c.values for k, c in gap.items()})
    assert outcome_kc_transforms(dataclasses.replace(outcome, channels=gap), START) == []


# --- messages rewritten in place -------------------------------------------------


def test_a_message_rewritten_in_place_equals_one_built_fresh_with_the_same_values():
    """
    The bytes of an InPlaceMessage are those rclpy serialises for a fresh message.

    Several rounds of values (NaN, extremes of the integer types among them) are written
    into one reused message; each round's bytes deserialise to a message equal, field by
    field, to an Odometry built fresh with those values (the bytes themselves may differ
    in the CDR padding, which carries no value).
    """
    from nav_msgs.msg import Odometry
    from rclpy.serialization import deserialize_message

    from vd_solvers.conversions import InPlaceMessage

    doubles = ('pose.pose.position.x', 'pose.pose.orientation.w', 'twist.twist.angular.z',
               'twist.twist.linear.y')
    template = Odometry(child_frame_id='car2/base_link')
    template.header.frame_id = 'car2/odom'
    template.pose.covariance[0] = -1.0
    packed = InPlaceMessage(template)
    values, seconds = packed.slots(doubles), packed.slots(['header.stamp.sec'])
    nanoseconds = packed.slots(['header.stamp.nanosec'])
    rng = np.random.default_rng(7)
    rounds = [(rng.normal(size=4) * 10.0 ** rng.integers(-5, 6, size=4), int(s), int(n))
              for s, n in zip(rng.integers(0, 2**31, size=5), rng.integers(0, 10**9, size=5))]
    rounds += [(np.array([np.nan, -0.0, np.inf, 5e-324]), 2**31 - 1, 2**32 - 1),
               (np.zeros(4), -2**31, 0)]
    for floats, sec, nanosec in rounds:
        values.write(floats)
        seconds.write(sec)
        nanoseconds.write(nanosec)
        fresh = Odometry(child_frame_id='car2/base_link')
        fresh.header.frame_id = 'car2/odom'
        fresh.header.stamp.sec, fresh.header.stamp.nanosec = sec, nanosec
        fresh.pose.covariance[0] = -1.0
        (fresh.pose.pose.position.x, fresh.pose.pose.orientation.w,
         fresh.twist.twist.angular.z, fresh.twist.twist.linear.y) = floats.tolist()
        back = deserialize_message(packed.data(), Odometry)
        assert _flat(back).keys() == _flat(fresh).keys()
        for key, value in _flat(fresh).items():
            np.testing.assert_array_equal(_flat(back)[key], value, err_msg=key)


def _flat(msg, prefix: str = '') -> dict:
    """Return every leaf field of a message by its dotted path."""
    out = {}
    for name in msg.get_fields_and_field_types():
        value = getattr(msg, name)
        if hasattr(value, 'get_fields_and_field_types'):
            out.update(_flat(value, f'{prefix}{name}.'))
        else:
            out[prefix + name] = value
    return out


@pytest.mark.parametrize('fields, message', [
    (['header.frame_id'], 'Odometry: field header.frame_id is string; in place: double, '
                          'int32, uint32'),
    (['pose.pose.position.w'], 'Odometry: field pose.pose.position.w is not a field; in '
                               'place: double, int32, uint32'),
    (['header.stamp.sec', 'pose.pose.position.x'],
     'Odometry: fields header.stamp.sec, pose.pose.position.x are not of one type '
     '(double, int32)'),
])
def test_a_field_that_cannot_be_rewritten_in_place_is_refused_by_name(fields, message):
    from nav_msgs.msg import Odometry

    from vd_solvers.conversions import InPlaceMessage

    with pytest.raises(ValueError) as err:
        InPlaceMessage(Odometry()).slots(fields)
    assert str(err.value) == message


def test_a_stamp_is_read_out_of_any_serialised_message_but_not_a_field_after_a_string():
    """A header's stamp lies before its frame: read from messages with other frames."""
    from nav_msgs.msg import Odometry
    from rclpy.serialization import serialize_message

    from vd_solvers.conversions import InPlaceMessage

    packed = InPlaceMessage(Odometry())
    sec, nanosec = packed.slots(['header.stamp.sec']), packed.slots(['header.stamp.nanosec'])
    for frame, child, s, n in (('odom', 'base_link', 12, 345), ('car2/odom', 'x', 0, 10**9 - 1),
                               ('', 'a/very/long/child/frame', 2**31 - 1, 0)):
        msg = Odometry(child_frame_id=child)
        msg.header.frame_id = frame
        msg.header.stamp.sec, msg.header.stamp.nanosec = s, n
        data = serialize_message(msg)
        assert sec.read(data).tolist() == [s] and nanosec.read(data).tolist() == [n]
    after = packed.slots(['pose.pose.position.x'])
    with pytest.raises(ValueError) as err:
        after.read(serialize_message(Odometry()))
    assert str(err.value) == ('fields after a string lie where its length puts them: '
                              'deserialise the message to read them')
