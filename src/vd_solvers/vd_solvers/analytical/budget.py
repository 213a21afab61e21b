# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Understeer-gradient budget and effective axle cornering stiffness.

The linear-range understeer gradient of a car is the sum of the tire's own
term and of every mechanism that steers or cambers the wheels, or moves the
lateral force between the axles, in proportion to the lateral acceleration
(Gillespie, "Fundamentals of Vehicle Dynamics", ch. 6, "Understeer gradient"
and its summary table; Milliken & Milliken, "Race Car Vehicle Dynamics",
ch. 5, "effective axle cornering stiffness")::

    K = tire + roll_steer + lateral_compliance_steer + aligning_torque + camber
        + aligning_moment + rolling_resistance + rolling_resistance_pitch
                                                                (linear, a_y -> 0)
        + load_transfer + tire_nonlinearity           (over the linear range)

Each compliance term is a front minus rear difference of the axles' *compliance
slip* e_i: the kinematic slip angle of axle i (delta - beta - a r/V at the
front) minus its tires' slip angle, per unit lateral acceleration. With N_i the
static axle load, f_i = N_i/(2 g) the lateral force per wheel per m/s^2,
rho the roll gradient (rad per m/s^2), C_w the cornering stiffness of one
tire at the static wheel load and the signs of
:class:`~vd_solvers.analytical.params.AxleCompliance` (steer positive to the
left, ISO 8855; a left turn has positive a_y, roll and tire forces)::

    tire                      (N_f/C_f - N_r/C_r)/g                     (eq. 2 / g)
    roll_steer                e_i = -roll_steer_i rho
    lateral_compliance_steer  e_i = -c_i f_i
    aligning_torque           e_i = +c_Mz,i t_i f_i    (Mz = -t F_y on each wheel)
    camber                    e_i = -(C_gamma,i / C_w,i) (roll_camber_i rho
                                     - lateral_compliance_camber_i f_i)

The camber term uses the lean of both wheels towards +y: roll_camber rho from
the body roll plus -lateral_compliance_camber f from the lateral force (both
wheels lean the same way by left/right symmetry); a lean gamma gives the tire a
force C_gamma gamma, so the slip needed falls by C_gamma gamma / C_w.

Two terms move lateral force from one axle to the other: the yaw balance of the
single track, a F_f - b F_r + M = 0, holds moments besides the axle forces'.
The tires' aligning moments M_z = -t F_y put each axle's force t behind it; the
rolling resistance, larger on the outer wheel by the load transfer, turns the car
out of the turn (M = -sum t_i rho_rr,i dF_zi, rho_rr the free-rolling F_x/F_z).
With F_f + F_r = m a_y::

    F_f = (m a_y (b + t_r) - M_rr) / (L - t_f + t_r)

and the axle slips move by dF_i / C_i,eff (C_i,eff of the compliance terms):

    aligning_moment           dF_f = m (b + t_r)/(L - t_f + t_r) - m b/L  per m/s^2
    rolling_resistance        dF_f = sum t_i rho_rr,i tau_i / (L - t_f + t_r)
                              (tau_i: the load transfer per m/s^2, eq. 4)

One term moves vertical load between the axles: the free-rolling tires'
rolling-resistance moments M_y = -rho_rr,i F_z R_l,i (the contact pressure's centre
ahead of the wheel centre) in the body's pitch balance take
dN = sum rho_rr,i R_l,i N_i / L from the front axle to the rear, at any speed. The
lateral forces stay where the yaw balance puts them; the tires' cornering stiffness
follows the loads::

    rolling_resistance_pitch  e_i = N_i/g (1/C_i(N_i -+ dN) - 1/C_i(N_i))
                              (C_i(N): the axle's two tires at N/2 each; - front,
                              + rear)

The terms so far are linear: the bicycle model with C_eff has exactly their sum
as K. Over the linear range the full vehicle and the two-track model report
(ISO 4138, a least-squares slope over 1..3 m/s^2) two more, second order in a_y,
which only a model with the wheel loads and the tires' curves holds; the
two-track model (:mod:`.cornering`) supplies them when it is given:

    load_transfer             the loads' change of the axles' stiffness
                              (C(N/2 + dF) + C(N/2 - dF) - 2 C(N/2) = C'' dF^2):
                              the gradient with the loads less that with every
                              wheel at its static load
    tire_nonlinearity         the tires' curves at the slip of 1..3 m/s^2:
                              the gradient at static loads less the linear one

