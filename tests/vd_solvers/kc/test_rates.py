# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Exact rates at design, instant centres, swing arms and the roll centre.

The rates of the channels at design (implicit function theorem on the
converged tangent, ``solver.sensitivity``) against Richardson-extrapolated
central differences of full equilibrium solves; the instant centres against
their geometric construction from the arm lines (Milliken & Milliken, Race Car
Vehicle Dynamics, SAE 1995, ch. 17: the front-view instant centre of a double
wishbone is where the arm lines meet; the side-view one of arms pivoting about
lateral axes likewise), and the kinematic roll centre against the force-based
one (virtual work).
"""
from __future__ import annotations

import numpy as np
from numpy.testing import assert_allclose
import pytest

from vd_solvers.kc.channels import channels
from vd_solvers.kc.events import KCModel
from vd_solvers.kc.metrics import derived_metrics
from vd_solvers.kc.model import SpringSpec, SuspensionInput
from vd_solvers.kc.solver import Solution, solve_static
from vd_solvers.kc.system import LoadCase

CHANNELS = ('toe', 'camber', 'wheel_travel', 'pad_force', 'contact_point', 'wheel_centre',
            'spring_length', 'steer_angle')


def _solved_rates(model: KCModel, load_of, h: float, ratio=None) -> dict[str, np.ndarray]:
    """Richardson-extrapolated central difference of full solves at +-h, +-2h."""
    out = []
    for t in (-2 * h, -h, h, 2 * h):
        load = load_of(t)
        state, ev, conv = solve_static(model.system, load, 'finite difference')
        sol = Solution((state,), (ev,), (conv,))
        out.append(channels(model.system, model.template, sol, [load], ratio))
    return {n: (8 * (out[2][n][0] - out[1][n][0]) - (out[3][n][0] - out[0][n][0])) / (12 * h)
            for n in CHANNELS}


def _assert_rates(exact, solved, rtol: float, atol: float = 1e-15) -> None:
    """Each channel's rate within ``rtol`` of its largest entry (``atol`` for a held one)."""
    for name in CHANNELS:
        scale = float(np.max(np.abs(exact[name])))
        assert float(np.max(np.abs(solved[name] - exact[name]))) <= rtol * scale + atol, name


@pytest.mark.parametrize('factory', ['macpherson_front', 'hmmwv_front'])
def test_travel_rates_equal_differences_of_full_solves(factory: str, request) -> None:
    model = KCModel(request.getfixturevalue(factory)(), factory)
    result = model.run('parallel_wheel_travel', steps=11)
    solved = _solved_rates(model, lambda t: LoadCase(pad=np.array([t, t])), 2.5e-4)
    _assert_rates(result.rate_up, solved, 1e-8)
    _assert_rates(result.rate_down, solved, 1e-8)


def test_compliance_rates_equal_differences_of_full_solves(hmmwv_front) -> None:
    """Bushed HMMWV: lateral force, and braking and traction on their own sides."""
    model = KCModel(hmmwv_front(), 'hmmwv')
    lateral = model.run('lateral_force', steps=11)

    def on_both(v, k):
        f = np.zeros((2, 3))
        f[:, k] = v
        return f

    solved = _solved_rates(model, lambda t: LoadCase(contact_force=on_both(t, 1)), 5.0)
    _assert_rates(lateral.rate_up, solved, 1e-8)
    lon = model.run('longitudinal_force', steps=11)
    brake = _solved_rates(model, lambda t: LoadCase(contact_force=on_both(t, 0)), 5.0)
    drive = _solved_rates(model, lambda t: LoadCase(centre_force=on_both(t, 0)), 5.0)
    _assert_rates(lon.rate_down, brake, 1e-8)
    _assert_rates(lon.rate_up, drive, 1e-8)
    # the two load paths differ: braking winds the locked wheel up at the contact point
    brake_x, drive_x = lon.rate_down['wheel_centre'][0, 0], lon.rate_up['wheel_centre'][0, 0]
    assert abs(brake_x - drive_x) > 0.01 * abs(drive_x)


