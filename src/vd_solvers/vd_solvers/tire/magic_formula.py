# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
PAC2002 (MF-Tyre 5.2) Magic Formula: pure and combined slip, moments, radii, relaxation.

Equations: Pacejka, "Tire and Vehicle Dynamics", 3rd ed., sec. 4.3.2,
eqs. (4.E1)-(4.E30), in the PAC2002 / MF-Tyre 5.2 form used by Adams
(no inflation pressure, turn slip or MF 6.1 terms such as PKY4-PKY7, PEY5):

    Fz0' = FNOMIN LFZO,  dfz = (Fz - Fz0') / Fz0'
    F    = D sin(C arctan(B x - E (B x - arctan(B x)))) + SV,  x = slip + SH

    lateral (x = alpha_y, gamma_y = gamma LGAY)
    C  = PCY1 LCY
    mu = (PDY1 + PDY2 dfz) (1 - PDY3 gamma_y^2) LMUY,   D = mu Fz
    E  = (PEY1 + PEY2 dfz) (1 - (PEY3 + PEY4 gamma_y) sgn(alpha_y)) LEY  <= 1
    K  = PKY1 Fz0' sin(2 arctan(Fz / (PKY2 Fz0'))) (1 - PKY3 |gamma_y|) LKY,  B = K / (C D)
    SH = (PHY1 + PHY2 dfz) LHY + PHY3 gamma_y
    SV = Fz ((PVY1 + PVY2 dfz) LVY + (PVY3 + PVY4 dfz) gamma_y) LMUY

    longitudinal (x = kappa_x, gamma_x = gamma LGAX)
    C  = PCX1 LCX
    mu = (PDX1 + PDX2 dfz) (1 - PDX3 gamma_x^2) LMUX,   D = mu Fz
    E  = (PEX1 + PEX2 dfz + PEX3 dfz^2) (1 - PEX4 sgn(kappa_x)) LEX  <= 1
    K  = Fz (PKX1 + PKX2 dfz) exp(PKX3 dfz) LKX,  B = K / (C D)
    SH = (PHX1 + PHX2 dfz) LHX
    SV = Fz (PVX1 + PVX2 dfz) LVX LMUX

