# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
MF-Tyre 6.1 / 6.2 evaluation against references outside the implementation.

* ``mf6_reference.Mf6``: the published equations written out a second time, scalar, one
  wheel at a time, over a grid of loads, slips, cambers and inflation pressures;
* limits: MF 6.x with the pressure and 6.x-only terms absent and INFLPRES = NOMPRES equals
  the same coefficients evaluated as PAC2002 where the two forms coincide (zero camber);
  pure slip is combined slip at zero other slip; a tire mounted on its other side is the
  mirror image; turn slip at phit = 0 gives the plain model's camber thrust;
* closed forms: the pressure factors of the cornering and slip stiffness, peak friction
  and vertical stiffness (Pacejka 4.E13, 4.E15, 4.E23, 4.E25; Besselink eq. 5).

``python tests/vd_solvers/tire/test_mf6.py`` prints the largest difference to the reference
per force and moment over the grid (MF 5.2 against test_combined's PAC2002 reference).
"""
from __future__ import annotations

import dataclasses
import itertools
import math
from pathlib import Path
import re

import numpy as np
import numpy.testing as npt
import pytest

from vd_data_server.tir import TireProperties, parse_tir_text, read_tir
from vd_solvers.tire.magic_formula import MagicFormula, vertical_stiffness

if __package__:
    from .mf6_reference import Mf6
else:  # run as a script (main below): this folder is on sys.path
    from mf6_reference import Mf6

DATA_DIR = Path(__file__).resolve().parents[3] / 'src' / 'vd_data_server' / 'data' / 'tires'
MF62 = DATA_DIR / 'MF62_255_55R20.tir'
SEDAN = DATA_DIR / 'Sedan_Pac02Tire.tir'
OUTPUTS = ('fx', 'fy', 'mx', 'my', 'mz')
# the two evaluations differ by rounding only (different order of the same operations)
RTOL = 1e-9
ATOL = {'fx': 1e-7, 'fy': 1e-7, 'mx': 1e-9, 'my': 1e-9, 'mz': 1e-9}

LOADS = (0.3, 0.7, 1.0, 1.5, 2.2)  # x FNOMIN
KAPPAS = (-0.3, -0.08, -0.01, 0.0, 0.02, 0.1, 0.5)
ALPHAS = (-0.3, -0.1, -0.02, 0.0, 0.01, 0.06, 0.25)
GAMMAS = (-0.08, 0.0, 0.05)
PRESSURES = (2.1e5, 2.6e5, 3.4e5)
SPEED = 25.0


def mf62_text() -> str:
    return MF62.read_text(encoding='ascii')


def mf61_text() -> str:
    """Return the sample as an MF 6.1 file: FITTYP 61, without the 6.2-only keys."""
    text = re.sub(r'(?m)^FITTYP\s*=.*$', 'FITTYP = 61', mf62_text())
    for key in ('Q_FCY2', 'Q_CAM1', 'Q_CAM2', 'Q_CAM3', 'Q_FYS1', 'Q_FYS2', 'Q_FYS3',
                'ENV_C1', 'ENV_C2'):
        text = re.sub(rf'(?m)^{key}\s*=.*\n', '', text)
    return text


def with_line(text: str, key: str, line: str) -> str:
    new, count = re.subn(rf'(?m)^{key}\s*=.*$', line, text)
    assert count == 1, key
    return new


TIRES = {
    'MF62': lambda: parse_tir_text(mf62_text(), 'mf62.tir'),
    'MF61': lambda: parse_tir_text(mf61_text(), 'mf61.tir'),
    # scaling factors != 1 so that a factor in the wrong place shows
    'MF61_scaled': lambda: parse_tir_text(
        re.sub(r'(?m)^(L(?:FZO|KY|MUY|MUX|KX|TR|RES|S|KYC|KZC|XAL|YKA|VYKA|MX|MY|HY|VY))\s*=.*$',
               lambda m: f'{m[1]} = {0.8 + 0.03 * len(m[1])}', mf61_text()), 'scaled.tir'),
}


def grid_agreement(props: TireProperties, normalisation: str = 'mf-tyre',
                   turn_slip: bool = False, phit: float = 0.0) -> dict[str, float]:
    """Largest |vd - reference| per output over the grid."""
    worst = dict.fromkeys(OUTPUTS, 0.0)
    fnomin = props.fnomin
    for pressure in PRESSURES:
        props_n = dataclasses.replace(props, aligning_normalisation=normalisation)
        tire = MagicFormula(props_n, pressure=pressure)
        ref = Mf6(props_n, pressure, normalisation, turn_slip)
        fz, kappa, alpha, gamma = (np.array(v, dtype=float) for v in zip(*itertools.product(
            [f * fnomin for f in LOADS], KAPPAS, ALPHAS, GAMMAS)))
        got = tire.steady_state(fz, kappa, alpha, gamma, SPEED, phit=phit)
        for i in range(fz.size):
            want = ref.evaluate(fz[i], kappa[i], alpha[i], gamma[i], SPEED, phit)
            for key in OUTPUTS:
                value = float(getattr(got, key)[i])
                npt.assert_allclose(value, want[key], rtol=RTOL, atol=ATOL[key],
                                    err_msg=f'{key} at Fz {fz[i]:g}, kappa {kappa[i]:g}, '
                                    f'alpha {alpha[i]:g}, gamma {gamma[i]:g}, p {pressure:g}')
                worst[key] = max(worst[key], abs(value - want[key]))
    return worst


@pytest.mark.parametrize('tire', list(TIRES))
@pytest.mark.parametrize('normalisation', ['mf-tyre', 'book'])
def test_forces_and_moments_match_the_equations_on_a_grid(tire: str, normalisation: str) -> None:
    grid_agreement(TIRES[tire](), normalisation)


def test_turn_slip_matches_the_equations_on_a_grid() -> None:
    props = parse_tir_text(with_line(mf62_text(), 'USE_MODE', 'USE_MODE = 125'), 'turn.tir')
    for phit in (-0.2, 0.0, 0.05):
        grid_agreement(props, turn_slip=True, phit=phit)


def test_radii_and_relaxation_lengths_match_the_equations() -> None:
    props = TIRES['MF61']()
    for pressure in PRESSURES:
        tire = MagicFormula(props, pressure=pressure)
        ref = Mf6(props, pressure)
        for load, omega in itertools.product(LOADS, (0.0, 40.0, 90.0)):
            fz = load * props.fnomin
            loaded, effective = tire.radii(fz, omega)
            npt.assert_allclose(loaded, ref.loaded_radius(fz, omega), rtol=1e-12)
            npt.assert_allclose(effective, ref.effective_radius(fz, omega), rtol=1e-12)
            npt.assert_allclose(tire.loaded_radius(fz, 0.0, 2000.0, -3000.0, omega),
                                ref.loaded_radius(fz, omega, 2000.0, -3000.0), rtol=1e-12)
            for gamma in GAMMAS:
                npt.assert_allclose(tire.relaxation_lengths(fz, gamma),
                                    ref.relaxation(fz, gamma), rtol=1e-12)


def test_the_vertical_force_inverts_the_loaded_radius() -> None:
    """Fz(R_omega - R_l(Fz)) = Fz, with and (6.2) without the camber terms."""
    tire = MagicFormula(TIRES['MF62']())
    fz = np.array([1000.0, 4000.0, 6752.0, 12000.0])
    for gamma, fy in ((0.0, 0.0), (0.06, 0.0), (-0.04, 2500.0)):
        r_l = tire.loaded_radius(fz, gamma, 0.0, fy, 50.0)
        r_omega = tire.radii(0.0, 50.0)[0]
        npt.assert_allclose(tire.vertical_force(r_omega - r_l, gamma, 0.0, fy, 50.0), fz,
                            rtol=1e-9)


def test_vertical_stiffness_is_the_files_at_the_nominal_load_and_pressure() -> None:
    """VERTICAL_STIFFNESS is dFz/drho at FNOMIN (Besselink eq. 4); PFZ1 scales it (eq. 5)."""
    props = TIRES['MF61']()
    for pressure in PRESSURES:
        tire = MagicFormula(props, pressure=pressure)
        r_omega = tire.radii(0.0)[0]
        # at the nominal pressure the tangent at FNOMIN; at another pressure the curve
        # scales by (1 + PFZ1 dpi), so take its slope at the nominal load's deflection
        nominal = MagicFormula(props)
        rho0 = r_omega - nominal.radii(props.fnomin)[0]
        h = 1e-7
        slope = float((tire.vertical_force(rho0 + h) - tire.vertical_force(rho0 - h)) / (2 * h))
        dpi = (pressure - 2.6e5) / 2.6e5
        npt.assert_allclose(slope, 322913.0 * (1 + 0.8156607 * dpi), rtol=1e-6)
        npt.assert_allclose(tire.vertical_stiffness, 322913.0 * (1 + 0.8156607 * dpi),
                            rtol=1e-12)


def test_the_vertical_stiffness_without_the_model_follows_the_closed_form() -> None:
    """vertical_stiffness(): C_z = VERTICAL_STIFFNESS (1 + PFZ1 dpi) (eq. 5), no model built."""
    props = TIRES['MF61']()
    npt.assert_allclose(vertical_stiffness(props), 322913.0, rtol=1e-12)
    for pressure in PRESSURES:
        dpi = (pressure - 2.6e5) / 2.6e5
        npt.assert_allclose(vertical_stiffness(props, pressure),
                            322913.0 * (1 + 0.8156607 * dpi), rtol=1e-12)


def test_pressure_factors_follow_the_closed_forms() -> None:
    """Kya, Kxk, mu_x, mu_y against 4.E25, 4.E15, 4.E13, 4.E23 with the file's PPX/PPY."""
    props = TIRES['MF62']()
    fz = props.fnomin  # dfz = 0: only the pressure factors remain
    nominal = MagicFormula(props)
    for pressure in PRESSURES:
        dpi = (pressure - 2.6e5) / 2.6e5
        tire = MagicFormula(props, pressure=pressure)
        pky4, pky2 = -3.267949, 3.660821
        ratio_ky = ((1 + 0.4181535 * dpi) * math.sin(pky4 * math.atan(1 / (pky2 * (1 + 1.079097
                                                                               * dpi))))
                    / math.sin(pky4 * math.atan(1 / pky2)))
        # cornering stiffness without the shift: K_ya = B C D (PHY*, camber shift, PVY*)
        ky = float(tire.cornering_stiffness(fz))
        ky_nom = float(nominal.cornering_stiffness(fz))
        npt.assert_allclose(ky / ky_nom, ratio_ky, rtol=2e-3)  # SHy moves the slope a little
        npt.assert_allclose(tire.slip_stiffness(fz) / nominal.slip_stiffness(fz),
                            1 - 1.043804 * dpi - 0.1445248 * dpi ** 2, rtol=1e-12)
        npt.assert_allclose(tire.peak_lateral_friction(fz) / nominal.peak_lateral_friction(fz),
                            1 + 0.06690019 * dpi - 0.105666 * dpi ** 2, rtol=1e-12)


@pytest.mark.parametrize('tire', ['MF61', 'MF62'])
def test_pure_slip_is_combined_slip_at_zero_other_slip(tire: str) -> None:
    mf = MagicFormula(TIRES[tire]())
    fz = np.array([2000.0, 6752.0, 11000.0])
    alpha = np.array([0.02, -0.1, 0.3])
    kappa = np.array([0.03, -0.2, 0.5])
    for gamma in GAMMAS:
        npt.assert_allclose(mf.steady_state(fz, 0.0, alpha, gamma).fy, mf.fy(fz, alpha, gamma),
                            rtol=1e-12)
        npt.assert_allclose(mf.steady_state(fz, kappa, 0.0, gamma).fx, mf.fx(fz, kappa, gamma),
                            rtol=1e-12)


def test_mounting_on_the_other_side_mirrors_the_tire() -> None:
    """The sample is measured RIGHT; on the LEFT it is the mirror image (MF-Tyre practice)."""
    props = TIRES['MF62']()
    right, left = MagicFormula(props, side='RIGHT'), MagicFormula(props, side='LEFT')
    fz, kappa, alpha, gamma = 5000.0, 0.04, 0.07, 0.03
    measured = right.steady_state(fz, kappa, alpha, gamma, 10.0)
    mirrored = left.steady_state(fz, kappa, -alpha, -gamma, 10.0)
    npt.assert_allclose([mirrored.fx, mirrored.my], [measured.fx, measured.my], rtol=1e-12)
    npt.assert_allclose([mirrored.fy, mirrored.mx, mirrored.mz],
                        [-measured.fy, -measured.mx, -measured.mz], rtol=1e-12)
    npt.assert_allclose(left.fy(fz, -alpha, -gamma), -right.fy(fz, alpha, gamma), rtol=1e-12)


def pac2002_as_mf61() -> TireProperties:
    """
    Return the sedan's PAC2002 coefficients written as an MF 6.1 file.

    INFLPRES = NOMPRES, no pressure coefficients, and without the PAC2002-only keys (PHY3,
    LGA*, relaxation PTX/PTY...), which MF 6.1 does not define.
    """
    text = SEDAN.read_text(encoding='ascii')
    text = text.replace("PROPERTY_FILE_FORMAT     ='PAC2002'", 'FITTYP = 61')
    text = text.replace('[DIMENSION]', '[OPERATING_CONDITIONS]\nINFLPRES = 220000\n'
                        'NOMPRES = 220000\n[DIMENSION]')
    for key in ('PHY3', 'LGAX', 'LGAY', 'LGAZ', 'LSGKP', 'LSGAL', 'LGYR', 'PTX1', 'PTX2',
                'PTX3', 'PTY1', 'PTY2', 'QTZ1', 'MBELT'):
        text = re.sub(rf'(?m)^{key}\s*=.*\n', '', text)
    return parse_tir_text(text, 'sedan_mf61.tir')


@pytest.mark.parametrize('normalisation', ['mf-tyre', 'book'])
def test_mf61_without_pressure_terms_is_pac2002_at_zero_camber(normalisation: str) -> None:
    """
    Where the two versions' forms coincide, the same coefficients give the same tire.

    At zero camber SHy (PHY3 vs Kyg0), Fy' of Mz (Fy - SVyk vs Gyk Fy0(gamma = 0)) and My
    (QSY7 = 1, QSY8 = 0 absent) reduce to one another; Fx is the same at any camber.
    """
    pac = MagicFormula(dataclasses.replace(read_tir(SEDAN),
                                           aligning_normalisation=normalisation))
    mf61 = MagicFormula(dataclasses.replace(pac2002_as_mf61(),
                                            aligning_normalisation=normalisation))
    fz, kappa, alpha = (np.array(v, dtype=float) for v in zip(*itertools.product(
        [f * 4850.0 for f in LOADS], KAPPAS, ALPHAS)))
    a, b = pac.steady_state(fz, kappa, alpha, 0.0, SPEED), mf61.steady_state(fz, kappa, alpha,
                                                                             0.0, SPEED)
    for key in OUTPUTS:
        npt.assert_allclose(getattr(b, key), getattr(a, key), rtol=1e-12, atol=1e-9,
                            err_msg=key)
    npt.assert_allclose(mf61.fx(fz, kappa, 0.05), pac.fx(fz, kappa, 0.05), rtol=1e-12)
    npt.assert_allclose(mf61.radii(fz), pac.radii(fz), rtol=1e-14)


def test_turn_slip_at_zero_path_curvature_keeps_the_camber_thrust() -> None:
    """
    With turn slip on, camber acts through the spin phi (Pacejka 4.76, 4.89).

    For small camber at phit = 0 the lateral force is the plain model's Kyg0 gamma times
    R0 / R_e (the spin is omega sin(gamma) / V_c = sin(gamma) / R_e, the turn-slip functions
    take R0 phi); a path curving left (phit > 0) acts like a camber with the top to the
    right: it adds force in the direction of that camber thrust.
    """
    plain = MagicFormula(TIRES['MF62']())
    turn = MagicFormula(parse_tir_text(with_line(mf62_text(), 'USE_MODE', 'USE_MODE = 125'),
                                       'turn.tir'))
    fz = 6752.0
    gamma = 0.002
    thrust_plain = plain.steady_state(fz, 0.0, 0.0, gamma).fy - plain.steady_state(fz, 0.0, 0.0,
                                                                                    0.0).fy
    thrust_turn = turn.steady_state(fz, 0.0, 0.0, gamma).fy - turn.steady_state(fz, 0.0, 0.0,
                                                                                 0.0).fy
    r_e = float(plain.radii(fz)[1])
    npt.assert_allclose(thrust_turn, thrust_plain * 0.393581 / r_e, rtol=2e-3)
    assert thrust_plain < 0.0  # PKY6 < 0: the top leaning right pushes the tire right
    left_turn = turn.steady_state(fz, 0.0, 0.0, 0.0, phit=0.01).fy
    assert left_turn < turn.steady_state(fz, 0.0, 0.0, 0.0).fy


def test_e_t_is_evaluated_at_the_pure_slip_trail_angle() -> None:
    """
    Combined Mz takes E_t at alpha_t (Pacejka 4.E44 in 4.E73), not at alpha_t,eq.

    Where QEZ4 and a large kappa make the two differ, vd's Mz is the one with alpha_t.
    """
    props = TIRES['MF62']()
    tire = MagicFormula(props)
    ref = Mf6(props)
    fz, kappa, alpha = 6752.0, 0.05, -0.0436  # 2.5 deg, braking: 4.6 N*m apart (7 %)
    got = float(tire.steady_state(fz, kappa, alpha, 0.0).mz)
    at_alpha_t = ref.evaluate(fz, kappa, alpha, 0.0, 0.0)['mz']
    at_equivalent = ref.evaluate(fz, kappa, alpha, 0.0, 0.0, et_at_equivalent=True)['mz']
    npt.assert_allclose(got, at_alpha_t, rtol=1e-10)
    assert abs(at_equivalent - at_alpha_t) > 0.05 * abs(at_alpha_t)


def main() -> None:
    """Print the agreement with the references, per force and moment."""
    from test_combined import reference as pac2002_reference

    rows = []
    for name, make in TIRES.items():
        for normalisation in ('mf-tyre', 'book'):
            rows.append((f'{name} ({normalisation})', grid_agreement(make(), normalisation)))
    turn = parse_tir_text(with_line(mf62_text(), 'USE_MODE', 'USE_MODE = 125'), 'turn.tir')
    rows.append(('MF62 turn slip, phit 0.05 1/m', grid_agreement(turn, turn_slip=True,
                                                                  phit=0.05)))
    for path in (SEDAN, DATA_DIR / 'HMMWV_Pac02Tire.tir'):
        props = read_tir(path)
        tire = MagicFormula(props)
        worst = dict.fromkeys(OUTPUTS, 0.0)
        for f, k, a, g in itertools.product(LOADS, KAPPAS, ALPHAS, GAMMAS):
            fz = f * props.fnomin
            got = tire.steady_state(fz, k, a, g, SPEED)
            want = pac2002_reference(props, fz, k, a, g, SPEED)
            for key in OUTPUTS:
                worst[key] = max(worst[key], abs(float(getattr(got, key)) - want[key]))
        rows.append((f'{path.stem} (PAC2002)', worst))
    points = len(LOADS) * len(KAPPAS) * len(ALPHAS) * len(GAMMAS)
    print(f'max |vd - reference| over {points} points x {len(PRESSURES)} pressures (6.x)')
    print(f"{'tire':34s}" + ''.join(f'{k:>12s}' for k in OUTPUTS))
    for name, worst in rows:
        print(f'{name:34s}' + ''.join(f'{worst[k]:12.2e}' for k in OUTPUTS))


if __name__ == '__main__':
    main()
