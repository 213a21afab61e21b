# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Every sample brake set against the braking-distribution rules of UN Regulation No. 13.

UN R13, Annex 10 ("Distribution of braking among the axles of vehicles"; the same text as
Directive 71/320/EEC, Annex II, Appendix, as consolidated at legislation.gov.uk/eudr/1971/320,
whose numbering is used here), paragraph 2 (symbols): P the vehicle
mass, P1 and P2 the static axle loads, h the centre-of-gravity height, E the wheelbase,
z the braking rate (deceleration over g), T1 and T2 the axles' brake forces at the road,
N1 = P1 g + z P g h / E and N2 = P2 g - z P g h / E the normal reactions when braking,
f_i = T_i / N_i the adhesion utilised by axle i, k the tyre-road adhesion coefficient.

* paragraph 3.1.1, first part (all categories): for k between 0.2 and 0.8 the braking
  rate reached before any axle uses more than k must be z >= 0.10 + 0.85 (k - 0.20);
* paragraph 3.1.1, second part (for all states of load; the range of category M1), with
  the formulae of paragraph 3.1.3 (f1 = T1 / N1, f2 = T2 / N2): for all braking rates
  between 0.15 and 0.8 the adhesion utilisation curve of the front axle lies above that
  of the rear axle, f1 >= f2 (the inversion M1 may have between z 0.3 and 0.45 is not
  used).

The brake forces are worked here from the group files alone, not through the brake model:
line pressure p to torque T = 2 mu p (n pi d^2 / 4) r_e per wheel (Limpert, Brake Design
and Safety, 3rd ed. 2011, ch. 3), the rear pressure through the proportioning valve
(p up to the knee p_k, then p_k + s (p - p_k)), the force at the road T / r with the
tyre's static loaded radius r = R0 - F_z / c_z (.tir UNLOADED_RADIUS and
VERTICAL_STIFFNESS), and the axle loads from the sprung mass and its centre of gravity
plus the unsprung masses at the wheel centres. The data describe one state of load (the
regulation asks for laden and unladen).
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from vd_data_server.datafile import load_group_file
from vd_data_server.tir import read_tir

DATA = Path(__file__).resolve().parents[2] / 'src' / 'vd_data_server' / 'data'
G = 9.80665
BRAKE_SETS = sorted(DATA.glob('*/brakes/*.yaml'))
#: paragraph 3.1.1: the braking rates over which the front axle must lock first (M1)
Z_RANGE = (0.15, 0.8)
#: paragraph 3.1.1: the adhesion coefficients of the z >= 0.10 + 0.85 (k - 0.20) rule
K_RANGE = (0.2, 0.8)


def _group(vehicle: Path, group: str, variant: str = 'X'):
    return load_group_file(vehicle / group / f'{variant}.yaml',
                           display=f'{vehicle.name}/{group}/{variant}.yaml', group=group,
                           variant=variant)


def _vehicle(vehicle: Path) -> dict[str, float]:
    """Mass P, static axle loads P1, P2 (kg), h and E (m), loaded tyre radii (m)."""
    mass = _group(vehicle, 'mass')
    m_s = mass.scalar('sprung_mass')
    x_s, _, z_s = mass.point('sprung_cog')
    parts = [(m_s, x_s, z_s)]
    for axle in ('front', 'rear'):
        x, _, z = _group(vehicle, f'{axle}_hardpoints').point('points.wheel_centre')
        parts.append((2.0 * mass.scalar(f'unsprung_mass_{axle}'), x, z))
    total = sum(p[0] for p in parts)
    x_g = sum(p[0] * p[1] for p in parts) / total
    h = sum(p[0] * p[2] for p in parts) / total
    x_front = parts[1][1]
    wheelbase = _group(vehicle, 'geometry').scalar('wheelbase')
    a = x_front - x_g
    p1, p2 = total * (wheelbase - a) / wheelbase, total * a / wheelbase
    radii = {}
    for axle, load in (('front', p1), ('rear', p2)):
        tir = read_tir(DATA / _group(vehicle, f'{axle}_tire').text('file'))
        radii[axle] = tir.unloaded_radius - 0.5 * load * G / tir.vertical_stiffness
    return {'P': total, 'P1': p1, 'P2': p2, 'h': h, 'E': wheelbase,
            'r1': radii['front'], 'r2': radii['rear']}


