# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
What the analytical rung takes from the K&C rung of the same configuration.

Per axle, from K&C events run on demand and cached by data hash
(:func:`vd_solvers.kc.cache.kc_result`, each event with its default
parameters, so the numbers equal those of ``vd run EVENT --axle AXLE``):

* roll stiffness (incl. anti-roll bar): ``opposite_wheel_travel``,
  ``roll_stiffness``;
* roll-centre height: ``parallel_wheel_travel``, ``roll_centre_height_kinematic``;
* roll steer, roll camber: ``opposite_wheel_travel``, ``roll_steer``,
  ``roll_camber``;
* lateral-force compliance steer and camber: ``lateral_force``,
  ``lateral_compliance_steer``, ``lateral_compliance_camber``;
* aligning-torque compliance steer: ``aligning_torque``,
  ``aligning_torque_compliance_steer``

(event, derived metric of docs/kc.md), and from the axle's .tir file at the
static wheel load: the pneumatic trail at zero slip
(:meth:`MagicFormula.pneumatic_trail`), the camber stiffness (the
derivative of the lateral force with respect to the lean of the wheel top
towards +y, at zero slip), the rolling resistance -M_y / (F_z R_l) of the
free-rolling tire (the speed-independent part, at ROLLING_SPEED) and the loaded
radius R_l. The K&C
metrics are SI (rad/N, rad/rad, N*m/rad), as the analytical parameters.
"""
from __future__ import annotations

from dataclasses import dataclass

from vd_data_server.errors import DataError
from vd_data_server.model import Configuration
from vd_data_server.tire_group import tire_properties
from vd_solvers.analytical.params import AxleCompliance
from vd_solvers.errors import SolverError
from vd_solvers.kc.cache import kc_model, kc_result
from vd_solvers.kc.metrics import derived_metrics
from vd_solvers.tire.magic_formula import MagicFormula

#: K&C events the analytical rung needs, per axle
KC_EVENTS = ('parallel_wheel_travel', 'opposite_wheel_travel', 'lateral_force', 'aligning_torque')
#: step of the central difference of the lateral force in camber, rad
CAMBER_STEP = 1e-6
#: speed of the rolling-resistance evaluation, m/s: low, so QSY3/QSY4 (speed) drop out
ROLLING_SPEED = 1e-3


@dataclass(frozen=True)
class AxleSuspension:
    """Roll properties of one axle from the K&C model."""

    roll_stiffness: float  # N*m/rad, incl. anti-roll bar
    roll_centre_height: float  # m
    source: str


@dataclass(frozen=True)
class KCInputs:
    """Roll properties and compliance of both axles, keyed 'front'/'rear'."""

    suspension: dict[str, AxleSuspension]
    compliance: dict[str, AxleCompliance]


def camber_stiffness(mf: MagicFormula, fz: float) -> float:
    """
    Lateral force towards +y per rad of lean of the wheel top towards +y, N/rad.

    The .tir inclination angle (ISO 8855) is positive with the top to the
    right (-y), so the lean towards +y is -gamma; central difference at zero
    slip.
    """
    h = CAMBER_STEP
    return float((mf.fy(fz, 0.0, -h) - mf.fy(fz, 0.0, h)) / (2.0 * h))


def rolling_resistance(mf: MagicFormula, fz: float) -> float:
    """Free-rolling -F_x / F_z: the rolling-resistance moment over the loaded radius, -."""
    my = float(mf.steady_state(fz, 0.0, 0.0, 0.0, ROLLING_SPEED).my)
    loaded, _ = mf.radii(fz)
    return -my / (fz * float(loaded))


def kc_inputs(config: Configuration, static_loads: tuple[float, float]) -> KCInputs:
    """
    K&C roll properties and compliance of ``config`` (module doc).

    ``static_loads``: static load of one front and one rear wheel, N.
    Raises SolverError / DataError when the configuration has no K&C model.
    """
    suspension, compliance = {}, {}
    for axle, fz in zip(('front', 'rear'), static_loads):
        model = kc_model(config, axle)
        results = {event: kc_result(config, axle, event) for event in KC_EVENTS}
        m = derived_metrics(results, model.inp.tire_vertical_stiffness)
        tag = f'data hash {config.data_hash}'
        suspension[axle] = AxleSuspension(
            m['roll_stiffness'][0], m['roll_centre_height_kinematic'][0],
            f'K&C {axle} axle (opposite and parallel wheel travel, {tag})')
        group = config.group(f'{axle}_tire')
        mf = MagicFormula(tire_properties(group))
        tir = group.text('file')

        def kc(metric: str, event: str) -> str:
            value, unit = m[metric]
            return f'K&C {axle} {event} {metric} {value:.4g} {unit} ({tag})'

        compliance[axle] = AxleCompliance(
            lateral_compliance_steer=m['lateral_compliance_steer'][0],
            lateral_compliance_camber=m['lateral_compliance_camber'][0],
            roll_steer=m['roll_steer'][0],
            roll_camber=m['roll_camber'][0],
            aligning_torque_compliance_steer=m['aligning_torque_compliance_steer'][0],
            pneumatic_trail=float(mf.pneumatic_trail(fz)),
            camber_stiffness=camber_stiffness(mf, fz),
            rolling_resistance=rolling_resistance(mf, fz),
            loaded_radius=float(mf.radii(fz)[0]),
            sources={
                'lateral_compliance_steer': kc('lateral_compliance_steer', 'lateral_force'),
                'lateral_compliance_camber': kc('lateral_compliance_camber', 'lateral_force'),
                'roll_steer': kc('roll_steer', 'opposite_wheel_travel'),
                'roll_camber': kc('roll_camber', 'opposite_wheel_travel'),
                'aligning_torque_compliance_steer': kc('aligning_torque_compliance_steer',
                                                       'aligning_torque'),
                'pneumatic_trail': f'{tir} pneumatic trail at {fz:.0f} N, zero slip',
                'camber_stiffness': f'{tir} camber stiffness at {fz:.0f} N, zero slip',
                'rolling_resistance': f'{tir} rolling resistance at {fz:.0f} N',
                'loaded_radius': f'{tir} loaded radius at {fz:.0f} N',
            })
    return KCInputs(suspension, compliance)


def try_kc_inputs(config: Configuration, static_loads: tuple[float, float]) -> KCInputs | str:
    """
    Return :func:`kc_inputs`, or why the configuration has no K&C model.

    The reason is given when its data cannot be assembled into one. A K&C
    event that fails on a model that could be assembled is an error, not a
    reason to drop the K&C values.
    """
    try:
        for axle in ('front', 'rear'):
            kc_model(config, axle)
    except (SolverError, DataError, KeyError) as err:
        return f'no K&C model ({err})'
    return kc_inputs(config, static_loads)


__all__ = ['KC_EVENTS', 'AxleSuspension', 'KCInputs', 'camber_stiffness', 'rolling_resistance',
           'kc_inputs', 'try_kc_inputs']
