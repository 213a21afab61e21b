# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Kinematics of the K&C rig.

Symmetry, design pose, a closed-form four-bar, residuals, continuation and steering.
"""
from __future__ import annotations

import numpy as np
import pytest
from scipy.optimize import brentq

from vd_solvers.kc.events import EVENTS, KCModel, run_event
from vd_solvers.kc.model import SpringSpec, SuspensionInput
from vd_solvers.kc.solver import CONSTRAINT_TOL, FORCE_TOL

MIRROR = np.array([1.0, -1.0, 1.0])


@pytest.mark.parametrize('factory', ['macpherson_front', 'multilink_rear', 'hmmwv_front'])
def test_parallel_travel_left_equals_mirrored_right(
    factory: str, request: pytest.FixtureRequest
) -> None:
    result = run_event(request.getfixturevalue(factory)(), 'parallel_wheel_travel')
    ch = result.channels
    for name in ('toe', 'camber', 'caster', 'kingpin_inclination', 'scrub_radius',
                 'mechanical_trail', 'pad_force', 'spring_length', 'wheel_travel'):
        np.testing.assert_allclose(
            ch[name][:, 0], ch[name][:, 1], atol=1e-9, rtol=1e-9, err_msg=name
        )
    for name in ('wheel_centre', 'contact_point'):
        np.testing.assert_allclose(
            ch[name][:, 0], ch[name][:, 1] * MIRROR, atol=1e-9, err_msg=name
        )
    for name in (k for k in ch if k.startswith('bushing_')):
        np.testing.assert_allclose(
            ch[name][:, 0], ch[name][:, 1], atol=1e-6, rtol=1e-7, err_msg=name
        )
    # Parallel travel does not twist the bar.
    if 'arb_twist' in ch:
        np.testing.assert_allclose(ch['arb_twist'], 0.0, atol=1e-12)


@pytest.mark.parametrize('factory', ['macpherson_front', 'multilink_rear', 'double_wishbone'])
def test_design_toe_and_camber_reproduced_at_zero_travel(
    factory: str, request: pytest.FixtureRequest
) -> None:
    inp = request.getfixturevalue(factory)(toe=np.radians(0.15), camber=np.radians(-1.2))
    result = run_event(inp, 'parallel_wheel_travel')
    at = int(np.argmin(np.abs(result.channels['pad_travel'][:, 0])))
    assert result.channels['pad_travel'][at, 0] == 0.0
    np.testing.assert_allclose(result.channels['toe'][at], np.radians(0.15), atol=1e-12)
    np.testing.assert_allclose(result.channels['camber'][at], np.radians(-1.2), atol=1e-12)
    np.testing.assert_allclose(result.channels['wheel_travel'][at], 0.0, atol=1e-12)


@pytest.mark.parametrize(
    'factory', ['macpherson_front', 'multilink_rear', 'double_wishbone', 'hmmwv_front']
)
def test_every_step_meets_the_tolerances(factory: str, request: pytest.FixtureRequest) -> None:
    inp = request.getfixturevalue(factory)()
    model = KCModel(inp)
    for event in EVENTS:
        if event == 'steering' and inp.steering is None:
            continue
        ch = model.run(event).channels
        assert np.all(ch['constraint_residual'] <= CONSTRAINT_TOL), event
        assert np.all(ch['force_residual'] <= FORCE_TOL), event
        assert ch['constraint_residual'].shape == (101,)


# A planar double wishbone: every point in the y-z plane x = 0 except the
# pivots (on axes parallel to x) and the tie rod, which is the lower arm
# shifted 0.12 m rearward, so the upright moves in its plane as a four-bar.
PLANAR = {
    'lca_front': [0.20, 0.30, 0.15],
    'lca_rear': [-0.20, 0.30, 0.15],
    'lca_outer': [0.0, 0.72, 0.12],
    'uca_front': [0.15, 0.42, 0.45],
    'uca_rear': [-0.15, 0.42, 0.45],
    'uca_outer': [0.0, 0.68, 0.48],
    'tierod_inner': [-0.12, 0.30, 0.15],
    'tierod_outer': [-0.12, 0.72, 0.12],
    'spring_upper': [0.0, 0.50, 0.60],
    'spring_lower': [0.0, 0.55, 0.14],
    'damper_upper': [0.0, 0.50, 0.60],
    'damper_lower': [0.0, 0.55, 0.14],
    'wheel_centre': [0.0, 0.80, 0.30],
}
PLANAR_RADIUS = 0.30
PLANAR_CAMBER = np.radians(-1.0)


def _planar_input() -> SuspensionInput:
    return SuspensionInput(
        template='double_wishbone',
        axle='rear',
        hardpoints={k: np.array(v) for k, v in PLANAR.items()},
        spring=SpringSpec(rate=30000.0, preload=3000.0),
        tire_radius=PLANAR_RADIUS,
        tire_vertical_stiffness=2.5e5,
        corner_load=4000.0,
        camber=PLANAR_CAMBER,
    )


def _four_bar(travel: float) -> tuple[float, float]:
    """
    Return camber (rad) and contact-point y (m) at contact-point travel.

    Both come from circle intersection in the y-z plane.
    """
    p = {k: np.array(v[1:]) for k, v in PLANAR.items()}
    a0, b0 = p['lca_front'], p['uca_front']
    a_design, b_design, w_design = p['lca_outer'], p['uca_outer'], p['wheel_centre']
    la, lb = np.linalg.norm(a_design - a0), np.linalg.norm(b_design - b0)
    lc = np.linalg.norm(b_design - a_design)
    theta0 = np.arctan2(*(a_design - a0)[::-1])

    def pose(theta: float) -> tuple[float, np.ndarray]:
        a = a0 + la * np.array([np.cos(theta), np.sin(theta)])
        d = np.linalg.norm(b0 - a)
        along = (lc**2 - lb**2 + d**2) / (2 * d)
        h = np.sqrt(lc**2 - along**2)
        u = (b0 - a) / d
        normal = np.array([-u[1], u[0]])
        # the branch of the design: upper ball joint outboard of the chord
        cands = [a + along * u + s * h * normal for s in (1.0, -1.0)]
        b = min(cands, key=lambda c: np.linalg.norm(c - b_design))
        beta = np.arctan2(*(b - a)[::-1]) - np.arctan2(*(b_design - a_design)[::-1])
        rot = np.array([[np.cos(beta), -np.sin(beta)], [np.sin(beta), np.cos(beta)]])
        return beta, a + rot @ (w_design - a_design)

    def contact(theta: float) -> tuple[float, np.ndarray]:
        beta, w = pose(theta)
        camber = PLANAR_CAMBER - beta  # rotation about +x tilts a left wheel's top inward
        return camber, w + PLANAR_RADIUS * np.array([-np.sin(camber), -np.cos(camber)])

    z0 = contact(theta0)[1][1]
    theta = brentq(lambda t: contact(t)[1][1] - z0 - travel, theta0 - 0.5, theta0 + 0.5)
    camber, cp = contact(theta)
    return camber, cp[0]


def test_planar_double_wishbone_matches_closed_form_four_bar() -> None:
    result = run_event(
        _planar_input(), 'parallel_wheel_travel', travel_min=-0.06, travel_max=0.06, steps=25
    )
    ch = result.channels
    np.testing.assert_allclose(ch['toe'], 0.0, atol=1e-12)  # stays planar
    for i in (0, 6, 12, 18, 24):
        travel = ch['pad_travel'][i, 0]
        camber, cp_y = _four_bar(travel)
        assert ch['camber'][i, 0] == pytest.approx(camber, abs=1e-10)
        assert ch['contact_point'][i, 0, 1] == pytest.approx(cp_y, abs=1e-10)
        assert ch['track'][i] == pytest.approx(2 * cp_y, abs=1e-10)
    assert abs(ch['camber'][0, 0] - ch['camber'][-1, 0]) > np.radians(1.0)  # a real test


def test_solution_does_not_depend_on_the_step_size(double_wishbone) -> None:
    model = KCModel(double_wishbone())
    fine = model.run('parallel_wheel_travel', steps=101).channels
    coarse = model.run('parallel_wheel_travel', steps=5).channels
    for name in ('toe', 'camber', 'pad_force', 'wheel_centre'):
        np.testing.assert_allclose(
            coarse[name], fine[name][::25], atol=1e-9, rtol=1e-10, err_msg=name
        )


def test_opposite_travel_is_antisymmetric(multilink_rear) -> None:
    ch = run_event(multilink_rear(), 'opposite_wheel_travel').channels
    # left at +t equals right at -t (reversed sweep)
    np.testing.assert_allclose(ch['camber'][:, 0], ch['camber'][::-1, 1], atol=1e-9)
    np.testing.assert_allclose(ch['pad_force'][:, 0], ch['pad_force'][::-1, 1], rtol=1e-9)
    np.testing.assert_allclose(ch['arb_twist'], -ch['arb_twist'][::-1], atol=1e-12)


def test_steering_sweep_turns_the_wheels_left_for_positive_angle(macpherson_front) -> None:
    inp = macpherson_front()
    result = run_event(inp, 'steering')
    ch = result.channels
    assert result.params['steering_wheel_angle'] == pytest.approx(
        inp.steering.rack_travel_limit / inp.steering.rack_ratio
    )
    # Rack behind the axle: a left turn moves the rack right.
    np.testing.assert_allclose(
        ch['rack_travel'], -inp.steering.rack_ratio * ch['steering_wheel_angle'], atol=1e-12
    )
    assert np.all(np.diff(ch['steer_angle'], axis=0) > 0.0)
    assert ch['steer_angle'][-1, 0] > ch['steer_angle'][-1, 1] > 0.0  # inner wheel turns more
    np.testing.assert_allclose(ch['steer_angle'][:, 0], -ch['steer_angle'][::-1, 1], atol=1e-9)