def test_steering_rates_equal_differences_of_full_solves(macpherson_front) -> None:
    inp = macpherson_front()
    model = KCModel(inp, 'macpherson')
    result = model.run('steering', steps=11)
    sign, ratio = model.system.outputs.steer_sign, inp.steering.rack_ratio
    solved = _solved_rates(model, lambda a: LoadCase(rack=sign * a * ratio), 1e-3, ratio)
    # the pads hold the wheel height: its rate is zero up to the solves' round-off
    _assert_rates(result.rate_up, solved, 1e-8, atol=1e-12)


@pytest.mark.parametrize('factory', ['macpherson_front', 'multilink_rear'])
def test_kinematic_roll_centre_equals_the_force_based_one(factory: str, request) -> None:
    """
    Check the roll centre from the instant centres against the pads' jacking.

    Rigid linkage: the lines to the front-view instant centres and the pads'
    jacking under a lateral force are one virtual-work statement, exactly.
    """
    inp = request.getfixturevalue(factory)()
    model = KCModel(inp, factory)
    results = {e: model.run(e, steps=11) for e in ('parallel_wheel_travel', 'lateral_force')}
    m = derived_metrics(results, inp.tire_vertical_stiffness)
    assert m['roll_centre_height_force'][0] == pytest.approx(
        m['roll_centre_height_kinematic'][0], rel=1e-9)
    # the design value of the channel along the travel
    ch = results['parallel_wheel_travel'].channels
    assert ch['roll_centre_height'][5] == pytest.approx(m['roll_centre_height_kinematic'][0],
                                                        rel=1e-9)


# A planar double wishbone (front view): every point in the y-z plane x = 0 except the
# pivots, on axes parallel to x; the tie rod is the lower arm shifted rearward.
FRONT_VIEW = {
    'lca_front': [0.20, 0.30, 0.15], 'lca_rear': [-0.20, 0.30, 0.15],
    'lca_outer': [0.0, 0.72, 0.12],
    'uca_front': [0.15, 0.42, 0.45], 'uca_rear': [-0.15, 0.42, 0.45],
    'uca_outer': [0.0, 0.68, 0.48],
    'tierod_inner': [-0.12, 0.30, 0.15], 'tierod_outer': [-0.12, 0.72, 0.12],
    'spring_upper': [0.0, 0.50, 0.60], 'spring_lower': [0.0, 0.55, 0.14],
    'damper_upper': [0.0, 0.50, 0.60], 'damper_lower': [0.0, 0.55, 0.14],
    'wheel_centre': [0.0, 0.80, 0.30],
}
# Arms pivoting about lateral axes (side view): the pivots at equal x and z, apart in y;
# the tie rod is a lateral link (along y at design), so at design the upright moves in
# side view only (three of its points without lateral velocity).
SIDE_VIEW = {
    'lca_front': [0.30, 0.30, 0.15], 'lca_rear': [0.30, 0.55, 0.15],
    'lca_outer': [0.0, 0.72, 0.12],
    'uca_front': [0.25, 0.35, 0.45], 'uca_rear': [0.25, 0.55, 0.45],
    'uca_outer': [0.0, 0.68, 0.48],
    'tierod_inner': [0.15, 0.40, 0.30], 'tierod_outer': [0.15, 0.70, 0.30],
    'spring_upper': [0.15, 0.50, 0.60], 'spring_lower': [0.15, 0.55, 0.14],
    'damper_upper': [0.15, 0.50, 0.60], 'damper_lower': [0.15, 0.55, 0.14],
    'wheel_centre': [0.0, 0.80, 0.30],
}


def _input(points: dict) -> SuspensionInput:
    return SuspensionInput(
        template='double_wishbone', axle='rear',
        hardpoints={k: np.array(v) for k, v in points.items()},
        spring=SpringSpec(rate=30000.0, preload=3000.0), tire_radius=0.30,
        tire_vertical_stiffness=2.5e5, corner_load=4000.0, camber=np.radians(-1.0))


def _meet(p1, q1, p2, q2) -> np.ndarray:
    """Intersection of the line p1-q1 with the line p2-q2 in a plane (2-vectors)."""
    a = np.column_stack((q1 - p1, p2 - q2))
    s = np.linalg.solve(a, p2 - p1)
    return p1 + s[0] * (q1 - p1)


