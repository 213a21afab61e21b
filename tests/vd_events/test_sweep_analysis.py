# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""Sensitivity, main effects and Pareto fronts against closed-form answers."""
from __future__ import annotations

import itertools

import numpy as np
from numpy.testing import assert_allclose

from vd_events.sweeps.sweep import first_order_indices, main_effects, pareto_front, src


def test_src_of_a_linear_response():
    rng = np.random.default_rng(1)
    x = rng.uniform(0.0, 1.0, (50, 3))
    y = 2.0 * x[:, 0] - 1.0 * x[:, 1] + 0.0 * x[:, 2] + 5.0
    coef, r2 = src(x, y)
    expected = np.array([2.0, -1.0, 0.0]) * x.std(axis=0) / y.std()
    assert_allclose(coef, expected, atol=1e-12)
    assert_allclose(r2, 1.0, atol=1e-12)


def test_src_squares_add_up_to_r2_on_an_orthogonal_design():
    # a full factorial grid has uncorrelated columns: sum SRC_i^2 = R^2 for a linear fit
    x = np.array(list(itertools.product([0.0, 1.0, 2.0], [-1.0, 1.0], [0.0, 0.5, 1.0, 1.5])))
    rng = np.random.default_rng(2)
    y = 3.0 * x[:, 0] - 2.0 * x[:, 1] + 0.5 * x[:, 2] + rng.normal(0.0, 0.3, len(x))
    coef, r2 = src(x, y)
    assert 0.5 < r2 < 1.0
    assert_allclose(np.sum(coef ** 2), r2, rtol=1e-12)


def test_src_undefined_with_too_few_points():
    coef, r2 = src(np.array([[0.0, 1.0], [1.0, 0.0]]), np.array([1.0, 2.0]))
    assert np.all(np.isnan(coef)) and np.isnan(r2)


def test_first_order_indices_of_an_additive_function():
    # y = a(x1) + b(x2) on a 3 x 4 grid: S_i = Var(a) / (Var(a) + Var(b)) exactly
    l1, l2 = [0.0, 1.0, 2.0], [0.0, 1.0, 2.0, 3.0]
    x = np.array(list(itertools.product(l1, l2)))
    y = 3.0 * x[:, 0] + x[:, 1] ** 2
    va, vb = np.var(3.0 * np.array(l1)), np.var(np.array(l2) ** 2)
    assert_allclose(first_order_indices(x, y, [l1, l2]), [va / (va + vb), vb / (va + vb)],
                    rtol=1e-12)
    levels, means = main_effects(x[:, 0], y, l1)
    assert_allclose(means, 3.0 * np.array(l1) + np.mean(np.array(l2) ** 2), rtol=1e-12)


def test_pareto_front():
    a = np.array([1.0, 2.0, 3.0, 2.5, np.nan, 1.0])
    b = np.array([3.0, 2.0, 1.0, 2.5, 0.0, 3.5])
    assert list(pareto_front(a, b, ('minimize', 'minimize'))) == [0, 1, 2]
    # maximising a flips the front: the largest a, then the points no other beats in both
    assert list(pareto_front(a, b, ('maximize', 'minimize'))) == [2]
