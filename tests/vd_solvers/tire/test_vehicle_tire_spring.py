# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The full vehicle's vertical tire: the 6.x load-deflection curve, the linear C_z for PAC2002.

``magic_formula.four_wheel_springs`` is the tire force the vehicle step uses at each wheel's
deflection R0 - R_l. The reference for MF 6.x is the curve written out here from Besselink
et al., Vehicle System Dynamics 48 (S1), 2010, eqs. 1 and 4 (Pacejka 2012, A3.3), with the
MF 6.2 parameters as MFeval's calculateFz62 uses them at zero camber (the F_y term times
(rho/R0)^Q_FCY2) and bottoming beyond R_omega - RIM_RADIUS - BOTTOM_OFFST:

    R_omega = R0 (Q_RE0 + Q_V1 (omega R0 / V0)^2),  rho = R_omega - R_l,
    Fz = (1 + Q_V2 |omega| R0/V0 - (Q_FCX Fx/FNOMIN)^2 - (Q_FCY' Fy/FNOMIN)^2)(1 + PFZ1 dpi)
         (Q_FZ1 rho/R0 + Q_FZ2 (rho/R0)^2) FNOMIN,
    Q_FZ1 = sqrt((VERTICAL_STIFFNESS R0 / FNOMIN)^2 - 4 Q_FZ2) (the tangent at FNOMIN).

With camber (6.2) the force is the one ``MagicFormula.vertical_force`` gives (the K&C and
``vd tire`` use it; tests/vd_solvers/tire/test_mf6.py checks it). PAC2002: Fz = C_z
deflection with C_z = VERTICAL_STIFFNESS.
"""
from __future__ import annotations

import itertools
import math
from pathlib import Path
import re

import numpy as np
import numpy.testing as npt

from vd_data_server.study import load_study
from vd_data_server.tir import TireProperties, parse_tir_text, read_tir
from vd_solvers.tire.magic_formula import MagicFormula, four_wheel_springs
from vd_solvers.vehicle.model import VehicleModel
from vd_solvers.vehicle_data import static_wheel_loads

DATA_DIR = Path(__file__).resolve().parents[3] / 'src' / 'vd_data_server' / 'data' / 'tires'
MF62 = DATA_DIR / 'MF62_255_55R20.tir'
MF62_STUDY = DATA_DIR.parent / 'studies' / 'sedan_mf62.yaml'
SEDAN = DATA_DIR / 'Sedan_Pac02Tire.tir'
DEFLECTIONS = (-0.004, 0.001, 0.012, 0.03, 0.1)  # m; 0.1 bottoms the 6.2 sample
FORCES = ((0.0, 0.0), (4000.0, -2500.0), (-6000.0, 5000.0))  # (Fx, Fy) N
SPINS = (0.0, 30.0, 90.0)  # rad/s


def _mf61_text() -> str:
    """Return the 6.2 sample as an MF 6.1 file (FITTYP 61, without the 6.2 vertical keys)."""
    text = re.sub(r'(?m)^FITTYP\s*=.*$', 'FITTYP = 61', MF62.read_text(encoding='ascii'))
    for key in ('Q_FCY2', 'Q_CAM1', 'Q_CAM2', 'Q_CAM3', 'Q_FYS1', 'Q_FYS2', 'Q_FYS3',
                'BOTTOM_OFFST', 'BOTTOM_STIFF', 'ENV_C1', 'ENV_C2'):
        text = re.sub(rf'(?m)^{key}\s*=.*\n', '', text)
    return text


def curve(props: TireProperties, deflection: float, fx: float, fy: float, omega: float,
          pressure: float) -> float:
    """Fz of the module doc's curve at zero camber, written out from the file's keys."""
    def key(block: str, name: str, default: float = 0.0) -> float:
        return float(props.sections[block].get(name, default))

    r0 = key('DIMENSION', 'UNLOADED_RADIUS')
    fnom = key('VERTICAL', 'FNOMIN')
    v0 = key('MODEL', 'LONGVL')
    dpi = (pressure - key('OPERATING_CONDITIONS', 'NOMPRES')) / key('OPERATING_CONDITIONS',
                                                                     'NOMPRES')
    q_fz2 = key('VERTICAL', 'Q_FZ2')
    q_fz1 = math.sqrt((key('VERTICAL', 'VERTICAL_STIFFNESS') * r0 / fnom) ** 2 - 4 * q_fz2)
    r_omega = r0 * (key('VERTICAL', 'Q_RE0', 1.0)
                    + key('VERTICAL', 'Q_V1') * (omega * r0 / v0) ** 2)
    rho = deflection + r_omega - r0  # R_omega - R_l, R_l = R0 - deflection
    if rho <= 0.0:
        return 0.0
    q_fcy = key('VERTICAL', 'Q_FCY')
    if props.file_format == 'MF62':
        q_fcy *= (rho / r0) ** key('VERTICAL', 'Q_FCY2')
    fc = ((1 + key('VERTICAL', 'Q_V2') * abs(omega) * r0 / v0
           - (key('VERTICAL', 'Q_FCX') * fx / fnom) ** 2 - (q_fcy * fy / fnom) ** 2)
          * (1 + key('VERTICAL', 'PFZ1') * dpi))
    fz = fc * (q_fz1 * rho / r0 + q_fz2 * (rho / r0) ** 2) * fnom
    bottom = key('VERTICAL', 'BOTTOM_STIFF')
    if bottom > 0.0:
        start = r_omega - key('DIMENSION', 'RIM_RADIUS') - key('VERTICAL', 'BOTTOM_OFFST')
        fz += bottom * max(rho - start, 0.0)
    return fz


def _four(front: MagicFormula, rear: MagicFormula, deflection: float, gamma: float,
          fx: float, fy: float, omega: float, mirror: float = 1.0) -> np.ndarray:
    def four(x: float) -> np.ndarray:
        return np.full(4, float(x))
    return four_wheel_springs(front.coefficients, rear.coefficients, four(deflection),
                              four(gamma), four(fx), four(fy), four(omega), four(mirror))


def test_mf6_tires_follow_the_load_deflection_curve() -> None:
    for pressure in (2.1e5, 2.6e5, 3.0e5):
        mf62 = MagicFormula(parse_tir_text(MF62.read_text(encoding='ascii'), 'mf62.tir'),
                            pressure=pressure)
        mf61 = MagicFormula(parse_tir_text(_mf61_text(), 'mf61.tir'), pressure=pressure)
        for deflection, (fx, fy), omega in itertools.product(DEFLECTIONS, FORCES, SPINS):
            for mirror in (1.0, -1.0):
                got = _four(mf62, mf61, deflection, 0.0, fx, fy, omega, mirror)
                for w, tire in enumerate((mf62, mf62, mf61, mf61)):
                    want = curve(tire.props, deflection, fx, fy, omega, pressure)
                    npt.assert_allclose(got[w], want, rtol=1e-12, atol=1e-9,
                                        err_msg=f'{tire.props.file_format} at {deflection} m, '
                                        f'Fx {fx}, Fy {fy}, {omega} rad/s, p {pressure}')


def test_mf62_camber_is_the_vertical_force_of_the_tire() -> None:
    tire = MagicFormula(read_tir(MF62))
    for deflection, gamma, (fx, fy), omega in itertools.product(
            DEFLECTIONS[1:], (-0.06, 0.04), FORCES, SPINS):
        r_omega = float(tire.radii(0.0, omega)[0])  # R_l at no load = R_omega
        for mirror in (1.0, -1.0):
            got = _four(tire, tire, deflection, gamma, fx, fy, omega, mirror)
            want = tire.vertical_force(deflection + r_omega - tire.unloaded_radius,
                                       mirror * gamma, fx, mirror * fy, omega)
            # rounding only: rho is summed in another order
            npt.assert_allclose(got, float(want), rtol=1e-12, atol=1e-9)


def test_pac2002_tires_keep_their_linear_stiffness() -> None:
    props = read_tir(SEDAN)
    tire = MagicFormula(props)
    cz = props.number('VERTICAL', 'VERTICAL_STIFFNESS')
    for deflection, (fx, fy), omega in itertools.product(DEFLECTIONS, FORCES, SPINS):
        npt.assert_allclose(_four(tire, tire, deflection, 0.05, fx, fy, omega),
                            cz * deflection, rtol=1e-15)


def test_the_static_deflection_carries_the_load() -> None:
    """MagicFormula.deflection (the vehicle's initial state) inverts the spring, Fx = Fy = 0."""
    mf62 = MagicFormula(read_tir(MF62))
    sedan = MagicFormula(read_tir(SEDAN))
    for fz, omega, gamma in itertools.product((500.0, 4000.0, 6752.0, 11000.0), SPINS,
                                              (0.0, -0.03, 0.05)):
        for tire in (mf62, sedan):
            deflection = float(tire.deflection(fz, omega, gamma))
            npt.assert_allclose(_four(tire, tire, deflection, gamma, 0.0, 0.0, omega), fz,
                                rtol=1e-12)
    # PAC2002: Fz / C_z, the linear deflection
    assert float(sedan.deflection(4000.0)) == 4000.0 / sedan.vertical_stiffness


def test_the_car_on_mf62_tires_starts_on_its_static_loads() -> None:
    """
    The initial state of the sedan on the MF 6.2 sample (with its static camber) is at rest.

    Its tires carry the static wheel loads through the 6.2 curve, camber included.
    """
    for name in ('mf62', 'mf62_low_pressure'):
        config = load_study(MF62_STUDY).configurations[name]
        vehicle = VehicleModel(config)
        q, v = vehicle.initial_state(0.0)
        _, wheel, _ = vehicle.forces(q, v, 0.0, np.zeros(4), np.zeros((2, 4)), None, 0.005)
        assert np.all(np.abs(wheel.gamma) > 0.005)  # the static camber enters
        front, rear = static_wheel_loads(config)
        npt.assert_allclose(wheel.fz, [front, front, rear, rear], rtol=1e-6)