def _gain(brakes, axle: str) -> float:
    """Torque per line pressure of one wheel's caliper, N m / Pa: 2 mu A r_e."""
    d = brakes.scalar(f'{axle}.piston_diameter')
    n = brakes.scalar(f'{axle}.pistons') if f'{axle}.pistons' in brakes.values else 1.0
    area = n * math.pi * d**2 / 4.0
    return 2.0 * brakes.scalar(f'{axle}.pad_friction') * area * brakes.scalar(
        f'{axle}.effective_radius')


def _utilisation(path: Path) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Braking rate z and adhesion utilisation f1, f2 over the master pressure."""
    vehicle = path.parents[1]
    v = _vehicle(vehicle)
    brakes = load_group_file(path, display=str(path.relative_to(DATA)), group='brakes',
                             variant=path.stem)
    knee = brakes.scalar('knee_pressure') if 'knee_pressure' in brakes.values else math.inf
    slope = brakes.scalar('knee_slope') if 'knee_slope' in brakes.values else 1.0
    p = np.linspace(0.0, 400e5, 40001)
    p_rear = np.where(p <= knee, p, knee + slope * (p - knee))
    t1 = 2.0 * _gain(brakes, 'front') * p / v['r1']
    t2 = 2.0 * _gain(brakes, 'rear') * p_rear / v['r2']
    weight = v['P'] * G
    z = (t1 + t2) / weight
    transfer = z * weight * v['h'] / v['E']
    f1 = t1 / (v['P1'] * G + transfer)
    f2 = t2 / (v['P2'] * G - transfer)
    keep = z <= 1.0
    return z[keep], f1[keep], f2[keep]


def test_every_vehicle_has_brake_sets() -> None:
    assert {p.parents[1].name for p in BRAKE_SETS} >= {'sedan', 'hmmwv'}


@pytest.mark.parametrize('path', BRAKE_SETS, ids=lambda p: str(p.relative_to(DATA)))
def test_front_axle_locks_first(path: Path) -> None:
    """Annex 10, 3.1.1 (M1): f1 >= f2 for 0.15 <= z <= 0.8."""
    z, f1, f2 = _utilisation(path)
    band = (z >= Z_RANGE[0]) & (z <= Z_RANGE[1])
    assert band.sum() > 100
    worst = int(np.argmin(f1[band] - f2[band]))
    assert np.all(f1[band] >= f2[band]), (
        f'{path.relative_to(DATA)}: the rear axle locks first at z = {z[band][worst]:.3f} '
        f'(f1 {f1[band][worst]:.3f} < f2 {f2[band][worst]:.3f})')


@pytest.mark.parametrize('path', BRAKE_SETS, ids=lambda p: str(p.relative_to(DATA)))
def test_braking_rate_at_each_adhesion(path: Path) -> None:
    """Annex 10, 3.1.1: z >= 0.10 + 0.85 (k - 0.20) for 0.2 <= k <= 0.8."""
    z, f1, f2 = _utilisation(path)
    utilised = np.maximum(f1, f2)
    assert np.all(np.diff(utilised) >= 0.0) and utilised[-1] > K_RANGE[1]
    for k in np.linspace(*K_RANGE, 61):
        # the braking rate at which the first axle reaches the adhesion k
        z_k = float(np.interp(k, utilised, z))
        assert z_k >= 0.10 + 0.85 * (k - 0.20), (
            f'{path.relative_to(DATA)}: on adhesion {k:.2f} only z = {z_k:.3f} before an '
            f'axle locks (needs {0.10 + 0.85 * (k - 0.20):.3f})')


def test_a_rear_biased_set_fails() -> None:
    """The check finds a brake set whose rear axle locks first (equal brakes, no valve)."""
    # HMMWV geometry: static front share b / E = 0.515, ideal front share above 0.545 for
    # z >= 0.15; equal brakes give 0.50 everywhere
    v = _vehicle(DATA / 'hmmwv')
    z = np.linspace(*Z_RANGE, 66)
    transfer = z * v['h'] / v['E']
    f1 = 0.5 * z / (v['P1'] / v['P'] + transfer)
    f2 = 0.5 * z / (v['P2'] / v['P'] - transfer)
    assert np.all(f2 > f1)
