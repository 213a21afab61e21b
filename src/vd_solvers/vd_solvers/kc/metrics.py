"""
K&C outputs: per-step, per-wheel channels and the derived metrics.

Angles follow ISO 8855 / SAE J670, per wheel, with the steering axis k
(unit, lower -> upper point from the template), spin axis a (outward) and
side sign s (+1 left, -1 right):

* toe          atan2(a_x, s a_y), positive toe-in
* camber       -asin(a_z), positive top outward; relative to the body. On
  this rig the pads stay level, so camber to the road is the same number.
* steer angle  -s toe, positive to the left (counter-clockwise from above)
* caster       atan2(-k_x, k_z), positive when the axis top leans rearward
* kingpin incl. atan2(-s k_y, k_z), positive when the top leans inboard
* scrub radius (contact point - axis ground point) . outward lateral
  direction of the wheel: positive when the axis meets the ground inboard
* mech. trail  (axis ground point - contact point) . wheel heading: positive
  when the axis meets the ground ahead of the contact point.

The contact point lies one loaded radius from the wheel centre along the road
normal projected into the wheel plane; the axis ground point is where the
steering axis pierces the level plane through the contact point.

Channels are SI (m, rad, N, N*m, J); derived metrics carry engineering units.
"""
from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING

import numpy as np

from vd_solvers.errors import SolverError

from .solver import Solution
from .system import LoadCase, System, contact_direction
from .templates import SuspensionTemplate

if TYPE_CHECKING:
    from .events import EventResult

SIDE_SIGNS = np.array([1.0, -1.0])

# Half-widths of the windows for slopes "at design" (quadratic least squares).
TRAVEL_WINDOW = 0.010  # m of wheel travel
FORCE_WINDOW = 500.0  # N of applied force
MOMENT_WINDOW = 25.0  # N*m of applied aligning torque
RACK_WINDOW = 0.005  # m of rack travel
ACKERMANN_REFERENCE_ANGLE = np.radians(20.0)  # inner road-wheel angle, rad
# A compliance below this (m/N) is reported as infinite stiffness (rigid).
RIGID_COMPLIANCE = 1e-12

DEG = 180.0 / np.pi


def wheel_angles(axis: np.ndarray) -> dict[str, np.ndarray]:
    """Toe, camber and steer angle (rad) from outward spin axes (..., 2, 3)."""
    toe = np.arctan2(axis[..., 0], SIDE_SIGNS * axis[..., 1])
    camber = -np.arcsin(np.clip(axis[..., 2], -1.0, 1.0))
    return {'toe': toe, 'camber': camber, 'steer_angle': -SIDE_SIGNS * toe}


def steering_geometry(
    upper: np.ndarray, lower: np.ndarray, contact: np.ndarray, axis: np.ndarray
) -> dict[str, np.ndarray]:
    """
    Caster, kingpin inclination (rad), scrub radius and mechanical trail
    (m) from steering-axis points, contact points and spin axes (..., 2, 3).
    """
    k = upper - lower
    k = k / np.linalg.norm(k, axis=-1, keepdims=True)
    caster = np.arctan2(-k[..., 0], k[..., 2])
    kpi = np.arctan2(-SIDE_SIGNS * k[..., 1], k[..., 2])
    ground = lower + k * ((contact[..., 2] - lower[..., 2]) / k[..., 2])[..., None]
    lateral = axis.copy()
    lateral[..., 2] = 0.0
    lateral /= np.linalg.norm(lateral, axis=-1, keepdims=True)
    heading = np.stack((lateral[..., 1], -lateral[..., 0], np.zeros_like(lateral[..., 0])), -1)
    heading *= SIDE_SIGNS[:, None]
    offset = contact - ground
    return {
        'caster': caster,
        'kingpin_inclination': kpi,
        'scrub_radius': np.einsum('...i,...i->...', offset, lateral),
        'mechanical_trail': -np.einsum('...i,...i->...', offset, heading),
        'steering_axis_ground': ground,
    }


