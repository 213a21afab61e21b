# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Tests of the PAC2002 Magic Formula.

References are independent of the implementation: the PAC2002 equations
written out step by step with ``math`` from the coefficients in the file,
finite differences, numerical maxima and symmetry properties.
"""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path
import re
import warnings

import numpy as np
import numpy.testing as npt
import pytest
from scipy.optimize import minimize_scalar

from vd_data_server.errors import DataError
from vd_data_server.tir import TireProperties, parse_tir_text, read_tir
from vd_solvers.errors import SolverError
from vd_solvers.tire.magic_formula import MagicFormula, vertical_stiffness

DATA_DIR = Path(__file__).resolve().parents[3] / 'src' / 'vd_data_server' / 'data' / 'tires'
SEDAN = DATA_DIR / 'Sedan_Pac02Tire.tir'
HMMWV = DATA_DIR / 'HMMWV_Pac02Tire.tir'
RTOL = 1e-12

# A tire without shifts and without the sgn(slip) terms (PHY*, PVY*, PEY3, PEY4,
# PHX*, PVX*, PEX4 absent, hence 0), but with load and camber effects.
SYMMETRIC_FNOMIN = 4000.0
SYMMETRIC_SCALING = {'LFZO': 0.9, 'LMUY': 0.95, 'LKY': 1.1}
SYMMETRIC_LATERAL = {
    'PCY1': 1.4, 'PDY1': 1.1, 'PDY2': -0.12, 'PDY3': 2.0, 'PEY1': -0.6, 'PEY2': -0.3,
    'PKY1': -18.0, 'PKY2': 1.8, 'PKY3': 0.3,
}  # fmt: skip
SYMMETRIC_LONGITUDINAL = {
    'PCX1': 1.6, 'PDX1': 1.2, 'PDX2': -0.1, 'PEX1': 0.4, 'PEX2': 0.2, 'PEX3': 0.05,
    'PKX1': 22.0, 'PKX2': 0.5, 'PKX3': 0.2,
}  # fmt: skip


def tir_text(
    lateral: dict[str, float],
    longitudinal: dict[str, float] = SYMMETRIC_LONGITUDINAL,
    scaling: dict[str, float] = SYMMETRIC_SCALING,
    model: str = "PROPERTY_FILE_FORMAT = 'PAC2002'\nTYRESIDE = 'LEFT'",
) -> str:
    """Return a minimal PAC2002 file holding the given coefficients."""

    def block(values: dict[str, float]) -> str:
        return '\n'.join(f'{key} = {value!r}' for key, value in values.items())

    return f"""$ synthetic test tire
