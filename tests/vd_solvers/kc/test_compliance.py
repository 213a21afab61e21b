# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""Force elements, bushings and force events: rates, energy, reversibility."""
from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from vd_solvers.kc.events import KCModel, run_event, run_suite
from vd_solvers.kc.metrics import derived_metrics, slope_at
from vd_solvers.kc.model import Bushing, Curve, SpringSpec, SteeringSpec


def test_wheel_rate_is_spring_rate_times_installation_ratio_squared(double_wishbone) -> None:
    inp = double_wishbone()
    upper, lower = inp.hardpoints['spring_upper'], inp.hardpoints['spring_lower']
    rate = 369149.0
    # No preload and no masses: the pad carries the spring alone, so the
    # geometric stiffness of a preload (F * d2L/dz2) does not enter.
    free = float(np.linalg.norm(upper - lower))
    inp = replace(inp, spring=SpringSpec(rate=rate, free_length=free), masses={})
    ch = run_event(inp, 'parallel_wheel_travel', travel_min=-0.0005, travel_max=0.0005,
                   steps=21).channels
    z = ch['wheel_travel'][:, 0]
    ratio = -slope_at(z, ch['spring_length'][:, 0], 0.0, 0.01)
    wheel_rate = slope_at(z, ch['pad_force'][:, 0], 0.0, 0.01)
    assert 0.3 < ratio < 0.7  # spring on the lower arm, about halfway out
    assert wheel_rate == pytest.approx(rate * ratio**2, rel=1e-6)


def test_virtual_work_equals_stored_energy(hmmwv_front) -> None:
    """
    Check virtual work under a small lateral load on the bushed double wishbone.

    The work of the contact forces equals the change of elastic energy
    (bushings, spring).
    """
    inp = hmmwv_front(masses={})
    ch = run_event(inp, 'lateral_force', force_min=-400.0, force_max=400.0, steps=161).channels
    f = ch['contact_force'][:, :, 1]
    y = ch['contact_point'][:, :, 1]
    mid = 80
    assert f[mid, 0] == 0.0
    work = sum(np.trapezoid(f[mid:, s], y[mid:, s]) for s in range(2))
    stored = ch['elastic_energy'][-1] - ch['elastic_energy'][mid]
    assert work > 0.0
    assert stored == pytest.approx(work, rel=2e-3)


def test_reversing_the_lateral_load_reverses_the_compliance(hmmwv_front) -> None:
    ch = run_event(hmmwv_front(), 'lateral_force', force_min=-200.0, force_max=200.0,
                   steps=5).channels
    for name in ('toe', 'camber'):
        plus, minus = ch[name][4] - ch[name][2], ch[name][0] - ch[name][2]
        assert np.all(np.abs(plus) > 1e-7), name
        np.testing.assert_allclose(plus, -minus, rtol=2e-2, err_msg=name)
    # the mirror image of the left wheel under +F is the right wheel under -F
    np.testing.assert_allclose(ch['toe'][4, 0] - ch['toe'][2, 0],
                               ch['toe'][0, 1] - ch['toe'][2, 1], rtol=1e-6)


def test_bar_roll_stiffness_from_torsion_and_motion_ratio(macpherson_front) -> None:
    inp = macpherson_front()
    results = run_suite(inp)
    m = derived_metrics(results, inp.tire_vertical_stiffness)
    par = results['parallel_wheel_travel'].channels
    at = int(np.argmin(np.abs(par['pad_travel'][:, 0])))
    # bar arm rotation per wheel travel, from the kinematics
    motion = slope_at(par['wheel_travel'][:, 0], par['arb_arm_angle'][:, 0], 0.0, 0.01)
    track = par['track'][at]
    bar = inp.stabilizer.torsional_stiffness * (motion * track) ** 2  # N*m/rad
    assert m['roll_stiffness_bar'][0] == pytest.approx(bar, rel=2e-3)
    assert m['roll_stiffness'][0] == pytest.approx(m['roll_stiffness_no_bar'][0] + bar, rel=1e-3)