def channels(
    system: System,
    template: SuspensionTemplate,
    solution: Solution,
    cases: list[LoadCase],
    rack_ratio: float | None,
) -> dict[str, np.ndarray]:
    """
    All per-step channels of a solved event.

    Shapes: per wheel (n, 2) [left, right], vectors (n, 2, 3), bushings
    (n, 2, 6) keyed ``bushing_force.<name>`` / ``bushing_deflection.<name>``
    (bushing frame; x y z in N and m, rx ry rz in N*m and rad; force positive
    along positive deflection), axle-level (n,).
    """
    out = system.outputs
    design = system.design_state()
    wc0, _, _ = system.contact_points(design)
    world = np.array([system.marker_world(s)[0] for s in solution.states])
    vec = np.array([system.marker_world(s)[1] for s in solution.states])
    wheel_idx = np.array([w.centre for w in out.wheels])
    axis_idx = np.array([w.axis for w in out.wheels])
    radius = np.array([w.radius for w in out.wheels])
    centre, axis = world[:, wheel_idx], vec[:, axis_idx]
    contact = centre + radius[None, :, None] * contact_direction(axis.reshape(-1, 3)).reshape(axis.shape)
    points = {
        name: np.stack([world[:, out.tracked[s][name]] for s in range(2)], axis=1)
        for name in out.tracked[0]
    }
    upper, lower = template.steering_axis(points)
    ch: dict[str, np.ndarray] = {
        'wheel_travel': centre[..., 2] - wc0[:, 2],
        'pad_travel': np.array([c.pad for c in cases]),
        'wheel_centre': centre,
        'contact_point': contact,
        'track': contact[:, 0, 1] - contact[:, 1, 1],
        'contact_force': np.array([c.contact_force for c in cases]),
        'centre_force': np.array([c.centre_force for c in cases]),
        'contact_moment': np.array([c.contact_moment for c in cases]),
    }
    ch.update(wheel_angles(axis))
    ch.update(steering_geometry(upper, lower, contact, axis))
    evals = solution.evaluations
    x = np.array([e.x for e in evals])
    d1 = np.array([e.d1 for e in evals])
    y = np.array([e.y for e in evals])
    lam = np.array([s.lam for s in solution.states])
    # The pad constraint is the contact-point height: its reaction on the
    # wheel is -lambda, upward positive.
    ch['pad_force'] = -lam[:, out.pad_rows]
    ch['spring_length'] = x[:, out.spring_length]
    ch['spring_force'] = -d1[:, out.spring]
    ch['damper_length'] = x[:, out.damper_length]
    for name, idx, sign in (
        ('bump_stop', out.bump_stop, -1.0),
        ('rebound_stop', out.rebound_stop, 1.0),
    ):
        if idx is not None:
            ch[f'{name}_force'] = sign * d1[:, idx]
            ch[f'{name}_deflection'] = sign * y[:, idx]
    for name, idx in out.bushings.items():
        ch[f'bushing_force.{name}'] = d1[:, idx]
        ch[f'bushing_deflection.{name}'] = y[:, idx]
    if out.arb_arms is not None and out.droplink_rows is not None:
        # arm (or, for the beam-model bar, drop-link end node) rotation about y
        rot = np.array([s.R[out.arb_arms] for s in solution.states])
        ch['arb_arm_angle'] = np.arctan2(rot[..., 0, 2], rot[..., 0, 0])
        ch['droplink_force'] = lam[:, out.droplink_rows]
        if out.arb_twist is not None:
            ch['arb_twist'] = np.arcsin(y[:, out.arb_twist])
            ch['arb_torque'] = d1[:, out.arb_twist] * np.sqrt(1.0 - y[:, out.arb_twist] ** 2)
        else:
            ch['arb_twist'] = ch['arb_arm_angle'][:, 0] - ch['arb_arm_angle'][:, 1]
    if out.rack_part is not None:
        rack = np.array([s.p[out.rack_part, 1] for s in solution.states]) - design.p[out.rack_part, 1]
        ch['rack_travel'] = rack
        if out.rack_measure is not None:
            ch['rack_force'] = d1[:, out.rack_measure]
        else:
            ch['rack_force'] = lam[:, out.rack_row]
        if rack_ratio is not None:
            ch['steering_wheel_angle'] = out.steer_sign * np.array([c.rack for c in cases]) / rack_ratio
    energy = np.array([e.energy for e in evals])
    ch['elastic_energy'] = energy[:, out.elastic].sum(axis=1)
    ch['constraint_residual'] = np.array([c.constraint_residual for c in solution.convergence])
    ch['force_residual'] = np.array([c.force_residual for c in solution.convergence])
    ch['iterations'] = np.array([c.iterations for c in solution.convergence])
    return ch


