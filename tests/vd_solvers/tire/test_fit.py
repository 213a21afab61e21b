# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Tests of the SimpleTire fit to the PAC2002 Magic Formula.

References: PAC2002's mu_y is a straight line in Fz, so its fit is exact and
checked against the hand formula; the cornering stiffness is checked against
the Magic Formula it was fitted to, and eqs. 8-9 against finite differences.
"""

from __future__ import annotations

from pathlib import Path
import re

import numpy as np
import numpy.testing as npt
import pytest
from scipy.optimize import minimize_scalar

from vd_data_server.tir import parse_tir_text, read_tir
from vd_solvers.errors import SolverError
from vd_solvers.tire.fit import fit_simple_tire
from vd_solvers.tire.magic_formula import MagicFormula
from vd_solvers.tire.simple import SimpleTire

DATA_DIR = Path(__file__).resolve().parents[3] / 'src' / 'vd_data_server' / 'data' / 'tires'
SEDAN = DATA_DIR / 'Sedan_Pac02Tire.tir'
HMMWV = DATA_DIR / 'HMMWV_Pac02Tire.tir'
SEDAN_RANGE = (2000.0, 6000.0)
HMMWV_RANGE = (10000.0, 30000.0)
RTOL = 1e-12
# Eq. 7 is a parabola; PAC2002's K_y(Fz) ~ sin(2 atan(Fz / (PKY2 Fz0'))) is not.
STIFFNESS_FIT_RTOL = 0.02

SEDAN_FZ0_SCALED = 4850.0 * 0.81  # FNOMIN LFZO
SEDAN_PDY1, SEDAN_PDY2 = 1.0489, -0.18033
SEDAN_PEY1, SEDAN_PEY2 = -0.0074722, -0.0063208


def sedan_text_with(line: str) -> str:
    """Sedan file text with ``line`` in place of the line assigning the same key."""
    key = line.split('=')[0].strip()
    text, count = re.subn(rf'(?m)^{key}\s*=.*$', line, SEDAN.read_text(encoding='ascii'))
    assert count == 1
    return text


@pytest.fixture(scope='module')
def sedan_mf() -> MagicFormula:
    return MagicFormula(read_tir(SEDAN))


@pytest.fixture(scope='module')
def sedan_fit(sedan_mf: MagicFormula) -> SimpleTire:
    return fit_simple_tire(sedan_mf, SEDAN_RANGE)


def test_reference_load_is_middle_of_range(sedan_fit: SimpleTire) -> None:
    npt.assert_allclose(sedan_fit.fz0, 4000.0, rtol=RTOL)


def test_friction_fit_reproduces_pac2002_line(sedan_fit: SimpleTire) -> None:
    # mu_y = PDY1 + PDY2 (Fz - Fz0') / Fz0' = mu0 (1 - mu1 (Fz - fz0)), LMUY = 1.
    mu0 = SEDAN_PDY1 + SEDAN_PDY2 * (4000.0 - SEDAN_FZ0_SCALED) / SEDAN_FZ0_SCALED
    mu1 = -SEDAN_PDY2 / (SEDAN_FZ0_SCALED * mu0)
    npt.assert_allclose((sedan_fit.mu0, sedan_fit.mu1), (mu0, mu1), rtol=1e-10)


def test_shape_is_scaled_pcy1(sedan_fit: SimpleTire) -> None:
    npt.assert_allclose(sedan_fit.shape, 1.3507, rtol=RTOL)  # PCY1 LCY, LCY = 1


def test_curvature_is_even_part_of_ey_at_reference_load(sedan_fit: SimpleTire) -> None:
    expected = SEDAN_PEY1 + SEDAN_PEY2 * (4000.0 - SEDAN_FZ0_SCALED) / SEDAN_FZ0_SCALED  # LEY = 1
    npt.assert_allclose(sedan_fit.curvature, expected, rtol=RTOL)


def test_curvature_is_limited_to_one() -> None:
    mf = MagicFormula(parse_tir_text(sedan_text_with('PEY1 = 1.8'), 'x'))
    assert fit_simple_tire(mf, SEDAN_RANGE).curvature == 1.0


@pytest.mark.parametrize(('path', 'fz_range'), [(SEDAN, SEDAN_RANGE), (HMMWV, HMMWV_RANGE)])
def test_fit_is_exact_at_the_reference_load(path: Path, fz_range: tuple[float, float]) -> None:
    # where the bicycle model uses the tire: the static wheel load = fz0
    mf = MagicFormula(read_tir(path))
    fit = fit_simple_tire(mf, fz_range)
    fz0 = 0.5 * (fz_range[0] + fz_range[1])
    npt.assert_allclose(fit.cornering_stiffness(fz0), -mf.cornering_stiffness(fz0), rtol=1e-13)
    npt.assert_allclose(fit.friction(fz0), mf.peak_lateral_friction(fz0), rtol=1e-13)


@pytest.mark.parametrize(('path', 'fz_range'), [(SEDAN, SEDAN_RANGE), (HMMWV, HMMWV_RANGE)])
def test_fit_reproduces_cornering_stiffness_around_the_reference_load(
        path: Path, fz_range: tuple[float, float]) -> None:
    # the middle half of the range (fz0 +- 25 % of its width): the line through
    # the exact point at fz0 cannot also follow the MF's curvature to the ends
    mf = MagicFormula(read_tir(path))
    low, high = fz_range
    fz = np.linspace(0.75 * low + 0.25 * high, 0.25 * low + 0.75 * high, 101)
    fitted = fit_simple_tire(mf, fz_range).cornering_stiffness(fz)
    npt.assert_allclose(fitted, -mf.cornering_stiffness(fz), rtol=STIFFNESS_FIT_RTOL)


@pytest.mark.parametrize('fz', [2000.0, 4000.0, 6000.0])
def test_simple_tire_slope_at_zero_is_its_cornering_stiffness(
    sedan_fit: SimpleTire, fz: float
) -> None:
    step = 1e-6
    slope = (sedan_fit.lateral_force(fz, step) - sedan_fit.lateral_force(fz, -step)) / (2.0 * step)
    npt.assert_allclose(slope, sedan_fit.cornering_stiffness(fz), rtol=1e-6)


@pytest.mark.parametrize('fz', [2000.0, 4000.0, 6000.0])
def test_simple_tire_slope_at_zero_matches_magic_formula(
    sedan_mf: MagicFormula, sedan_fit: SimpleTire, fz: float
) -> None:
    step = 1e-6
    slope = (sedan_fit.lateral_force(fz, step) - sedan_fit.lateral_force(fz, -step)) / (2.0 * step)
    npt.assert_allclose(slope, -sedan_mf.cornering_stiffness(fz), rtol=STIFFNESS_FIT_RTOL)


def test_simple_tire_peak_is_magic_formula_peak(
    sedan_mf: MagicFormula, sedan_fit: SimpleTire
) -> None:
    fz = 5000.0
    result = minimize_scalar(
        lambda a: -float(sedan_fit.lateral_force(fz, a)),
        bounds=(0.0, 1.0),
        method='bounded',
        options={'xatol': 1e-10},
    )
    npt.assert_allclose(-result.fun, sedan_mf.peak_lateral_friction(fz) * fz, rtol=1e-9)


def test_fitted_tire_gives_positive_force_for_positive_slip(sedan_fit: SimpleTire) -> None:
    assert np.all(sedan_fit.lateral_force([2000.0, 4000.0, 6000.0], 0.05) > 0.0)


def test_source_names_file_and_range(sedan_fit: SimpleTire) -> None:
    assert sedan_fit.source == ('Sedan_Pac02Tire.tir (PAC2002): exact at Fz 4000 N, slopes fitted '
                                'over 2000..6000 N, n=20')


# --- bad input --------------------------------------------------------------------


@pytest.mark.parametrize(
    'fz_range', [(0.0, 5000.0), (-1000.0, 5000.0), (6000.0, 2000.0), (3000.0, 3000.0)]
)
def test_bad_load_range_is_refused(sedan_mf: MagicFormula, fz_range: tuple[float, float]) -> None:
    with pytest.raises(ValueError) as info:
        fit_simple_tire(sedan_mf, fz_range)
    assert str(info.value) == f'fz_range must satisfy 0 < low < high, got {fz_range!r}'


def test_too_few_points_are_refused(sedan_mf: MagicFormula) -> None:
    with pytest.raises(ValueError) as info:
        fit_simple_tire(sedan_mf, SEDAN_RANGE, n=1)
    assert str(info.value) == 'n must be at least 2, got 1'


def test_positive_pky1_is_refused(sedan_fit: SimpleTire) -> None:
    mf = MagicFormula(parse_tir_text(sedan_text_with('PKY1 = 21.92'), 'flipped.tir'))
    with pytest.raises(SolverError) as info:
        fit_simple_tire(mf, SEDAN_RANGE)
    # K_y is proportional to PKY1, so the fit of the flipped file is the negated fit.
    assert str(info.value) == (
        f'flipped.tir: cornering stiffness of fy_iso fitted as c0 = {-sedan_fit.c0:g} 1/rad, '
        "not > 0; the file's PKY1 should be negative (TYDEX convention)"
    )