def test_roll_stiffness_without_bar_from_wheel_rate(multilink_rear) -> None:
    inp = multilink_rear(stabilizer=None)
    results = run_suite(inp)
    m = derived_metrics(results, inp.tire_vertical_stiffness)
    track = results['parallel_wheel_travel'].channels['track'][50]
    # independent suspension: K_roll = wheel rate * t^2 / 2
    expected = m['wheel_rate'][0] * track**2 / 2  # N*m/rad
    assert m['roll_stiffness'][0] == pytest.approx(expected, rel=5e-3)


def test_bump_stop_engages_after_its_clearance(macpherson_front) -> None:
    inp = macpherson_front()
    ch = run_event(inp, 'parallel_wheel_travel', travel_min=-0.10, travel_max=0.10).channels
    compression = -(ch['damper_length'][:, 0] - ch['damper_length'][50, 0])
    free = compression < inp.bump_stop.clearance - 1e-9
    assert np.all(ch['bump_stop_force'][free] == 0.0)
    engaged = compression > inp.bump_stop.clearance + 1e-3
    assert np.any(engaged)
    expected = inp.bump_stop.curve.value(compression[engaged] - inp.bump_stop.clearance)
    np.testing.assert_allclose(ch['bump_stop_force'][engaged, 0], expected, rtol=1e-9)
    extension = -compression
    assert np.any(extension > inp.rebound_stop.clearance)
    assert np.all(ch['rebound_stop_force'][extension > inp.rebound_stop.clearance + 1e-3] > 0.0)
    # the stops stiffen the wheel rate at the ends of travel
    rate = np.gradient(ch['pad_force'][:, 0], ch['wheel_travel'][:, 0])
    assert rate[-1] > 1.2 * rate[50]


def test_spring_preload_trimmed_to_the_corner_load(multilink_rear) -> None:
    inp = multilink_rear()
    assert inp.spring.preload is None and inp.spring.free_length is None
    ch = run_event(inp, 'parallel_wheel_travel').channels
    np.testing.assert_allclose(ch['pad_force'][50], inp.corner_load, rtol=1e-9)


def test_rack_compliance_steers_under_lateral_force(macpherson_front) -> None:
    rigid = macpherson_front()
    soft = macpherson_front(steering=replace(rigid.steering, rack_stiffness=2e6))
    a = run_event(rigid, 'lateral_force').channels
    b = run_event(soft, 'lateral_force').channels
    np.testing.assert_allclose(a['steer_angle'] - a['steer_angle'][50], 0.0, atol=1e-12)
    assert np.ptp(b['rack_travel']) > 1e-5
    assert np.ptp(b['steer_angle']) > 1e-4
    # rack force balances the spring: F = k * (rack travel - command)
    np.testing.assert_allclose(b['rack_force'], 2e6 * b['rack_travel'], rtol=1e-9, atol=1e-9)


def test_bushing_on_a_link_end_makes_the_link_a_part(multilink_rear) -> None:
    k, kr = 2e6, 500.0
    inp = multilink_rear(bushings={'lateral_inner': Bushing((k, k, k, kr, kr, kr))})
    model = KCModel(inp)
    assert 'lateral_link.left' in model.system.part_names
    ch = model.run('lateral_force').channels
    assert ch['bushing_force.lateral_inner'].shape == (101, 2, 6)
    m = derived_metrics({'lateral_force': model.run('lateral_force')}, inp.tire_vertical_stiffness)
    assert np.isfinite(m['lateral_stiffness'][0])
    assert abs(m['lateral_compliance_camber'][0]) > np.radians(1e-4) / 1e3  # 1e-4 deg/kN