# --- derived metrics ----------------------------------------------------------


def _fit_slope(x: np.ndarray, y: np.ndarray) -> float:
    """
    dy/dx at x = 0 from a quadratic least-squares fit (a line when fewer
    than four points).
    """
    if x.size < 2:
        raise SolverError("fewer than two steps in a metric's slope window; refine the event")
    coef = np.polyfit(x, y, 2 if x.size >= 4 else 1)
    return float(coef[-2])


def slope_at(x: np.ndarray, y: np.ndarray, x0: float, half_width: float) -> float:
    """
    dy/dx at x0 from the points within ``half_width`` of x0 (at least the
    three nearest, so a coarse sweep still gives a slope, over a wider window).
    """
    distance = np.abs(x - x0)
    mask = distance <= half_width + 1e-12
    if np.count_nonzero(mask) < 3:
        mask = distance <= np.sort(distance)[min(2, distance.size - 1)] + 1e-12
    return _fit_slope(x[mask] - x0, y[mask])


def _one_sided(x: np.ndarray, y: np.ndarray, sign: float, half_width: float) -> float:
    """
    Slope at 0 from the points with sign*x in [0, half_width] (at least the two
    nearest on that side).
    """
    side = sign * x >= -1e-12
    mask = side & (sign * x <= half_width + 1e-12)
    if np.count_nonzero(mask) < 2:
        reach = np.sort(sign * x[side])[: 2]
        mask = side & (sign * x <= reach[-1] + 1e-12)
    return _fit_slope(x[mask], y[mask])


def _stiffness(compliance: float) -> float:
    """N/mm from a compliance in m/N; inf for a rigid connection."""
    if abs(compliance) < RIGID_COMPLIANCE:
        return float('inf')
    return 1e-3 / compliance


