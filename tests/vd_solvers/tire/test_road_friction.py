# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Road friction per wheel: the factor lambda*_mu on LMUX and LMUY (Pacejka 2012, 4.E7).

MF-Tyre takes the road's friction as a factor on the friction scaling factors, so a wheel
on a road of friction ``mu`` gives what the same tire gives with LMUX and LMUY multiplied
by ``mu`` in its file, wherever they enter (peak friction, the vertical shifts, the trail's
and the residual torque's LKY/LMUY and D_r). The references are the second evaluations of
the equations written out in the tests (``mf6_reference.Mf6`` for MF 6.x, the PAC2002 list
of ``test_combined``), each reading the file with LMUX and LMUY scaled; vd evaluates the
unscaled file with the road friction as an argument, several frictions in one call.
"""
from __future__ import annotations

import dataclasses
import itertools
from pathlib import Path
import re

import numpy as np
import numpy.testing as npt
import pytest

from vd_data_server.tir import TireProperties, parse_tir_text, read_tir
from vd_solvers.tire.magic_formula import MagicFormula, combined_forces
from vd_solvers.vehicle.forces import wheel_tires

if __package__:
    from .mf6_reference import Mf6
    from .test_combined import reference as pac2002_reference
else:  # run as a script: this folder is on sys.path
    from mf6_reference import Mf6
    from test_combined import reference as pac2002_reference

DATA_DIR = Path(__file__).resolve().parents[3] / 'src' / 'vd_data_server' / 'data' / 'tires'
MF62 = DATA_DIR / 'MF62_255_55R20.tir'
OUTPUTS = ('fx', 'fy', 'mx', 'my', 'mz')
# the two evaluations differ by rounding only (different order of the same operations)
RTOL = 1e-9
ATOL = {'fx': 1e-7, 'fy': 1e-7, 'mx': 1e-9, 'my': 1e-9, 'mz': 1e-9}
FRICTIONS = (0.3, 0.55, 1.0, 1.2)
LOADS = (0.4, 1.0, 1.8)  # x FNOMIN
SLIPS = ((0.05, 0.06, 0.02), (-0.08, 0.1, -0.03), (0.2, -0.04, 0.0), (-0.01, -0.15, 0.05),
         (0.0, 0.0, 0.0))  # (kappa, alpha, gamma)
SPEED = 15.0


def _mf62_text(use_mode: int | None = None) -> str:
    text = MF62.read_text(encoding='ascii')
    if use_mode is not None:
        text = re.sub(r'(?m)^USE_MODE\s*=.*$', f'USE_MODE = {use_mode}', text)
    return text


def _scaled(props: TireProperties, mu: float) -> TireProperties:
    """``props`` with LMUX and LMUY multiplied by ``mu`` in [SCALING_COEFFICIENTS]."""
    scaling = dict(props.sections.get('SCALING_COEFFICIENTS', {}))
    for key in ('LMUX', 'LMUY'):
        scaling[key] = float(scaling.get(key, 1.0)) * mu
    return dataclasses.replace(props, sections={**props.sections,
                                                'SCALING_COEFFICIENTS': scaling})


def _grid(props: TireProperties) -> tuple[np.ndarray, ...]:
    """(fz, kappa, alpha, gamma, road) over loads x slips x frictions."""
    rows = [(f * props.fnomin, k, a, g, mu)
            for f, (k, a, g), mu in itertools.product(LOADS, SLIPS, FRICTIONS)]
    return tuple(np.array(column) for column in zip(*rows))


TIRES = {
    'MF62': lambda: parse_tir_text(_mf62_text(), 'mf62.tir'),
    'MF62_turn_slip': lambda: parse_tir_text(_mf62_text(125), 'turn.tir'),
    # LMUX, LMUY and the factors they meet (LKY in Bt and Br) != 1, so that a road friction
    # applied to the wrong factor shows
    'MF62_scaled': lambda: parse_tir_text(
        re.sub(r'(?m)^(LMUX|LMUY|LKY|LVY|LKYC|LRES)\s*=.*$',
               lambda m: f'{m[1]} = {0.8 + 0.05 * len(m[1])}', _mf62_text()), 'scaled.tir'),
}


@pytest.mark.parametrize('name', list(TIRES))
def test_road_friction_is_lmux_and_lmuy_scaled_in_the_mf6_equations(name: str) -> None:
    props = TIRES[name]()
    turn = name.endswith('turn_slip')
    phit = 0.04 if turn else 0.0
    fz, kappa, alpha, gamma, road = _grid(props)
    got = MagicFormula(props).steady_state(fz, kappa, alpha, gamma, SPEED, phit=phit,
                                           road_friction=road)
    for i in range(fz.size):
        ref = Mf6(_scaled(props, road[i]), turn_slip=turn)
        want = ref.evaluate(fz[i], kappa[i], alpha[i], gamma[i], SPEED, phit)
        for key in OUTPUTS:
            npt.assert_allclose(float(getattr(got, key)[i]), want[key], rtol=RTOL,
                                atol=ATOL[key], err_msg=f'{key} at mu {road[i]:g}, Fz {fz[i]:g}')


@pytest.mark.parametrize('path', ['HMMWV_Pac02Tire.tir', 'Sedan_Pac02Tire.tir'])
def test_road_friction_is_lmux_and_lmuy_scaled_in_the_pac2002_equations(path: str) -> None:
    props = read_tir(DATA_DIR / path)
    fz, kappa, alpha, gamma, road = _grid(props)
    got = MagicFormula(props).steady_state(fz, kappa, alpha, gamma, SPEED, road_friction=road)
    for i in range(fz.size):
        want = pac2002_reference(_scaled(props, road[i]), fz[i], kappa[i], alpha[i], gamma[i],
                                 SPEED)
        for key, value in want.items():
            npt.assert_allclose(float(getattr(got, key)[i]), value, rtol=1e-10, atol=1e-9,
                                err_msg=f'{key} at mu {road[i]:g}, Fz {fz[i]:g}')


def test_the_vehicle_call_takes_a_friction_per_wheel() -> None:
    """wheel_tires: each wheel's forces are its tire's at its own road friction."""
    front = MagicFormula(parse_tir_text(_mf62_text(), 'mf62.tir'))
    rear = MagicFormula(read_tir(DATA_DIR / 'Sedan_Pac02Tire.tir'))
    fz = np.array([5200.0, 3900.0, 4300.0, 0.0])
    kappa = np.array([0.03, -0.05, 0.12, 0.02])
    alpha = np.array([0.04, 0.06, -0.02, 0.01])
    gamma = np.array([-0.02, 0.02, -0.01, 0.01])
    vx = np.full(4, 20.0)
    mirror = np.array([1.0, -1.0, 1.0, -1.0])
    road = np.array([0.4, 1.0, 0.7, 0.9])
    got = wheel_tires(front.coefficients, rear.coefficients, fz, kappa, alpha, gamma, vx,
                      mirror, road)
    for w in range(4):
        tire = front if w < 2 else rear
        scaled = MagicFormula(_scaled(tire.props, road[w]))
        want = scaled.steady_state(fz[w], kappa[w], alpha[w], gamma[w], vx[w], mirror[w])
        npt.assert_allclose(got[:, w], [float(v) for v in want], rtol=1e-12, atol=1e-9)
    # the default is the tire's own friction
    npt.assert_array_equal(
        wheel_tires(front.coefficients, rear.coefficients, fz, kappa, alpha, gamma, vx, mirror),
        wheel_tires(front.coefficients, rear.coefficients, fz, kappa, alpha, gamma, vx, mirror,
                    np.ones(4)))
    assert np.all(got[:, 3] == 0.0)  # off the ground whatever the road


def test_a_scalar_friction_applies_to_every_wheel() -> None:
    tire = MagicFormula(parse_tir_text(_mf62_text(), 'mf62.tir'))
    p = tire.coefficients
    n = 5
    fz = np.linspace(2000.0, 8000.0, n)
    args = (p, fz, np.full(n, 0.05), np.full(n, 0.08), np.zeros(n), np.full(n, 20.0),
            np.ones(n), np.zeros(n))
    for a, b in zip(combined_forces(*args, 0.6), combined_forces(*args, np.full(n, 0.6))):
        npt.assert_array_equal(a, b)