Combined slip, aligning, overturning and rolling-resistance moments, radii and
relaxation lengths (:meth:`MagicFormula.steady_state`, :meth:`~MagicFormula.radii`,
:meth:`~MagicFormula.relaxation_lengths`), PAC2002 form of Pacejka sec. 4.3.2 and the
MF-Tyre 5.2 equation manual (eq. numbers of Pacejka's 4.E list):

    aligning moment, pure (4.E31-4.E49; gamma_z = gamma LGAZ)
    SH_t = QHZ1 + QHZ2 dfz + (QHZ3 + QHZ4 dfz) gamma_z,   alpha_t = alpha + SH_t
    B_t  = (QBZ1 + QBZ2 dfz + QBZ3 dfz^2)(1 + QBZ4 gamma_z + QBZ5 |gamma_z|) LKY / LMUY
    C_t  = QCZ1
    D_t  = Fz (QDZ1 + QDZ2 dfz)(1 + QDZ3 gamma_z + QDZ4 gamma_z^2)(R0 / Fz0') LTR
    E_t  = (QEZ1 + QEZ2 dfz + QEZ3 dfz^2)(1 + (QEZ4 + QEZ5 gamma_z)(2/pi) atan(B_t C_t alpha_t))
           <= 1
    t    = D_t cos(C_t atan(B_t alpha_t - E_t (B_t alpha_t - atan(B_t alpha_t)))) cos(alpha)
    alpha_r = alpha + SH_y + SV_y / K_y,   B_r = QBZ9 LKY / LMUY + QBZ10 B_y C_y
    D_r  = Fz R0 ((QDZ6 + QDZ7 dfz) LRES + (QDZ8 + QDZ9 dfz) gamma_z) LMUY
    M_zr = D_r cos(atan(B_r alpha_r)) cos(alpha),   M_z0 = -t F_y0 + M_zr

    combined slip (4.E50-4.E67)
    G_xa = cos(C_xa atan(B_xa a_s - E_xa (B_xa a_s - atan B_xa a_s))) / (same at a_s = SH_xa),
           a_s = alpha + RHX1, B_xa = RBX1 cos(atan(RBX2 kappa)) LXAL, C_xa = RCX1,
           E_xa = REX1 + REX2 dfz <= 1;                         F_x = G_xa F_x0
    G_yk = the same with k_s = kappa + RHY1 + RHY2 dfz,
           B_yk = RBY1 cos(atan(RBY2 (alpha - RBY3))) LYKA,
           C_yk = RCY1, E_yk = REY1 + REY2 dfz <= 1
    SV_yk = mu_y Fz (RVY1 + RVY2 dfz + RVY3 gamma) cos(atan(RVY4 alpha))
            sin(RVY5 atan(RVY6 kappa)) LVYKA
                                                                F_y = G_yk F_y0 + SV_yk
    aligning moment, combined (4.E71-4.E78):
    alpha_t,eq = atan(sqrt(tan^2 alpha_t + (K_x/K_y)^2 kappa^2)) sgn alpha_t,
    the same for alpha_r, s = R0 (SSZ1 + SSZ2 F_y / Fz0' + (SSZ3 + SSZ4 dfz) gamma_z) LS,
    M_z = -t (F_y - SV_yk) + M_zr + s F_x

    overturning   M_x = Fz R0 (QSX1 LVMX - QSX2 gamma + QSX3 F_y / Fz0') LMX
    rolling res.  M_y = -sgn(V_x) Fz R0 (QSY1 + QSY2 F_x / Fz0' + QSY3 |V_x / LONGVL|
                                         + QSY4 (V_x / LONGVL)^4) LMY
    radii         R_l = R0 - Fz / C_z;
                  R_e = R0 - (FNOMIN / C_z)(DREFF atan(BREFF Fz / FNOMIN) + FREFF Fz / FNOMIN)
                  (R_e = R_l when BREFF, DREFF, FREFF are all absent)
    relaxation    sigma_kappa = Fz (PTX1 + PTX2 dfz) exp(-PTX3 dfz)(R0 / Fz0') LSGKP
                  sigma_alpha = PTY1 sin(2 atan(Fz / (PTY2 Fz0'))) (1 - PKY3 |gamma|) R0 LFZO LSGAL

Coefficients absent from the file are 0 and scaling factors 1, as in MF-Tyre: a file
without the combined-slip block has G_xa = G_yk = 1 (no friction-ellipse coupling), one
without PTX1/PTY1 has zero relaxation lengths (steady-state slip).
Slip angle alpha and inclination gamma are plain angles in rad (PAC2002 does
not use the tan(alpha) of MF 6.1); kappa is the longitudinal slip ratio.

Sign conventions
----------------
:meth:`MagicFormula.fy`, :meth:`~MagicFormula.fx` and
:meth:`~MagicFormula.cornering_stiffness` use the convention of the .tir file:
the TYDEX / ISO W-axis system of MF-Tyre and Adams (x forward, y left, z up,
forces on the tire from the road) with alpha = arctan(V_sy / |V_x|), i.e.
ISO 8855's slip angle, positive when the contact patch slides to the left.
Fitted files therefore have PKY1 < 0: a positive alpha gives a negative Fy and
the cornering stiffness dFy/dalpha is negative (about -77 kN/rad for the
sedan tire at 4850 N). kappa > 0 (driving) gives Fx > 0.

:meth:`MagicFormula.fy_iso` is the convention of the analytical models and of
:class:`vd_solvers.tire.simple.SimpleTire`: the same physical force along ISO
y (left), as a function of the vehicle-dynamics slip angle
alpha_vd = -alpha (e.g. alpha_front = delta - beta - a r / v), so a positive
alpha_vd gives a positive Fy: ``fy_iso(fz, a, g) == fy(fz, -a, g)``.

Mounting side
-------------
A .tir file describes the tire as measured on TYRESIDE. ``MagicFormula(props,
side="RIGHT")`` for a file measured 'LEFT' mirrors the tire (MF-Tyre practice):
Fy(alpha, gamma) = -Fy_file(-alpha, -gamma). Fx depends on gamma only through
gamma^2 in PAC2002 and is the same on both sides. Without ``side`` the tire is
evaluated as measured. For a tire without shifts and without the sgn terms
(PHY*, PVY*, PEY3, PEY4 = 0), Fy is odd in alpha at zero camber and mirroring
changes nothing.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Final, NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from vd_data_server.errors import DataError
from vd_data_server.tir import TireProperties
from vd_solvers.errors import SolverError

__all__ = ['MagicFormula', 'TireForces']

# Formats whose pure-slip equations are the PAC2002 ones above.
_SUPPORTED_FORMATS: Final[frozenset[str]] = frozenset({'PAC2002', 'MF52'})
# Coefficients used here, per block; absent ones are 0 (MF-Tyre default).
_COEFFICIENTS: Final[Mapping[str, tuple[str, ...]]] = MappingProxyType(
    {
        'LONGITUDINAL_COEFFICIENTS': (
            'PCX1', 'PDX1', 'PDX2', 'PDX3', 'PEX1', 'PEX2', 'PEX3', 'PEX4',
            'PKX1', 'PKX2', 'PKX3', 'PHX1', 'PHX2', 'PVX1', 'PVX2',
        ),
        'LATERAL_COEFFICIENTS': (
            'PCY1', 'PDY1', 'PDY2', 'PDY3', 'PEY1', 'PEY2', 'PEY3', 'PEY4',
            'PKY1', 'PKY2', 'PKY3', 'PHY1', 'PHY2', 'PHY3', 'PVY1', 'PVY2', 'PVY3', 'PVY4',
        ),
    }
)  # fmt: skip
# Combined slip, moments and transient coefficients (block, name); absent ones are 0.
_MORE_COEFFICIENTS: Final[tuple[tuple[str, tuple[str, ...]], ...]] = (
    ('LONGITUDINAL_COEFFICIENTS', ('RBX1', 'RBX2', 'RCX1', 'REX1', 'REX2', 'RHX1',
                                   'PTX1', 'PTX2', 'PTX3')),
    ('LATERAL_COEFFICIENTS', ('RBY1', 'RBY2', 'RBY3', 'RCY1', 'REY1', 'REY2', 'RHY1', 'RHY2',
                              'RVY1', 'RVY2', 'RVY3', 'RVY4', 'RVY5', 'RVY6', 'PTY1', 'PTY2')),
    ('ALIGNING_COEFFICIENTS', ('QBZ1', 'QBZ2', 'QBZ3', 'QBZ4', 'QBZ5', 'QBZ9', 'QBZ10', 'QCZ1',
                               'QDZ1', 'QDZ2', 'QDZ3', 'QDZ4', 'QDZ6', 'QDZ7', 'QDZ8', 'QDZ9',
                               'QEZ1', 'QEZ2', 'QEZ3', 'QEZ4', 'QEZ5',
                               'QHZ1', 'QHZ2', 'QHZ3', 'QHZ4', 'SSZ1', 'SSZ2', 'SSZ3', 'SSZ4')),
    ('OVERTURNING_COEFFICIENTS', ('QSX1', 'QSX2', 'QSX3')),
    ('ROLLING_COEFFICIENTS', ('QSY1', 'QSY2', 'QSY3', 'QSY4')),
    ('VERTICAL', ('BREFF', 'DREFF', 'FREFF', 'VERTICAL_DAMPING')),
)  # fmt: skip
# Scaling factors used here; absent ones are 1 (MF-Tyre default).
_SCALING_FACTORS: Final[tuple[str, ...]] = (
    'LFZO', 'LCX', 'LMUX', 'LEX', 'LKX', 'LHX', 'LVX', 'LGAX',
    'LCY', 'LMUY', 'LEY', 'LKY', 'LHY', 'LVY', 'LGAY',
    'LTR', 'LRES', 'LGAZ', 'LXAL', 'LYKA', 'LVYKA', 'LS', 'LSGKP', 'LSGAL', 'LMX', 'LVMX', 'LMY',
)  # fmt: skip
# E <= 1 (Pacejka 4.E14, 4.E24): beyond it B x - E (B x - atan B x) falls again
# at large x and the curve loses its single peak.
_MAX_CURVATURE: Final[float] = 1.0
_SIDES: Final[tuple[str, ...]] = ('LEFT', 'RIGHT')
# Loads (x the scaled nominal load) and slips at which a tire must give finite forces.
_CHECK_LOADS: Final[tuple[float, ...]] = (0.1, 0.5, 1.0, 2.0, 3.0)
_CHECK_SLIPS: Final[tuple[float, ...]] = (-0.5, -0.05, 0.0, 0.05, 0.5)


class TireForces(NamedTuple):
    """Steady-state forces (N) and moments (N*m) on the tire, TYDEX W axes (file convention)."""

    fx: np.ndarray
    fy: np.ndarray
    mx: np.ndarray  # overturning moment
    my: np.ndarray  # rolling-resistance moment
    mz: np.ndarray  # aligning moment


@dataclass(frozen=True)
class _Trail:
    """
    Pneumatic-trail factors (QBZ, QCZ, QDZ, QEZ, QHZ).

    t = D cos(C atan(B a - E (B a - atan B a))) cos(alpha).
    """

    b: np.ndarray
    c: float
    d: np.ndarray
    e_even: np.ndarray  # E_t without the sgn-like (2/pi) atan(B C a) factor
    e_odd: np.ndarray   # QEZ4 + QEZ5 gamma_z
    sh: np.ndarray

    def trail(self, alpha_t: np.ndarray, alpha: np.ndarray) -> np.ndarray:
        """T at the (equivalent) trail slip angle alpha_t, m; cos(alpha) of the true slip angle."""
        bx = self.b * alpha_t
        e = np.minimum(self.e_even * (1.0 + self.e_odd * (2.0 / np.pi) * np.arctan(bx * self.c)),
                       _MAX_CURVATURE)
        return self.d * np.cos(self.c * np.arctan(bx - e * (bx - np.arctan(bx)))) * np.cos(alpha)


@dataclass(frozen=True)
class _Curve:
    """
    Factors of one pure-slip curve F(x) = D sin(C atan(B x - E (B x - atan B x))) + SV.

    E = min(e_even (1 - e_odd sgn(x)), 1) with x = slip + SH.
    """

    b: np.ndarray
    c: float
    d: np.ndarray
    e_even: np.ndarray
    e_odd: np.ndarray
    sh: np.ndarray
    sv: np.ndarray

    def curvature(self, x: np.ndarray) -> np.ndarray:
        """E at x = slip + SH."""
        return _curvature(self.e_even, self.e_odd, x)

    def force(self, slip: np.ndarray) -> np.ndarray:
        """F at the given slip."""
        x = slip + self.sh
        bx = self.b * x
        e = self.curvature(x)
        return self.d * np.sin(self.c * np.arctan(bx - e * (bx - np.arctan(bx)))) + self.sv

    def slope_at_zero_slip(self) -> np.ndarray:
        """dF/dslip at slip = 0, i.e. at x = SH (equals B C D where SH = 0)."""
        x = self.sh
        bx = self.b * x
        e = self.curvature(x)
        phi = bx - e * (bx - np.arctan(bx))
        dphi_dx = self.b * (1.0 - e + e / (1.0 + bx**2))
        return self.d * np.cos(self.c * np.arctan(phi)) * self.c * dphi_dx / (1.0 + phi**2)


@dataclass(frozen=True)
class MagicFormula:
    """
    Steady-state pure-slip PAC2002 forces of one tire (see module doc).

    All methods broadcast their array arguments and return arrays. Loads are in
    N, angles in rad; a wheel with Fz <= 0 is off the ground and carries no force.
    """

    props: TireProperties
    side: str | None = None  # 'LEFT' / 'RIGHT' mounting side; None: as measured
    _c: Mapping[str, float] = field(init=False, repr=False, compare=False)
    _mirror: float = field(init=False, repr=False, compare=False)  # -1.0 mirrors, 1.0 not

    def __post_init__(self) -> None:
        props = self.props
        if props.file_format not in _SUPPORTED_FORMATS:
            raise SolverError(
                f'{props.path}: MagicFormula evaluates PAC2002 / MF 5.2 files, '
                f'this one is {props.file_format}'
            )
        coefficients = {
            name: props.number(block, name, 0.0)
            for block, names in _COEFFICIENTS.items() for name in names
        }
        coefficients.update({name: props.number(block, name, 0.0)
                             for block, names in _MORE_COEFFICIENTS for name in names})
        coefficients.update({name: props.number('SCALING_COEFFICIENTS', name, 1.0)
                             for name in _SCALING_FACTORS})
        coefficients['R0'] = props.unloaded_radius
        coefficients['FNOMIN'] = props.fnomin
        coefficients['CZ'] = props.number('VERTICAL', 'VERTICAL_STIFFNESS', 0.0)
        coefficients['LONGVL'] = props.number('MODEL', 'LONGVL', 0.0)
        # LFZO > 0 and the divisors != 0 are checked where the properties are read
        # (vd_data_server.tir.check_values), so `vd data check` refuses what a run would
        coefficients['FZ0_PRIME'] = props.fnomin * coefficients['LFZO']
        # Frozen dataclass: derived fields are set once, here.
        object.__setattr__(self, '_c', MappingProxyType(coefficients))
        object.__setattr__(self, '_mirror', -1.0 if self._mirrored() else 1.0)
        self._check_finite()

    def _check_finite(self) -> None:
        """
        Check that the forces and stiffness are finite over the working range.

        Coefficients that are finite one by one can still overflow together (PKX3 = 3000
        in exp(PKX3 dfz)).
        """
        fz = self.nominal_load * np.array(_CHECK_LOADS)
        slip = np.array(_CHECK_SLIPS)[:, None]
        with np.errstate(all='ignore'):
            values = (self.fy(fz, slip), self.fx(fz, slip), self.cornering_stiffness(fz))
        for name, value in zip(('Fy', 'Fx', 'cornering stiffness'), values):
            if not np.all(np.isfinite(value)):
                raise DataError(
                    f'the Magic Formula gives a non-finite {name} within {_CHECK_LOADS[0]:g}..'
                    f'{_CHECK_LOADS[-1]:g} x the nominal load: coefficients out of range',
                    file=self.props.path,
                )

    def _mirrored(self) -> bool:
        """Return True if the tire is mounted on the side opposite to TYRESIDE."""
        if self.side is None:
            return False
        wanted = self.side.upper()
        if wanted not in _SIDES:
            raise ValueError(f"side must be 'LEFT' or 'RIGHT', got {self.side!r}")
        measured = self.props.get('MODEL', 'TYRESIDE')
        if not isinstance(measured, str) or measured.upper() not in _SIDES:
            raise DataError(
                f"key 'TYRESIDE' in block [MODEL] must be 'LEFT' or 'RIGHT', found {measured!r}",
                file=self.props.path,
                key='TYRESIDE',
            )
        return wanted != measured.upper()

    @property
    def nominal_load(self) -> float:
        """Scaled nominal load Fz0' = FNOMIN LFZO, N."""
        return self._c['FZ0_PRIME']

    @property
    def lateral_shape_factor(self) -> float:
        """C_y = PCY1 LCY, -."""
        return self._c['PCY1'] * self._c['LCY']

    def fy(self, fz: ArrayLike, alpha: ArrayLike, gamma: ArrayLike = 0.0) -> np.ndarray:
        """Pure-slip lateral force Fy0, N, file (TYDEX) convention: alpha > 0 gives Fy < 0."""
        fz_, alpha_, gamma_ = _arrays(fz, alpha, gamma)
        s = self._mirror
        loaded, fz_eval = self._loaded(fz_)
        force = s * self._lateral(fz_eval, s * gamma_).force(s * alpha_)
        return np.where(loaded, force, 0.0)

    def fy_iso(self, fz: ArrayLike, alpha: ArrayLike, gamma: ArrayLike = 0.0) -> np.ndarray:
        """
        Lateral force, N, for the vehicle-dynamics slip angle alpha = -alpha_TYDEX.

        Positive alpha gives positive Fy (ISO y, left), as in SimpleTire.
        """
        return self.fy(fz, -np.asarray(alpha, dtype=float), gamma)

    def fx(self, fz: ArrayLike, kappa: ArrayLike, gamma: ArrayLike = 0.0) -> np.ndarray:
        """Pure-slip longitudinal force Fx0, N; kappa > 0 (driving) gives Fx > 0."""
        fz_, kappa_, gamma_ = _arrays(fz, kappa, gamma)
        loaded, fz_eval = self._loaded(fz_)
        return np.where(loaded, self._longitudinal(fz_eval, gamma_).force(kappa_), 0.0)

    def cornering_stiffness(self, fz: ArrayLike, gamma: ArrayLike = 0.0) -> np.ndarray:
        """
        dFy/dalpha at alpha = 0, N/rad, file convention (negative for PKY1 < 0).

        Exact derivative of :meth:`fy`, so it includes the horizontal shift SH_y;
        where SH_y = 0 it equals K_y = B C D of the Magic Formula.
        """
        fz_, gamma_ = _arrays(fz, gamma)
        loaded, fz_eval = self._loaded(fz_)
        # d/dalpha [s F(s alpha, s gamma)] = s^2 F'(s alpha, s gamma), and s^2 = 1.
        slope = self._lateral(fz_eval, self._mirror * gamma_).slope_at_zero_slip()
        return np.where(loaded, slope, 0.0)

    def peak_lateral_friction(self, fz: ArrayLike, gamma: ArrayLike = 0.0) -> np.ndarray:
        """
        Return mu_y = D_y / Fz, -, per load.

        mu_y is the peak of |Fy - SV_y| over alpha (reached for C_y > 1, E_y < 1).
        """
        return self._peak_friction(*_arrays(fz, gamma))

    def _peak_friction(self, fz_: np.ndarray, gamma_: np.ndarray) -> np.ndarray:
        c = self._c
        dfz = (fz_ - c['FZ0_PRIME']) / c['FZ0_PRIME']
        gamma_y = gamma_ * c['LGAY']
        return (c['PDY1'] + c['PDY2'] * dfz) * (1.0 - c['PDY3'] * gamma_y**2) * c['LMUY']

    def lateral_curvature(self, fz: ArrayLike, gamma: ArrayLike = 0.0,
                          slip_sign: ArrayLike = 0.0) -> np.ndarray:
        """
        Curvature factor E_y, -, for sgn(alpha_y) = ``slip_sign`` (file convention).

        ``slip_sign = 0`` gives the part even in the slip, (PEY1 + PEY2 dfz) LEY:
        the mean of the two branches, used for a symmetric (odd) fit.
        """
        fz_, gamma_, sign_ = _arrays(fz, gamma, slip_sign)
        s = self._mirror
        e_even, e_odd = self._lateral_curvature_terms(fz_, s * gamma_)
        return _curvature(e_even, e_odd, s * sign_)

    def steady_state(self, fz: ArrayLike, kappa: ArrayLike, alpha: ArrayLike,
                     gamma: ArrayLike = 0.0, vx: ArrayLike = 0.0,
                     mirror: ArrayLike | None = None) -> TireForces:
        """
        Combined-slip forces and moments (module doc), file (TYDEX) convention.

        ``fz`` N, ``kappa`` -, ``alpha``/``gamma`` rad, ``vx`` m/s (rolling resistance
        only). ``mirror`` (+1 as measured, -1 mirrored, per element) overrides the
        mounting side given at construction, so the four wheels of a car are one call.
        Off the ground (Fz <= 0) every output is 0.
        """
        fz_, kappa_, alpha_, gamma_, vx_ = _arrays(fz, kappa, alpha, gamma, vx)
        s = np.broadcast_to(np.asarray(self._mirror if mirror is None else mirror, dtype=float),
                            fz_.shape)
        loaded, fz_e = self._loaded(fz_)
        a, g = s * alpha_, s * gamma_
        c = self._c
        fz0 = c['FZ0_PRIME']
        dfz = (fz_e - fz0) / fz0
        lat = self._lateral(fz_e, g)
        lon = self._longitudinal(fz_e, g)
        fy0 = lat.force(a)
        fx0 = lon.force(kappa_)
        # combined slip weighting (4.E50-4.E67)
        b_xa = c['RBX1'] * np.cos(np.arctan(c['RBX2'] * kappa_)) * c['LXAL']
        g_xa = _weight(b_xa, c['RCX1'], np.minimum(c['REX1'] + c['REX2'] * dfz, _MAX_CURVATURE),
                       a, np.full_like(a, c['RHX1']))
        b_yk = c['RBY1'] * np.cos(np.arctan(c['RBY2'] * (a - c['RBY3']))) * c['LYKA']
        g_yk = _weight(b_yk, c['RCY1'], np.minimum(c['REY1'] + c['REY2'] * dfz, _MAX_CURVATURE),
                       kappa_, c['RHY1'] + c['RHY2'] * dfz)
        mu_y = lat.d / fz_e
        sv_yk = (mu_y * fz_e * (c['RVY1'] + c['RVY2'] * dfz + c['RVY3'] * g)
                 * np.cos(np.arctan(c['RVY4'] * a))
                 * np.sin(c['RVY5'] * np.arctan(c['RVY6'] * kappa_)) * c['LVYKA'])  # fmt: skip
        fx = g_xa * fx0
        fy = g_yk * fy0 + sv_yk
        # aligning moment with equivalent slip angles (4.E71-4.E78)
        k_y = lat.b * lat.c * lat.d
        k_x = lon.b * lon.c * lon.d
        ratio = np.divide(k_x, k_y, out=np.zeros_like(k_x), where=k_y != 0.0)
        trail = self._trail_factors(fz_e, g)
        alpha_t = a + trail.sh
        alpha_r = a + lat.sh + np.divide(lat.sv, k_y, out=np.zeros_like(k_y), where=k_y != 0.0)
        t = trail.trail(_equivalent(alpha_t, ratio * kappa_), a)
        gamma_z = g * c['LGAZ']
        b_r = c['QBZ9'] * c['LKY'] / c['LMUY'] + c['QBZ10'] * lat.b * lat.c
        d_r = (fz_e * c['R0'] * ((c['QDZ6'] + c['QDZ7'] * dfz) * c['LRES']
                                 + (c['QDZ8'] + c['QDZ9'] * dfz) * gamma_z)
               * c['LMUY'])  # fmt: skip
        m_zr = d_r * np.cos(np.arctan(b_r * _equivalent(alpha_r, ratio * kappa_))) * np.cos(a)
        arm = c['R0'] * (c['SSZ1'] + c['SSZ2'] * fy / fz0
                         + (c['SSZ3'] + c['SSZ4'] * dfz) * gamma_z) * c['LS']
        mz = -t * (fy - sv_yk) + m_zr + arm * fx
        mx = (fz_e * c['R0'] * (c['QSX1'] * c['LVMX'] - c['QSX2'] * g + c['QSX3'] * fy / fz0)
              * c['LMX'])
        v_rel = vx_ / c['LONGVL'] if c['LONGVL'] > 0.0 else np.zeros_like(vx_)
        my = -np.sign(vx_) * fz_e * c['R0'] * (c['QSY1'] + c['QSY2'] * fx / fz0
                                               + c['QSY3'] * np.abs(v_rel)
                                               + c['QSY4'] * v_rel**4) * c['LMY']  # fmt: skip
        return TireForces(*(np.where(loaded, f, 0.0) for f in (fx, s * fy, s * mx, my, s * mz)))

    def slip_stiffness(self, fz: ArrayLike) -> np.ndarray:
        """Longitudinal slip stiffness K_x = B_x C_x D_x = dFx0/dkappa at kappa = -SH_x, N."""
        fz_ = np.asarray(fz, dtype=float)
        loaded, fz_e = self._loaded(fz_)
        curve = self._longitudinal(fz_e, np.zeros_like(fz_e))
        return np.where(loaded, curve.b * curve.c * curve.d, 0.0)

    def pure_aligning_moment(self, fz: ArrayLike, alpha: ArrayLike,
                             gamma: ArrayLike = 0.0) -> np.ndarray:
        """Pure side-slip aligning moment M_z0 = -t F_y0 + M_zr, N*m (file convention)."""
        zero = np.zeros_like(np.asarray(fz, dtype=float))
        return self.steady_state(fz, zero, alpha, gamma).mz

    def radii(self, fz: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
        """
        Return (loaded radius R_l, effective rolling radius R_e), m, at load ``fz`` N.

        See the module doc.
        """
        c = self._c
        if c['CZ'] <= 0.0:
            raise DataError("key 'VERTICAL_STIFFNESS' in block [VERTICAL] must be > 0 for the "
                            "tire radii", file=self.props.path, key='VERTICAL_STIFFNESS')
        fz_ = np.maximum(np.asarray(fz, dtype=float), 0.0)
        loaded = c['R0'] - fz_ / c['CZ']
        if c['BREFF'] == 0.0 and c['DREFF'] == 0.0 and c['FREFF'] == 0.0:
            return loaded, loaded
        rho = fz_ / c['FNOMIN']
        effective = c['R0'] - c['FNOMIN'] / c['CZ'] * (c['DREFF'] * np.arctan(c['BREFF'] * rho)
                                                      + c['FREFF'] * rho)
        return loaded, effective

    def relaxation_lengths(self, fz: ArrayLike,
                           gamma: ArrayLike = 0.0) -> tuple[np.ndarray, np.ndarray]:
        """
        Return (sigma_kappa, sigma_alpha), m: first-order transient slip lengths (module doc).

        Both are 0 off the ground.
        """
        fz_, gamma_ = _arrays(fz, gamma)
        c = self._c
        fz0 = c['FZ0_PRIME']
        loaded, fz_e = self._loaded(fz_)
        dfz = (fz_e - fz0) / fz0
        sigma_k = (fz_e * (c['PTX1'] + c['PTX2'] * dfz) * np.exp(-c['PTX3'] * dfz) * c['R0'] / fz0
                   * c['LSGKP'])
        sigma_a = (c['PTY1'] * np.sin(2.0 * np.arctan(fz_e / (c['PTY2'] * fz0)))
                   if c['PTY2'] != 0.0 else np.zeros_like(fz_e))
        sigma_a = sigma_a * (1.0 - c['PKY3'] * np.abs(gamma_)) * c['R0'] * c['LFZO'] * c['LSGAL']
        return np.where(loaded, sigma_k, 0.0), np.where(loaded, sigma_a, 0.0)

    @property
    def vertical_stiffness(self) -> float:
        """C_z, N/m ([VERTICAL] VERTICAL_STIFFNESS; 0 when absent)."""
        return self._c['CZ']

    @property
    def vertical_damping(self) -> float:
        """Tire vertical damping, N*s/m ([VERTICAL] VERTICAL_DAMPING; 0 when absent)."""
        return self._c['VERTICAL_DAMPING']

    @property
    def unloaded_radius(self) -> float:
        """R0, m."""
        return self._c['R0']

    def _trail_factors(self, fz: np.ndarray, gamma: np.ndarray) -> _Trail:
        """Pneumatic-trail factors of PAC2002 (Pacejka 4.E35-4.E40), as measured (no mirroring)."""
        c = self._c
        fz0 = c['FZ0_PRIME']
        dfz = (fz - fz0) / fz0
        gamma_z = gamma * c['LGAZ']
        return _Trail(
            b=((c['QBZ1'] + c['QBZ2'] * dfz + c['QBZ3'] * dfz**2)
               * (1.0 + c['QBZ4'] * gamma_z + c['QBZ5'] * np.abs(gamma_z))
               * c['LKY'] / c['LMUY']),
            c=c['QCZ1'],
            d=(fz * (c['QDZ1'] + c['QDZ2'] * dfz)
               * (1.0 + c['QDZ3'] * gamma_z + c['QDZ4'] * gamma_z**2)
               * c['R0'] / fz0 * c['LTR']),
            e_even=c['QEZ1'] + c['QEZ2'] * dfz + c['QEZ3'] * dfz**2,
            e_odd=c['QEZ4'] + c['QEZ5'] * gamma_z,
            sh=c['QHZ1'] + c['QHZ2'] * dfz + (c['QHZ3'] + c['QHZ4'] * dfz) * gamma_z,
        )  # fmt: skip

    def _loaded(self, fz: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Mask of wheels on the ground, and loads safe to evaluate (no 0/0 off the ground)."""
        loaded = fz > 0.0
        return loaded, np.where(loaded, fz, self._c['FZ0_PRIME'])

    def _lateral(self, fz: np.ndarray, gamma: np.ndarray) -> _Curve:
        """Lateral factors as measured (PAC2002, Pacejka 4.E19-4.E30)."""
        c = self._c
        fz0 = c['FZ0_PRIME']
        dfz = (fz - fz0) / fz0
        gamma_y = gamma * c['LGAY']
        shape = c['PCY1'] * c['LCY']
        peak = self._peak_friction(fz, gamma) * fz
        stiffness = (
            c['PKY1'] * fz0 * np.sin(2.0 * np.arctan(fz / (c['PKY2'] * fz0)))
            * (1.0 - c['PKY3'] * np.abs(gamma_y)) * c['LKY']
        )  # fmt: skip
        e_even, e_odd = self._lateral_curvature_terms(fz, gamma)
        return _Curve(
            b=stiffness / (shape * peak),
            c=shape,
            d=peak,
            e_even=e_even,
            e_odd=e_odd,
            sh=(c['PHY1'] + c['PHY2'] * dfz) * c['LHY'] + c['PHY3'] * gamma_y,
            sv=(fz * ((c['PVY1'] + c['PVY2'] * dfz) * c['LVY']
                      + (c['PVY3'] + c['PVY4'] * dfz) * gamma_y) * c['LMUY']),
        )

    def _lateral_curvature_terms(self, fz: np.ndarray,
                                 gamma: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """E_y = min(e_even (1 - e_odd sgn(alpha_y)), 1): returns (e_even, e_odd)."""
        c = self._c
        dfz = (fz - c['FZ0_PRIME']) / c['FZ0_PRIME']
        return (c['PEY1'] + c['PEY2'] * dfz) * c['LEY'], c['PEY3'] + c['PEY4'] * gamma * c['LGAY']

    def _longitudinal(self, fz: np.ndarray, gamma: np.ndarray) -> _Curve:
        """Longitudinal factors (PAC2002, Pacejka 4.E9-4.E18)."""
        c = self._c
        fz0 = c['FZ0_PRIME']
        dfz = (fz - fz0) / fz0
        gamma_x = gamma * c['LGAX']
        shape = c['PCX1'] * c['LCX']
        peak = (c['PDX1'] + c['PDX2'] * dfz) * (1.0 - c['PDX3'] * gamma_x**2) * c['LMUX'] * fz
        stiffness = fz * (c['PKX1'] + c['PKX2'] * dfz) * np.exp(c['PKX3'] * dfz) * c['LKX']
        return _Curve(
            b=stiffness / (shape * peak),
            c=shape,
            d=peak,
            e_even=(c['PEX1'] + c['PEX2'] * dfz + c['PEX3'] * dfz**2) * c['LEX'],
            e_odd=np.full_like(fz, c['PEX4']),
            sh=(c['PHX1'] + c['PHX2'] * dfz) * c['LHX'],
            sv=fz * (c['PVX1'] + c['PVX2'] * dfz) * c['LVX'] * c['LMUX'],
        )

    def pneumatic_trail(self, fz: ArrayLike, gamma: ArrayLike = 0.0) -> np.ndarray:
        """
        Pneumatic trail t at zero slip angle, m (PAC2002, Pacejka 3rd ed. 4.E31-4.E49).

        ``t = Dt cos(Ct arctan(Bt at - Et (Bt at - arctan(Bt at)))) cos(alpha)`` at alpha = 0,
        so at = SHt, with (gamma_z = gamma LGAZ, R0 = UNLOADED_RADIUS)::

            SHt = QHZ1 + QHZ2 dfz + (QHZ3 + QHZ4 dfz) gamma_z
            Bt  = (QBZ1 + QBZ2 dfz + QBZ3 dfz^2) (1 + QBZ4 gamma_z + QBZ5 |gamma_z|) LKY / LMUY
            Ct  = QCZ1
            Dt  = Fz (QDZ1 + QDZ2 dfz) (1 + QDZ3 gamma_z + QDZ4 gamma_z^2) (R0 / Fz0') LTR
            Et  = (QEZ1 + QEZ2 dfz + QEZ3 dfz^2)
                  (1 + (QEZ4 + QEZ5 gamma_z) (2/pi) arctan(Bt Ct at)) <= 1

        Positive t: the lateral force acts behind the contact centre, so the
        aligning torque -t Fy turns the wheel towards its direction of travel.
        The residual torque Mzr is not part of the trail. Off the ground: 0.
        """
        fz_, gamma_ = _arrays(fz, gamma)
        loaded, fz_eval = self._loaded(fz_)
        # the same trail factors as the aligning moment (one implementation)
        factors = self._trail_factors(fz_eval, self._mirror * gamma_)
        trail = factors.trail(factors.sh, np.zeros_like(fz_eval))
        return np.where(loaded, trail, 0.0)


def _weight(b: np.ndarray, c: float, e: np.ndarray, slip: np.ndarray,
            sh: np.ndarray) -> np.ndarray:
    """
    Return the combined-slip weighting G at ``slip``.

    G = cos(C atan(B x - E (B x - atan B x))) at x = slip + SH, over the same at x = SH.
    """

    def shape(x: np.ndarray) -> np.ndarray:
        bx = b * x
        return np.cos(c * np.arctan(bx - e * (bx - np.arctan(bx))))

    return shape(slip + sh) / shape(sh)


def _equivalent(alpha: np.ndarray, kappa_term: np.ndarray) -> np.ndarray:
    """
    Return the equivalent slip angle atan(sqrt(tan^2 alpha + (K_x/K_y kappa)^2)) sgn(alpha).

    Pacejka 4.E78.
    """
    return (np.arctan(np.sqrt(np.tan(alpha) ** 2 + kappa_term**2))
            * np.where(alpha < 0.0, -1.0, 1.0))


def _curvature(e_even: np.ndarray, e_odd: np.ndarray, x: np.ndarray) -> np.ndarray:
    """E = min(e_even (1 - e_odd sgn(x)), 1)."""
    return np.minimum(e_even * (1.0 - e_odd * np.sign(x)), _MAX_CURVATURE)


def _arrays(*values: ArrayLike) -> tuple[np.ndarray, ...]:
    """
    Return float arrays broadcast to one shape.

    They are returned as they are when they already are (the full vehicle calls this
    every step with four-wheel arrays).
    """
    first = values[0]
    if isinstance(first, np.ndarray):
        ready = tuple(v for v in values if isinstance(v, np.ndarray)
                      and v.dtype == np.float64 and v.shape == first.shape)
        if len(ready) == len(values):
            return ready
    return tuple(np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in values)))
