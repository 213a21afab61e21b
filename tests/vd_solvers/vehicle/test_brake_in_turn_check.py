# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Braking in a turn (ISO 7975) checked against a single-track model written here.

Why the sample HMMWV turns in when it brakes in a turn, and the sedan hardly does:

* the tires' load sensitivity, from the .tir coefficients alone: PAC2002's cornering
  stiffness is K(Fz) = PKY1 Fz0' sin(2 atan(Fz / (PKY2 Fz0'))), Fz0' = FNOMIN LFZO
  (Pacejka, Tire and Vehicle Dynamics, 2nd ed., eq. 4.E25 with the PAC2002 two-parameter
  form), so its load sensitivity eps = (Fz / K) dK/dFz = (1 - x^2) / (1 + x^2) with
  x = Fz / (PKY2 Fz0'). The HMMWV's tire (a 315/80 R22.5 truck tire scaled to
  Fz0' = 20.3 kN, the file's header) carries its 6 kN static load at x = 0.09: its
  cornering stiffness is proportional to the load (eps 0.98), while the sedan's tires
  at x = 0.4-0.7 have eps 0.4-0.7 (static loads and the loads of a 4 m/s^2 stop).
  Braking moves load to the front axle; with eps near 1 the front axle gains, and the
  rear loses, side force in proportion;
* the yaw response: a single-track model with the .tir's axle side forces at the axle
  loads of the quasi-static longitudinal load transfer m a_x h / L, the deceleration
  ramped in the event's ramp time, the speed falling with it and the steering held, gives
  the yaw-rate ratio r(t_0 + 1 s) / r_0; the same model without the load transfer turns
  out of the circle (ratio below 1). The single track has no compliance or roll steer of
  its own: its understeer beyond the tires is the full vehicle's at the initial steady
  state (one constant, the steer the vehicle holds less the single track's steady steer,
  per lateral acceleration), fed back from its lateral acceleration.

The single track omits the braking forces' reduction of the side forces (combined slip;
the front axle brakes most, which turns the car out), the pitch motion, and the change of
compliance steer under the brake forces: with the tires below 3 deg of slip the full
vehicle's ratio lies at most 10 % below the single track's, not above it; at the
standard's point, where the HMMWV's rear tires slide, further below.
"""
from __future__ import annotations

import math
from pathlib import Path
import re

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from vd_data_server.study import load_study
from vd_data_server.tire_group import tire_properties
from vd_solvers.tire.magic_formula import MagicFormula
from vd_solvers.vehicle.events import run_vehicle_event
from vd_solvers.vehicle.longitudinal_events import EVALUATION_TIME, STEADY_BEFORE
from vd_solvers.vehicle_data import mass_properties, static_wheel_loads

DATA = Path(__file__).resolve().parents[3] / 'src' / 'vd_data_server' / 'data'
HMMWV = ('hmmwv_longitudinal.yaml', 'no_abs')
SEDAN = ('sedan_longitudinal.yaml', 'abs')
#: the event's defaults: settle time (t_0) and pedal ramp time, s
SETTLE, RAMP = 8.0, 0.15


def _config(study: tuple[str, str]):
    return load_study(DATA / 'studies' / study[0]).configurations[study[1]]


def _tir(path: Path) -> dict[str, float]:
    """Return the numeric entries of a .tir file (NAME = value), read here."""
    out = {}
    for line in path.read_text(encoding='utf-8', errors='replace').splitlines():
        match = re.match(r'\s*([A-Z][A-Z0-9_]*)\s*=\s*([-+0-9.eE]+)', line)
        if match:
            out[match.group(1)] = float(match.group(2))
    return out


def _pac2002_stiffness(tir: dict[str, float], fz: float) -> float:
    fz0 = tir['FNOMIN'] * tir['LFZO']
    return abs(tir['PKY1'] * fz0 * math.sin(2.0 * math.atan(fz / (tir['PKY2'] * fz0)))
               * tir['LKY'])


def _load_sensitivity(tir: dict[str, float], fz: float) -> float:
    x = fz / (tir['PKY2'] * tir['FNOMIN'] * tir['LFZO'])
    return (1.0 - x * x) / (1.0 + x * x)


@pytest.mark.parametrize(('study', 'file', 'low', 'high'), [
    (HMMWV, 'HMMWV_Pac02Tire.tir', 0.97, 1.0),
    (SEDAN, 'Sedan_Pac02Tire.tir', 0.3, 0.75)])
def test_the_tires_load_sensitivity_at_the_static_wheel_loads(study, file, low, high) -> None:
    config = _config(study)
    tir = _tir(DATA / 'tires' / file)
    front, rear = static_wheel_loads(config)
    mp = mass_properties(config)
    # the load a 4 m/s^2 stop moves per wheel (quasi-static)
    moved = mp.mass * 4.0 * mp.cog_height / config.group('geometry').scalar('wheelbase') / 2
    tire = MagicFormula(tire_properties(config.group('front_tire')))
    for fz in (front, rear, front + moved, rear - moved):
        assert low <= _load_sensitivity(tir, fz) <= high, fz
        slope = (_pac2002_stiffness(tir, fz + 1.0) - _pac2002_stiffness(tir, fz - 1.0)) / 2.0
        assert slope * fz / _pac2002_stiffness(tir, fz) == pytest.approx(
            _load_sensitivity(tir, fz), abs=1e-6)
        # the vehicle's tire model has the same load sensitivity (its dFy/dalpha at
        # alpha = 0 includes the small horizontal shift SH_y, the same factor at both loads)
        model = [float(abs(tire.cornering_stiffness(fz + d))) for d in (-1.0, 0.0, 1.0)]
        assert (model[2] - model[0]) / 2.0 * fz / model[1] == pytest.approx(
            _load_sensitivity(tir, fz), abs=0.01)


def _single_track_ratio(config, outcome, deceleration: float, transfer: bool) -> float:
    """Return the yaw-rate ratio of the single-track model of the module doc."""
    mp = mass_properties(config)
    wheelbase = config.group('geometry').scalar('wheelbase')
    a = mp.cog_to_front_axle
    b = wheelbase - a
    m, h, iz = mp.mass, mp.cog_height, mp.yaw_inertia
    load_f, load_r = static_wheel_loads(config)
    tire_f = MagicFormula(tire_properties(config.group('front_tire')))
    tire_r = MagicFormula(tire_properties(config.group('rear_tire')))

    def axle_force(tire, fz: float, alpha: float) -> float:  # two wheels, ISO: F_y ~ alpha
        return 2.0 * math.copysign(abs(float(tire.fy(fz, abs(alpha)))), alpha)

    ch = {k: c.values for k, c in outcome.channels.items()}
    t = ch['time']
    before = (t >= SETTLE - STEADY_BEFORE) & (t < SETTLE)
    r0 = float(np.mean(ch['yaw_rate'][before]))
    v0 = float(np.mean(ch['speed'][before]))
    steer = float(np.mean((ch['steer_angle_front_left'] + ch['steer_angle_front_right'])[before]
                          / 2.0))
    ay0 = v0 * r0
    alpha_f = brentq(lambda x: axle_force(tire_f, load_f, x) - m * b / wheelbase * ay0, 0, 0.5)
    alpha_r = brentq(lambda x: axle_force(tire_r, load_r, x) - m * a / wheelbase * ay0, 0, 0.5)
    understeer = (steer - (wheelbase * r0 / v0 + alpha_f - alpha_r)) / ay0

    def decel(s: float) -> float:
        return deceleration * min(s / RAMP, 1.0)

    def rhs(s, y):
        vy, r, vx = y
        moved = m * decel(s) * h / wheelbase / 2.0 if transfer else 0.0
        delta = steer - understeer * vx * r
        fy_f = axle_force(tire_f, load_f + moved, delta - (vy + a * r) / vx)
        fy_r = axle_force(tire_r, load_r - moved, -(vy - b * r) / vx)
        return [(fy_f + fy_r) / m - vx * r, (a * fy_f - b * fy_r) / iz, -decel(s)]

    sol = solve_ivp(rhs, (0.0, EVALUATION_TIME), [b * r0 - alpha_r * v0, r0, v0],
                    max_step=0.005, rtol=1e-8, atol=1e-10)
    return float(sol.y[1, -1]) / r0


def _ratios(study, lateral: float, deceleration: float) -> tuple[float, float, float]:
    """Return the yaw-rate ratios of the full vehicle and the single track with and without."""
    config = _config(study)
    outcome = run_vehicle_event(config, 'brake_in_turn', [
        f'lateral_acceleration={lateral} m/s^2', f'deceleration={deceleration} m/s^2'])
    # the deceleration the vehicle reached (brakes, drag, rolling resistance, the drive
    # force gone) drives the single track; the yaw rate is what is compared
    reached = outcome.metrics['mean_longitudinal_deceleration'].value
    return (outcome.metrics['yaw_rate_ratio'].value,
            _single_track_ratio(config, outcome, reached, transfer=True),
            _single_track_ratio(config, outcome, reached, transfer=False))


@pytest.mark.parametrize(('study', 'lateral', 'deceleration'), [
    (HMMWV, 3.0, 3.0), (SEDAN, 5.0, 4.0)])
def test_the_yaw_response_is_the_single_track_with_load_transfer(study, lateral,
                                                                  deceleration) -> None:
    """Tires below 3 deg of slip: the single track is the full vehicle within 10 %."""
    vehicle, with_transfer, without = _ratios(study, lateral, deceleration)
    assert without < 1.0 < with_transfer
    assert 0.90 * with_transfer <= vehicle <= 1.01 * with_transfer


def test_the_hmmwvs_turn_in_at_the_standard_point_is_the_load_transfer() -> None:
    """
    Check the HMMWV's turn-in from 5 m/s^2 at 4 m/s^2 against the single track.

    Its rear tires slide (5.5 deg on the circle, 16 deg a second later): the single
    track, without the combined-slip loss of its braked front axle, turns in more than
    the full vehicle, and without the load transfer turns out.
    """
    vehicle, with_transfer, without = _ratios(HMMWV, 5.0, 4.0)
    assert without < 1.0
    assert 2.0 < vehicle <= 1.01 * with_transfer


def test_the_hmmwv_works_its_tires_at_several_times_the_sedans_slip_angle() -> None:
    """On the 5 m/s^2 circle: the axle slip angles the .tir needs for m_axle a_y."""
    angles = {}
    for study in (HMMWV, SEDAN):
        config = _config(study)
        mp = mass_properties(config)
        wheelbase = config.group('geometry').scalar('wheelbase')
        tire = MagicFormula(tire_properties(config.group('rear_tire')))
        load = static_wheel_loads(config)[1]
        need = mp.mass * mp.cog_to_front_axle / wheelbase * 5.0 / 2.0
        angles[study] = brentq(lambda x: abs(float(tire.fy(load, x))) - need, 0.0, 0.5)
    assert math.degrees(angles[HMMWV]) > 5.0
    assert math.degrees(angles[SEDAN]) < 2.0