def test_nonlinear_bushing_curve(hmmwv_front) -> None:
    base = hmmwv_front()
    progressive = Curve(np.array([-1e-3, -1e-4, 0.0, 1e-4, 1e-3]),
                        np.array([-2e5, -5e3, 0.0, 5e3, 2e5]))
    bushings = {
        name: replace(b, stiffness=(progressive, progressive, progressive) + b.stiffness[3:])
        for name, b in base.bushings.items()
    }
    ch = run_event(replace(base, bushings=bushings), 'longitudinal_force').channels
    d = ch['bushing_deflection.lca_front'][:, 0, :3]
    f = ch['bushing_force.lca_front'][:, 0, :3]
    np.testing.assert_allclose(f, progressive.value(d), rtol=1e-12, atol=1e-9)
    assert np.max(np.abs(d)) > 1e-4  # in the progressive range


def test_traction_jacking_matches_the_wheel_centre_path(double_wishbone) -> None:
    """Rigid linkage: pad-load change per traction force = -dx_wc/dz (virtual work)."""
    inp = double_wishbone()
    model = KCModel(inp)
    par = model.run('parallel_wheel_travel').channels
    lon = model.run('longitudinal_force').channels
    path = slope_at(par['wheel_travel'][:, 0], par['wheel_centre'][:, 0, 0], 0.0, 0.01)
    f = lon['centre_force'][:, 0, 0]
    jacking = slope_at(f[50:], lon['pad_force'][50:, 0], 0.0, 500.0)
    assert jacking == pytest.approx(-path, rel=1e-3, abs=1e-6)


def test_braking_reacts_in_the_upright(hmmwv_front) -> None:
    """
    Check that braking reacts in the upright.

    The locked wheel turns the brake force into a pitch moment on the
    upright: braking at the contact point winds the upright up more than the
    same traction force at the wheel centre.
    """
    ch = run_event(hmmwv_front(), 'longitudinal_force', force_min=-2000.0, force_max=2000.0,
                   steps=3).channels
    caster_brake = ch['caster'][0, 0] - ch['caster'][1, 0]
    caster_drive = ch['caster'][2, 0] - ch['caster'][1, 0]
    assert abs(caster_brake) > 2.0 * abs(caster_drive)


def test_steering_event_to_a_given_steering_wheel_angle(macpherson_front) -> None:
    inp = macpherson_front()
    limit = inp.steering.rack_travel_limit / inp.steering.rack_ratio
    result = run_event(inp, 'steering', steering_wheel_angle=0.5 * limit, steps=21)
    assert result.channels['steering_wheel_angle'][-1] == pytest.approx(0.5 * limit)
    assert abs(result.channels['rack_travel'][-1]) == pytest.approx(
        0.5 * inp.steering.rack_travel_limit)


def test_compliant_rack_lags_its_command(macpherson_front) -> None:
    steering = SteeringSpec(rack_ratio=0.008, rack_travel_limit=0.05, rack_stiffness=5e6)
    ch = run_event(macpherson_front(steering=steering), 'steering', steps=11).channels
    command = -0.008 * ch['steering_wheel_angle']  # rack behind the axle
    np.testing.assert_allclose(ch['rack_travel'] - command, ch['rack_force'] / 5e6, atol=1e-12)
    assert np.max(np.abs(ch['rack_force'])) > 1.0


def test_column_twist_adds_rack_compliance_in_series(macpherson_front) -> None:
    ratio = 0.008
    both = SteeringSpec(ratio, 0.05, rack_stiffness=5e6, column_stiffness=2000.0)
    assert both.rack_compliance() == pytest.approx(1 / 5e6 + ratio**2 / 2000.0)
    ch = run_event(macpherson_front(steering=both), 'lateral_force', steps=5).channels
    np.testing.assert_allclose(ch['rack_travel'], ch['rack_force'] * both.rack_compliance(),
                               atol=1e-15)