Effective axle cornering stiffness: N_i/C_eff,i = N_i/C_i + g e_i, so the
bicycle model with C_eff has exactly K = tire + the linear terms. With a
rigid axle (all compliance zero, no trail or rolling resistance) C_eff is the
bare tire's C itself.
"""
from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
import math

from vd_solvers.analytical.params import AxleCompliance, VehicleParams
from vd_solvers.analytical.two_track import roll_geometry
from vd_solvers.errors import SolverError

#: budget terms: Gillespie's order, then the force shifts, then the range terms
TERMS = ('tire', 'load_transfer', 'roll_steer', 'lateral_compliance_steer', 'aligning_torque',
         'camber', 'aligning_moment', 'rolling_resistance', 'rolling_resistance_pitch',
         'tire_nonlinearity')
#: the terms second order in a_y, from the two-track model over the linear range
RANGE_TERMS = ('load_transfer', 'tire_nonlinearity')
#: the terms that move lateral force between the axles
SHIFT_TERMS = ('aligning_moment', 'rolling_resistance')
#: the terms that move vertical load between the axles
PITCH_TERMS = ('rolling_resistance_pitch',)
#: the source of every compliance term of a parameter set without K&C results
BARE_TIRE = 'bare tire: no K&C results'
#: the source of a range term the two-track model did not supply
NO_RANGE = 'not evaluated: the two-track model over the linear range gives it'


@dataclass(frozen=True)
class BudgetTerm:
    """One term of the budget, rad/(m/s^2): front minus rear compliance slip."""

    name: str
    front: float
    rear: float
    source: str
    value: float  # front - rear (the tire term: (N_f/C_f - N_r/C_r)/g as eq. 2 rounds it)


@dataclass(frozen=True)
class UndersteerBudget:
    """The terms (in :data:`TERMS` order) and their sum, rad/(m/s^2)."""

    terms: tuple[BudgetTerm, ...]
    roll_gradient: float  # rad/(m/s^2), used by the roll terms (0 if none needs it)

    @property
    def total(self) -> float:
        total = 0.0
        for term in self.terms:
            total += term.value
        return total

    def term(self, name: str) -> BudgetTerm:
        return next(t for t in self.terms if t.name == name)


def _axle(p: VehicleParams, axle: str) -> tuple[float, float, AxleCompliance]:
    """Return the static axle load N (N), bare axle cornering stiffness (N/rad), compliance."""
    if axle == 'front':
        load, tire, comp = p.axle_load_front, p.tire_front, p.compliance_front
    else:
        load, tire, comp = p.axle_load_rear, p.tire_rear, p.compliance_rear
    return load, 2.0 * float(tire.cornering_stiffness(load / 2.0)), comp


def compliance_slip(p: VehicleParams, axle: str, roll_gradient: float) -> dict[str, float]:
    """Compliance slip per unit a_y of ``axle`` per term, rad/(m/s^2) (module doc)."""
    load, stiffness, c = _axle(p, axle)
    force = load / (2.0 * p.g)  # N per wheel per m/s^2
    wheel_stiffness = stiffness / 2.0
    lean = c.roll_camber * roll_gradient - c.lateral_compliance_camber * force
    return {
        'roll_steer': -c.roll_steer * roll_gradient,
        'lateral_compliance_steer': -c.lateral_compliance_steer * force,
        'aligning_torque': c.aligning_torque_compliance_steer * c.pneumatic_trail * force,
        'camber': -c.camber_stiffness / wheel_stiffness * lean,
    }


def force_shift(p: VehicleParams) -> dict[str, float]:
    """
    Front axle's extra lateral force per unit a_y per shift term, N/(m/s^2) (module doc).

    The rear axle's is the opposite.
    """
    from vd_solvers.analytical.two_track import load_transfer

    t_f = p.compliance_front.pneumatic_trail
    t_r = p.compliance_rear.pneumatic_trail
    lever = p.wheelbase - t_f + t_r
    transfer = load_transfer(p, 1.0)  # N per m/s^2, front and rear (linear range)
    rolling = (p.track_front * p.compliance_front.rolling_resistance * float(transfer[0])
               + p.track_rear * p.compliance_rear.rolling_resistance * float(transfer[1]))
    return {
        'aligning_moment': p.mass * ((p.cog_to_rear_axle + t_r) / lever
                                     - p.cog_to_rear_axle / p.wheelbase),
        'rolling_resistance': rolling / lever,
    }


def pitch_load_shift(p: VehicleParams) -> float:
    """
    Load the rolling-resistance moments take from the front axle to the rear, N.

    sum rho_rr,i R_l,i N_i / L over the axles (module doc).
    """
    front, rear = p.compliance_front, p.compliance_rear
    moment = (front.rolling_resistance * front.loaded_radius * p.axle_load_front
              + rear.rolling_resistance * rear.loaded_radius * p.axle_load_rear)
    return moment / p.wheelbase


def pitch_slip(p: VehicleParams) -> tuple[float, float]:
    """Front and rear axle slip per unit a_y of the rolling-resistance pitch, rad/(m/s^2)."""
    shift = pitch_load_shift(p)
    out = []
    for axle, sign in (('front', -1.0), ('rear', 1.0)):
        load, stiffness, _ = _axle(p, axle)
        tire = p.tire_front if axle == 'front' else p.tire_rear
        moving = 2.0 * float(tire.cornering_stiffness((load + sign * shift) / 2.0))
        out.append(load / p.g * (1.0 / moving - 1.0 / stiffness))
    return out[0], out[1]


def _roll_gradient(p: VehicleParams) -> float:
    """Roll gradient, rad/(m/s^2), where a roll term needs it (0.0 otherwise)."""
    needs = any(c.roll_steer != 0.0 or (c.roll_camber != 0.0 and c.camber_stiffness != 0.0)
                for c in (p.compliance_front, p.compliance_rear))
    return roll_geometry(p).roll_gradient if needs else 0.0


def _compliance_stiffness(p: VehicleParams, rho: float) -> tuple[float, float]:
    """Effective axle stiffness of the compliance terms alone, N/rad (front, rear)."""
    out = []
    for axle in ('front', 'rear'):
        load, stiffness, _ = _axle(p, axle)
        slip = load / stiffness + p.g * sum(compliance_slip(p, axle, rho).values())
        if not slip > 0.0:
            raise SolverError(
                f"{axle} axle: the compliance slip "
                f"{math.degrees(slip - load / stiffness):.4g} deg/g cancels the tires' "
                f"{math.degrees(load / stiffness):.4g} deg/g: no positive effective cornering "
                "stiffness")
        out.append(load / slip)
    return out[0], out[1]


def shift_slip(p: VehicleParams, rho: float) -> dict[str, tuple[float, float]]:
    """Front and rear axle slip per unit a_y of each shift term, rad/(m/s^2)."""
    c_f, c_r = _compliance_stiffness(p, rho)
    return {name: (shift / c_f, -shift / c_r) for name, shift in force_shift(p).items()}


def understeer_budget(p: VehicleParams,
                      range_terms: Mapping[str, tuple[float, str]] | None = None
                      ) -> UndersteerBudget:
    """
    Return the budget of ``p`` (module doc); each term names its sources.

    ``range_terms``: ``load_transfer`` and ``tire_nonlinearity`` (rad/(m/s^2), source)
    from the two-track model over the linear range; without them both are 0 and say so.
    """
    rho = _roll_gradient(p)
    load_f, c_f, comp_f = _axle(p, 'front')
    load_r, c_r, comp_r = _axle(p, 'rear')
    slip_f = compliance_slip(p, 'front', rho)
    slip_r = compliance_slip(p, 'rear', rho)
    shifts = shift_slip(p, rho)
    pitch = pitch_slip(p)
    ranges = dict(range_terms or {})
    terms = []
    for name in TERMS:
        if name == 'tire':
            terms.append(BudgetTerm('tire', load_f / c_f / p.g, load_r / c_r / p.g,
                                    f"front: {p.sources.get('tire_front', 'tire_front')}; "
                                    f"rear: {p.sources.get('tire_rear', 'tire_rear')}",
                                    (load_f / c_f - load_r / c_r) / p.g))
        elif name in RANGE_TERMS:
            value, source = ranges.get(name, (0.0, NO_RANGE))
            terms.append(BudgetTerm(name, value, 0.0, source, value))
        elif name in SHIFT_TERMS:
            front, rear = shifts[name]
            terms.append(BudgetTerm(name, front, rear, _source(p, name, comp_f, comp_r),
                                    front - rear))
        elif name in PITCH_TERMS:
            terms.append(BudgetTerm(name, pitch[0], pitch[1],
                                    _source(p, name, comp_f, comp_r), pitch[0] - pitch[1]))
        else:
            terms.append(BudgetTerm(name, slip_f[name], slip_r[name],
                                    _source(p, name, comp_f, comp_r),
                                    slip_f[name] - slip_r[name]))
    return UndersteerBudget(tuple(terms), rho)


_TERM_FIELDS = {
    'aligning_moment': ('pneumatic_trail',),
    'rolling_resistance': ('rolling_resistance',),
    'rolling_resistance_pitch': ('rolling_resistance', 'loaded_radius'),
    'roll_steer': ('roll_steer',),
    'lateral_compliance_steer': ('lateral_compliance_steer',),
    'aligning_torque': ('aligning_torque_compliance_steer', 'pneumatic_trail'),
    'camber': ('roll_camber', 'lateral_compliance_camber', 'camber_stiffness'),
}


def _source(p: VehicleParams, name: str, front: AxleCompliance, rear: AxleCompliance) -> str:
    parts = []
    for axle, comp in (('front', front), ('rear', rear)):
        found = [comp.sources[f] for f in _TERM_FIELDS[name] if f in comp.sources]
        parts.append(f"{axle}: {', '.join(found) if found else BARE_TIRE}")
    if name in ('roll_steer', 'camber', 'rolling_resistance') and any(
            comp.sources for comp in (front, rear)):
        parts.append("roll gradient from roll stiffness "
                     f"{p.sources.get('roll_stiffness_front', 'roll_stiffness_front')}")
    return '; '.join(parts)


def effective_axle_cornering_stiffness(p: VehicleParams) -> tuple[float, float]:
    """
    Front and rear effective axle cornering stiffness, N/rad (module doc).

    The bare tires' value (two tires at the static wheel load, thesis eq. 7)
    for a rigid axle; SolverError if the compliance leaves no positive
    stiffness (the axle would steer itself beyond its tires' slip).
    """
    if all(c.is_rigid and c.pneumatic_trail == 0.0 and c.rolling_resistance == 0.0
           for c in (p.compliance_front, p.compliance_rear)):
        return _axle(p, 'front')[1], _axle(p, 'rear')[1]
    rho = _roll_gradient(p)
    shifts = shift_slip(p, rho)
    pitch = pitch_slip(p)
    out = []
    for k, axle in enumerate(('front', 'rear')):
        load, stiffness, _ = _axle(p, axle)
        slip = (load / stiffness + p.g * sum(compliance_slip(p, axle, rho).values())
                + p.g * sum(pair[k] for pair in shifts.values()) + p.g * pitch[k])
        if not slip > 0.0:
            raise SolverError(
                f"{axle} axle: the compliance slip {math.degrees(slip - load / stiffness):.4g} "
                f"deg/g cancels the tires' {math.degrees(load / stiffness):.4g} deg/g: no "
                "positive effective cornering stiffness")
        out.append(load / slip)
    return out[0], out[1]


__all__ = ['TERMS', 'RANGE_TERMS', 'SHIFT_TERMS', 'PITCH_TERMS', 'BARE_TIRE', 'NO_RANGE',
           'BudgetTerm', 'UndersteerBudget', 'compliance_slip', 'force_shift', 'shift_slip',
           'pitch_load_shift', 'pitch_slip', 'understeer_budget',
           'effective_axle_cornering_stiffness']