def derived_metrics(
    results: Mapping[str, EventResult],
    tire_vertical_stiffness: float,
    *,
    cg_height: float | None = None,
    wheelbase: float | None = None,
    brake_fraction: float = 1.0,
    drive_fraction: float = 1.0,
) -> dict[str, tuple[float, str]]:
    """
    Derived metrics (name -> (value, unit)) from the events present.

    Slopes are at the design position, from the left wheel unless stated
    (the right is its mirror image); docs/kc.md defines each metric.
    ``cg_height``/``wheelbase`` enable the anti-pitch percentages and the
    Ackermann figure; ``brake_fraction``/``drive_fraction`` are this axle's
    share of the braking and driving force.
    """
    m: dict[str, tuple[float, str]] = {}
    par = results.get('parallel_wheel_travel')
    if par is not None:
        ch = par.channels
        z = ch['wheel_travel'][:, 0]
        at = int(np.argmin(np.abs(ch['pad_travel'][:, 0])))
        m['toe'] = (ch['toe'][at, 0] * DEG, 'deg')
        m['camber'] = (ch['camber'][at, 0] * DEG, 'deg')
        m['caster'] = (ch['caster'][at, 0] * DEG, 'deg')
        m['kingpin_inclination'] = (ch['kingpin_inclination'][at, 0] * DEG, 'deg')
        m['scrub_radius'] = (ch['scrub_radius'][at, 0] * 1e3, 'mm')
        m['mechanical_trail'] = (ch['mechanical_trail'][at, 0] * 1e3, 'mm')
        m['bump_steer'] = (slope_at(z, ch['toe'][:, 0], 0.0, TRAVEL_WINDOW) * DEG, 'deg/m')
        m['camber_gain'] = (slope_at(z, ch['camber'][:, 0], 0.0, TRAVEL_WINDOW) * DEG, 'deg/m')
        m['track_change'] = (slope_at(z, ch['contact_point'][:, 0, 1], 0.0, TRAVEL_WINDOW), 'm/m')
        m['wheelbase_change'] = (slope_at(z, ch['contact_point'][:, 0, 0], 0.0, TRAVEL_WINDOW), 'm/m')
        wheel_rate = slope_at(z, ch['pad_force'][:, 0], 0.0, TRAVEL_WINDOW)
        m['wheel_rate'] = (wheel_rate, 'N/m')
        m['ride_rate'] = (
            wheel_rate * tire_vertical_stiffness / (wheel_rate + tire_vertical_stiffness),
            'N/m',
        )
        m['installation_ratio'] = (slope_at(z, -ch['spring_length'][:, 0], 0.0, TRAVEL_WINDOW), '-')
        cp = ch['contact_point']
        heights = [
            cp[at, s, 1] * slope_at(cp[:, s, 2], cp[:, s, 1], cp[at, s, 2], TRAVEL_WINDOW)
            for s in range(2)
        ]
        m['roll_centre_height_kinematic'] = (float(np.mean(heights)), 'm')
    opp = results.get('opposite_wheel_travel')
    if opp is not None:
        phi, moment = _roll(opp)
        m['roll_stiffness'] = (slope_at(phi, moment, 0.0, _roll_window(opp)) / DEG, 'N*m/deg')
        ch = opp.channels
        steer = ch['steer_angle'].mean(axis=1)
        m['roll_steer'] = (slope_at(phi, steer, 0.0, _roll_window(opp)), 'deg/deg')
        camber_ground = ch['camber'][:, 0] - phi
        m['roll_camber'] = (slope_at(phi, camber_ground, 0.0, _roll_window(opp)), 'deg/deg')
        bare = results.get('opposite_wheel_travel_no_bar')
        if bare is not None:
            phi0, moment0 = _roll(bare)
            k0 = slope_at(phi0, moment0, 0.0, _roll_window(bare)) / DEG
            m['roll_stiffness_no_bar'] = (k0, 'N*m/deg')
            m['roll_stiffness_bar'] = (m['roll_stiffness'][0] - k0, 'N*m/deg')
    lat = results.get('lateral_force')
    if lat is not None:
        ch = lat.channels
        f = ch['contact_force'][:, 0, 1]
        inboard = -SIDE_SIGNS  # lateral force toward the vehicle centre per unit +y
        toe = [inboard[s] * slope_at(f, ch['toe'][:, s], 0.0, FORCE_WINDOW) for s in range(2)]
        camber = [inboard[s] * slope_at(f, ch['camber'][:, s], 0.0, FORCE_WINDOW) for s in range(2)]
        m['lateral_compliance_steer'] = (float(np.mean(toe)) * DEG * 1e3, 'deg/kN')
        m['lateral_compliance_camber'] = (float(np.mean(camber)) * DEG * 1e3, 'deg/kN')
        dy = [slope_at(f, ch['contact_point'][:, s, 1], 0.0, FORCE_WINDOW) for s in range(2)]
        m['lateral_stiffness'] = (_stiffness(float(np.mean(dy))), 'N/mm')
        cp = ch['contact_point']
        at = int(np.argmin(np.abs(f)))
        heights = [
            -cp[at, s, 1] * slope_at(f, ch['pad_force'][:, s], 0.0, FORCE_WINDOW) for s in range(2)
        ]
        m['roll_centre_height_force'] = (float(np.mean(heights)), 'm')
    aligning = results.get('aligning_torque')
    if aligning is not None:
        ch = aligning.channels
        mz = ch['contact_moment'][:, 0, 2]
        steer = [slope_at(mz, ch['steer_angle'][:, s], 0.0, MOMENT_WINDOW) for s in range(2)]
        m['aligning_torque_compliance_steer'] = (float(np.mean(steer)) * DEG * 1e3, 'deg/(kN*m)')
    lon = results.get('longitudinal_force')
    if lon is not None:
        ch = lon.channels
        f = ch['contact_force'][:, 0, 0] + ch['centre_force'][:, 0, 0]
        # Wheel-centre compliance for both (K&C practice): under braking the
        # locked wheel winds up and rolls on the floating pad, so the lowest
        # point of the wheel is not the tire material the force acts on.
        dx_brake = _one_sided(f, ch['wheel_centre'][:, 0, 0], -1.0, FORCE_WINDOW)
        dx_drive = _one_sided(f, ch['wheel_centre'][:, 0, 0], 1.0, FORCE_WINDOW)
        m['longitudinal_stiffness_braking'] = (_stiffness(dx_brake), 'N/mm')
        m['longitudinal_stiffness_traction'] = (_stiffness(dx_drive), 'N/mm')
        m['longitudinal_compliance_steer_braking'] = (
            _one_sided(f, ch['toe'][:, 0], -1.0, FORCE_WINDOW) * DEG * 1e3, 'deg/kN'
        )
        # Pad-load change per unit longitudinal force: the tangent of the
        # side-view force line (braking at the contact point, traction at the
        # wheel centre), positive when the wheel is pushed down.
        tan_brake = -_one_sided(f, ch['pad_force'][:, 0], -1.0, FORCE_WINDOW)
        tan_drive = _one_sided(f, ch['pad_force'][:, 0], 1.0, FORCE_WINDOW)
        m['svsa_angle_braking'] = (np.degrees(np.arctan(tan_brake)), 'deg')
        m['svsa_angle_traction'] = (np.degrees(np.arctan(tan_drive)), 'deg')
        if cg_height is not None and wheelbase is not None:
            front = lon.axle == 'front'
            ratio = wheelbase / cg_height * 100.0
            brake = (1.0 if front else -1.0) * tan_brake * brake_fraction * ratio
            drive = (-1.0 if front else 1.0) * tan_drive * drive_fraction * ratio
            m['anti_dive' if front else 'anti_lift_braking'] = (brake, '%')
            m['anti_lift_traction' if front else 'anti_squat'] = (drive, '%')
    steer = results.get('steering')
    if steer is not None:
        ch = steer.channels
        mean = ch['steer_angle'].mean(axis=1)
        rack = np.abs(ch['rack_travel'])
        near = rack <= max(RACK_WINDOW, np.sort(rack)[min(2, rack.size - 1)]) + 1e-12
        m['steering_ratio'] = (_fit_slope(mean[near], ch['steering_wheel_angle'][near]), '-')
        if wheelbase is not None:
            m['ackermann'] = (_ackermann(ch, wheelbase), '%')
    return m


