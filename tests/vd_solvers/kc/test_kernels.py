# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The K&C building blocks against central finite differences.

As scipy tests its building blocks: every primitive's gradient and marker-level
second derivatives, the rotation chart, the force laws and the assembled
tangent of the equilibrium are checked against central differences of the
functions they differentiate; the exponential map against scipy's rotation
vectors.
"""
from __future__ import annotations

import numpy as np
from numpy.testing import assert_allclose
import pytest
from scipy.spatial.transform import Rotation

from vd_solvers.kc.events import KCModel
from vd_solvers.kc.forces import LinearLaw, SpringLaw, StopLaw, TorsionLaw
from vd_solvers.kc.joints import PAIRS, SLOTS, PrimKind, kernel
from vd_solvers.kc.model import Curve
from vd_solvers.kc.solver import Sensitivity, moved, rotation_vectors_to_matrices, solve_static
from vd_solvers.kc.system import LoadCase

H = 1e-6  # central-difference step (values of order 1): truncation ~1e-12


def _slots(kind: PrimKind, rng: np.random.Generator, n: int = 4) -> list[np.ndarray]:
    out = []
    for marker in SLOTS[kind]:
        x = rng.normal(size=(n, 3))
        if marker == 'v':
            x /= np.linalg.norm(x, axis=1, keepdims=True)
            if kind is PrimKind.CPZ:
                x[:, 2] *= 0.3  # a wheel axis: far from vertical
                x /= np.linalg.norm(x, axis=1, keepdims=True)
        out.append(x)
    return out


def _param(kind: PrimKind, rng: np.random.Generator, n: int = 4) -> np.ndarray:
    if kind is PrimKind.COMP:
        return rng.normal(size=(n, 3))
    if kind is PrimKind.CPZ:
        return np.full((n, 1), 0.35)
    return np.zeros((n, 0))


@pytest.mark.parametrize('kind', list(PrimKind))
def test_primitive_gradients_are_the_derivatives_of_their_values(kind: PrimKind) -> None:
    rng = np.random.default_rng(kind.value)
    q, param = _slots(kind, rng), _param(kind, rng)
    _, grads, _ = kernel(kind, q, param)
    for slot in range(len(q)):
        for i in range(3):
            plus = [x.copy() for x in q]
            minus = [x.copy() for x in q]
            plus[slot][:, i] += H
            minus[slot][:, i] -= H
            fd = (kernel(kind, plus, param)[0] - kernel(kind, minus, param)[0]) / (2 * H)
            assert_allclose(grads[slot][:, i], fd, rtol=1e-8, atol=1e-9,
                            err_msg=f'{kind.name} slot {slot} component {i}')


@pytest.mark.parametrize('kind', list(PrimKind))
def test_primitive_hessians_are_the_derivatives_of_their_gradients(kind: PrimKind) -> None:
    """Every listed slot pair's block, and zero for the pairs not listed."""
    rng = np.random.default_rng(10 + kind.value)
    q, param = _slots(kind, rng), _param(kind, rng)
    _, _, hess = kernel(kind, q, param)
    blocks = dict(zip(PAIRS[kind], hess))
    for a in range(len(q)):
        for b in range(len(q)):
            fd = np.zeros((q[0].shape[0], 3, 3))
            for j in range(3):
                plus = [x.copy() for x in q]
                minus = [x.copy() for x in q]
                plus[b][:, j] += H
                minus[b][:, j] -= H
                fd[:, :, j] = (kernel(kind, plus, param)[1][a]
                               - kernel(kind, minus, param)[1][a]) / (2 * H)
            expected = blocks.get((a, b), np.zeros_like(fd))
            assert_allclose(np.broadcast_to(expected, fd.shape), fd, rtol=1e-7, atol=1e-7,
                            err_msg=f'{kind.name} pair ({a}, {b})')


def test_exponential_map_equals_scipys_rotation_vectors() -> None:
    rng = np.random.default_rng(3)
    theta = np.vstack((rng.normal(size=(6, 3)), 1e-9 * rng.normal(size=(3, 3)),
                       np.zeros((1, 3)), [[np.pi - 1e-6, 0.0, 0.0]]))
    assert_allclose(rotation_vectors_to_matrices(theta),
                    Rotation.from_rotvec(theta).as_matrix(), atol=1e-14)