def _tracked(model: KCModel, travel: float) -> dict[str, np.ndarray]:
    """Left-side hard points and contact point at a pad travel (positions only)."""
    system = model.system
    state, _, _ = solve_static(system, LoadCase(pad=np.array([travel, travel])), 'geometry')
    world = system.marker_world(state)[0]
    points = {k: world[i] for k, i in system.outputs.tracked[0].items()}
    points['contact'] = system.contact_points(state)[2][0]
    return points


def test_front_view_instant_centre_is_where_the_arm_lines_meet() -> None:
    model = KCModel(_input(FRONT_VIEW), 'front view')
    result = model.run('parallel_wheel_travel', travel_min=-0.06, travel_max=0.06, steps=7)
    ch = result.channels
    yz = slice(1, 3)
    for i, travel in enumerate(ch['pad_travel'][:, 0]):
        p = _tracked(model, travel)
        ic = _meet(p['lca_front'][yz], p['lca_outer'][yz], p['uca_front'][yz], p['uca_outer'][yz])
        assert_allclose(ch['front_view_instant_centre'][i, 0, 1:], ic, rtol=1e-9, atol=1e-9)
        assert_allclose(ch['front_view_instant_centre'][i, 0, 0], p['wheel_centre'][0],
                        atol=1e-12)
        cp = p['contact'][yz]
        assert ch['fvsa_length'][i, 0] == pytest.approx(cp[0] - ic[0], rel=1e-9)
        # roll centre: the line contact point -> instant centre at the centre plane
        height = cp[1] + (ic[1] - cp[1]) * (0.0 - cp[0]) / (ic[0] - cp[0])
        assert ch['roll_centre_height'][i] == pytest.approx(height - cp[1], rel=1e-8)
        assert ch['roll_centre_lateral'][i] == pytest.approx(0.0, abs=1e-9)
    assert np.ptp(ch['roll_centre_height']) > 0.02  # the roll centre moves with the travel
    m = derived_metrics({'parallel_wheel_travel': result}, 2.5e5)
    assert m['front_view_instant_centre_y'][0] == pytest.approx(
        ch['front_view_instant_centre'][3, 0, 1], rel=1e-12)
    assert m['fvsa_length'] == (pytest.approx(ch['fvsa_length'][3, 0], rel=1e-12), 'm')


def test_side_view_instant_centre_is_where_the_arm_lines_meet() -> None:
    model = KCModel(_input(SIDE_VIEW), 'side view')
    result = model.run('parallel_wheel_travel', travel_min=-0.04, travel_max=0.04, steps=5)
    at = result.design
    xz = [0, 2]
    p = _tracked(model, 0.0)
    ic = _meet(p['lca_front'][xz], p['lca_outer'][xz], p['uca_front'][xz], p['uca_outer'][xz])
    # the construction by hand: lines z = 0.15 + 0.1 (x - 0.3), z = 0.45 - 0.12 (x - 0.25)
    assert ic[0] == pytest.approx(0.36 / 0.22, rel=1e-12)
    assert_allclose(at['side_view_instant_centre'][0, xz], ic, rtol=1e-9)
    assert_allclose(result.channels['side_view_instant_centre'][2, 0, xz], ic, rtol=1e-9)
    cp = p['contact'][xz]
    assert at['svsa_length'][0] == pytest.approx(ic[0] - cp[0], rel=1e-9)
    assert at['svsa_angle'][0] == pytest.approx(np.arctan2(ic[1] - cp[1], abs(ic[0] - cp[0])),
                                                rel=1e-9)
    # a pure side-view motion at design: no camber change, the front-view swing arm infinite
    assert abs(result.rate_up['camber'][0]) < 1e-12
    assert abs(at['fvsa_length'][0]) > 1e3
    m = derived_metrics({'parallel_wheel_travel': result}, 2.5e5)
    assert m['svsa_length'][0] == pytest.approx(ic[0] - cp[0], rel=1e-9)
    assert m['side_view_instant_centre_z'][0] == pytest.approx(ic[1], rel=1e-9)
