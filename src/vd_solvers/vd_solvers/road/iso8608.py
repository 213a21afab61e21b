# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
ISO 8608:2016 random road profiles of a road class, generated from a seed.

The standard classifies a road by its displacement power spectral density
G_d(n) = G_d(n0) (n / n0)^-w, n0 = 0.1 cycles/m, w = 2, with G_d(n0) per class A..H
(the geometric mean of each class: 16e-6 m^3 for A, four times more for each class after).
A profile of that spectrum is a sum of cosines at the spatial frequencies n_k = k / L of
a periodic profile of length L, k such that N_MIN <= n_k <= N_MAX (ISO 8608's band),
each line carrying the variance of its share of the band (n_k +- dn / 2, dn = 1 / L, cut
at the band's ends: the PSD integrated in closed form, G_d(n0) n0^2 (1 / a - 1 / b)) as
amplitude sqrt(2 var_k), and a phase drawn uniformly from a seeded generator. The
profile's variance over one period is then the band's, G_d(n0) n0^2 (1 / n1 - 1 / n2).
The period is at least 1 / N_MIN, so the band's longest wave is in it; a shorter road is
the start of that period.

ISO 8608 does not define the coherence of the two wheel tracks: ``tracks='parallel'``
gives both the same profile (pure heave, the usual ride check), ``'independent'`` draws
the right track's phases after the left's (heave, roll and warp excited alike).
"""
from __future__ import annotations

import math

import numpy as np

from .surface import TrackProfile

N0 = 0.1  # cycles/m, the reference spatial frequency
WAVINESS = 2.0  # w
N_MIN, N_MAX = 0.011, 2.83  # cycles/m, the band ISO 8608 classifies
CLASSES = {c: 16e-6 * 4.0**i for i, c in enumerate('ABCDEFGH')}  # G_d(n0), m^3
TRACKS = ('parallel', 'independent')


def psd(road_class: str, n: np.ndarray | float) -> np.ndarray:
    """Return G_d(n) of a class's geometric mean, m^3, at spatial frequencies n (cycles/m)."""
    return CLASSES[_class(road_class)] * (np.asarray(n, dtype=float) / N0) ** -WAVINESS


def band_variance(road_class: str, n1: float = N_MIN, n2: float = N_MAX) -> float:
    """Return the profile variance of a class over the band n1..n2, m^2 (PSD integrated)."""
    return CLASSES[_class(road_class)] * N0**2 * (1.0 / n1 - 1.0 / n2)


def heights(road_class: str, length: float, spacing: float, rng: np.random.Generator
            ) -> np.ndarray:
    """Draw one track's heights at x = 0, spacing, ..., length (m) of the class."""
    count = int(round(length / spacing))
    if count < 2 or abs(count * spacing - length) > 1e-9 * max(length, 1.0):
        raise ValueError(f'the road length ({length} m) must be a multiple (at least 2) of '
                         f'the spacing ({spacing} m)')
    if not spacing < 0.5 / N_MAX:
        raise ValueError(f'a spacing of {spacing} m cannot carry the ISO 8608 band up to '
                         f'{N_MAX} cycles/m (at most {0.5 / N_MAX:.3f} m)')
    points = max(count, math.ceil(1.0 / (N_MIN * spacing)))
    points += points % 2
    dn = 1.0 / (points * spacing)
    k = np.arange(points // 2 + 1)
    low = np.clip((k - 0.5) * dn, N_MIN, N_MAX)
    high = np.clip((k + 0.5) * dn, N_MIN, N_MAX)
    high[-1] = low[-1]  # the Nyquist line carries no cosine of free phase
    amplitude = np.zeros(k.size)
    line = high > low
    amplitude[line] = np.sqrt(2.0 * CLASSES[_class(road_class)] * N0**2
                              * (1.0 / low[line] - 1.0 / high[line]))
    phase = rng.uniform(0.0, 2.0 * math.pi, size=k.size)
    coefficients = 0.5 * points * amplitude * np.exp(1j * phase)
    z = np.fft.irfft(coefficients, points)
    return np.append(z, z[:1])[:count + 1] if count == points else z[:count + 1]


def random_road(road_class: str, length: float, track_width: float, seed: int,
                spacing: float = 0.05, tracks: str = 'parallel',
                friction: float = 1.0) -> TrackProfile:
    """Draw a straight road of ``length`` m of ISO 8608 class ``road_class`` from ``seed``."""
    if tracks not in TRACKS:
        raise ValueError(f"unknown track coherence '{tracks}' (one of {', '.join(TRACKS)})")
    if not length > 0.0 or not spacing > 0.0:
        raise ValueError('the road length and spacing must be positive')
    rng = np.random.default_rng(seed)
    left = heights(road_class, length, spacing, rng)
    right = left if tracks == 'parallel' else heights(road_class, length, spacing, rng)
    x = np.linspace(0.0, length, left.size)
    return TrackProfile(x, left, right, track_width, friction,
                        f'ISO 8608 class {_class(road_class)} road, seed {seed}, {tracks} '
                        f'tracks, {N_MIN}..{N_MAX} cycles/m, {length:g} m')


def _class(road_class: str) -> str:
    c = str(road_class).strip().upper()
    if c not in CLASSES:
        raise ValueError(f"unknown ISO 8608 road class '{road_class}' (one of A..H)")
    return c


__all__ = ['N0', 'WAVINESS', 'N_MIN', 'N_MAX', 'CLASSES', 'TRACKS', 'psd', 'band_variance',
           'heights', 'random_road']
