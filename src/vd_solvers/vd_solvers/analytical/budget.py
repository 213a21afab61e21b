# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Understeer-gradient budget and effective axle cornering stiffness.

The linear-range understeer gradient of a car is the sum of the tires' own
term and of every mechanism that steers or cambers the wheels in proportion to
the lateral acceleration (Gillespie, "Fundamentals of Vehicle Dynamics",
ch. 6, "Understeer gradient" and its summary table; Milliken & Milliken,
"Race Car Vehicle Dynamics", ch. 5, "effective axle cornering stiffness")::

    K = tire + load_transfer + roll_steer + lateral_compliance_steer
        + aligning_torque + camber                          rad/(m/s^2)

Each term is a front minus rear difference of the axles' *compliance slip*
e_i: the kinematic slip angle of axle i (delta - beta - a r/V at the front)
minus its tires' slip angle, per unit lateral acceleration. With N_i the
static axle load, f_i = N_i/(2 g) the lateral force per wheel per m/s^2,
rho the roll gradient (rad per m/s^2), C_w the cornering stiffness of one
tire at the static wheel load and the signs of
:class:`~vd_solvers.analytical.params.AxleCompliance` (steer positive to the
left, ISO 8855; a left turn has positive a_y, roll and tire forces)::

    tire                      (N_f/C_f - N_r/C_r)/g                     (eq. 2 / g)
    load_transfer             0: the two tires' stiffness change is second
                              order in a_y (C(N/2 + dF) + C(N/2 - dF) - 2 C(N/2)
                              = C'' dF^2), so it leaves the linear range; the
                              two-track model carries it at the limit
    roll_steer                e_i = -roll_steer_i rho
    lateral_compliance_steer  e_i = -c_i f_i
    aligning_torque           e_i = +c_Mz,i t_i f_i    (Mz = -t F_y on each wheel)
    camber                    e_i = -(C_gamma,i / C_w,i) (roll_camber_i rho
                                     - lateral_compliance_camber_i f_i)

The camber term uses the lean of both wheels towards +y: roll_camber rho from
the body roll plus -lateral_compliance_camber f from the lateral force (both
wheels lean the same way by left/right symmetry); a lean gamma gives the tire a
force C_gamma gamma, so the slip needed falls by C_gamma gamma / C_w.

Effective axle cornering stiffness: N_i/C_eff,i = N_i/C_i + g e_i, so the
bicycle model with C_eff has exactly K = tire + sum of the other terms. With a
rigid axle (all compliance zero) C_eff is the bare tire's C itself.
"""
from __future__ import annotations

from dataclasses import dataclass
import math

from vd_solvers.analytical.params import AxleCompliance, VehicleParams
from vd_solvers.analytical.two_track import roll_geometry
from vd_solvers.errors import SolverError

#: budget terms in the order Gillespie tabulates them
TERMS = ('tire', 'load_transfer', 'roll_steer', 'lateral_compliance_steer', 'aligning_torque',
         'camber')
#: the source of every compliance term of a parameter set without K&C results
BARE_TIRE = 'bare tire: no K&C results'


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
        'load_transfer': 0.0,
        'roll_steer': -c.roll_steer * roll_gradient,
        'lateral_compliance_steer': -c.lateral_compliance_steer * force,
        'aligning_torque': c.aligning_torque_compliance_steer * c.pneumatic_trail * force,
        'camber': -c.camber_stiffness / wheel_stiffness * lean,
    }


def _roll_gradient(p: VehicleParams) -> float:
    """Roll gradient, rad/(m/s^2), where a roll term needs it (0.0 otherwise)."""
    needs = any(c.roll_steer != 0.0 or (c.roll_camber != 0.0 and c.camber_stiffness != 0.0)
                for c in (p.compliance_front, p.compliance_rear))
    return roll_geometry(p).roll_gradient if needs else 0.0


def understeer_budget(p: VehicleParams) -> UndersteerBudget:
    """Return the budget of ``p`` (module doc); each term names its sources."""
    rho = _roll_gradient(p)
    load_f, c_f, comp_f = _axle(p, 'front')
    load_r, c_r, comp_r = _axle(p, 'rear')
    slip_f = compliance_slip(p, 'front', rho)
    slip_r = compliance_slip(p, 'rear', rho)
    terms = [BudgetTerm('tire', load_f / c_f / p.g, load_r / c_r / p.g,
                        f"front: {p.sources.get('tire_front', 'tire_front')}; "
                        f"rear: {p.sources.get('tire_rear', 'tire_rear')}",
                        (load_f / c_f - load_r / c_r) / p.g)]
    for name in TERMS[1:]:
        terms.append(BudgetTerm(name, slip_f[name], slip_r[name],
                                _source(p, name, comp_f, comp_r), slip_f[name] - slip_r[name]))
    return UndersteerBudget(tuple(terms), rho)


_TERM_FIELDS = {
    'roll_steer': ('roll_steer',),
    'lateral_compliance_steer': ('lateral_compliance_steer',),
    'aligning_torque': ('aligning_torque_compliance_steer', 'pneumatic_trail'),
    'camber': ('roll_camber', 'lateral_compliance_camber', 'camber_stiffness'),
}


def _source(p: VehicleParams, name: str, front: AxleCompliance, rear: AxleCompliance) -> str:
    if name == 'load_transfer':
        return 'second order in a_y: zero in the linear range (two-track model at the limit)'
    parts = []
    for axle, comp in (('front', front), ('rear', rear)):
        found = [comp.sources[f] for f in _TERM_FIELDS[name] if f in comp.sources]
        parts.append(f"{axle}: {', '.join(found) if found else BARE_TIRE}")
    if name in ('roll_steer', 'camber') and any(comp.sources for comp in (front, rear)):
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
    rho = None
    out = []
    for axle in ('front', 'rear'):
        load, stiffness, comp = _axle(p, axle)
        if comp.is_rigid:
            out.append(stiffness)
            continue
        if rho is None:
            rho = _roll_gradient(p)
        slip = load / stiffness + p.g * sum(compliance_slip(p, axle, rho).values())
        if not slip > 0.0:
            raise SolverError(
                f"{axle} axle: the compliance slip {math.degrees(slip - load / stiffness):.4g} "
                f"deg/g cancels the tires' {math.degrees(load / stiffness):.4g} deg/g: no "
                "positive effective cornering stiffness")
        out.append(load / slip)
    return out[0], out[1]


__all__ = ['TERMS', 'BARE_TIRE', 'BudgetTerm', 'UndersteerBudget', 'compliance_slip',
           'understeer_budget', 'effective_axle_cornering_stiffness']
