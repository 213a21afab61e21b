# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The ladder of models on one configuration: bicycle, two-track and full vehicle side by side.

``ladder(config)`` runs every rung on the same configuration and data hash and returns,
per rung, the steady-state understeer gradient (ISO 4138: a least-squares slope over
LINEAR_RANGE of the excess steer, 40 m circle), roll gradient and yaw-rate gain (steady
yaw rate over steering-wheel angle at SPEED and STEP_LATERAL_ACCELERATION), and the
step response in the linear range (natural frequency, damping ratio, yaw-rate
overshoot) where the rung has one:

* bicycle: the budget (``analytical/budget.py``): its linear terms are the bicycle's K,
  its range terms come from the two-track model; the roll gradient it uses (eq. 3 with
  the tires' compliance); the linear single track's gain and step response;
* two-track: the wheel-by-wheel steady state (``analytical/cornering.py``); steady
  state only;
* full vehicle: ``constant_radius_turn`` (steady-state method, linear range) and
  ``step_steer`` at SPEED to STEP_LATERAL_ACCELERATION with a fixed STEP_TIME_STEP step,
  on LADDER_FIDELITY K&C maps whatever the configuration's flexible switch (the
  analytical rungs read the rigid K&C results);
* single track of the full vehicle's own axles: the linear single track (mass and yaw
  inertia of the configuration) with the full vehicle's effective axle cornering
  stiffnesses (each axle's yaw moment over its lever arm, the tires' aligning moments
  and the longitudinal forces' moments included, over the single-track slip angle, at
  the step's steady state) and its axles' effective relaxation lengths: the tires'
  (.tir, static load) times C_eff / C_tire, the compliance steer in series shortening
  (or lengthening) the lag as it softens (stiffens) the axle.

Natural frequency and damping of the full vehicle and of the single-track reference are
identified the same way: a second-order yaw-rate response with a zero,
K (1 + T s) / (1 + 2 zeta s / w + s^2 / w^2), fitted by least squares to the response to
the recorded steering-wheel input. The bicycle's are its eigenvalues'.

Every difference between rungs is named: the budget's terms, the two-track's effects
(``cornering.Effects`` switched off one by one) and what remains.
"""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
import math

import numpy as np
from scipy import optimize, signal

from vd_data_server.model import Configuration
from vd_data_server.tire_group import tire_properties
from vd_solvers.analytical import bicycle, cornering, two_track
from vd_solvers.analytical.budget import understeer_budget
from vd_solvers.analytical.from_config import cornering_vehicle, vehicle_params
from vd_solvers.analytical.kc_link import kc_inputs
from vd_solvers.results import EventOutcome
from vd_solvers.tire.magic_formula import MagicFormula
from vd_solvers.vehicle_data import mass_properties, static_wheel_loads

from .constant_radius import LINEAR_RANGE
from .events import run_vehicle_event

#: circle of the steady-state gradients, m (the full vehicle's default)
RADIUS = 40.0
#: speed and lateral acceleration of the yaw-rate gain and the step response
SPEED = 100.0 / 3.6
STEP_LATERAL_ACCELERATION = 1.0
#: integration step of the full vehicle's step steer: its overshoot converges at first
#: order in the step (on the sedan 5 ms gives 2.2 points more than 1 ms, 2 ms 0.7)
STEP_TIME_STEP = 0.001
#: simulated time of the step steer, s: the step at 1 s, the last second its steady state
STEP_DURATION = 4.0
#: the constant radius turn of the ladder: the linear range, converged to 0.3 %
TURN = ('start_lateral_acceleration=1 m/s^2', 'max_lateral_acceleration=3 m/s^2',
        'steady_tolerance=0.004')
#: averaging window of the step's steady state, s (the event's)
STEADY_WINDOW = 1.0
#: the K&C fidelity of the full vehicle's maps on the ladder: that of the analytical rungs
LADDER_FIDELITY = 'rigid'


@dataclass(frozen=True)
class Rung:
    """One model's numbers (SI; nan where the model has none)."""

    understeer_gradient: float  # rad/(m/s^2)
    roll_gradient: float  # rad/(m/s^2)
    yaw_rate_gain: float  # 1/s per rad of steering-wheel angle
    natural_frequency: float = math.nan  # Hz
    damping_ratio: float = math.nan  # -
    overshoot: float = math.nan  # %, yaw rate


@dataclass(frozen=True)
class Term:
    """A named contribution or difference, rad/(m/s^2), and where it comes from."""

    name: str
    value: float
    source: str


@dataclass(frozen=True)
class Ladder:
    """The rungs of one configuration and the named terms between them."""

    configuration: str
    data_hash: str
    bicycle: Rung
    two_track: Rung
    vehicle: Rung
    single_track: Rung  # the reference built from the full vehicle's axles
    budget: tuple[Term, ...]
    two_track_effects: tuple[Term, ...]
    remaining: tuple[Term, ...]


def ladder(config: Configuration, progress: Callable[[str], None] | None = None) -> Ladder:
    """Run every rung on ``config`` (module doc)."""
    say = progress or (lambda stage: None)
    say('K&C and analytical rungs')
    kc = kc_inputs(config, static_wheel_loads(config))
    p = vehicle_params(config, kc.suspension, kc.compliance)
    vehicle = cornering_vehicle(config, p)
    ratio = vehicle.steering.ratio
    ranges = cornering.range_terms(vehicle, RADIUS)
    budget = understeer_budget(p, ranges)
    gradients = cornering.gradients(vehicle, RADIUS)
    effects = []
    for name in ('aligning_moment', 'longitudinal', 'load_transfer', 'steering_map'):
        without = cornering.gradients(vehicle.with_effects(**{name: False}), RADIUS)
        effects.append(Term(name, gradients.understeer - without.understeer,
                            f'two-track with less without {name}'))
    say('full vehicle: constant radius turn')
    turn = run_vehicle_event(config, 'constant_radius_turn', TURN, fidelity=LADDER_FIDELITY)
    say('full vehicle: step steer')
    step = run_vehicle_event(config, 'step_steer', [
        f'speed={SPEED} m/s', f'lateral_acceleration={STEP_LATERAL_ACCELERATION} m/s^2',
        f'time_step={STEP_TIME_STEP} s', 'step_tolerance=0 m/s', f'duration={STEP_DURATION} s'],
        fidelity=LADDER_FIDELITY)
    reached = step.metrics['steady_lateral_acceleration'].value
    full_step = _identified(step, step.channels['yaw_rate'].values)
    reference = _single_track(config, step)
    k_bicycle = bicycle.understeer_gradient(p)
    response = bicycle.bicycle_response(p, SPEED)
    bicycle_rung = Rung(
        understeer_gradient=budget.total,
        roll_gradient=two_track.roll_geometry(p).roll_gradient,
        yaw_rate_gain=SPEED / (p.wheelbase + k_bicycle * SPEED**2) / ratio,
        natural_frequency=response.natural_frequency / (2.0 * math.pi),
        damping_ratio=response.damping_ratio,
        overshoot=_bicycle_overshoot(p, step))
    two_track_rung = Rung(gradients.understeer, gradients.roll,
                          cornering.yaw_rate_gain(vehicle, SPEED, reached))
    vehicle_rung = Rung(turn.metrics['understeer_gradient'].value,
                        turn.metrics['roll_gradient'].value,
                        step.metrics['yaw_rate_gain'].value, *full_step)
    budget_terms = tuple(Term(t.name, t.value, t.source) for t in budget.terms)
    remaining = (
        Term('vehicle_minus_two_track',
             vehicle_rung.understeer_gradient - two_track_rung.understeer_gradient,
             'full vehicle less two-track: what the two-track does not hold'),
        Term('two_track_minus_budget',
             two_track_rung.understeer_gradient - budget.total,
             "two-track less the budget: the steering map's Ackermann, static toe and "
             "camber, the Magic Formula's shifts and the longitudinal forces' lateral "
             'components, which the budget does not hold'),
    )
    return Ladder(config.name, config.data_hash, bicycle_rung, two_track_rung, vehicle_rung,
                  reference, budget_terms, tuple(effects), remaining)


def _identified(outcome: EventOutcome, yaw_rate: np.ndarray) -> tuple[float, float, float]:
    """Natural frequency (Hz), damping and overshoot (%) of a yaw-rate response (module doc)."""
    t = outcome.channels['time'].values
    steer = (outcome.channels['steering_wheel_angle'].values
             / outcome.metrics['steering_ratio'].value)
    steady = float(np.mean(yaw_rate[t >= t[-1] - STEADY_WINDOW]))
    overshoot = 100.0 * (float(np.max(yaw_rate)) / steady - 1.0)
    tt = t - t[0]

    def response(x: np.ndarray) -> np.ndarray:
        gain, zero, omega, zeta = x
        system = signal.lti([gain * zero, gain], [1.0 / omega**2, 2.0 * zeta / omega, 1.0])
        return signal.lsim(system, steer, tt)[1]

    start = np.array([steady / steer[-1], 0.2, 2.0 * math.pi, 0.7])
    fit = optimize.least_squares(lambda x: response(x) - yaw_rate, start,
                                 bounds=([0.0, 0.0, 0.5, 0.05], [np.inf, 5.0, 100.0, 3.0]),
                                 x_scale=start)
    return fit.x[2] / (2.0 * math.pi), float(fit.x[3]), overshoot


def _single_track(config: Configuration, step: EventOutcome) -> Rung:
    """Return the single track of the full vehicle's own axles (module doc), same input."""
    ch = {k: c.values for k, c in step.channels.items()}
    mp = mass_properties(config)
    a = mp.cog_to_front_axle
    length = config.group('geometry').scalar('wheelbase')
    b = length - a
    ratio = step.metrics['steering_ratio'].value
    u = step.metrics['speed'].value
    t = ch['time']
    steady = t >= t[-1] - STEADY_WINDOW
    turning = ch['yaw_rate'] / ch['speed']
    alpha_f = ch['steering_wheel_angle'] / ratio - ch['sideslip'] - a * turning
    alpha_r = -ch['sideslip'] + b * turning
    forces = axle_forces(config, step)
    c_eff = (forces[0][steady].mean() / alpha_f[steady].mean(),
             forces[1][steady].mean() / alpha_r[steady].mean())
    loads = static_wheel_loads(config)
    lags = []
    for k, (axle, fz) in enumerate(zip(('front', 'rear'), loads)):
        tire = MagicFormula(tire_properties(config.group(f'{axle}_tire')))
        sigma = float(tire.relaxation_lengths(fz)[1])
        c_tire = 2.0 * abs(float(tire.cornering_stiffness(fz)))
        lags.append(max(sigma * c_eff[k] / c_tire / u, 1e-4))
    m, izz = mp.mass, mp.yaw_inertia
    tf, tr = lags
    # states: lateral velocity, yaw rate, front and rear transient slip
    matrix = np.array([[0.0, -u, c_eff[0] / m, c_eff[1] / m],
                       [0.0, 0.0, a * c_eff[0] / izz, -b * c_eff[1] / izz],
                       [-1.0 / (u * tf), -a / (u * tf), -1.0 / tf, 0.0],
                       [-1.0 / (u * tr), b / (u * tr), 0.0, -1.0 / tr]])
    system = (matrix, np.array([[0.0], [0.0], [1.0 / tf], [0.0]]),
              np.array([[0.0, 1.0, 0.0, 0.0]]), np.zeros((1, 1)))
    steer = ch['steering_wheel_angle'] / ratio
    yaw = signal.lsim(system, steer, t - t[0])[1]
    k = m / length * (b / c_eff[0] - a / c_eff[1])
    gain = u / (length + k * u**2) / ratio
    return Rung(k, math.nan, gain, *_identified(step, yaw))


def axle_forces(config: Configuration, outcome: EventOutcome) -> tuple[np.ndarray, np.ndarray]:
    """
    Return each axle's effective lateral force over time, N.

    The axle's yaw moment about the CoG over its lever arm: the wheels' forces in body axes,
    the track offsets of their longitudinal forces and their aligning moments.
    """
    ch = {k: c.values for k, c in outcome.channels.items()}
    mp = mass_properties(config)
    out = []
    for axle in ('front', 'rear'):
        x, y, _ = config.group(f'{axle}_hardpoints').point('points.wheel_centre')
        moment = np.zeros_like(ch['time'])
        for side, sign in (('left', 1.0), ('right', -1.0)):
            w = f'{axle}_{side}'
            delta = ch[f'wheel_steer_{w}']
            fx, fy = ch[f'tire_force_x_{w}'], ch[f'tire_force_y_{w}']
            f_long = fx * np.cos(delta) - fy * np.sin(delta)
            f_lat = fx * np.sin(delta) + fy * np.cos(delta)
            moment = moment + (x - mp.cog_x) * f_lat - sign * abs(y) * f_long \
                + ch[f'aligning_moment_{w}']
        out.append(moment / (x - mp.cog_x))
    return out[0], out[1]


def _bicycle_overshoot(p, step: EventOutcome) -> float:
    """Yaw-rate overshoot (%) of the linear single track on the full vehicle's input."""
    ss = bicycle.state_space(p, SPEED)
    t = step.channels['time'].values
    steer = (step.channels['steering_wheel_angle'].values
             / step.metrics['steering_ratio'].value)
    yaw = signal.lsim((ss.a, ss.b, ss.c[:1], ss.d[:1]), steer, t - t[0])[1]
    steady = float(np.mean(yaw[t >= t[-1] - STEADY_WINDOW]))
    return 100.0 * (float(np.max(yaw)) / steady - 1.0)


def table(result: Ladder) -> str:
    """Return the ladder as a text table in display units (deg/g, deg, Hz)."""
    g = 9.80665

    def dg(x: float) -> str:
        return '-' if math.isnan(x) else f'{math.degrees(x * g):.3f}'

    def num(x: float, fmt: str) -> str:
        return '-' if math.isnan(x) else format(x, fmt)

    lines = [f'{result.configuration} (data hash {result.data_hash})',
             f"{'rung':<36}{'K_us deg/g':>11}{'roll deg/g':>11}{'r/dsw 1/s':>10}"
             f"{'f_n Hz':>8}{'zeta':>7}{'overshoot %':>12}"]
    for label, rung in (('bicycle (budget)', result.bicycle), ('two-track', result.two_track),
                        ('full vehicle', result.vehicle),
                        ("single track of the vehicle's axles", result.single_track)):
        lines.append(f'{label:<36}{dg(rung.understeer_gradient):>11}{dg(rung.roll_gradient):>11}'
                     f'{num(rung.yaw_rate_gain, ".4f"):>10}'
                     f'{num(rung.natural_frequency, ".3f"):>8}{num(rung.damping_ratio, ".3f"):>7}'
                     f'{num(rung.overshoot, ".1f"):>12}')
    lines.append('budget: ' + ', '.join(f'{t.name} {dg(t.value)}' for t in result.budget))
    lines.append('two-track effects: ' + ', '.join(f'{t.name} {dg(t.value)}'
                                                   for t in result.two_track_effects))
    lines.append('remaining: ' + ', '.join(f'{t.name} {dg(t.value)}' for t in result.remaining))
    return '\n'.join(lines)


def main(argv: list[str] | None = None) -> int:
    """Print the ladder of every configuration of the studies given (paths to master files)."""
    import sys

    from vd_data_server.study import load_study

    for path in (argv if argv is not None else sys.argv[1:]):
        for config in load_study(path).configurations.values():
            print(table(ladder(config)), flush=True)
            print(flush=True)
    return 0


__all__ = ['RADIUS', 'SPEED', 'STEP_LATERAL_ACCELERATION', 'Rung', 'Term', 'Ladder', 'ladder',
           'axle_forces', 'table', 'main', 'LINEAR_RANGE']

if __name__ == '__main__':
    raise SystemExit(main())
