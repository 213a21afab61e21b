# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
ISO 8608 random roads: the drawn profile has the class's spectrum and variance.

References: ISO 8608:2016, G_d(n) = G_d(n0) (n / n0)^-2, n0 = 0.1 cycles/m, class geometric
means 16e-6 m^3 (A) x 4 per class; the variance over a band is the integral of G_d
(G_d(n0) n0^2 (1 / n1 - 1 / n2)), and the log-log slope of the spectrum is -2.
"""
from __future__ import annotations

import numpy as np
import pytest
from scipy import signal

from vd_solvers.road import iso8608

N1, N2 = 0.011, 2.83


def test_class_means_of_the_standard():
    # ISO 8608 Table: A 16, B 64, C 256, D 1024, E 4096, F 16384, G 65536, H 262144 (1e-6 m^3)
    expected = [16, 64, 256, 1024, 4096, 16384, 65536, 262144]
    assert [iso8608.CLASSES[c] * 1e6 for c in 'ABCDEFGH'] == pytest.approx(expected)


@pytest.mark.parametrize('road_class', ['A', 'C', 'E'])
def test_profile_variance_is_the_integral_of_the_class_spectrum(road_class):
    length = 1000.0
    road = iso8608.random_road(road_class, length, 1.5, seed=3)
    z = road.left[:-1]  # one period of the periodic profile
    closed_form = 256e-6 * 4.0 ** ('ABCDEFGH'.index(road_class) - 2) * 0.1**2 * (1 / N1 - 1 / N2)
    # over one period the cosines are orthogonal: the variance is the band's exactly
    assert np.var(z) == pytest.approx(closed_form, rel=1e-9)
    assert np.mean(z) == pytest.approx(0.0, abs=1e-12)


def test_spectrum_slope_is_minus_two_and_level_is_the_class():
    spacing = 0.05
    road = iso8608.random_road('C', 2000.0, 1.5, seed=11, spacing=spacing)
    n, g = signal.welch(road.left, fs=1.0 / spacing, nperseg=8192)  # one-sided, m^2/(cycle/m)
    band = (n > 0.05) & (n < 2.0)
    slope, intercept = np.polyfit(np.log10(n[band]), np.log10(g[band]), 1)
    assert slope == pytest.approx(-2.0, abs=0.1)
    level_at_n0 = 10 ** (intercept + slope * np.log10(0.1))
    assert level_at_n0 == pytest.approx(256e-6, rel=0.25)  # class C mean, a random draw


def test_seed_reproduces_and_tracks():
    a = iso8608.random_road('B', 200.0, 1.6, seed=7)
    b = iso8608.random_road('B', 200.0, 1.6, seed=7)
    c = iso8608.random_road('B', 200.0, 1.6, seed=8)
    assert np.array_equal(a.left, b.left)
    assert not np.array_equal(a.left, c.left)
    assert np.array_equal(a.left, a.right)  # parallel tracks: pure heave
    ind = iso8608.random_road('B', 200.0, 1.6, seed=7, tracks='independent')
    assert np.array_equal(ind.left, a.left)
    assert abs(np.corrcoef(ind.left, ind.right)[0, 1]) < 0.5
    assert 'class B' in a.description and 'seed 7' in a.description


def test_bad_roads_are_refused():
    with pytest.raises(ValueError, match="unknown ISO 8608 road class 'Z'"):
        iso8608.random_road('Z', 100.0, 1.5, seed=1)
    with pytest.raises(ValueError, match='cannot carry the ISO 8608 band'):
        iso8608.random_road('A', 100.0, 1.5, seed=1, spacing=0.5)
    with pytest.raises(ValueError, match="unknown track coherence 'both'"):
        iso8608.random_road('A', 100.0, 1.5, seed=1, tracks='both')
    with pytest.raises(ValueError, match='must be a multiple'):
        iso8608.random_road('A', 100.03, 1.5, seed=1, spacing=0.05)