def test_stop_curve_starting_beyond_contact_rises_from_zero() -> None:
    from vd_solvers.kc.forces import StopLaw

    law = StopLaw(Curve(np.array([0.005, 0.010]), np.array([150.0, 450.0])), clearance=0.02,
                  direction=-1.0)
    # 1 mm past contact: on the straight line from (0, 0) to (5 mm, 150 N)
    _, force, _ = law.evaluate(np.array([-0.021]))
    assert -force[0] == pytest.approx(30.0)
    _, force, _ = law.evaluate(np.array([-0.019]))
    assert force[0] == 0.0


def test_stiff_bushings_converge_to_the_ideal_joints(hmmwv_front) -> None:
    """
    Check that very stiff bushings reproduce the ideal joints.

    Chrono's arm bushings are free only about the pivot axis; made 1000x
    stiffer they must reproduce the revolute joints they replace.
    """
    ideal = hmmwv_front(with_bushings=False)
    base = hmmwv_front()
    stiff = replace(
        base,
        bushings={n: replace(b, stiffness=tuple(1e3 * k for k in b.stiffness))
                  for n, b in base.bushings.items()},
    )
    a = run_event(ideal, 'parallel_wheel_travel', steps=21).channels
    b = run_event(stiff, 'parallel_wheel_travel', steps=21).channels
    for name in ('toe', 'camber', 'pad_force'):
        scale = np.max(np.abs(a[name] - a[name][10]))
        np.testing.assert_allclose(b[name], a[name], atol=2e-3 * scale, err_msg=name)


# --- aligning torque (moment about +z at both contact points) ------------------------------


def test_rigid_steering_does_not_steer_under_aligning_torque(macpherson_front) -> None:
    ch = run_event(macpherson_front(), 'aligning_torque').channels
    np.testing.assert_allclose(ch['steer_angle'] - ch['steer_angle'][50], 0.0, atol=1e-12)
    np.testing.assert_array_equal(ch['contact_moment'][:, :, 2],
                                  np.repeat(ch['contact_moment'][:, :1, 2], 2, 1))


def test_aligning_torque_steers_through_the_rack_compliance(macpherson_front) -> None:
    rigid = macpherson_front()
    k = 2e6
    soft = run_event(macpherson_front(steering=replace(rigid.steering, rack_stiffness=k)),
                     'aligning_torque', moment_min=-50.0, moment_max=50.0, steps=11)

    def compliance(stiffness: float) -> float:
        """Exact d steer angle / d Mz of the left wheel at design."""
        steer = replace(rigid.steering, rack_stiffness=stiffness)
        run = run_event(macpherson_front(steering=steer), 'aligning_torque', moment_min=-50.0,
                        moment_max=50.0, steps=11)
        return float(run.rate_up['steer_angle'][0] / run.rate_up['contact_moment'][0, 2])

    ch = soft.channels
    mz = ch['contact_moment'][:, 0, 2]
    # the rack force balances its spring
    np.testing.assert_allclose(ch['rack_force'], k * ch['rack_travel'], rtol=1e-9, atol=1e-9)
    # both wheels turn the way the moment turns them, by the same angle (mirror symmetry)
    left = slope_at(mz, ch['steer_angle'][:, 0], 0.0, 25.0)
    right = slope_at(mz, ch['steer_angle'][:, 1], 0.0, 25.0)
    assert left > 0.0
    assert right == pytest.approx(left, rel=1e-9)
    # the fit over +-25 N*m is the exact rate within its bias
    assert compliance(k) == pytest.approx(left, rel=1e-5)
    # a rigid linkage on one compliant rack, in parallel with the constant geometric
    # stiffness of the corner load on the inclined steering axis: 1/compliance is
    # affine in the rack stiffness
    inverse = [1.0 / compliance(k / n) for n in (1.0, 2.0, 4.0)]
    assert inverse[0] - inverse[1] == pytest.approx(2.0 * (inverse[1] - inverse[2]), rel=1e-9)
    m = derived_metrics({'aligning_torque': soft}, rigid.tire_vertical_stiffness)
    assert m['aligning_torque_compliance_steer'] == (pytest.approx(1.0 / inverse[0], rel=1e-12),
                                                    'rad/(N*m)')
