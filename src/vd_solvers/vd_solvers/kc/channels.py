# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
K&C channels: what is computed per step of an event, per wheel.

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

Kinematic channels of the travel events (:func:`instant_centres`) come from
the wheel carrier's exact velocity along the travel (the twist of the
upright per unit pad travel, :func:`.solver.sensitivity`): the front-view
and side-view instant centres, the swing-arm lengths and the kinematic roll
centre (Milliken & Milliken, Race Car Vehicle Dynamics, SAE 1995, ch. 17).

All channels are SI (m, rad, N, N*m, J); :data:`UNITS` names the unit of each.
"""
from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from .solver import Sensitivity, Solution
from .system import LoadCase, System, contact_direction
from .templates import SuspensionTemplate

SIDE_SIGNS = np.array([1.0, -1.0])

#: SI unit of every channel (bushing channels by kind: see :func:`bushing_unit`)
UNITS = {
    'wheel_travel': 'm', 'pad_travel': 'm', 'wheel_centre': 'm', 'contact_point': 'm',
    'track': 'm', 'contact_force': 'N', 'centre_force': 'N', 'contact_moment': 'N*m',
    'toe': 'rad', 'camber': 'rad', 'caster': 'rad', 'kingpin_inclination': 'rad',
    'scrub_radius': 'm', 'mechanical_trail': 'm', 'steer_angle': 'rad', 'pad_force': 'N',
    'spring_length': 'm', 'spring_force': 'N', 'damper_length': 'm', 'bump_stop_force': 'N',
    'bump_stop_deflection': 'm', 'rebound_stop_force': 'N', 'rebound_stop_deflection': 'm',
    'arb_twist': 'rad', 'arb_torque': 'N*m', 'arb_arm_angle': 'rad', 'droplink_force': 'N',
    'rack_travel': 'm', 'rack_force': 'N', 'steering_wheel_angle': 'rad',
    'elastic_energy': 'J', 'constraint_residual': 'm', 'force_residual': 'N',
    'iterations': '-', 'camber_ground': 'rad', 'steering_axis_ground': 'm',
    'front_view_instant_centre': 'm', 'side_view_instant_centre': 'm', 'fvsa_length': 'm',
    'svsa_length': 'm', 'svsa_angle': 'rad', 'roll_centre_height': 'm',
    'roll_centre_lateral': 'm',
}
#: channels that describe the solve, not the axle (no rate at design)
SOLVER_CHANNELS = ('constraint_residual', 'force_residual', 'iterations')
#: events whose driving parameter is a wheel motion: they carry the kinematic channels
TRAVEL_EVENTS = ('parallel_wheel_travel', 'opposite_wheel_travel')


def bushing_unit(name: str, component: int) -> str:
    """SI unit of component 0..5 (x y z rx ry rz) of bushing channel ``name``."""
    if 'force' in name:
        return 'N' if component < 3 else 'N*m'
    return 'm' if component < 3 else 'rad'


def wheel_angles(axis: np.ndarray) -> dict[str, np.ndarray]:
    """Compute toe, camber and steer angle (rad) from outward spin axes (..., 2, 3)."""
    toe = np.arctan2(axis[..., 0], SIDE_SIGNS * axis[..., 1])
    camber = -np.arcsin(np.clip(axis[..., 2], -1.0, 1.0))
    return {'toe': toe, 'camber': camber, 'steer_angle': -SIDE_SIGNS * toe}


def steering_geometry(
    upper: np.ndarray, lower: np.ndarray, contact: np.ndarray, axis: np.ndarray
) -> dict[str, np.ndarray]:
    """
    Compute caster, kingpin inclination, scrub radius and mechanical trail.

    Angles in rad, lengths in m, from steering-axis points, contact points
    and spin axes (..., 2, 3).
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
    cases: Sequence[LoadCase],
    rack_ratio: float | None,
    rates: Sequence[Sensitivity] | None = None,
) -> dict[str, np.ndarray]:
    """
    Compute all per-step channels of a solved event.

    ``rates``: the equilibrium's rate along the travel per step, for the
    kinematic channels of :func:`instant_centres` (travel events).

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
    direction = contact_direction(axis.reshape(-1, 3)).reshape(axis.shape)
    contact = centre + radius[None, :, None] * direction
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
        rack = np.array([s.p[out.rack_part, 1] for s in solution.states])
        ch['rack_travel'] = rack - design.p[out.rack_part, 1]
        if out.rack_measure is not None:
            ch['rack_force'] = d1[:, out.rack_measure]
        else:
            ch['rack_force'] = lam[:, out.rack_row]
        if rack_ratio is not None:
            command = np.array([c.rack for c in cases])
            ch['steering_wheel_angle'] = out.steer_sign * command / rack_ratio
    energy = np.array([e.energy for e in evals])
    ch['elastic_energy'] = energy[:, out.elastic].sum(axis=1)
    ch['constraint_residual'] = np.array([c.constraint_residual for c in solution.convergence])
    ch['force_residual'] = np.array([c.force_residual for c in solution.convergence])
    ch['iterations'] = np.array([c.iterations for c in solution.convergence])
    if rates is not None:
        centre_rate, omega = carrier_twist(system, solution, rates)
        ch.update(instant_centres(centre, contact, centre_rate, omega))
    return ch



def instant_centres(centre: np.ndarray, contact: np.ndarray, centre_rate: np.ndarray,
                    omega: np.ndarray) -> dict[str, np.ndarray]:
    """
    Kinematic channels from the wheel carrier's twist along a travel event.

    ``centre``, ``contact`` (n, 2, 3): wheel centres and contact points;
    ``centre_rate`` (n, 2, 3): wheel-centre velocity and ``omega`` (n, 2, 3)
    the upright's angular velocity, per unit of the swept pad travel. With v
    the wheel-centre velocity and w the angular velocity:

    * ``front_view_instant_centre`` (n, 2, 3): the point of the transverse
      plane through the wheel centre where the carrier's velocity has no y
      and z component: y = y_wc - v_z / w_x, z = z_wc + v_y / w_x;
    * ``side_view_instant_centre`` (n, 2, 3): the point of the longitudinal
      plane through the wheel centre where it has no x and z component:
      x = x_wc + v_z / w_y, z = z_wc - v_x / w_y;
    * ``fvsa_length`` (n, 2): front-view swing-arm length, s (y_cp - y_IC),
      positive with the instant centre inboard of the contact point;
    * ``svsa_length`` (n, 2): side-view swing-arm length x_IC - x_cp,
      positive with the instant centre ahead of the contact point;
    * ``svsa_angle`` (n, 2): elevation of the side-view instant centre seen
      from the contact point, atan2(z_IC - z_cp, |x_IC - x_cp|);
    * ``roll_centre_height``, ``roll_centre_lateral`` (n,): the kinematic
      roll centre, where the front-view lines of both wheels through the
      contact point and normal to its velocity (the line to the front-view
      instant centre) meet; its height above the mid-point of the contact
      points and its y. A parallel pair (no intersection) gives inf.

    An infinite swing arm (w_x or w_y zero) gives inf coordinates.
    """
    with np.errstate(divide='ignore', invalid='ignore'):
        fv = centre.copy()
        fv[..., 1] = centre[..., 1] - centre_rate[..., 2] / omega[..., 0]
        fv[..., 2] = centre[..., 2] + centre_rate[..., 1] / omega[..., 0]
        sv = centre.copy()
        sv[..., 0] = centre[..., 0] + centre_rate[..., 2] / omega[..., 1]
        sv[..., 2] = centre[..., 2] - centre_rate[..., 0] / omega[..., 1]
    contact_rate = centre_rate + np.cross(omega, contact - centre)
    normal = contact_rate[..., 1:]  # front view (y, z): the line is normal to it
    a = normal  # (n, 2 lines, 2 coordinates)
    b = np.einsum('nsi,nsi->ns', normal, contact[..., 1:])
    det = a[:, 0, 0] * a[:, 1, 1] - a[:, 0, 1] * a[:, 1, 0]
    with np.errstate(divide='ignore', invalid='ignore'):
        y_rc = (b[:, 0] * a[:, 1, 1] - b[:, 1] * a[:, 0, 1]) / det
        z_rc = (a[:, 0, 0] * b[:, 1] - a[:, 1, 0] * b[:, 0]) / det
        dx = sv[..., 0] - contact[..., 0]
        return {
            'front_view_instant_centre': fv,
            'side_view_instant_centre': sv,
            'fvsa_length': SIDE_SIGNS * (contact[..., 1] - fv[..., 1]),
            'svsa_length': dx,
            'svsa_angle': np.arctan2(sv[..., 2] - contact[..., 2], np.abs(dx)),
            'roll_centre_height': z_rc - contact[..., 2].mean(axis=1),
            'roll_centre_lateral': y_rc,
        }


def carrier_twist(system: System, solution: Solution,
                  rates: Sequence[Sensitivity]) -> tuple[np.ndarray, np.ndarray]:
    """Wheel-centre velocity and upright angular velocity (n, 2, 3) per step."""
    out = system.outputs
    parts = np.array([w.part for w in out.wheels])
    world = np.array([system.marker_world(s)[0] for s in solution.states])
    centre = world[:, [w.centre for w in out.wheels]]
    origin = np.array([s.p[parts] for s in solution.states])
    dq = np.array([r.dq[parts] for r in rates])
    omega = dq[..., 3:]
    return dq[..., :3] + np.cross(omega, centre - origin), omega
