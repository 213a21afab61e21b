# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""Bad inputs and impossible events fail loudly with SolverError."""
from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from vd_solvers.errors import SolverError
from vd_solvers.kc.events import KCModel, run_event
from vd_solvers.kc.model import Bushing, SpringSpec, SteeringSpec


def test_unknown_template(double_wishbone) -> None:
    with pytest.raises(SolverError, match="unknown suspension template 'trailing_arm'"):
        KCModel(double_wishbone(template='trailing_arm'))


def test_missing_hard_point_is_named(double_wishbone) -> None:
    inp = double_wishbone()
    points = {k: v for k, v in inp.hardpoints.items() if k != 'uca_outer'}
    with pytest.raises(SolverError, match="hard point 'uca_outer' is missing"):
        KCModel(replace(inp, hardpoints=points))


def test_missing_bar_point_is_named(macpherson_front) -> None:
    inp = macpherson_front()
    points = {k: v for k, v in inp.hardpoints.items() if k != 'arb_pivot'}
    with pytest.raises(SolverError, match="'arb_pivot' is missing"):
        KCModel(replace(inp, hardpoints=points))


def test_label_prefixes_errors(double_wishbone) -> None:
    with pytest.raises(SolverError, match=r'^sedan-base: unknown suspension template'):
        KCModel(double_wishbone(template='nope'), label='sedan-base')


@pytest.mark.parametrize(
    ('overrides', 'message'),
    [
        ({'bushings': {'lca_middle': Bushing((1e6,) * 6)}},
         "bushing 'lca_middle' does not name a connection"),
        ({'masses': {'knuckle': 10.0}}, "mass 'knuckle' names no part"),
        ({'spring': SpringSpec()}, 'exactly one of rate and curve'),
        ({'spring': SpringSpec(rate=-1.0, preload=0.0)}, 'spring rate must be a positive'),
        ({'tire_radius': 0.0}, 'tire_radius'),
        ({'steering': SteeringSpec(0.008, 0.05)}, 'front axle only'),
        ({'joint_axes': {'lca_front': (np.eye(3)[0], np.eye(3)[1])}}, 'not a universal joint'),
    ],
)
def test_bad_inputs(double_wishbone, overrides: dict, message: str) -> None:
    with pytest.raises(SolverError, match=message):
        KCModel(double_wishbone(**overrides))


def test_locked_mechanism_names_event_and_step(double_wishbone) -> None:
    """
    Check that a locked mechanism is reported as singular.

    An upper ball joint on the arm's own pivot axis: the arm's rotation is
    unrestrained (nothing holds it), the equations are singular.
    """
    inp = double_wishbone()
    points = dict(inp.hardpoints)
    points['uca_outer'] = 0.5 * (points['uca_front'] + points['uca_rear'])
    with pytest.raises(SolverError,
                       match=r"event 'parallel_wheel_travel', step 50 of 0..100 .*singular"):
        KCModel(replace(inp, hardpoints=points), label='locked').run('parallel_wheel_travel')


def test_travel_beyond_the_mechanism_range(double_wishbone) -> None:
    message = r"^dw: event 'parallel_wheel_travel', step \d+ of 0..100 \(pad travel = "
    with pytest.raises(SolverError, match=message):
        KCModel(double_wishbone(), label='dw').run('parallel_wheel_travel', travel_min=-0.8,
                                                   travel_max=0.8)


def test_steering_beyond_the_rack_limit(macpherson_front) -> None:
    with pytest.raises(SolverError, match='beyond the 52.4 mm limit'):
        run_event(macpherson_front(), 'steering', steering_wheel_angle=np.radians(720.0))


def test_steering_needs_a_rack(multilink_rear) -> None:
    with pytest.raises(SolverError, match='no steering'):
        run_event(multilink_rear(), 'steering')


@pytest.mark.parametrize(
    ('event', 'params', 'message'),
    [
        ('bounce', {}, "unknown event 'bounce'"),
        ('parallel_wheel_travel', {'amplitude': 0.1}, 'unknown parameter'),
        ('parallel_wheel_travel', {'steps': 2}, 'steps must be an integer >= 3'),
        ('lateral_force', {'force_min': 10.0, 'force_max': -10.0}, 'low < high'),
    ],
)
def test_bad_event_parameters(double_wishbone, event: str, params: dict, message: str) -> None:
    with pytest.raises(SolverError, match=message):
        run_event(double_wishbone(), event, **params)