[UNITS]
LENGTH = 'meter'
FORCE = 'newton'
ANGLE = 'radian'
[MODEL]
{model}
[DIMENSION]
UNLOADED_RADIUS = 0.3
[VERTICAL]
FNOMIN = {SYMMETRIC_FNOMIN!r}
[SCALING_COEFFICIENTS]
{block(scaling)}
[LONGITUDINAL_COEFFICIENTS]
{block(longitudinal)}
[LATERAL_COEFFICIENTS]
{block(lateral)}
"""


# Scaling factors != 1 so that a factor in the wrong place shows.
SCALED = {
    'LCY': 1.1, 'LMUY': 0.9, 'LEY': 1.2, 'LKY': 0.85, 'LHY': 1.3, 'LVY': 0.7, 'LGAY': 1.15,
    'LCX': 0.95, 'LMUX': 1.05, 'LEX': 0.8, 'LKX': 1.1, 'LHX': 1.2, 'LVX': 0.9, 'LGAX': 0.85,
}  # fmt: skip


def sedan_scaled() -> TireProperties:
    """
    Return the sedan tire with the scaling factors of SCALED.

    PDX3 (absent in the file) is added for camber in Fx.
    """
    text = SEDAN.read_text(encoding='ascii').replace(
        '[LONGITUDINAL_COEFFICIENTS]', '[LONGITUDINAL_COEFFICIENTS]\nPDX3 = 5.0'
    )
    for key, value in SCALED.items():
        text, count = re.subn(rf'(?m)^{key}\s*=.*$', f'{key} = {value!r}', text)
        assert count == 1
    return parse_tir_text(text, 'sedan_scaled')


TIRES = {
    'sedan': lambda: read_tir(SEDAN),
    'hmmwv': lambda: read_tir(HMMWV),
    'sedan_scaled': sedan_scaled,
}


@pytest.fixture(scope='module')
def sedan() -> TireProperties:
    return read_tir(SEDAN)


@pytest.fixture(scope='module')
def symmetric() -> MagicFormula:
    return MagicFormula(parse_tir_text(tir_text(SYMMETRIC_LATERAL), 'symmetric'))


# --- the PAC2002 equations, evaluated by hand -------------------------------------


@pytest.mark.parametrize(
    ('tire', 'fz'), [('sedan', 5500.0), ('hmmwv', 25000.0), ('sedan_scaled', 2500.0)]
)
@pytest.mark.parametrize(
    ('alpha', 'gamma'), [(0.07, 0.03), (-0.07, 0.03), (0.2, -0.02), (-0.004, 0.0)]
)
def test_fy_matches_hand_evaluated_pac2002(
    tire: str, fz: float, alpha: float, gamma: float
) -> None:
    props = TIRES[tire]()

    def p(key: str) -> float:
        return props.number('LATERAL_COEFFICIENTS', key, 0.0)

    def scale(key: str) -> float:
        return props.number('SCALING_COEFFICIENTS', key, 1.0)

    fnomin = props.number('VERTICAL', 'FNOMIN')
    fz0_scaled = fnomin * scale('LFZO')
    dfz = (fz - fz0_scaled) / fz0_scaled
    gamma_y = gamma * scale('LGAY')
    sh = (p('PHY1') + p('PHY2') * dfz) * scale('LHY') + p('PHY3') * gamma_y
    alpha_y = alpha + sh
    c = p('PCY1') * scale('LCY')
    mu = (p('PDY1') + p('PDY2') * dfz) * (1.0 - p('PDY3') * gamma_y**2) * scale('LMUY')
    d = mu * fz
    e = (p('PEY1') + p('PEY2') * dfz) * (
        1.0 - (p('PEY3') + p('PEY4') * gamma_y) * math.copysign(1.0, alpha_y)
    )
    e = min(e * scale('LEY'), 1.0)
    k = (
        p('PKY1') * fnomin * math.sin(2.0 * math.atan(fz / (p('PKY2') * fnomin * scale('LFZO'))))
        * (1.0 - p('PKY3') * abs(gamma_y)) * scale('LFZO') * scale('LKY')
    )  # fmt: skip
    b = k / (c * d)
    sv = (
        fz
        * ((p('PVY1') + p('PVY2') * dfz) * scale('LVY') + (p('PVY3') + p('PVY4') * dfz) * gamma_y)
        * scale('LMUY')
    )
    expected = (
        d * math.sin(c * math.atan(b * alpha_y - e * (b * alpha_y - math.atan(b * alpha_y)))) + sv
    )

    npt.assert_allclose(MagicFormula(props).fy(fz, alpha, gamma), expected, rtol=RTOL)


@pytest.mark.parametrize(
    ('tire', 'fz'), [('sedan', 3000.0), ('hmmwv', 15000.0), ('sedan_scaled', 7000.0)]
)
@pytest.mark.parametrize(('kappa', 'gamma'), [(0.08, 0.03), (-0.08, 0.03), (0.3, -0.05)])
def test_fx_matches_hand_evaluated_pac2002(
    tire: str, fz: float, kappa: float, gamma: float
) -> None:
    props = TIRES[tire]()

    def p(key: str) -> float:
        return props.number('LONGITUDINAL_COEFFICIENTS', key, 0.0)

    def scale(key: str) -> float:
        return props.number('SCALING_COEFFICIENTS', key, 1.0)

    fz0_scaled = props.number('VERTICAL', 'FNOMIN') * scale('LFZO')
    dfz = (fz - fz0_scaled) / fz0_scaled
    gamma_x = gamma * scale('LGAX')
    sh = (p('PHX1') + p('PHX2') * dfz) * scale('LHX')
    kappa_x = kappa + sh
    c = p('PCX1') * scale('LCX')
    d = (p('PDX1') + p('PDX2') * dfz) * (1.0 - p('PDX3') * gamma_x**2) * scale('LMUX') * fz
    e = (p('PEX1') + p('PEX2') * dfz + p('PEX3') * dfz**2) * (
        1.0 - p('PEX4') * math.copysign(1.0, kappa_x)
    )
    e = min(e * scale('LEX'), 1.0)
    k = fz * (p('PKX1') + p('PKX2') * dfz) * math.exp(p('PKX3') * dfz) * scale('LKX')
    b = k / (c * d)
    sv = fz * (p('PVX1') + p('PVX2') * dfz) * scale('LVX') * scale('LMUX')
    expected = (
        d * math.sin(c * math.atan(b * kappa_x - e * (b * kappa_x - math.atan(b * kappa_x)))) + sv
    )

    npt.assert_allclose(MagicFormula(props).fx(fz, kappa, gamma), expected, rtol=RTOL)


def test_peak_lateral_friction_matches_hand_formula(sedan: TireProperties) -> None:
    fz, gamma = 6000.0, 0.04
    fz0_scaled = 4850.0 * 0.81  # FNOMIN, LFZO of the file; LMUY = LGAY = 1
    expected = (1.0489 - 0.18033 * (fz - fz0_scaled) / fz0_scaled) * (1.0 + 2.8821 * gamma**2)
    npt.assert_allclose(MagicFormula(sedan).peak_lateral_friction(fz, gamma), expected, rtol=RTOL)


def test_curvature_above_one_is_limited_to_one() -> None:
    lateral = {**SYMMETRIC_LATERAL, 'PEY1': 1.5, 'PEY2': 0.0}
    mf = MagicFormula(parse_tir_text(tir_text(lateral), 'x'))
    fz, alpha = 3000.0, 0.1
    fz0_scaled = SYMMETRIC_FNOMIN * SYMMETRIC_SCALING['LFZO']
    d = (1.1 - 0.12 * (fz - fz0_scaled) / fz0_scaled) * 0.95 * fz
    k = -18.0 * fz0_scaled * math.sin(2.0 * math.atan(fz / (1.8 * fz0_scaled))) * 1.1
    b = k / (1.4 * d)
    # E = 1 turns B x - E (B x - atan(B x)) into atan(B x).
    npt.assert_allclose(
        mf.fy(fz, alpha), d * math.sin(1.4 * math.atan(math.atan(b * alpha))), rtol=RTOL
    )


@pytest.mark.parametrize(
    ('slip_sign', 'factor'), [(1.0, 1.0 + 9.9935), (-1.0, 1.0 - 9.9935), (0.0, 1.0)]
)
def test_lateral_curvature_branches(
    sedan: TireProperties, slip_sign: float, factor: float
) -> None:
    fz = 5000.0
    fz0_scaled = 4850.0 * 0.81
    even = -0.0074722 - 0.0063208 * (fz - fz0_scaled) / fz0_scaled  # PEY1 + PEY2 dfz, LEY = 1
    # 1 - PEY3 sgn(alpha_y) with PEY3 = -9.9935; sgn = 0 gives the even part.
    npt.assert_allclose(
        MagicFormula(sedan).lateral_curvature(fz, 0.0, slip_sign), even * factor, rtol=RTOL
    )


# --- closed-form properties -----------------------------------------------------------


@pytest.mark.parametrize(
    ('path', 'loads'), [(SEDAN, (2000.0, 4850.0, 8000.0)), (HMMWV, (10000.0, 35000.0, 60000.0))]
)
@pytest.mark.parametrize('gamma', [0.0, 0.03])
def test_cornering_stiffness_is_slope_of_fy_at_zero_slip(
    path: Path, loads: tuple[float, ...], gamma: float
) -> None:
    mf = MagicFormula(read_tir(path))
    fz = np.asarray(loads)
    step = 1e-6
    slope = (mf.fy(fz, step, gamma) - mf.fy(fz, -step, gamma)) / (2.0 * step)
    npt.assert_allclose(mf.cornering_stiffness(fz, gamma), slope, rtol=1e-5)


def test_cornering_stiffness_without_shift_is_bcd(symmetric: MagicFormula) -> None:
    fz = np.array([1500.0, 3600.0, 7000.0])
    fz0_scaled = SYMMETRIC_FNOMIN * SYMMETRIC_SCALING['LFZO']
    expected = (
        -18.0
        * fz0_scaled
        * np.sin(2.0 * np.arctan(fz / (1.8 * fz0_scaled)))
        * SYMMETRIC_SCALING['LKY']
    )
    npt.assert_allclose(symmetric.cornering_stiffness(fz), expected, rtol=RTOL)


@pytest.mark.parametrize('fz', [1500.0, 3600.0, 7000.0])
def test_peak_lateral_force_is_mu_times_load(symmetric: MagicFormula, fz: float) -> None:
    # PKY1 < 0: the peak of |Fy| for alpha > 0 is the minimum of Fy.
    result = minimize_scalar(
        lambda a: float(symmetric.fy(fz, a)),
        bounds=(0.0, 1.0),
        method='bounded',
        options={'xatol': 1e-10},
    )
    fz0_scaled = SYMMETRIC_FNOMIN * SYMMETRIC_SCALING['LFZO']
    mu = (1.1 - 0.12 * (fz - fz0_scaled) / fz0_scaled) * SYMMETRIC_SCALING['LMUY']
    npt.assert_allclose(-result.fun, mu * fz, rtol=1e-9)
    npt.assert_allclose(symmetric.peak_lateral_friction(fz), mu, rtol=RTOL)


@pytest.mark.parametrize('gamma', [0.0, 0.05])
def test_fy_is_odd_in_alpha_without_shifts(symmetric: MagicFormula, gamma: float) -> None:
    fz = np.array([[1500.0], [4000.0], [7000.0]])
    alpha = np.linspace(0.001, 0.6, 25)
    npt.assert_allclose(
        symmetric.fy(fz, -alpha, gamma), -symmetric.fy(fz, alpha, gamma), rtol=RTOL, atol=1e-9
    )


def test_fx_is_odd_in_kappa_without_shifts(symmetric: MagicFormula) -> None:
    fz = np.array([[1500.0], [4000.0], [7000.0]])
    kappa = np.linspace(0.001, 0.8, 25)
    npt.assert_allclose(
        symmetric.fx(fz, -kappa, 0.02), -symmetric.fx(fz, kappa, 0.02), rtol=RTOL, atol=1e-9
    )


def test_file_convention_positive_slip_gives_negative_fy(sedan: TireProperties) -> None:
    # PKY1 = -21.92 < 0: TYDEX / ISO-W slip angle.
    fy = MagicFormula(sedan).fy([2000.0, 4850.0, 8000.0], 0.05)
    assert np.all(fy < 0.0)


def test_positive_slip_ratio_gives_positive_fx(sedan: TireProperties) -> None:
    assert np.all(MagicFormula(sedan).fx([2000.0, 4850.0, 8000.0], 0.05) > 0.0)


def test_fy_iso_is_fy_at_opposite_slip_angle(sedan: TireProperties) -> None:
    mf = MagicFormula(sedan)
    alpha = np.linspace(-0.3, 0.3, 13)
    npt.assert_allclose(mf.fy_iso(4000.0, alpha, 0.02), mf.fy(4000.0, -alpha, 0.02), rtol=RTOL)


@pytest.mark.parametrize('path', [SEDAN, HMMWV])
def test_fy_iso_has_positive_slope_at_zero_slip(path: Path) -> None:
    mf = MagicFormula(read_tir(path))
    fz, step = mf.nominal_load, 1e-6
    slope = (mf.fy_iso(fz, step) - mf.fy_iso(fz, -step)) / (2.0 * step)
    assert slope > 0.0
    npt.assert_allclose(slope, -mf.cornering_stiffness(fz), rtol=1e-5)


def test_nominal_load_is_scaled_fnomin(sedan: TireProperties) -> None:
    npt.assert_allclose(MagicFormula(sedan).nominal_load, 4850.0 * 0.81, rtol=RTOL)


def test_lateral_shape_factor_is_scaled_pcy1(sedan: TireProperties) -> None:
    npt.assert_allclose(MagicFormula(sedan).lateral_shape_factor, 1.3507, rtol=RTOL)


def test_arguments_broadcast(sedan: TireProperties) -> None:
    mf = MagicFormula(sedan)
    fz = np.array([[2000.0], [5000.0]])
    alpha = np.array([-0.1, 0.0, 0.05])
    expected = [[float(mf.fy(f, a, 0.01)) for a in alpha] for f in fz[:, 0]]
    npt.assert_allclose(mf.fy(fz, alpha, 0.01), expected, rtol=RTOL)


def test_no_force_off_the_ground(sedan: TireProperties) -> None:
    mf = MagicFormula(sedan)
    fz = np.array([0.0, -100.0])
    with warnings.catch_warnings():
        warnings.simplefilter('error')  # no 0/0 on the way
        results = np.concatenate([mf.fy(fz, 0.1), mf.fx(fz, 0.1), mf.cornering_stiffness(fz)])
    npt.assert_array_equal(results, 0.0)


# --- mounting side ----------------------------------------------------------------------


def test_tire_on_the_other_side_is_mirrored(sedan: TireProperties) -> None:
    left, right = MagicFormula(sedan), MagicFormula(sedan, side='right')
    fz = np.array([[2000.0], [6000.0]])
    alpha = np.linspace(-0.2, 0.2, 9)
    npt.assert_allclose(right.fy(fz, alpha, 0.03), -left.fy(fz, -alpha, -0.03), rtol=RTOL)


def test_mirrored_cornering_stiffness_is_taken_at_opposite_camber(sedan: TireProperties) -> None:
    left, right = MagicFormula(sedan), MagicFormula(sedan, side='RIGHT')
    npt.assert_allclose(
        right.cornering_stiffness(4000.0, 0.03), left.cornering_stiffness(4000.0, -0.03), rtol=RTOL
    )


def test_tire_on_the_measured_side_is_not_mirrored(sedan: TireProperties) -> None:
    alpha = np.linspace(-0.2, 0.2, 9)
    npt.assert_array_equal(
        MagicFormula(sedan, side='LEFT').fy(4000.0, alpha, 0.03),
        MagicFormula(sedan).fy(4000.0, alpha, 0.03),
    )


def test_mirroring_leaves_fx_unchanged(sedan: TireProperties) -> None:
    kappa = np.linspace(-0.2, 0.2, 9)
    npt.assert_array_equal(
        MagicFormula(sedan, side='RIGHT').fx(4000.0, kappa, 0.03),
        MagicFormula(sedan).fx(4000.0, kappa, 0.03),
    )


def test_mirroring_a_symmetric_tire_changes_nothing() -> None:
    props = parse_tir_text(tir_text(SYMMETRIC_LATERAL), 'symmetric')
    alpha = np.linspace(-0.4, 0.4, 17)
    npt.assert_allclose(
        MagicFormula(props, side='RIGHT').fy(3000.0, alpha),
        MagicFormula(props).fy(3000.0, alpha),
        rtol=RTOL,
        atol=1e-9,
    )


# --- bad input ------------------------------------------------------------------------------


@pytest.mark.parametrize('build', [MagicFormula, vertical_stiffness])
def test_an_unknown_format_is_refused(sedan: TireProperties, build) -> None:
    props = dataclasses.replace(sedan, file_format='MF70', path='mf70.tir')
    with pytest.raises(SolverError) as info:
        build(props)
    assert (
        str(info.value)
        == 'mf70.tir: MagicFormula evaluates PAC2002, MF 5.2, 6.1 and 6.2 files, '
        'this one is MF70'
    )


def test_unknown_side_is_refused(sedan: TireProperties) -> None:
    with pytest.raises(ValueError) as info:
        MagicFormula(sedan, side='UP')
    assert str(info.value) == "side must be 'LEFT' or 'RIGHT', got 'UP'"


def test_side_needs_tyreside() -> None:
    props = parse_tir_text(
        tir_text(SYMMETRIC_LATERAL, model="PROPERTY_FILE_FORMAT = 'PAC2002'"), 'x.tir'
    )
    with pytest.raises(DataError) as info:
        MagicFormula(props, side='LEFT')
    assert (info.value.detail, info.value.key) == (
        "key 'TYRESIDE' missing in block [MODEL]",
        'TYRESIDE',
    )


def test_unknown_tyreside_is_refused() -> None:
    model = "PROPERTY_FILE_FORMAT = 'PAC2002'\nTYRESIDE = 'MIDDLE'"
    props = parse_tir_text(tir_text(SYMMETRIC_LATERAL, model=model), 'x.tir')
    with pytest.raises(DataError) as info:
        MagicFormula(props, side='LEFT')
    assert (info.value.detail, info.value.key) == (
        "key 'TYRESIDE' in block [MODEL] must be 'LEFT' or 'RIGHT', found 'MIDDLE'",
        'TYRESIDE',
    )


def test_non_positive_lfzo_is_refused() -> None:
    """Refused when the file is read, before any model is built from it."""
    text = tir_text(SYMMETRIC_LATERAL, scaling={'LFZO': 0.0})
    line = next(n for n, t in enumerate(text.splitlines(), start=1) if t.startswith('LFZO'))
    with pytest.raises(DataError) as info:
        parse_tir_text(text, 'x.tir')
    assert (str(info.value), info.value.key) == (
        f"x.tir: LFZO: line {line}: key 'LFZO' in block [SCALING_COEFFICIENTS] must be > 0, "
        "found 0.0",
        'LFZO',
    )


# --- pneumatic trail (PAC2002, Pacejka 3rd ed. 4.E31-4.E49) ------------------------


def _trail_by_hand(props: TireProperties, fz: float, gamma: float) -> float:
    """
    t(alpha = 0) written out with math, one equation a line.

    Dt is normalised by FNOMIN (MF-Tyre) or Fz0' (Pacejka 4.E42) as the properties say.
    """
    q = lambda name: props.number('ALIGNING_COEFFICIENTS', name, 0.0)  # noqa: E731
    lam = lambda name: props.number('SCALING_COEFFICIENTS', name, 1.0)  # noqa: E731
    fz0 = props.fnomin * lam('LFZO')
    fzn = props.fnomin if props.aligning_normalisation == 'mf-tyre' else fz0
    dfz = (fz - fz0) / fz0
    gz = gamma * lam('LGAZ')
    sht = q('QHZ1') + q('QHZ2') * dfz + (q('QHZ3') + q('QHZ4') * dfz) * gz
    alpha_t = 0.0 + sht
    bt = (q('QBZ1') + q('QBZ2') * dfz + q('QBZ3') * dfz**2) * (
        1 + q('QBZ4') * gz + q('QBZ5') * abs(gz)
    )
    bt *= lam('LKY') / lam('LMUY')
    ct = q('QCZ1')
    dt = fz * (q('QDZ1') + q('QDZ2') * dfz) * (1 + q('QDZ3') * gz + q('QDZ4') * gz**2)
    dt *= props.unloaded_radius / fzn * lam('LTR')
    et = (q('QEZ1') + q('QEZ2') * dfz + q('QEZ3') * dfz**2)
    et *= 1 + (q('QEZ4') + q('QEZ5') * gz) * (2 / math.pi) * math.atan(bt * ct * alpha_t)
    et = min(et, 1.0)
    x = bt * alpha_t
    return dt * math.cos(ct * math.atan(x - et * (x - math.atan(x)))) * math.cos(0.0)


@pytest.mark.parametrize('normalisation', ['mf-tyre', 'book'])
@pytest.mark.parametrize('path', [SEDAN, HMMWV])
@pytest.mark.parametrize(
    'fz, gamma', [(2000.0, 0.0), (4850.0, 0.0), (7000.0, 0.03), (4000.0, -0.02)]
)
def test_pneumatic_trail_is_pac2002_by_hand(path: Path, fz: float, gamma: float,
                                            normalisation: str) -> None:
    props = dataclasses.replace(read_tir(path), aligning_normalisation=normalisation)
    expected = _trail_by_hand(props, fz, gamma)
    npt.assert_allclose(MagicFormula(props).pneumatic_trail(fz, gamma), expected, rtol=RTOL)


def test_pneumatic_trail_of_the_sedan_tire_is_a_few_centimetres() -> None:
    # QDZ1 R0 = 0.0935 * 0.344 m = 32 mm at the nominal load (Dt at dfz = 0)
    trail = float(MagicFormula(read_tir(SEDAN)).pneumatic_trail(4850.0))
    assert 0.02 < trail < 0.04


def test_pneumatic_trail_mirrors_camber_and_is_zero_off_the_ground() -> None:
    props = read_tir(SEDAN)
    right = MagicFormula(props, side='RIGHT')
    npt.assert_allclose(
        right.pneumatic_trail(4000.0, 0.02), _trail_by_hand(props, 4000.0, -0.02), rtol=RTOL
    )
    npt.assert_array_equal(MagicFormula(props).pneumatic_trail([0.0, -10.0]), [0.0, 0.0])