def _roll(result: EventResult) -> tuple[np.ndarray, np.ndarray]:
    """
    Roll angle (rad, ISO: right side down positive) and the pads' roll
    moment (N*m) of an opposite-travel event.
    """
    ch = result.channels
    at = int(np.argmin(np.abs(ch['pad_travel'][:, 0])))
    track = ch['track'][at]
    z = ch['wheel_travel']
    force = ch['pad_force']
    phi = np.arctan((z[:, 1] - z[:, 0]) / track)
    return phi, 0.5 * track * (force[:, 1] - force[:, 0])


def _roll_window(result: EventResult) -> float:
    at = int(np.argmin(np.abs(result.channels['pad_travel'][:, 0])))
    return 2.0 * TRAVEL_WINDOW / float(result.channels['track'][at])


def _ackermann(ch: Mapping[str, np.ndarray], wheelbase: float) -> float:
    """
    Ackermann % in a left turn at the reference inner (left) wheel angle:
    (inner - outer) / (inner - ideal outer) * 100, ideal outer from the
    turn centre on the rear-axle line and the steering-axis ground points.
    """
    inner, outer = ch['steer_angle'][:, 0], ch['steer_angle'][:, 1]
    order = np.argsort(inner)
    reference = min(ACKERMANN_REFERENCE_ANGLE, 0.8 * float(inner.max()))
    delta_o = float(np.interp(reference, inner[order], outer[order]))
    mid = int(np.argmin(np.abs(inner)))
    ground = ch['steering_axis_ground'][mid]
    pivot_track = float(ground[0, 1] - ground[1, 1])
    ideal = np.arctan(wheelbase / (wheelbase / np.tan(reference) + pivot_track))
    return float((reference - delta_o) / (reference - ideal) * 100.0)
