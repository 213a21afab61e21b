# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
ISO 2631-1:1997 whole-body vibration: frequency weightings and the ride measures built on them.

The weightings are the analog filters of the standard's Annex A (Table A.2), products of

* band limiting, a second-order Butterworth high pass at f1 and low pass at f2:
  H_h(p) = p^2 / (p^2 + sqrt(2) w1 p + w1^2), H_l(p) = w2^2 / (p^2 + sqrt(2) w2 p + w2^2);
* the acceleration-velocity transition
  H_t(p) = (1 + p / w3) / (1 + p / (Q4 w4) + p^2 / w4^2);
* the upward step (Wk only)
  H_s(p) = (1 + p / (Q5 w5) + p^2 / w5^2) / (1 + p / (Q6 w6) + p^2 / w6^2) (w5 / w6)^2;

with p = j 2 pi f and w_i = 2 pi f_i. ``Wk`` weights vertical (z) acceleration at the seat,
``Wd`` horizontal (x, y) acceleration, ``We`` rotational acceleration (roll, pitch, yaw).

A signal is weighted in the frequency domain: its discrete Fourier transform times the
weighting's complex response at each bin, zero-padded to twice its length so that the
filter's response does not wrap around (the analog filter exactly, with no bilinear warping
near the Nyquist frequency). Measures of section 6: the weighted r.m.s. a_w (6.1), the
crest factor (6.2) and the fourth-power vibration dose value VDV = (int a_w^4 dt)^(1/4) (6.3.2).

Signals in SI (m/s^2, rad/s^2), rates in Hz.
"""
from __future__ import annotations

from dataclasses import dataclass
import math

import numpy as np
from numpy.typing import ArrayLike


@dataclass(frozen=True)
class Weighting:
    """The parameters of one frequency weighting (ISO 2631-1:1997, Table A.2); Hz."""

    name: str
    f1: float
    f2: float
    f3: float
    f4: float
    q4: float
    f5: float | None = None
    q5: float | None = None
    f6: float | None = None
    q6: float | None = None


WEIGHTINGS = {
    'Wk': Weighting('Wk', 0.4, 100.0, 12.5, 12.5, 0.63, 2.37, 0.91, 3.35, 0.91),
    'Wd': Weighting('Wd', 0.4, 100.0, 2.0, 2.0, 0.63),
    'We': Weighting('We', 0.4, 100.0, 1.0, 1.0, 0.63),
}


def response(name: str, frequency: ArrayLike) -> np.ndarray:
    """Return the complex response of weighting ``name`` (Wk, Wd, We) at ``frequency`` (Hz)."""
    try:
        w = WEIGHTINGS[name]
    except KeyError:
        raise ValueError(f"unknown ISO 2631-1 weighting '{name}' (one of "
                         f"{', '.join(WEIGHTINGS)})") from None
    p = 2j * math.pi * np.asarray(frequency, dtype=float)
    w1, w2, w3, w4 = (2.0 * math.pi * f for f in (w.f1, w.f2, w.f3, w.f4))
    root2 = math.sqrt(2.0)
    h = p**2 / (p**2 + root2 * w1 * p + w1**2)
    h = h * w2**2 / (p**2 + root2 * w2 * p + w2**2)
    h = h * (1.0 + p / w3) / (1.0 + p / (w.q4 * w4) + p**2 / w4**2)
    if w.f5 is not None and w.f6 is not None and w.q5 is not None and w.q6 is not None:
        w5, w6 = 2.0 * math.pi * w.f5, 2.0 * math.pi * w.f6
        h = h * ((1.0 + p / (w.q5 * w5) + p**2 / w5**2)
                 / (1.0 + p / (w.q6 * w6) + p**2 / w6**2) * (w5 / w6) ** 2)
    return h


def weighted(signal: ArrayLike, rate: float, name: str) -> np.ndarray:
    """Weight a signal (uniformly sampled at ``rate`` Hz) by ``name``; same length."""
    a = np.asarray(signal, dtype=float)
    if a.ndim != 1 or a.size < 2:
        raise ValueError('a weighted signal needs at least two samples in one dimension')
    if not rate > 0.0:
        raise ValueError(f'the sample rate must be positive (got {rate})')
    n = 2 * a.size
    spectrum = np.fft.rfft(a, n)
    spectrum *= response(name, np.fft.rfftfreq(n, 1.0 / rate))
    return np.fft.irfft(spectrum, n)[:a.size]


def rms(signal: ArrayLike) -> float:
    """Root mean square of a signal (6.1: a_w of a weighted one)."""
    a = np.asarray(signal, dtype=float)
    return float(np.sqrt(np.mean(a * a)))


def crest_factor(weighted_signal: ArrayLike) -> float:
    """Largest absolute weighted value over the weighted r.m.s. (6.2)."""
    a = np.asarray(weighted_signal, dtype=float)
    return float(np.max(np.abs(a)) / rms(a))


def vdv(weighted_signal: ArrayLike, rate: float) -> float:
    """Fourth-power vibration dose value (int a_w^4 dt)^(1/4), m/s^1.75 (6.3.2)."""
    a = np.asarray(weighted_signal, dtype=float)
    return float((np.sum(a**4) / rate) ** 0.25)


__all__ = ['Weighting', 'WEIGHTINGS', 'response', 'weighted', 'rms', 'crest_factor', 'vdv']
