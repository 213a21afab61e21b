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