def test_rotation_chart_is_the_second_derivative_of_the_rotated_marker() -> None:
    """
    d^2/dth^2 of G.(exp([th]x) w) at th = 0 is sym(G w^T) - (G.w) I.

    The chart the Newton update uses (R <- exp([th]x) R): the term of
    ``assembly._chart`` that turns marker gradients into the tangent's
    rotation blocks.
    """
    from vd_solvers.kc.system import _chart

    rng = np.random.default_rng(4)
    g, w = rng.normal(size=(5, 3)), rng.normal(size=(5, 3))
    h = 1e-4
    fd = np.zeros((5, 3, 3))
    eye = np.eye(3)
    for i in range(3):
        for j in range(3):
            total = 0.0
            for si, sj in ((1, 1), (1, -1), (-1, 1), (-1, -1)):
                theta = np.tile(h * (si * eye[i] + sj * eye[j]), (5, 1))
                rotated = np.einsum('nij,nj->ni', rotation_vectors_to_matrices(theta), w)
                total = total + si * sj * np.einsum('ni,ni->n', g, rotated)
            fd[:, i, j] = total / (4 * h * h)
    assert_allclose(_chart(g, w), fd, atol=1e-7)


@pytest.mark.parametrize('law', [
    LinearLaw(np.array([3.0e4]), np.array([120.0])),
    SpringLaw(0.05, rate=4.0e4),
    SpringLaw(0.05, curve=Curve(np.array([0.0, 0.04, 0.08]), np.array([0.0, 1.0e3, 4.0e3]))),
    StopLaw(Curve(np.array([0.0, 0.01, 0.03]), np.array([0.0, 500.0, 6000.0])), 0.01, -1.0),
    TorsionLaw(1.0e4),
], ids=['linear', 'spring', 'spring curve', 'bump stop', 'torsion'])
def test_force_laws_are_the_derivatives_of_their_energy(law) -> None:
    """V' and V'' of every law against central differences (away from curve knots)."""
    delta = np.array([-0.0313, -0.0171, -0.0052, 0.0067, 0.0149])
    h = 1e-7
    energy, d1, d2 = law.evaluate(delta)
    e_plus, d1_plus, _ = law.evaluate(delta + h)
    e_minus, d1_minus, _ = law.evaluate(delta - h)
    assert_allclose(d1, (e_plus - e_minus) / (2 * h), rtol=1e-7, atol=1e-6)
    assert_allclose(d2, (d1_plus - d1_minus) / (2 * h), rtol=1e-6, atol=1e-3)
    assert np.all(np.isfinite(energy))


def _unit_rate(n_parts: int, n_con: int, part: int, k: int) -> Sensitivity:
    dq = np.zeros((n_parts, 6))
    dq[part, k] = 1.0
    return Sensitivity(dq, np.zeros(n_con))


def test_assembled_tangent_is_the_derivative_of_the_force_residual(hmmwv_front) -> None:
    """
    Check the tangent of the bushed HMMWV axle at 30 mm of bump.

    Spring curve away from its knots: every column of the tangent K (at fixed
    multipliers) against a central difference of the force
    residual along that pose coordinate, in the chart of the Newton update.
    """
    inp = hmmwv_front()
    model = KCModel(inp, 'hmmwv', solved=True)
    system = model.system
    load = LoadCase(pad=np.array([0.03, 0.03]))
    state, ev, _ = solve_static(system, load, 'tangent check')
    k = ev.tangent(state.lam)
    h = 1e-6
    worst = 0.0
    for part in range(system.n_parts):
        for c in range(6):
            rate = _unit_rate(system.n_parts, system.n_con, part, c)
            plus = system.evaluate(moved(state, rate, h), load).force_residual(state.lam)
            minus = system.evaluate(moved(state, rate, -h), load).force_residual(state.lam)
            fd = (plus - minus) / (2 * h)
            column = k[:, 6 * part + c]
            scale = max(float(np.max(np.abs(column))), 1.0)
            worst = max(worst, float(np.max(np.abs(fd - column))) / scale)
    assert worst < 1e-6


def test_assembled_tangent_in_roll_with_bar_and_rack(macpherson_front) -> None:
    """The same on the MacPherson axle with its anti-roll bar and rack, in roll."""
    model = KCModel(macpherson_front(), 'macpherson')
    system = model.system
    load = LoadCase(pad=np.array([-0.06, 0.02]))
    state, ev, _ = solve_static(system, load, 'tangent check')
    k = ev.tangent(state.lam)
    h = 1e-6
    for part in range(system.n_parts):
        for c in range(6):
            rate = _unit_rate(system.n_parts, system.n_con, part, c)
            plus = system.evaluate(moved(state, rate, h), load).force_residual(state.lam)
            minus = system.evaluate(moved(state, rate, -h), load).force_residual(state.lam)
            column = k[:, 6 * part + c]
            scale = max(float(np.max(np.abs(column))), 1.0)
            assert float(np.max(np.abs((plus - minus) / (2 * h) - column))) / scale < 1e-6, (
                system.part_names[part], c)
