# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
ISO 2631-1:1997 frequency weightings against the standard's own table, and the ride measures.

The references are ISO 2631-1:1997 Table 3 (the weighting factors x 1000 of Wk and Wd at the
one-third-octave band centres, computed by the standard from its Annex A formulas with the
band limiting), and closed forms of a sine: a_w = |W(f)| A / sqrt(2), crest factor sqrt(2),
VDV = A |W| (3 T / 8)^(1/4).
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from vd_solvers.standards import iso2631

# ISO 2631-1:1997, Table 3: frequency (Hz) -> factor x 1000
WK_TABLE = {0.1: 31.2, 0.125: 48.6, 0.16: 79.0, 0.2: 121.0, 0.25: 182.0, 0.315: 263.0,
            0.4: 352.0, 0.5: 418.0, 0.63: 459.0, 0.8: 477.0, 1.0: 482.0, 1.25: 484.0,
            1.6: 494.0, 2.0: 531.0, 2.5: 631.0, 3.15: 804.0, 4.0: 967.0, 5.0: 1039.0,
            6.3: 1054.0, 8.0: 1036.0, 10.0: 988.0, 12.5: 902.0, 16.0: 768.0, 20.0: 636.0,
            25.0: 513.0, 31.5: 405.0, 40.0: 314.0, 50.0: 246.0, 63.0: 186.0, 80.0: 132.0}
WD_TABLE = {0.1: 62.4, 0.2: 243.0, 0.5: 853.0, 1.0: 1011.0, 2.0: 890.0, 4.0: 512.0,
            8.0: 253.0}


@pytest.mark.parametrize('name, table', [('Wk', WK_TABLE), ('Wd', WD_TABLE)])
def test_the_weightings_are_the_standards_table(name, table):
    f = np.array(sorted(table))
    computed = 1000.0 * np.abs(iso2631.response(name, f))
    expected = np.array([table[x] for x in sorted(table)])
    # the table is rounded to three significant figures
    assert np.all(np.abs(computed - expected) <= 0.0051 * expected), (computed, expected)


def test_we_is_the_rotational_weighting_of_annex_a():
    """We: band limiting 0.4..100 Hz and an a-v transition at 1 Hz, Q 0.63 (Table A.2)."""
    f = np.array([0.5, 1.0, 4.0, 16.0])
    p = 2j * math.pi * f
    w1, w2, w3 = 2 * math.pi * 0.4, 2 * math.pi * 100.0, 2 * math.pi * 1.0
    written_out = (p**2 / (p**2 + math.sqrt(2) * w1 * p + w1**2)
                   * w2**2 / (p**2 + math.sqrt(2) * w2 * p + w2**2)
                   * (1 + p / w3) / (1 + p / (0.63 * w3) + p**2 / w3**2))
    np.testing.assert_allclose(iso2631.response('We', f), written_out, rtol=1e-12)


@pytest.mark.parametrize('frequency', [1.0, 5.0, 8.0])
def test_a_sine_is_weighted_by_the_magnitude_at_its_frequency(frequency):
    rate, duration, amplitude = 400.0, 20.0, 1.5
    t = np.arange(0.0, duration, 1.0 / rate)
    a = amplitude * np.sin(2 * math.pi * frequency * t)
    aw = iso2631.weighted(a, rate, 'Wk')
    steady = aw[int(5.0 * rate):-int(5.0 * rate)]  # away from the ends of the record
    gain = abs(iso2631.response('Wk', frequency))
    assert iso2631.rms(steady) == pytest.approx(gain * amplitude / math.sqrt(2), rel=2e-3)
    assert iso2631.crest_factor(steady) == pytest.approx(math.sqrt(2), rel=2e-3)
    span = steady.size / rate
    assert iso2631.vdv(steady, rate) == pytest.approx(
        gain * amplitude * (3.0 * span / 8.0) ** 0.25, rel=3e-3)


def test_weighting_keeps_length_and_refuses_bad_input():
    assert iso2631.weighted(np.ones(7), 100.0, 'Wd').shape == (7,)
    with pytest.raises(ValueError, match="unknown ISO 2631-1 weighting 'Wz'"):
        iso2631.response('Wz', 1.0)
    with pytest.raises(ValueError, match='sample rate must be positive'):
        iso2631.weighted(np.ones(7), 0.0, 'Wk')
