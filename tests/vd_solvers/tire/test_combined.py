# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Combined slip, moments, radii and relaxation lengths of the PAC2002 Magic Formula.

The reference is the MF-Tyre 5.2 / PAC2002 equation list (Pacejka, "Tire and Vehicle
Dynamics", 3rd ed., 4.E1-4.E78; the MF-Tyre 5.2 equation manual for rolling resistance,
overturning moment and the effective rolling radius), evaluated here term by term with
``math`` from the coefficients in the file: one wheel at a time, no code shared with the
implementation. Properties (friction-ellipse reduction, pure = combined at zero other
slip, mirroring) complete it.

In the combined aligning moment E_t is evaluated at the pure-slip alpha_t (Pacejka 4.E44,
used unchanged by 4.E73), not at the equivalent angle; Mx and My normalise Fy and Fx by
FNOMIN (Pacejka 4.E69, 4.E70; MF-Tyre); the trail and the Fx arm are normalised by
FNOMIN ('mf-tyre', MF-Tyre as reproduced by MFeval) or Fz0' ('book', Pacejka 4.E42, 4.E76).
"""
from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import numpy as np
import numpy.testing as npt
import pytest

from vd_data_server.tir import read_tir
from vd_solvers.tire.magic_formula import MagicFormula

DATA_DIR = Path(__file__).resolve().parents[3] / 'src' / 'vd_data_server' / 'data' / 'tires'
HMMWV = DATA_DIR / 'HMMWV_Pac02Tire.tir'
SEDAN = DATA_DIR / 'Sedan_Pac02Tire.tir'
RTOL = 1e-10


def reference(props, fz: float, kappa: float, alpha: float, gamma: float, vx: float,
              normalisation: str = 'mf-tyre') -> dict:
    """PAC2002 combined-slip forces and moments of one wheel, written out by hand."""

    def c(key: str) -> float:
        for block in ('LONGITUDINAL_COEFFICIENTS', 'LATERAL_COEFFICIENTS',
                      'ALIGNING_COEFFICIENTS', 'OVERTURNING_COEFFICIENTS',
                      'ROLLING_COEFFICIENTS'):
            if key in props.sections.get(block, {}):
                return float(props.sections[block][key])
        return 0.0

    def lam(key: str) -> float:
        return float(props.sections['SCALING_COEFFICIENTS'].get(key, 1.0))

    r0 = props.number('DIMENSION', 'UNLOADED_RADIUS')
    fnomin = props.number('VERTICAL', 'FNOMIN')
    fz0 = fnomin * lam('LFZO')
    fzn = fnomin if normalisation == 'mf-tyre' else fz0
    dfz = (fz - fz0) / fz0
    # pure longitudinal (4.E9-4.E18)
    gx = gamma * lam('LGAX')
    shx = (c('PHX1') + c('PHX2') * dfz) * lam('LHX')
    kx_ = kappa + shx
    cx = c('PCX1') * lam('LCX')
    dx = (c('PDX1') + c('PDX2') * dfz) * (1 - c('PDX3') * gx * gx) * lam('LMUX') * fz
    ex = min((c('PEX1') + c('PEX2') * dfz + c('PEX3') * dfz * dfz)
             * (1 - c('PEX4') * math.copysign(1.0, kx_) if kx_ != 0 else 1.0) * lam('LEX'), 1.0)
    kxk = fz * (c('PKX1') + c('PKX2') * dfz) * math.exp(c('PKX3') * dfz) * lam('LKX')
    bx = kxk / (cx * dx)
    svx = fz * (c('PVX1') + c('PVX2') * dfz) * lam('LVX') * lam('LMUX')
    fx0 = dx * math.sin(cx * math.atan(bx * kx_ - ex * (bx * kx_ - math.atan(bx * kx_)))) + svx
    # pure lateral (4.E19-4.E30)
    gy = gamma * lam('LGAY')
    shy = (c('PHY1') + c('PHY2') * dfz) * lam('LHY') + c('PHY3') * gy
    ay = alpha + shy
    cy = c('PCY1') * lam('LCY')
    muy = (c('PDY1') + c('PDY2') * dfz) * (1 - c('PDY3') * gy * gy) * lam('LMUY')
    dy = muy * fz
    sgn = math.copysign(1.0, ay) if ay != 0 else 0.0
    ey = min((c('PEY1') + c('PEY2') * dfz) * (1 - (c('PEY3') + c('PEY4') * gy) * sgn)
             * lam('LEY'), 1.0)
    kya = (c('PKY1') * fz0 * math.sin(2 * math.atan(fz / (c('PKY2') * fz0)))
           * (1 - c('PKY3') * abs(gy)) * lam('LKY'))
    by = kya / (cy * dy)
    svy = fz * ((c('PVY1') + c('PVY2') * dfz) * lam('LVY') + (c('PVY3') + c('PVY4') * dfz) * gy) \
        * lam('LMUY')
    fy0 = dy * math.sin(cy * math.atan(by * ay - ey * (by * ay - math.atan(by * ay)))) + svy
    # combined (4.E50-4.E67)
    shxa = c('RHX1')
    bxa = c('RBX1') * math.cos(math.atan(c('RBX2') * kappa)) * lam('LXAL')
    cxa = c('RCX1')
    exa = min(c('REX1') + c('REX2') * dfz, 1.0)

    def g(b, cc, e, x):
        return math.cos(cc * math.atan(b * x - e * (b * x - math.atan(b * x))))

    fx = g(bxa, cxa, exa, alpha + shxa) / g(bxa, cxa, exa, shxa) * fx0
    shyk = c('RHY1') + c('RHY2') * dfz
    byk = c('RBY1') * math.cos(math.atan(c('RBY2') * (alpha - c('RBY3')))) * lam('LYKA')
    cyk = c('RCY1')
    eyk = min(c('REY1') + c('REY2') * dfz, 1.0)
    dvyk = muy * fz * (c('RVY1') + c('RVY2') * dfz + c('RVY3') * gamma) \
        * math.cos(math.atan(c('RVY4') * alpha))
    svyk = dvyk * math.sin(c('RVY5') * math.atan(c('RVY6') * kappa)) * lam('LVYKA')
    fy = g(byk, cyk, eyk, kappa + shyk) / g(byk, cyk, eyk, shyk) * fy0 + svyk
    # aligning moment (4.E31-4.E49, combined 4.E71-4.E78)
    gz = gamma * lam('LGAZ')
    sht = c('QHZ1') + c('QHZ2') * dfz + (c('QHZ3') + c('QHZ4') * dfz) * gz
    at = alpha + sht
    bt = (c('QBZ1') + c('QBZ2') * dfz + c('QBZ3') * dfz ** 2) \
        * (1 + c('QBZ4') * gz + c('QBZ5') * abs(gz)) * lam('LKY') / lam('LMUY')
    ct = c('QCZ1')
    dt = fz * (c('QDZ1') + c('QDZ2') * dfz) * (1 + c('QDZ3') * gz + c('QDZ4') * gz ** 2) \
        * (r0 / fzn) * lam('LTR')
    kyk_ratio = kxk / kya  # K_x / K_y of the pure-slip curves
    at_eq = math.atan(math.sqrt(math.tan(at) ** 2 + (kyk_ratio * kappa) ** 2)) \
        * (1.0 if at >= 0 else -1.0)
    et = min((c('QEZ1') + c('QEZ2') * dfz + c('QEZ3') * dfz ** 2)
             * (1 + (c('QEZ4') + c('QEZ5') * gz) * (2 / math.pi) * math.atan(bt * ct * at)),
             1.0)
    t = dt * math.cos(ct * math.atan(bt * at_eq - et * (bt * at_eq - math.atan(bt * at_eq)))) \
        * math.cos(alpha)
    ar = alpha + shy + svy / kya
    ar_eq = math.atan(math.sqrt(math.tan(ar) ** 2 + (kyk_ratio * kappa) ** 2)) \
        * (1.0 if ar >= 0 else -1.0)
    br = c('QBZ9') * lam('LKY') / lam('LMUY') + c('QBZ10') * by * cy
    dr = fz * r0 * ((c('QDZ6') + c('QDZ7') * dfz) * lam('LRES')
                    + (c('QDZ8') + c('QDZ9') * dfz) * gz) * lam('LMUY')
    mzr = dr * math.cos(math.atan(br * ar_eq)) * math.cos(alpha)
    s = r0 * (c('SSZ1') + c('SSZ2') * fy / fzn + (c('SSZ3') + c('SSZ4') * dfz) * gz) * lam('LS')
    mz = -t * (fy - svyk) + mzr + s * fx
    mx = fz * r0 * (c('QSX1') * lam('LVMX') - c('QSX2') * gamma + c('QSX3') * fy / fnomin) \
        * lam('LMX')
    vref = props.number('MODEL', 'LONGVL')
    my = -math.copysign(1.0, vx) * fz * r0 * (c('QSY1') + c('QSY2') * fx / fnomin
                                             + c('QSY3') * abs(vx / vref)
                                             + c('QSY4') * (vx / vref) ** 4) * lam('LMY')
    return {'fx': fx, 'fy': fy, 'mz': mz, 'mx': mx, 'my': my}


@pytest.mark.parametrize('normalisation', ['mf-tyre', 'book'])
@pytest.mark.parametrize('path', [HMMWV, SEDAN])
@pytest.mark.parametrize(('kappa', 'alpha', 'gamma'), [
    (0.05, 0.06, 0.02), (-0.08, 0.1, -0.03), (0.2, -0.04, 0.0), (-0.01, -0.15, 0.05)])
def test_combined_slip_matches_the_pac2002_equations(path, kappa, alpha, gamma,
                                                     normalisation) -> None:
    props = dataclasses.replace(read_tir(path), aligning_normalisation=normalisation)
    tire = MagicFormula(props)
    fz = 1.2 * props.fnomin
    got = tire.steady_state(fz, kappa, alpha, gamma, 15.0)
    want = reference(props, fz, kappa, alpha, gamma, 15.0, normalisation)
    for key, value in want.items():
        npt.assert_allclose(float(getattr(got, key)), value, rtol=RTOL, atol=1e-9, err_msg=key)


def test_the_hmmwv_file_reduces_each_force_under_the_other_slip() -> None:
    """
    Friction ellipse (Pacejka 4.3.2).

    Combined slip lowers |Fy| with kappa and |Fx| with alpha.
    """
    tire = MagicFormula(read_tir(HMMWV))
    fz = tire.nominal_load
    pure = tire.steady_state(fz, 0.0, 0.08)
    braked = tire.steady_state(fz, -0.1, 0.08)
    assert abs(braked.fy) < 0.8 * abs(pure.fy)
    straight = tire.steady_state(fz, 0.1, 0.0)
    cornering = tire.steady_state(fz, 0.1, 0.1)
    assert abs(cornering.fx) < 0.9 * abs(straight.fx)


def test_pure_slip_is_combined_slip_at_zero_other_slip() -> None:
    tire = MagicFormula(read_tir(HMMWV))
    fz = np.array([10000.0, 30000.0, 45000.0])
    alpha = np.array([0.02, -0.1, 0.3])
    kappa = np.array([0.03, -0.2, 0.5])
    npt.assert_allclose(tire.steady_state(fz, 0.0, alpha, 0.01).fy, tire.fy(fz, alpha, 0.01),
                        rtol=1e-12)
    npt.assert_allclose(tire.steady_state(fz, kappa, 0.0, 0.01).fx, tire.fx(fz, kappa, 0.01),
                        rtol=1e-12)


def test_a_file_without_combined_coefficients_has_no_coupling() -> None:
    """The sedan file has no RBX/RBY/RHY...: G_xa = G_yk = 1 (MF-Tyre default of absent keys)."""
    tire = MagicFormula(read_tir(SEDAN))
    fz = tire.nominal_load
    npt.assert_allclose(tire.steady_state(fz, 0.1, 0.08).fy, tire.fy(fz, 0.08), rtol=1e-12)
    npt.assert_allclose(tire.steady_state(fz, 0.1, 0.08).fx, tire.fx(fz, 0.1), rtol=1e-12)


def test_mirrored_wheel_forces_and_moments_are_the_mirror_image() -> None:
    tire = MagicFormula(read_tir(HMMWV))
    fz, kappa, alpha, gamma = 30000.0, 0.04, 0.07, 0.02
    left = tire.steady_state(fz, kappa, alpha, gamma, 10.0)
    right = tire.steady_state(fz, kappa, -alpha, -gamma, 10.0, mirror=-1.0)
    npt.assert_allclose([right.fx, right.my], [left.fx, left.my], rtol=1e-12)
    npt.assert_allclose([right.fy, right.mx, right.mz], [-left.fy, -left.mx, -left.mz],
                        rtol=1e-12)


def test_aligning_moment_is_restoring_at_small_slip_and_falls_off_beyond_the_trail_peak() -> None:
    """
    Pneumatic trail: Mz opposes the slip angle near zero and decays at large slip angles.

    Near zero Fy < 0 for alpha > 0 in TYDEX, so Mz > 0; the decay is Pacejka fig. 4.16.
    """
    tire = MagicFormula(read_tir(SEDAN))
    fz = tire.nominal_load
    alpha = np.linspace(0.01, 0.3, 60)
    mz = tire.pure_aligning_moment(fz, alpha)
    assert mz[0] > 0.0
    peak = int(np.argmax(mz))
    assert 0 < peak < alpha.size - 1
    assert mz[-1] < 0.5 * mz[peak]


def test_radii_follow_the_vertical_stiffness_and_the_effective_radius_formula() -> None:
    props = read_tir(SEDAN)
    tire = MagicFormula(props)
    fz = np.array([1000.0, 4850.0, 8000.0])
    loaded, effective = tire.radii(fz)
    r0 = props.number('DIMENSION', 'UNLOADED_RADIUS')
    cz = props.number('VERTICAL', 'VERTICAL_STIFFNESS')
    npt.assert_allclose(loaded, r0 - fz / cz, rtol=1e-14)
    fn = props.fnomin
    want = [r0 - fn / cz * (0.27 * math.atan(8.4 * f / fn) + 0.07 * f / fn) for f in fz]
    npt.assert_allclose(effective, want, rtol=1e-14)  # DREFF 0.27, BREFF 8.4, FREFF 0.07
    # from the nominal load up the rolling radius lies between the loaded and the free one
    assert np.all(effective[1:] > loaded[1:]) and np.all(effective < r0)


def test_relaxation_lengths_follow_pac2002() -> None:
    props = read_tir(SEDAN)
    tire = MagicFormula(props)
    fz = 6000.0
    fz0 = props.fnomin * 0.81  # LFZO
    r0 = 0.344
    dfz = (fz - fz0) / fz0
    sigma_k = fz * (2.3657 + 1.4112 * dfz) * math.exp(-0.56626 * dfz) * r0 / fz0
    sigma_a = 2.1439 * math.sin(2 * math.atan(fz / (1.9829 * fz0))) * r0 * 0.81
    got_k, got_a = tire.relaxation_lengths(fz)
    npt.assert_allclose([got_k, got_a], [sigma_k, sigma_a], rtol=1e-12)
    zero_k, zero_a = tire.relaxation_lengths(0.0)
    assert zero_k == 0.0 and zero_a == 0.0
