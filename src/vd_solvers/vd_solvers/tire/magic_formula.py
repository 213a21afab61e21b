# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Magic Formula tire of a .tir file: PAC2002 / MF-Tyre 5.2, MF-Tyre 6.1 and 6.2, one implementation.

Sources, cited in the equations below as
  [P]  H. B. Pacejka, "Tire and Vehicle Dynamics", 3rd ed., Elsevier 2012, sec. 4.3.2,
       eqs. (4.E1)-(4.E78), and sec. 4.3.3 (turn slip, eqs. 4.75-4.106);
  [B]  I. J. M. Besselink, A. J. C. Schmeitz, H. B. Pacejka, "An improved Magic Formula/
       Swift tyre model that can handle inflation pressure changes", Vehicle System
       Dynamics 48 (S1), 2010, pp. 337-352 (eqs. A1-A60 of its appendix, eqs. 1-19 of the
       text for radii, vertical and structural stiffness);
  [Bd] the draft of [B], TU Eindhoven repository, purl.tue.nl/677330157969510.pdf, eq. (49);
  [M]  MFeval 4.0 (M. Furlan Tassara, BSD-3), whose documentation ("Changes in the
       equations") lists where the book differs from TNO MF-Tyre 6.1.2 and which form
       reproduces MF-Tyre; its "calculateFz62" gives the MF-Tyre 6.2 vertical model
       (MF-Tyre/MF-Swift 6.2 equation manual, revision 20130706);
  [5]  the MF-Tyre 5.2 / PAC2002 forms where they differ from 6.x (as [M] states them).
The version is the file's (`TireProperties.file_format`, from FITTYP / PROPERTY_FILE_FORMAT);
it switches the few terms that differ (marked 5.2 / 6.x below), every other equation is
shared. Coefficients absent from the file are 0 and scaling factors 1 (MF-Tyre), except
PKY4 = 2 (the PAC2002 value), Q_RE0 = 1 and QSY7 = 1.

Basic quantities ([P] 4.E1, 4.E2a, 4.E2b)
    Fz0' = FNOMIN LFZO,  dfz = (Fz - Fz0') / Fz0',  dpi = (p - p0) / p0
    p = INFLPRES (6.x [OPERATING_CONDITIONS]) or IP (PAC2002 [TIRE_CONDITIONS]), overridden by
    ``MagicFormula(props, pressure=...)``; p0 = NOMPRES or IP_NOM; dpi = 0 without them.
    alpha and gamma are used as given (MF-Tyre; [P]'s alpha* = tan alpha, gamma* = sin gamma
    is the option [M] calls "not used by TNO"). gamma_x,y,z = gamma LGAX,Y,Z (LGA* are
    PAC2002 factors; 6.x files have none, so they are 1).

Longitudinal, pure slip ([P] 4.E9-4.E18)
    Fx0 = Dx sin(Cx atan(Bx kx - Ex (Bx kx - atan(Bx kx)))) + SVx,  kx = kappa + SHx
    Cx = PCX1 LCX
    mux = (PDX1 + PDX2 dfz)(1 + PPX3 dpi + PPX4 dpi^2)(1 - PDX3 gamma_x^2) LMUX
    Dx = mux Fz zeta1
    Ex = (PEX1 + PEX2 dfz + PEX3 dfz^2)(1 - PEX4 sgn kx) LEX  <= 1
    Kxk = Fz (PKX1 + PKX2 dfz) exp(PKX3 dfz)(1 + PPX1 dpi + PPX2 dpi^2) LKX,  Bx = Kxk/(Cx Dx)
    SHx = (PHX1 + PHX2 dfz) LHX,  SVx = Fz (PVX1 + PVX2 dfz) LVX LMUX zeta1

Lateral, pure slip ([P] 4.E19-4.E30)
    Fy0 = Dy sin(Cy atan(By ay - Ey (By ay - atan(By ay)))) + SVy,  ay = alpha + SHy
    Cy = PCY1 LCY
    muy = (PDY1 + PDY2 dfz)(1 + PPY3 dpi + PPY4 dpi^2)(1 - PDY3 gamma_y^2) LMUY
    Dy = muy Fz zeta2
    Ey = (PEY1 + PEY2 dfz)(1 + PEY5 gamma_y^2 - (PEY3 + PEY4 gamma_y) sgn ay) LEY  <= 1
    Kya = PKY1 Fz0' (1 + PPY1 dpi)(1 - PKY3 |gamma_y|)
          sin(PKY4 atan(Fz / ((PKY2 + PKY5 gamma_y^2)(1 + PPY2 dpi) Fz0'))) zeta3 LKY
    By = Kya / (Cy Dy)
    SVyg = Fz (PVY3 + PVY4 dfz) gamma_y LKYC LMUY zeta2            (4.E29)
    SVy = Fz (PVY1 + PVY2 dfz) LVY LMUY zeta2 + SVyg                (4.E28)
    SHy = (PHY1 + PHY2 dfz) LHY + PHY3 gamma_y                                    [5]
    SHy = (PHY1 + PHY2 dfz) LHY + (Kyg0 gamma_y - SVyg) / Kya zeta0 + zeta4 - 1  (4.E27), 6.x
    Kyg0 = Fz (PKY6 + PKY7 dfz)(1 + PPY5 dpi) LKYC                  (4.E30), 6.x

Combined slip ([P] 4.E50-4.E67)
    Fx = Gxa Fx0,  Gxa = cos(Cxa atan(Bxa as - Exa (Bxa as - atan(Bxa as)))) / (same at SHxa)
    as = alpha + SHxa, SHxa = RHX1, Bxa = (RBX1 + RBX3 gamma^2) cos(atan(RBX2 kappa)) LXAL,
    Cxa = RCX1, Exa = REX1 + REX2 dfz <= 1
    Fy = Gyk Fy0 + SVyk, Gyk as Gxa with ks = kappa + SHyk, SHyk = RHY1 + RHY2 dfz,
    Byk = (RBY1 + RBY4 gamma^2) cos(atan(RBY2 (alpha - RBY3))) LYKA, Cyk = RCY1,
    Eyk = REY1 + REY2 dfz <= 1
    SVyk = muy Fz (RVY1 + RVY2 dfz + RVY3 gamma) cos(atan(RVY4 alpha)) zeta2
           sin(RVY5 atan(RVY6 kappa)) LVYKA
    USE_MODE (last digit) 3 evaluates uncombined (Gxa = Gyk = 1, SVyk = 0, no kappa in Mz),
    1 gives Fx and My only, 2 Fy, Mx and Mz only, 4 combined, 5 combined with turn slip.

Road friction ([P] 4.E7 with its lambda*_mu; MF-Tyre's road friction factor)
    A road of friction mu_road (``road_friction``, per wheel, 1 by default: the friction the
    tire was measured on) enters as lambda*_mu = LMU mu_road: LMUX and LMUY are multiplied by
    mu_road wherever they appear here, i.e. in mux and SVx, in muy, SVy and SVyg (and so in
    SVyk and the turn-slip moment through muy), in the LKY/LMUY of Bt and Br, and in Dr.
    The slip-speed decay of [P] 4.E7 (LMUV) is not modelled, so lambda*_mu = LMU mu_road.

Aligning moment ([P] 4.E31-4.E49 pure; 4.E71-4.E78, [B] A54-A56 combined)
    Mz = -t Fy' + Mzr + s Fx
    t = Dt cos(Ct atan(Bt at,eq - Et (Bt at,eq - atan(Bt at,eq)))) cos alpha          (4.E73)
    at = alpha + SHt,  SHt = QHZ1 + QHZ2 dfz + (QHZ3 + QHZ4 dfz) gamma_z            (4.E35)
    at,eq = atan(sqrt(tan^2 at + (Kxk/Kya)^2 kappa^2)) sgn at                       [B] A55
    Bt = (QBZ1 + QBZ2 dfz + QBZ3 dfz^2)(1 + QBZ4 gamma_z + QBZ5 |gamma_z|) LKY/LMUY  [B] A58
    Ct = QCZ1
    Dt = Fz (QDZ1 + QDZ2 dfz)(1 - PPZ1 dpi)(1 + QDZ3 gamma_z + QDZ4 gamma_z^2)
         (R0 / Fzn) LTR zeta5                                                        [B] A60
    Et = (QEZ1 + QEZ2 dfz + QEZ3 dfz^2)(1 + (QEZ4 + QEZ5 gamma_z)(2/pi) atan(Bt Ct at)) <= 1,
         at the pure-slip at, also in combined slip                               (4.E44)
    Mzr = Dr cos(Cr atan(Br ar,eq)),  ar = alpha + SHy + SVy/Kya,  ar,eq as at,eq   [B] A54
    Br = (QBZ9 LKY/LMUY + QBZ10 By Cy) zeta6,  Cr = zeta7                    (4.E45, 4.E46)
    Dr = Fz R0 [(QDZ6 + QDZ7 dfz) LRES zeta2 + ((QDZ8 + QDZ9 dfz)(1 + PPZ2 dpi)
         + (QDZ10 + QDZ11 dfz) |gamma_z|) gamma_z LKZC zeta0] LMUY cos alpha + zeta8 - 1 (4.E47)
    s = R0 (SSZ1 + SSZ2 Fy/Fzn + (SSZ3 + SSZ4 dfz) gamma_z) LS                        [B] A56
    Fy' = Fy - SVyk                                                                  [5]
    Fy' = Gyk Fy0(gamma = 0)                                                    (4.E74), 6.x
    Fzn, the load the trail and the Fx arm are normalised by, is the one switch between
    sources (``TireProperties.aligning_normalisation``): 'mf-tyre' (default) FNOMIN, the
    form [M] found to reproduce MF-Tyre 6.1.2 (t multiplied by LFZO, s by Fz0 in [B] A56);
    'book' Fz0' = FNOMIN LFZO ([P] 4.E42, 4.E76; Chrono's ChPac02Tire). They differ where
    LFZO != 1.

Overturning moment ([Bd] eq. 49; without QSX12-QSX14 it is [P] 4.E69, and with QSX1-QSX3
only the MF 5.2 form [5])
    Mx = R0 Fz LMX [QSX1 LVMX - QSX2 gamma (1 + PPMX1 dpi) - QSX12 gamma |gamma|
         + QSX3 Fy/FNOMIN + QSX4 cos(QSX5 atan((QSX6 Fz/FNOMIN)^2))
           sin(QSX7 gamma + QSX8 atan(QSX9 Fy/FNOMIN))
         + QSX10 atan(QSX11 Fz/FNOMIN) gamma] + R0 Fy LMX (QSX13 + QSX14 |gamma|)

Rolling resistance moment (V0 = LONGVL)
    My = -sgn(Vx) Fz R0 (QSY1 + QSY2 Fx/FNOMIN + QSY3 |Vx/V0| + QSY4 (Vx/V0)^4) LMY      [5]
    My = -sgn(Vx) FNOMIN R0 (QSY1 + QSY2 Fx/FNOMIN + QSY3 |Vx/V0| + QSY4 (Vx/V0)^4
         + (QSY5 + QSY6 Fz/FNOMIN) gamma^2) (Fz/FNOMIN)^QSY7 (p/p0)^QSY8 LMY       [B] A48, 6.x

Radii and vertical stiffness ([B] eqs. 1, 4, 5, 7; [P] A3.3; [M] for 6.2)
    R_omega = R0 (Q_RE0 + Q_V1 (omega R0 / V0)^2),  Cz = VERTICAL_STIFFNESS (1 + PFZ1 dpi)
    Re = R_omega - (FNOMIN/Cz)(DREFF atan(BREFF Fz/FNOMIN) + FREFF Fz/FNOMIN)
         (Re = Rl when BREFF, DREFF, FREFF are all absent)
    Fz = fc (Q_FZ1 rho/R0 + Q_FZ2 (rho/R0)^2) FNOMIN,  Q_FZ1 = sqrt((Cz0 R0/FNOMIN)^2 - 4 Q_FZ2),
    fc = (1 + Q_V2 |omega| R0/V0 - (Q_FCX Fx/FNOMIN)^2 - (Q_FCY Fy/FNOMIN)^2)(1 + PFZ1 dpi),
    Rl = R_omega - rho. Without Q_* this is Rl = R0 - Fz/Cz, the PAC2002 loaded radius.
    6.2 adds the camber deflection rho_zg (Q_CAM1-3, [M]), the term (rho/R0)^Q_FCY2 on the Fy
    influence, the camber shift Sfyg (Q_FYS1-3) of Fy, and (vd's reading of the 6.2
    parameter definitions) bottoming: BOTTOM_STIFF times the deflection beyond
    R_omega - RIM_RADIUS - BOTTOM_OFFST.
    The full vehicle's tire (:func:`four_wheel_springs`) is this curve, all of it, for MF 6.x
    files, at the wheel's deflection R0 - R_l (rho = R_omega - R_l), spin, camber and its
    previous step's Fx, Fy; for PAC2002 / MF 5.2 files it is the linear Fz = Cz (R0 - R_l).

Relaxation lengths
    sigma_kappa = Fz (PTX1 + PTX2 dfz) exp(-PTX3 dfz)(R0/Fz0') LSGKP                   [5]
    sigma_alpha = PTY1 sin(2 atan(Fz/(PTY2 Fz0')))(1 - PKY3 |gamma|) R0 LFZO LSGAL         [5]
    sigma_kappa = |Kxk| / Cx,  sigma_alpha = |Kya| / Cy                         [B] 17-19, 6.x
    Cx = LONGITUDINAL_STIFFNESS (1 + PCFX1 dfz + PCFX2 dfz^2)(1 + PCFX3 dpi), Cy likewise
    (PCFY1-3); no [STRUCTURAL] stiffness: 0 (steady-state slip).

Turn slip ([P] 4.75-4.106 with [M]'s reading of the MF-Tyre manual), USE_MODE digit 5, 6.x
    spin phi = phit + (1 - eps_g) sin(gamma) omega / Vc,  eps_g = PECP1 (1 + PECP2 dfz),
    omega / Vc = (1 + kappa) cos(alpha) / Re (free rolling at the slip ratio), phit = turn
    slip (yaw rate of the wheel about the upward road normal over Vc, 1/m, + turning left).
    The sign is fixed so that with phit = 0 turn slip reproduces the camber thrust Kyg0 gamma
    of the plain model (KyRp0 = Kyg0/(1 - eps_g), [P] 4.89); [M] writes the camber term with
    the other sign.
    zeta1 = cos(atan(PDXP1 (1 + PDXP2 dfz) cos(atan(PDXP3 kappa)) R0 phi))        (4.105)
    zeta2 = cos(atan(Byp (R0 |phi| + PDYP4 sqrt(R0 |phi|)))),
            Byp = PDYP1 (1 + PDYP2 dfz) cos(atan(PDYP3 tan alpha))              (4.77, 4.78)
    zeta3 = cos(atan(PKYP1 R0^2 phi^2))                                              (4.79)
    zeta0 = 0, zeta4 = 1 + SHyp - SVyg/Kya,  SHyp = DHyp sin(CHyp atan(BHyp R0 phi
            - EHyp (BHyp R0 phi - atan(BHyp R0 phi)))), CHyp = PHYP1,
            DHyp = PHYP2 + PHYP3 dfz, EHyp = PHYP4 <= 1,
            BHyp = Kyg0 / ((1 - eps_g) CHyp DHyp Kya0)                   (4.80-4.89)
    zeta5 = cos(atan(QDTP1 R0 phi)),  zeta6 = cos(atan(QBRP1 R0 phi))          (4.91, 4.102)
    Mzp_inf = QCRP1 |muy| R0 Fz sqrt(Fz/Fz0') LMP, CDrp = QDRP1,
    DDrp = Mzp_inf / sin(pi/2 CDrp), BDrp = KzgR0 / (CDrp DDrp (1 - eps_g)),
    KzgR0 = Fz R0 (QDZ8 + QDZ9 dfz)(1 + PPZ2 dpi) LKZC (dMzr/dgamma at gamma = 0),
    Drp = DDrp sin(CDrp atan(BDrp R0 phi)),
    Mzp90 = Mzp_inf (2/pi) atan(QCRP2 R0 |phit|) Gyk,
    zeta7 = (2/pi) acos(Mzp90 / |Drp|),  zeta8 = 1 + Drp                       (4.94-4.103)
    Without turn slip every zeta is 1.

Not modelled: the low-speed reduction below VXLOW and the saturation of inputs to the
file's ranges (FZMIN..., [M] "useLimitsCheck"); reverse running (sgn Vcx terms); the book's
friction decay with slip speed (LMUV, 4.E7, 4.E8 with A_mu = 1 as [M] found for MF-Tyre);
the contact patch and the MF-Swift (rigid ring, enveloping) parts.

Sign conventions
----------------
:meth:`MagicFormula.fy`, :meth:`~MagicFormula.fx` and
:meth:`~MagicFormula.cornering_stiffness` use the convention of the .tir file:
the TYDEX / ISO W-axis system of MF-Tyre and Adams (x forward, y left, z up,
forces on the tire from the road) with alpha = arctan(V_sy / |V_x|), i.e.
ISO 8855's slip angle, positive when the contact patch slides to the left.
Fitted files therefore have a negative cornering stiffness: a positive alpha gives a
negative Fy (about -77 kN/rad for the sedan tire at 4850 N, PKY1 < 0 with PKY4 = 2;
-142 kN/rad for the MF 6.2 sample at 6752 N, PKY1 > 0 with PKY4 < 0). kappa > 0
(driving) gives Fx > 0.

:meth:`MagicFormula.fy_iso` is the convention of the analytical models and of
:class:`vd_solvers.tire.simple.SimpleTire`: the same physical force along ISO
y (left), as a function of the vehicle-dynamics slip angle
alpha_vd = -alpha (e.g. alpha_front = delta - beta - a r / v), so a positive
alpha_vd gives a positive Fy: ``fy_iso(fz, a, g) == fy(fz, -a, g)``.

Mounting side
-------------
A .tir file describes the tire as measured on TYRESIDE. ``MagicFormula(props,
side="RIGHT")`` for a file measured 'LEFT' mirrors the tire (MF-Tyre practice):
Fy(alpha, gamma) = -Fy_file(-alpha, -gamma), and Mx, Mz and the turn slip likewise.
Without ``side`` the tire is evaluated as measured. For a tire without shifts and without
the sgn terms (PHY*, PVY*, PEY3, PEY4 = 0), Fy is odd in alpha at zero camber and mirroring
changes nothing.

Speed
-----
Every equation is written once, as a function of one wheel's floats and one float vector of
coefficients (``_p``, indexed by the module constants below): no Python objects, no
dictionary look-ups, no temporary arrays per call. :func:`wheel_forces` is the one-wheel
kernel; :func:`four_wheel_forces` calls it for the compiled vehicle step, and
:func:`combined_forces` and every :class:`MagicFormula` method loop over arrays of wheels
and call the same functions, so compiled (:mod:`vd_solvers.compiled`) a call allocates its
outputs only.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Final, NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from vd_data_server.errors import DataError
from vd_data_server.tir import TireProperties
from vd_solvers.compiled import jit
from vd_solvers.errors import SolverError

__all__ = ['ALIGNING_NORMALISATIONS', 'COEFFICIENTS', 'MagicFormula', 'TireForces',
           'combined_forces', 'four_wheel_forces', 'four_wheel_springs', 'radii_at',
           'relaxation_at', 'slip_stiffness_at', 'vertical_stiffness', 'wheel_forces']

#: Formats evaluated here (TireProperties.file_format).
_FORMATS: Final[tuple[str, ...]] = ('PAC2002', 'MF52', 'MF61', 'MF62')
#: Values of TireProperties.aligning_normalisation (module doc, "Fzn").
ALIGNING_NORMALISATIONS: Final[tuple[str, ...]] = ('mf-tyre', 'book')

_names: list[str] = []
_blocks: list[str] = []
_defaults: list[float] = []


def _block(block: str, default: float, names: str) -> range:
    """Register the coefficients ``names`` of ``block``; return their indices in ``_p``."""
    start = len(_names)
    for name in names.split():
        _names.append(name)
        _blocks.append(block)
        _defaults.append(default)
    return range(start, len(_names))


# Index constants of the coefficient vector, in the order registered. A test checks that
# each constant is the index of the coefficient of its name.
(LFZO, LCX, LMUX, LEX, LKX, LHX, LVX, LGAX, LCY, LMUY, LEY, LKY, LHY, LVY, LGAY, LTR, LRES,
 LGAZ, LXAL, LYKA, LVYKA, LS, LSGKP, LSGAL, LMX, LVMX, LMY, LKYC, LKZC, LMP) = _block(
    'SCALING_COEFFICIENTS', 1.0,
    'LFZO LCX LMUX LEX LKX LHX LVX LGAX LCY LMUY LEY LKY LHY LVY LGAY LTR LRES '
    'LGAZ LXAL LYKA LVYKA LS LSGKP LSGAL LMX LVMX LMY LKYC LKZC LMP')
(PCX1, PDX1, PDX2, PDX3, PEX1, PEX2, PEX3, PEX4, PKX1, PKX2, PKX3, PHX1, PHX2, PVX1, PVX2,
 PPX1, PPX2, PPX3, PPX4, RBX1, RBX2, RBX3, RCX1, REX1, REX2, RHX1, PTX1, PTX2, PTX3) = _block(
    'LONGITUDINAL_COEFFICIENTS', 0.0,
    'PCX1 PDX1 PDX2 PDX3 PEX1 PEX2 PEX3 PEX4 PKX1 PKX2 PKX3 PHX1 PHX2 PVX1 PVX2 '
    'PPX1 PPX2 PPX3 PPX4 RBX1 RBX2 RBX3 RCX1 REX1 REX2 RHX1 PTX1 PTX2 PTX3')
(PCY1, PDY1, PDY2, PDY3, PEY1, PEY2, PEY3, PEY4, PEY5, PKY1, PKY2, PKY3, PKY5, PKY6, PKY7,
 PHY1, PHY2, PHY3, PVY1, PVY2, PVY3, PVY4, PPY1, PPY2, PPY3, PPY4, PPY5, RBY1, RBY2, RBY3,
 RBY4, RCY1, REY1, REY2, RHY1, RHY2, RVY1, RVY2, RVY3, RVY4, RVY5, RVY6, PTY1, PTY2) = _block(
    'LATERAL_COEFFICIENTS', 0.0,
    'PCY1 PDY1 PDY2 PDY3 PEY1 PEY2 PEY3 PEY4 PEY5 PKY1 PKY2 PKY3 PKY5 PKY6 PKY7 '
    'PHY1 PHY2 PHY3 PVY1 PVY2 PVY3 PVY4 PPY1 PPY2 PPY3 PPY4 PPY5 RBY1 RBY2 RBY3 '
    'RBY4 RCY1 REY1 REY2 RHY1 RHY2 RVY1 RVY2 RVY3 RVY4 RVY5 RVY6 PTY1 PTY2')
(PKY4,) = _block('LATERAL_COEFFICIENTS', 2.0, 'PKY4')
(QBZ1, QBZ2, QBZ3, QBZ4, QBZ5, QBZ9, QBZ10, QCZ1, QDZ1, QDZ2, QDZ3, QDZ4, QDZ6, QDZ7, QDZ8,
 QDZ9, QDZ10, QDZ11, QEZ1, QEZ2, QEZ3, QEZ4, QEZ5, QHZ1, QHZ2, QHZ3, QHZ4, PPZ1, PPZ2, SSZ1,
 SSZ2, SSZ3, SSZ4) = _block(
    'ALIGNING_COEFFICIENTS', 0.0,
    'QBZ1 QBZ2 QBZ3 QBZ4 QBZ5 QBZ9 QBZ10 QCZ1 QDZ1 QDZ2 QDZ3 QDZ4 QDZ6 QDZ7 QDZ8 '
    'QDZ9 QDZ10 QDZ11 QEZ1 QEZ2 QEZ3 QEZ4 QEZ5 QHZ1 QHZ2 QHZ3 QHZ4 PPZ1 PPZ2 SSZ1 '
    'SSZ2 SSZ3 SSZ4')
(QSX1, QSX2, QSX3, QSX4, QSX5, QSX6, QSX7, QSX8, QSX9, QSX10, QSX11, QSX12, QSX13, QSX14,
 PPMX1) = _block(
    'OVERTURNING_COEFFICIENTS', 0.0,
    'QSX1 QSX2 QSX3 QSX4 QSX5 QSX6 QSX7 QSX8 QSX9 QSX10 QSX11 QSX12 QSX13 QSX14 PPMX1')
(QSY1, QSY2, QSY3, QSY4, QSY5, QSY6, QSY8) = _block(
    'ROLLING_COEFFICIENTS', 0.0, 'QSY1 QSY2 QSY3 QSY4 QSY5 QSY6 QSY8')
(QSY7,) = _block('ROLLING_COEFFICIENTS', 1.0, 'QSY7')
(PDXP1, PDXP2, PDXP3, PKYP1, PDYP1, PDYP2, PDYP3, PDYP4, PHYP1, PHYP2, PHYP3, PHYP4, PECP1,
 PECP2, QDTP1, QCRP1, QCRP2, QBRP1, QDRP1) = _block(
    'TURNSLIP_COEFFICIENTS', 0.0,
    'PDXP1 PDXP2 PDXP3 PKYP1 PDYP1 PDYP2 PDYP3 PDYP4 PHYP1 PHYP2 PHYP3 PHYP4 PECP1 '
    'PECP2 QDTP1 QCRP1 QCRP2 QBRP1 QDRP1')
(VERTICAL_STIFFNESS, VERTICAL_DAMPING, BREFF, DREFF, FREFF, Q_V1, Q_V2, Q_FZ2, Q_FCX, Q_FCY,
 PFZ1, Q_FCY2, Q_CAM1, Q_CAM2, Q_CAM3, Q_FYS1, Q_FYS2, Q_FYS3, BOTTOM_OFFST,
 BOTTOM_STIFF) = _block(
    'VERTICAL', 0.0,
    'VERTICAL_STIFFNESS VERTICAL_DAMPING BREFF DREFF FREFF Q_V1 Q_V2 Q_FZ2 Q_FCX Q_FCY PFZ1 '
    'Q_FCY2 Q_CAM1 Q_CAM2 Q_CAM3 Q_FYS1 Q_FYS2 Q_FYS3 BOTTOM_OFFST BOTTOM_STIFF')
(Q_RE0,) = _block('VERTICAL', 1.0, 'Q_RE0')
(WIDTH, ASPECT_RATIO, RIM_RADIUS) = _block('DIMENSION', 0.0, 'WIDTH ASPECT_RATIO RIM_RADIUS')
(LONGITUDINAL_STIFFNESS, LATERAL_STIFFNESS, PCFX1, PCFX2, PCFX3, PCFY1, PCFY2, PCFY3) = _block(
    'STRUCTURAL', 0.0,
    'LONGITUDINAL_STIFFNESS LATERAL_STIFFNESS PCFX1 PCFX2 PCFX3 PCFY1 PCFY2 PCFY3')
(LONGVL,) = _block('MODEL', 0.0, 'LONGVL')
# Values set from the file as a whole (not read by name): see MagicFormula.__post_init__.
(R0, FNOMIN, FZ0P, FZN, DPI, PRATIO, V6, V62, Q_FZ1, FX_ON, FY_ON, COMBINED, TURN, RE_LINEAR,
 PRESSURE) = _block(
    '', 0.0, 'R0 FNOMIN FZ0P FZN DPI PRATIO V6 V62 Q_FZ1 FX_ON FY_ON COMBINED TURN RE_LINEAR '
    'PRESSURE')

#: (name, block, default) of every coefficient read from a file, in index order.
COEFFICIENTS: Final[tuple[tuple[str, str, float], ...]] = tuple(
    (n, b, d) for n, b, d in zip(_names, _blocks, _defaults) if b)
_N: Final[int] = len(_names)
_NAMES: Final[tuple[str, ...]] = tuple(_names)

# PAC2002 names of the pressure coefficients 6.x calls PPZ1, PPZ2, PPMX1 (Adams PAC2002
# files, e.g. Chrono's), and where each version keeps its pressures.
_PRESSURE_ALIASES: Final[tuple[tuple[int, str, str], ...]] = (
    (PPZ1, 'ALIGNING_COEFFICIENTS', 'QPZ1'),
    (PPZ2, 'ALIGNING_COEFFICIENTS', 'QPZ2'),
    (PPMX1, 'OVERTURNING_COEFFICIENTS', 'QPX1'),
)
_PRESSURE_KEYS: Final[tuple[tuple[str, str, str], ...]] = (
    ('OPERATING_CONDITIONS', 'INFLPRES', 'NOMPRES'),
    ('TIRE_CONDITIONS', 'IP', 'IP_NOM'),
)
# USE_MODE: last digit -> (Fx on, Fy on, combined, turn slip) ([B], MF-Tyre / Adams IUSED).
_USE_MODES: Final[dict[int, tuple[float, float, float, float]]] = {
    1: (1.0, 0.0, 0.0, 0.0),
    2: (0.0, 1.0, 0.0, 0.0),
    3: (1.0, 1.0, 0.0, 0.0),
    4: (1.0, 1.0, 1.0, 0.0),
    5: (1.0, 1.0, 1.0, 1.0),
}
_DEFAULT_USE_MODE: Final[int] = 4
# E <= 1 ([P] 4.E14, 4.E24): beyond it B x - E (B x - atan B x) falls again
# at large x and the curve loses its single peak.
_MAX_CURVATURE: Final[float] = 1.0
_SIDES: Final[tuple[str, ...]] = ('LEFT', 'RIGHT')
# Loads (x the scaled nominal load) and slips at which a tire must give finite forces.
_CHECK_LOADS: Final[tuple[float, ...]] = (0.1, 0.5, 1.0, 2.0, 3.0)
_CHECK_SLIPS: Final[tuple[float, ...]] = (-0.5, -0.05, 0.0, 0.05, 0.5)
# Bisection steps of the 6.2 loaded radius with camber (deflection to 2^-60 of R_omega).
_RADIUS_ITERATIONS: Final[int] = 60
# |D_r,phi| below which zeta7's ratio is taken as 0 (no turn slip moment to shape), N*m.
_TINY_MOMENT: Final[float] = 1e-12


class TireForces(NamedTuple):
    """Steady-state forces (N) and moments (N*m) on the tire, TYDEX W axes (file convention)."""

    fx: np.ndarray
    fy: np.ndarray
    mx: np.ndarray  # overturning moment
    my: np.ndarray  # rolling-resistance moment
    mz: np.ndarray  # aligning moment


@dataclass(frozen=True)
class MagicFormula:
    """
    Steady-state Magic Formula forces and moments of one tire (see module doc).

    All methods broadcast their array arguments and return arrays. Loads are in
    N, angles in rad; a wheel with Fz <= 0 is off the ground and carries no force.
    ``pressure`` (Pa) replaces the file's inflation pressure (INFLPRES / IP).
    """

    props: TireProperties
    side: str | None = None  # 'LEFT' / 'RIGHT' mounting side; None: as measured
    pressure: float | None = None
    _p: np.ndarray = field(init=False, repr=False, compare=False)
    _mirror: float = field(init=False, repr=False, compare=False)  # -1.0 mirrors, 1.0 not

    def __post_init__(self) -> None:
        props = self.props
        _check_evaluated(props)
        # Frozen dataclass: derived fields are set once, here.
        object.__setattr__(self, '_p', _coefficients(props, self.pressure))
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

    # --- properties --------------------------------------------------------------------

    @property
    def coefficients(self) -> np.ndarray:
        """The coefficient vector the evaluation reads (a copy; indices: module constants)."""
        return self._p.copy()

    @property
    def nominal_load(self) -> float:
        """Scaled nominal load Fz0' = FNOMIN LFZO, N."""
        return float(self._p[FZ0P])

    @property
    def inflation_pressure(self) -> float:
        """Inflation pressure the tire is evaluated at, Pa (0 if the file has none)."""
        return float(self._p[PRESSURE])

    @property
    def lateral_shape_factor(self) -> float:
        """C_y = PCY1 LCY, -."""
        return float(self._p[PCY1] * self._p[LCY])

    @property
    def vertical_stiffness(self) -> float:
        """C_z = VERTICAL_STIFFNESS (1 + PFZ1 dpi), N/m: the tangent at FNOMIN (0 if absent)."""
        return _vertical_stiffness(self._p)

    @property
    def vertical_damping(self) -> float:
        """Tire vertical damping, N*s/m ([VERTICAL] VERTICAL_DAMPING; 0 when absent)."""
        return float(self._p[VERTICAL_DAMPING])

    @property
    def unloaded_radius(self) -> float:
        """R0, m."""
        return float(self._p[R0])

    # --- pure slip ---------------------------------------------------------------------

    def fy(self, fz: ArrayLike, alpha: ArrayLike, gamma: ArrayLike = 0.0) -> np.ndarray:
        """Pure-slip lateral force Fy0, N, file (TYDEX) convention: alpha > 0 gives Fy < 0."""
        shape, (fz_, alpha_, gamma_) = _flat(fz, alpha, gamma)
        return _pure_lateral_at(self._p, fz_, alpha_, gamma_, self._mirror).reshape(shape)

    def fy_iso(self, fz: ArrayLike, alpha: ArrayLike, gamma: ArrayLike = 0.0) -> np.ndarray:
        """
        Lateral force, N, for the vehicle-dynamics slip angle alpha = -alpha_TYDEX.

        Positive alpha gives positive Fy (ISO y, left), as in SimpleTire.
        """
        return self.fy(fz, -np.asarray(alpha, dtype=float), gamma)

    def fx(self, fz: ArrayLike, kappa: ArrayLike, gamma: ArrayLike = 0.0) -> np.ndarray:
        """Pure-slip longitudinal force Fx0, N; kappa > 0 (driving) gives Fx > 0."""
        shape, (fz_, kappa_, gamma_) = _flat(fz, kappa, gamma)
        return _pure_longitudinal_at(self._p, fz_, kappa_, gamma_).reshape(shape)

    def cornering_stiffness(self, fz: ArrayLike, gamma: ArrayLike = 0.0) -> np.ndarray:
        """
        dFy/dalpha at alpha = 0, N/rad, file convention (negative for PKY1 < 0).

        Exact derivative of :meth:`fy`, so it includes the horizontal shift SH_y;
        where SH_y = 0 it equals K_y = B C D of the Magic Formula.
        """
        shape, (fz_, gamma_) = _flat(fz, gamma)
        # d/dalpha [s F(s alpha, s gamma)] = s^2 F'(s alpha, s gamma), and s^2 = 1.
        return _cornering_stiffness_at(self._p, fz_, self._mirror * gamma_).reshape(shape)

    def slip_stiffness(self, fz: ArrayLike) -> np.ndarray:
        """Longitudinal slip stiffness K_xk = B_x C_x D_x = dFx0/dkappa at kappa = -SH_x, N."""
        shape, (fz_,) = _flat(fz)
        return slip_stiffness_at(self._p, fz_).reshape(shape)

    def peak_lateral_friction(self, fz: ArrayLike, gamma: ArrayLike = 0.0) -> np.ndarray:
        """
        Return mu_y = D_y / Fz, -, per load.

        mu_y is the peak of |Fy - SV_y| over alpha (reached for C_y > 1, E_y < 1).
        """
        shape, (fz_, gamma_) = _flat(fz, gamma)
        return _peak_lateral_friction_at(self._p, fz_, gamma_).reshape(shape)

    def lateral_curvature(self, fz: ArrayLike, gamma: ArrayLike = 0.0,
                          slip_sign: ArrayLike = 0.0) -> np.ndarray:
        """
        Curvature factor E_y, -, for sgn(alpha_y) = ``slip_sign`` (file convention).

        ``slip_sign = 0`` gives the part even in the slip,
        (PEY1 + PEY2 dfz)(1 + PEY5 gamma_y^2) LEY: the mean of the two branches, used for a
        symmetric (odd) fit.
        """
        shape, (fz_, gamma_, sign_) = _flat(fz, gamma, slip_sign)
        return _lateral_curvature_at(self._p, fz_, gamma_, sign_, self._mirror).reshape(shape)

    # --- combined slip -----------------------------------------------------------------

    def steady_state(self, fz: ArrayLike, kappa: ArrayLike, alpha: ArrayLike,
                     gamma: ArrayLike = 0.0, vx: ArrayLike = 0.0,
                     mirror: ArrayLike | None = None, phit: ArrayLike = 0.0,
                     road_friction: ArrayLike = 1.0) -> TireForces:
        """
        Combined-slip forces and moments (module doc), file (TYDEX) convention.

        ``fz`` N, ``kappa`` -, ``alpha``/``gamma`` rad, ``vx`` m/s (rolling resistance
        only), ``phit`` 1/m (turn slip, used where USE_MODE asks for it). ``mirror`` (+1 as
        measured, -1 mirrored, per element) overrides the mounting side given at
        construction, so the four wheels of a car are one call. ``road_friction`` is the
        road friction, a factor on LMUX and LMUY (module doc, "Road friction"), per element.
        Off the ground (Fz <= 0) every output is 0.
        """
        shape, (fz_, kappa_, alpha_, gamma_, vx_, s, phit_, road_) = _flat(
            fz, kappa, alpha, gamma, vx, self._mirror if mirror is None else mirror, phit,
            road_friction)
        forces = combined_forces(self._p, fz_, kappa_, alpha_, gamma_, vx_, s, phit_, road_)
        return TireForces(*(f.reshape(shape) for f in forces))

    def pure_aligning_moment(self, fz: ArrayLike, alpha: ArrayLike,
                             gamma: ArrayLike = 0.0) -> np.ndarray:
        """Pure side-slip aligning moment M_z0 = -t F_y0' + M_zr, N*m (file convention)."""
        zero = np.zeros_like(np.asarray(fz, dtype=float))
        return self.steady_state(fz, zero, alpha, gamma).mz

    def pneumatic_trail(self, fz: ArrayLike, gamma: ArrayLike = 0.0) -> np.ndarray:
        """
        Pneumatic trail t at zero slip angle, m ([P] 4.E31-4.E49, module doc).

        ``t = Dt cos(Ct arctan(Bt at - Et (Bt at - arctan(Bt at))))`` at alpha = 0, so
        at = SHt. Positive t: the lateral force acts behind the contact centre, so the
        aligning torque -t Fy turns the wheel towards its direction of travel. The residual
        torque Mzr is not part of the trail. Off the ground: 0.
        """
        shape, (fz_, gamma_) = _flat(fz, gamma)
        gamma_z = self._mirror * gamma_ * self._p[LGAZ]
        return _pneumatic_trail_at(self._p, fz_, gamma_z).reshape(shape)

    # --- radii, vertical force, relaxation ---------------------------------------------

    def radii(self, fz: ArrayLike, omega: ArrayLike = 0.0) -> tuple[np.ndarray, np.ndarray]:
        """
        Return (loaded radius R_l, effective rolling radius R_e), m, at load ``fz`` N.

        ``omega`` (rad/s) is the spin rate for the 6.x speed terms (Q_V1, Q_V2). See the
        module doc.
        """
        self._need_vertical_stiffness()
        shape, (fz_, omega_) = _flat(fz, omega)
        loaded, effective = radii_at(self._p, fz_, omega_)
        return loaded.reshape(shape), effective.reshape(shape)

    def loaded_radius(self, fz: ArrayLike, gamma: ArrayLike = 0.0, fx: ArrayLike = 0.0,
                      fy: ArrayLike = 0.0, omega: ArrayLike = 0.0) -> np.ndarray:
        """
        Return the loaded radius R_l, m, with the force, speed and (6.2) camber terms.

        The inverse of :meth:`vertical_force`; file convention for ``gamma`` and ``fy``.
        """
        self._need_vertical_stiffness()
        shape, (fz_, gamma_, fx_, fy_, omega_) = _flat(fz, gamma, fx, fy, omega)
        s = self._mirror
        return _loaded_radius_at(self._p, np.maximum(fz_, 0.0), s * gamma_, fx_, s * fy_,
                                 omega_).reshape(shape)

    def vertical_force(self, deflection: ArrayLike, gamma: ArrayLike = 0.0,
                       fx: ArrayLike = 0.0, fy: ArrayLike = 0.0,
                       omega: ArrayLike = 0.0) -> np.ndarray:
        """
        Vertical tire force Fz, N, at ``deflection`` = R_omega - R_l (m, >= 0).

        Module doc: the MF 6.1 / 6.2 load-deflection curve (linear C_z for PAC2002) with its
        force, speed, pressure and (6.2) camber and bottoming terms.
        """
        self._need_vertical_stiffness()
        shape, (rho, gamma_, fx_, fy_, omega_) = _flat(deflection, gamma, fx, fy, omega)
        s = self._mirror
        return _vertical_force_at(self._p, np.maximum(rho, 0.0), s * gamma_, fx_, s * fy_,
                                  omega_).reshape(shape)

    def deflection(self, fz: ArrayLike, omega: ArrayLike = 0.0,
                   gamma: ArrayLike = 0.0) -> np.ndarray:
        """
        Return R0 - R_l, m: the deflection of the full vehicle's tire at load ``fz`` N.

        The deflection at which :func:`four_wheel_springs` gives ``fz`` at spin ``omega``
        (rad/s), camber ``gamma`` (rad, file convention; it enters MF 6.2 only) and
        Fx = Fy = 0: MF 6.x the load-deflection curve (R0 minus :meth:`loaded_radius`),
        PAC2002 / MF 5.2 Fz / C_z.
        """
        self._need_vertical_stiffness()
        shape, (fz_, omega_, gamma_) = _flat(fz, omega, gamma)
        return _deflection_at(self._p, np.maximum(fz_, 0.0), omega_,
                              self._mirror * gamma_).reshape(shape)

    def relaxation_lengths(self, fz: ArrayLike,
                           gamma: ArrayLike = 0.0) -> tuple[np.ndarray, np.ndarray]:
        """
        Return (sigma_kappa, sigma_alpha), m: first-order transient slip lengths (module doc).

        Both are 0 off the ground.
        """
        shape, (fz_, gamma_) = _flat(fz, gamma)
        sigma_k, sigma_a = relaxation_at(self._p, fz_, self._mirror * gamma_)
        return sigma_k.reshape(shape), sigma_a.reshape(shape)

    def _need_vertical_stiffness(self) -> None:
        if self._p[VERTICAL_STIFFNESS] <= 0.0:
            raise DataError("key 'VERTICAL_STIFFNESS' in block [VERTICAL] must be > 0 for the "
                            "tire radii", file=self.props.path, key='VERTICAL_STIFFNESS')


# --- the coefficient vector ----------------------------------------------------------


def vertical_stiffness(props: TireProperties, pressure: float | None = None) -> float:
    """
    C_z of :attr:`MagicFormula.vertical_stiffness`, N/m, without building the model.

    For the K&C models, which take the tire's vertical stiffness and nothing else: the
    file must be one evaluated here, but the forces are not computed, so neither is their
    check over the working range (``vd data check`` builds the model and makes it).
    """
    _check_evaluated(props)
    return _vertical_stiffness(_coefficients(props, pressure))


def _vertical_stiffness(p: np.ndarray) -> float:
    """C_z = VERTICAL_STIFFNESS (1 + PFZ1 dpi), N/m, of the coefficient vector ``p``."""
    return float(p[VERTICAL_STIFFNESS] * (1.0 + p[PFZ1] * p[DPI]))


def _check_evaluated(props: TireProperties) -> None:
    """Raise SolverError / DataError unless ``props`` is a file evaluated here."""
    if props.file_format not in _FORMATS:
        raise SolverError(
            f'{props.path}: MagicFormula evaluates PAC2002, MF 5.2, 6.1 and 6.2 files, '
            f'this one is {props.file_format}'
        )
    if props.aligning_normalisation not in ALIGNING_NORMALISATIONS:
        raise DataError(
            f"aligning_normalisation must be one of {', '.join(ALIGNING_NORMALISATIONS)}, "
            f'found {props.aligning_normalisation!r}', file=props.path)


def _coefficients(props: TireProperties, pressure: float | None) -> np.ndarray:
    """Read every coefficient of ``props`` into one vector (indices: module constants)."""
    p = np.zeros(_N)
    for index, (name, block, default) in enumerate(COEFFICIENTS):
        p[index] = props.number(block, name, default)
    for index, block, name in _PRESSURE_ALIASES:
        given = props.sections.get(block, {})
        if name in given and _NAMES[index] not in given:
            p[index] = props.number(block, name)
    p[R0] = props.unloaded_radius
    p[FNOMIN] = props.fnomin
    # LFZO > 0 and the divisors != 0 are checked where the properties are read
    # (vd_data_server.tir.check_values), so `vd data check` refuses what a run would
    p[FZ0P] = props.fnomin * p[LFZO]
    p[FZN] = props.fnomin if props.aligning_normalisation == 'mf-tyre' else p[FZ0P]
    version6 = props.file_format in ('MF61', 'MF62')
    p[V6] = 1.0 if version6 else 0.0
    p[V62] = 1.0 if props.file_format == 'MF62' else 0.0
    inflation, nominal = 0.0, 0.0
    for block, key, nominal_key in _PRESSURE_KEYS:
        if nominal_key in props.sections.get(block, {}):
            nominal = props.number(block, nominal_key)
            inflation = props.number(block, key, nominal)
            break
    if pressure is not None:
        if nominal <= 0.0:
            raise DataError('the file gives no nominal inflation pressure (NOMPRES or IP_NOM): '
                            'a pressure cannot be set', file=props.path)
        inflation = float(pressure)
    p[PRESSURE] = inflation
    p[DPI] = (inflation - nominal) / nominal if nominal > 0.0 else 0.0
    p[PRATIO] = inflation / nominal if nominal > 0.0 else 1.0
    q_fz1 = props.number('VERTICAL', 'Q_FZ1', 0.0)
    if q_fz1 == 0.0 and p[VERTICAL_STIFFNESS] > 0.0:
        linear = p[VERTICAL_STIFFNESS] * p[R0] / p[FNOMIN]
        q_fz1 = float(np.sqrt(max(linear * linear - 4.0 * p[Q_FZ2], 0.0)))
    p[Q_FZ1] = q_fz1
    use_mode = int(props.number('MODEL', 'USE_MODE', _DEFAULT_USE_MODE)) % 10
    if use_mode not in _USE_MODES:
        raise DataError(f'USE_MODE ending in {use_mode} is not evaluated here '
                        f"(the last digit must be one of {', '.join(map(str, _USE_MODES))})",
                        file=props.path, key='USE_MODE')
    p[FX_ON], p[FY_ON], p[COMBINED], p[TURN] = _USE_MODES[use_mode]
    if p[TURN] != 0.0 and not version6:
        raise DataError('USE_MODE 5 (turn slip) needs an MF 6.1 / 6.2 file, this one is '
                        f'{props.file_format}', file=props.path, key='USE_MODE')
    p[RE_LINEAR] = 1.0 if p[BREFF] == 0.0 and p[DREFF] == 0.0 and p[FREFF] == 0.0 else 0.0
    return p


# --- the equations (module doc) ------------------------------------------------------
# Each equation is written once, on floats: p is the coefficient vector, every other input
# one wheel's value. The array functions further down loop over the wheels and call these;
# compiled, a loop costs no temporary arrays. ``lmux`` and ``lmuy`` are LMUX and LMUY times
# the road friction of the wheel ([P] 4.E7, lambda*_mu; module doc, "Road friction").


@jit
def _at_most_one(x: float) -> float:
    """min(x, 1) for the curvature factors E <= 1 ([P] 4.E14, 4.E24); nan stays nan."""
    return _MAX_CURVATURE if x > _MAX_CURVATURE else x


@jit
def _signum(x: float) -> float:
    """Return sgn x with sgn 0 = 0 (the sgn of [P] 4.E14, 4.E24 and of the rolling moment)."""
    if x > 0.0:
        return 1.0
    if x < 0.0:
        return -1.0
    return 0.0 * x  # 0, and nan for nan


@jit
def _sign(x: float) -> float:
    """Return sgn x with sgn 0 = +1 (equivalent slip angles, [B] A54-A55)."""
    return -1.0 if x < 0.0 else 1.0


@jit
def _dfz(p: np.ndarray, fz: float) -> float:
    """Return dfz = (Fz - Fz0') / Fz0' ([P] 4.E2a)."""
    return (fz - p[FZ0P]) / p[FZ0P]


@jit
def _magic(b: float, c: float, e: float, x: float) -> float:
    """C atan(B x - E (B x - atan(B x))): the argument of the Magic Formula's sine / cosine."""
    bx = b * x
    return c * np.arctan(bx - e * (bx - np.arctan(bx)))


@jit
def _kxk(p: np.ndarray, fz: float, dfz: float) -> float:
    """Longitudinal slip stiffness Kxk ([P] 4.E15)."""
    dpi = p[DPI]
    return (fz * (p[PKX1] + p[PKX2] * dfz) * np.exp(p[PKX3] * dfz)
            * (1.0 + p[PPX1] * dpi + p[PPX2] * dpi * dpi) * p[LKX])


@jit
def _longitudinal(p: np.ndarray, fz: float, dfz: float, gamma_x: float, kappa: float,
                  zeta1: float, lmux: float) -> tuple[float, float]:
    """Pure-slip Fx0 and Kxk ([P] 4.E9-4.E18)."""
    dpi = p[DPI]
    cx = p[PCX1] * p[LCX]
    mux = ((p[PDX1] + p[PDX2] * dfz) * (1.0 + p[PPX3] * dpi + p[PPX4] * dpi * dpi)
           * (1.0 - p[PDX3] * gamma_x * gamma_x) * lmux)
    dx = mux * fz * zeta1
    kxk = _kxk(p, fz, dfz)
    bx = kxk / (cx * dx)
    kappa_x = kappa + (p[PHX1] + p[PHX2] * dfz) * p[LHX]
    ex = _at_most_one((p[PEX1] + p[PEX2] * dfz + p[PEX3] * dfz * dfz)
                      * (1.0 - p[PEX4] * _signum(kappa_x)) * p[LEX])
    svx = fz * (p[PVX1] + p[PVX2] * dfz) * p[LVX] * lmux * zeta1
    return dx * np.sin(_magic(bx, cx, ex, kappa_x)) + svx, kxk


@jit
def _mu_y(p: np.ndarray, dfz: float, gamma_y: float, lmuy: float) -> float:
    """Lateral peak friction muy ([P] 4.E23)."""
    dpi = p[DPI]
    return ((p[PDY1] + p[PDY2] * dfz) * (1.0 + p[PPY3] * dpi + p[PPY4] * dpi * dpi)
            * (1.0 - p[PDY3] * gamma_y * gamma_y) * lmuy)


@jit
def _kya(p: np.ndarray, fz: float, gamma_y: float, zeta3: float) -> float:
    """Cornering stiffness Kya ([P] 4.E25)."""
    dpi = p[DPI]
    g2 = gamma_y * gamma_y
    return (p[PKY1] * p[FZ0P] * (1.0 + p[PPY1] * dpi) * (1.0 - p[PKY3] * abs(gamma_y))
            * np.sin(p[PKY4] * np.arctan(
                fz / ((p[PKY2] + p[PKY5] * g2) * (1.0 + p[PPY2] * dpi) * p[FZ0P])))
            * zeta3 * p[LKY])


@jit
def _kyg0(p: np.ndarray, fz: float, dfz: float) -> float:
    """Camber stiffness Kyg0 of MF 6.x ([P] 4.E30)."""
    return fz * (p[PKY6] + p[PKY7] * dfz) * (1.0 + p[PPY5] * p[DPI]) * p[LKYC]


@jit
def _ey(p: np.ndarray, dfz: float, gamma_y: float, sign: float) -> float:
    """Lateral curvature Ey for sgn(alpha_y) = ``sign`` ([P] 4.E24), at most 1."""
    return _at_most_one((p[PEY1] + p[PEY2] * dfz)
                        * (1.0 + p[PEY5] * gamma_y * gamma_y
                           - (p[PEY3] + p[PEY4] * gamma_y) * sign) * p[LEY])


@jit
def _lateral_shifts(p: np.ndarray, fz: float, dfz: float, gamma_y: float, kya: float,
                    zeta2: float, shyp: float, lmuy: float) -> tuple[float, float, float]:
    """
    Return (SHy, SVy, SVyg) ([P] 4.E27-4.E29; [5] for PAC2002 / MF 5.2).

    ``shyp`` is the turn-slip shift SHyp of 6.x, applied with zeta0 = 0 when turn slip is
    on (module doc).
    """
    svyg = fz * (p[PVY3] + p[PVY4] * dfz) * gamma_y * p[LKYC] * lmuy * zeta2
    svy = fz * (p[PVY1] + p[PVY2] * dfz) * p[LVY] * lmuy * zeta2 + svyg
    shy = (p[PHY1] + p[PHY2] * dfz) * p[LHY] + p[PHY3] * gamma_y
    if p[V6] != 0.0:
        if p[TURN] != 0.0:  # zeta0 = 0, zeta4 = 1 + SHyp - SVyg / Kya
            shy = shy + shyp - svyg / kya
        else:
            shy = shy + (_kyg0(p, fz, dfz) * gamma_y - svyg) / kya
    return shy, svy, svyg


@jit
def _lateral(p: np.ndarray, fz: float, dfz: float, gamma_y: float, alpha: float,
             zeta2: float, zeta3: float, shyp: float, lmuy: float
             ) -> tuple[float, float, float, float, float, float]:
    """Pure-slip Fy0 and its factors (muy, Kya, By, SHy, SVy) ([P] 4.E19-4.E30)."""
    cy = p[PCY1] * p[LCY]
    mu = _mu_y(p, dfz, gamma_y, lmuy)
    dy = mu * fz * zeta2
    kya = _kya(p, fz, gamma_y, zeta3)
    by = kya / (cy * dy)
    shy, svy, _ = _lateral_shifts(p, fz, dfz, gamma_y, kya, zeta2, shyp, lmuy)
    alpha_y = alpha + shy
    ey = _ey(p, dfz, gamma_y, _signum(alpha_y))
    return dy * np.sin(_magic(by, cy, ey, alpha_y)) + svy, mu, kya, by, shy, svy


@jit
def _pure_lateral(p: np.ndarray, fz: float, alpha: float, gamma: float) -> float:
    """Fy0 in the file frame: the steady state at kappa = 0, without turn slip input."""
    dfz = _dfz(p, fz)
    _, zeta2, zeta3, _, _, shyp, _, _ = _turn_slip(p, fz, dfz, 0.0, alpha, gamma, 0.0)
    return _lateral(p, fz, dfz, gamma * p[LGAY], alpha, zeta2, zeta3, shyp, p[LMUY])[0]


@jit
def _lateral_slope_at_zero(p: np.ndarray, fz: float, gamma: float) -> float:
    """
    dFy0/dalpha at alpha = 0 (x = SHy): D cos(C atan phi) C dphi/dx / (1 + phi^2).

    The turn-slip factors depend on alpha through cos(alpha) and tan^2(alpha) only, so their
    slope at alpha = 0 is 0 and they enter at their alpha = 0 values.
    """
    dfz = _dfz(p, fz)
    _, zeta2, zeta3, _, _, shyp, _, _ = _turn_slip(p, fz, dfz, 0.0, 0.0, gamma, 0.0)
    gamma_y = gamma * p[LGAY]
    cy = p[PCY1] * p[LCY]
    dy = _mu_y(p, dfz, gamma_y, p[LMUY]) * fz * zeta2
    kya = _kya(p, fz, gamma_y, zeta3)
    by = kya / (cy * dy)
    x, _, _ = _lateral_shifts(p, fz, dfz, gamma_y, kya, zeta2, shyp, p[LMUY])
    e = _ey(p, dfz, gamma_y, _signum(x))
    bx = by * x
    phi = bx - e * (bx - np.arctan(bx))
    dphi_dx = by * (1.0 - e + e / (1.0 + bx * bx))
    return dy * np.cos(cy * np.arctan(phi)) * cy * dphi_dx / (1.0 + phi * phi)


@jit
def _turn_slip(p: np.ndarray, fz: float, dfz: float, kappa: float, alpha: float,
               gamma: float, phit: float
               ) -> tuple[float, float, float, float, float, float, float, float]:
    """
    Return (zeta1, zeta2, zeta3, zeta5, zeta6, SHyp, phi, eps_g) (module doc, turn slip).

    All ones (and SHyp, phi, eps_g zero) where USE_MODE asks for no turn slip.
    """
    if p[TURN] == 0.0:
        return 1.0, 1.0, 1.0, 1.0, 1.0, 0.0, 0.0, 0.0
    eps_g = p[PECP1] * (1.0 + p[PECP2] * dfz)
    spin_rate = (1.0 + kappa) * np.cos(alpha) / _effective_radius(p, fz, 0.0)
    phi = phit + (1.0 - eps_g) * np.sin(gamma) * spin_rate
    r0_phi = p[R0] * phi
    zeta1 = np.cos(np.arctan(p[PDXP1] * (1.0 + p[PDXP2] * dfz)
                               * np.cos(np.arctan(p[PDXP3] * kappa)) * r0_phi))
    b_yp = (p[PDYP1] * (1.0 + p[PDYP2] * dfz)
            * np.cos(np.arctan(p[PDYP3] * np.tan(alpha))))
    zeta2 = np.cos(np.arctan(b_yp * (abs(r0_phi) + p[PDYP4] * np.sqrt(abs(r0_phi)))))
    zeta3 = np.cos(np.arctan(p[PKYP1] * r0_phi * r0_phi))
    kya0 = _kya(p, fz, 0.0, zeta3)
    c_hyp = p[PHYP1]
    d_hyp = p[PHYP2] + p[PHYP3] * dfz
    e_hyp = _at_most_one(p[PHYP4])
    b_hyp = _kyg0(p, fz, dfz) / ((1.0 - eps_g) * c_hyp * d_hyp * kya0)
    shyp = d_hyp * np.sin(_magic(b_hyp, c_hyp, e_hyp, r0_phi))
    zeta5 = np.cos(np.arctan(p[QDTP1] * r0_phi))
    zeta6 = np.cos(np.arctan(p[QBRP1] * r0_phi))
    return zeta1, zeta2, zeta3, zeta5, zeta6, shyp, phi, eps_g


@jit
def _weight(b: float, c: float, e: float, slip: float, sh: float) -> float:
    """Combined-slip weighting G = cos(magic(slip + SH)) / cos(magic(SH)) ([P] 4.E51, 4.E59)."""
    return np.cos(_magic(b, c, e, slip + sh)) / np.cos(_magic(b, c, e, sh))


@jit
def _trail_factors(p: np.ndarray, fz: float, dfz: float, gamma_z: float, alpha: float,
                   zeta5: float, lmuy: float) -> tuple[float, float, float, float]:
    """
    Return (Bt, Dt, alpha_t, Et) of the pneumatic trail ([P] 4.E35-4.E44, [B] A58, A60).

    alpha_t = ``alpha`` + SHt. Et is evaluated at this pure-slip alpha_t ([P] 4.E44), also
    where the trail is taken at the equivalent angle.
    """
    dpi = p[DPI]
    bt = ((p[QBZ1] + p[QBZ2] * dfz + p[QBZ3] * dfz * dfz)
          * (1.0 + p[QBZ4] * gamma_z + p[QBZ5] * abs(gamma_z)) * p[LKY] / lmuy)
    dt = (fz * (p[QDZ1] + p[QDZ2] * dfz) * (1.0 - p[PPZ1] * dpi)
          * (1.0 + p[QDZ3] * gamma_z + p[QDZ4] * gamma_z * gamma_z)
          * p[R0] / p[FZN] * p[LTR] * zeta5)
    alpha_t = alpha + p[QHZ1] + p[QHZ2] * dfz + (p[QHZ3] + p[QHZ4] * dfz) * gamma_z
    ct = p[QCZ1]
    et = _at_most_one((p[QEZ1] + p[QEZ2] * dfz + p[QEZ3] * dfz * dfz)
                      * (1.0 + (p[QEZ4] + p[QEZ5] * gamma_z) * (2.0 / np.pi)
                         * np.arctan(bt * ct * alpha_t)))
    return bt, dt, alpha_t, et


@jit
def _trail(p: np.ndarray, bt: float, dt: float, et: float, alpha_t: float,
           alpha: float) -> float:
    """Return t = Dt cos(Ct atan(Bt at - Et (Bt at - atan(Bt at)))) cos alpha ([P] 4.E73)."""
    return dt * np.cos(_magic(bt, p[QCZ1], et, alpha_t)) * np.cos(alpha)


@jit
def _equivalent(alpha: float, kappa_term: float) -> float:
    """atan(sqrt(tan^2 alpha + (Kxk/Kya kappa)^2)) sgn(alpha) ([B] A54, A55)."""
    return (np.arctan(np.sqrt(np.tan(alpha) ** 2 + kappa_term * kappa_term))
            * _sign(alpha))


@jit
def _free_radius(p: np.ndarray, omega: float) -> float:
    """R_omega = R0 (Q_RE0 + Q_V1 (omega R0 / V0)^2) ([B] eq. 1)."""
    if p[LONGVL] > 0.0:
        speed = omega * (p[R0] / p[LONGVL])
        return p[R0] * (p[Q_RE0] + p[Q_V1] * speed * speed)
    return p[R0] * p[Q_RE0]


@jit
def _effective_radius(p: np.ndarray, fz: float, omega: float) -> float:
    """R_e ([B] eqs. 1, 5, 7)."""
    r_omega = _free_radius(p, omega)
    cz = p[VERTICAL_STIFFNESS] * (1.0 + p[PFZ1] * p[DPI])
    rho = fz / p[FNOMIN]
    return r_omega - p[FNOMIN] / cz * (p[DREFF] * np.arctan(p[BREFF] * rho) + p[FREFF] * rho)


@jit
def _force_factor(p: np.ndarray, omega: float, fx: float, fy_term: float) -> float:
    """Return fc of the vertical force ([P] A3.3, [B] eq. 4): speed, force, pressure terms."""
    scale = p[R0] / p[LONGVL] if p[LONGVL] > 0.0 else 0.0
    speed = abs(omega * scale)
    fx_term = fx * (p[Q_FCX] / p[FNOMIN])
    return ((1.0 + p[Q_V2] * speed - fx_term * fx_term - fy_term * fy_term)
            * (1.0 + p[PFZ1] * p[DPI]))


@jit
def _loaded_radius(p: np.ndarray, fz: float, omega: float, fx: float, fy: float) -> float:
    """R_omega - rho with rho from Fz = fc (Q_FZ1 x + Q_FZ2 x^2) FNOMIN, x = rho/R0 (6.1)."""
    fc = _force_factor(p, omega, fx, fy * (p[Q_FCY] / p[FNOMIN]))
    c = fz / (fc * p[FNOMIN])
    # x = (-Q1 + sqrt(Q1^2 + 4 Q2 c)) / (2 Q2), written without the cancellation
    x = 2.0 * c / (p[Q_FZ1] + np.sqrt(p[Q_FZ1] * p[Q_FZ1] + 4.0 * p[Q_FZ2] * c))
    return _free_radius(p, omega) - x * p[R0]


@jit
def _vertical_force(p: np.ndarray, rho_free: float, gamma: float, fx: float, fy: float,
                    omega: float) -> float:
    """Fz at the deflection rho_free = R_omega - R_l ([P] A3.3, [B] eq. 4; 6.2 per [M])."""
    if not rho_free > 0.0:
        return 0.0
    r0, fnom = p[R0], p[FNOMIN]
    rho = rho_free
    fy_eff = fy
    fy_factor = p[Q_FCY] / fnom
    if p[V62] != 0.0:
        r_omega = _free_radius(p, omega)
        r_l = r_omega - rho_free
        ratio = r_l / r_omega
        fy_eff = fy - (p[Q_FYS1] + p[Q_FYS2] * ratio + p[Q_FYS3] * ratio * ratio) * gamma
        rho = max(rho_free + _camber_deflection(p, r_l, r_omega, rho_free, gamma), 0.0)
        fy_factor = (rho / r0) ** p[Q_FCY2] * p[Q_FCY] / fnom if rho > 0.0 else 0.0
    x = rho / r0
    fz = (_force_factor(p, omega, fx, fy_factor * fy_eff) * (p[Q_FZ1] * x + p[Q_FZ2] * x * x)
          * fnom)
    if p[BOTTOM_STIFF] > 0.0 and p[RIM_RADIUS] > 0.0:
        start = _free_radius(p, omega) - p[RIM_RADIUS] - p[BOTTOM_OFFST]
        fz = fz + p[BOTTOM_STIFF] * max(rho_free - start, 0.0)
    return fz


@jit
def _camber_deflection(p: np.ndarray, r_l: float, r_omega: float, rho_free: float,
                       gamma: float) -> float:
    """Deflection of the 6.2 tire from camber ([M] calculateFz62: Q_CAM1-3, tread width)."""
    tread = (1.075 - 0.5 * p[ASPECT_RATIO]) * p[WIDTH]
    loaded = p[Q_CAM1] * r_l + p[Q_CAM2] * r_l * r_l
    free = p[Q_CAM1] * r_omega + p[Q_CAM2] * r_omega * r_omega
    shape = loaded / free if free != 0.0 else 0.0
    return (shape * shape * tread / 8.0 * abs(np.tan(gamma))
            - p[Q_CAM3] * rho_free * abs(gamma))


@jit
def _loaded_radius_62(p: np.ndarray, fz: float, gamma: float, fx: float, fy: float,
                      omega: float) -> float:
    """R_l of the 6.2 vertical model with camber, by bisection on the deflection."""
    r_omega = _free_radius(p, omega)
    low = 0.0
    high = r_omega
    for _ in range(_RADIUS_ITERATIONS):
        mid = 0.5 * (low + high)
        if _vertical_force(p, mid, gamma, fx, fy, omega) > fz:
            high = mid
        else:
            low = mid
    return r_omega - 0.5 * (low + high)


@jit
def _tire_spring(p: np.ndarray, deflection: float, gamma: float, fx: float, fy: float,
                 omega: float) -> float:
    """
    Fz of the tire at ``deflection`` = R0 - R_l, the full vehicle's vertical tire (module doc).

    MF 6.x: the load-deflection curve of :func:`_vertical_force` at R_omega - R_l; PAC2002 /
    MF 5.2: the linear C_z (1 + PFZ1 dpi) deflection (negative for a negative deflection).
    """
    if p[V6] != 0.0:
        return _vertical_force(p, deflection + (_free_radius(p, omega) - p[R0]), gamma, fx, fy,
                               omega)
    return p[VERTICAL_STIFFNESS] * (1.0 + p[PFZ1] * p[DPI]) * deflection


@jit
def _deflection(p: np.ndarray, fz: float, omega: float, gamma: float) -> float:
    """R0 - R_l at which :func:`_tire_spring` carries ``fz`` >= 0 at Fx = Fy = 0."""
    if p[V62] != 0.0 and gamma != 0.0:
        return p[R0] - _loaded_radius_62(p, fz, gamma, 0.0, 0.0, omega)
    if p[V6] != 0.0:
        return p[R0] - _loaded_radius(p, fz, omega, 0.0, 0.0)
    return fz / (p[VERTICAL_STIFFNESS] * (1.0 + p[PFZ1] * p[DPI]))


@jit
def _relaxation(p: np.ndarray, fz: float, gamma: float) -> tuple[float, float]:
    """(sigma_kappa, sigma_alpha): [5] from PTX/PTY, 6.x from Kxk, Kya and [STRUCTURAL]."""
    dfz = _dfz(p, fz)
    if p[V6] != 0.0:
        dpi = p[DPI]
        cx = (p[LONGITUDINAL_STIFFNESS] * (1.0 + p[PCFX1] * dfz + p[PCFX2] * dfz * dfz)
              * (1.0 + p[PCFX3] * dpi))
        cy = (p[LATERAL_STIFFNESS] * (1.0 + p[PCFY1] * dfz + p[PCFY2] * dfz * dfz)
              * (1.0 + p[PCFY3] * dpi))
        sigma_k = abs(_kxk(p, fz, dfz)) / cx if cx > 0.0 else 0.0
        sigma_a = abs(_kya(p, fz, gamma, 1.0)) / cy if cy > 0.0 else 0.0
        return sigma_k, sigma_a
    fz0 = p[FZ0P]
    sigma_k = (fz * (p[PTX1] + p[PTX2] * dfz) * np.exp(-p[PTX3] * dfz) * p[R0] / fz0
               * p[LSGKP])
    sigma_a = p[PTY1] * np.sin(2.0 * np.arctan(fz / (p[PTY2] * fz0))) if p[PTY2] != 0.0 else 0.0
    sigma_a = sigma_a * (1.0 - p[PKY3] * abs(gamma)) * p[R0] * p[LFZO] * p[LSGAL]
    return sigma_k, sigma_a


@jit
def _steady_state(p: np.ndarray, fz: float, kappa: float, alpha: float, gamma: float,
                  vx: float, phit: float, road_friction: float
                  ) -> tuple[float, float, float, float, float]:
    """
    Combined-slip (Fx, Fy, Mx, My, Mz) in the file frame, load > 0 (module doc).

    ``road_friction`` is lambda*_mu / LMU ([P] 4.E7; module doc, "Road friction").
    """
    lmux = p[LMUX] * road_friction
    lmuy = p[LMUY] * road_friction
    dfz = _dfz(p, fz)
    gamma_y = gamma * p[LGAY]
    gamma_z = gamma * p[LGAZ]
    zeta1, zeta2, zeta3, zeta5, zeta6, shyp, phi, eps_g = _turn_slip(p, fz, dfz, kappa, alpha,
                                                                     gamma, phit)
    fy0, mu_y, kya, by, shy, svy = _lateral(p, fz, dfz, gamma_y, alpha, zeta2, zeta3, shyp,
                                            lmuy)
    fx0, kxk = _longitudinal(p, fz, dfz, gamma * p[LGAX], kappa, zeta1, lmux)
    # combined slip ([P] 4.E50-4.E67)
    if p[COMBINED] != 0.0:
        g2 = gamma * gamma
        b_xa = (p[RBX1] + p[RBX3] * g2) * np.cos(np.arctan(p[RBX2] * kappa)) * p[LXAL]
        e_xa = _at_most_one(p[REX1] + p[REX2] * dfz)
        fx = _weight(b_xa, p[RCX1], e_xa, alpha, p[RHX1]) * fx0
        b_yk = ((p[RBY1] + p[RBY4] * g2) * np.cos(np.arctan(p[RBY2] * (alpha - p[RBY3])))
                * p[LYKA])
        e_yk = _at_most_one(p[REY1] + p[REY2] * dfz)
        g_yk = _weight(b_yk, p[RCY1], e_yk, kappa, p[RHY1] + p[RHY2] * dfz)
        sv_yk = (mu_y * fz * (p[RVY1] + p[RVY2] * dfz + p[RVY3] * gamma)
                 * np.cos(np.arctan(p[RVY4] * alpha)) * zeta2
                 * np.sin(p[RVY5] * np.arctan(p[RVY6] * kappa)) * p[LVYKA])
        kappa_c = kappa
    else:
        fx = fx0
        g_yk = 1.0
        sv_yk = 0.0
        kappa_c = 0.0
    fy = g_yk * fy0 + sv_yk
    # aligning moment ([P] 4.E31-4.E49, 4.E71-4.E78; [B] A54-A60)
    ratio = kxk / kya * kappa_c if kya != 0.0 else 0.0
    bt, dt, alpha_t, et = _trail_factors(p, fz, dfz, gamma_z, alpha, zeta5, lmuy)
    t = _trail(p, bt, dt, et, _equivalent(alpha_t, ratio), alpha)
    alpha_r = alpha + shy + (svy / kya if kya != 0.0 else 0.0)
    zeta0 = 0.0 if p[TURN] != 0.0 else 1.0
    zeta7 = zeta8 = 1.0
    if p[TURN] != 0.0:
        mz_inf = abs(p[QCRP1] * abs(mu_y) * p[R0] * fz * np.sqrt(fz / p[FZ0P]) * p[LMP])
        c_drp = p[QDRP1]
        d_drp = mz_inf / np.sin(0.5 * np.pi * c_drp)
        kzg_r0 = (fz * p[R0] * (p[QDZ8] + p[QDZ9] * dfz) * (1.0 + p[PPZ2] * p[DPI])
                  * p[LKZC])
        b_drp = kzg_r0 / (c_drp * d_drp * (1.0 - eps_g))
        d_rp = d_drp * np.sin(c_drp * np.arctan(b_drp * p[R0] * phi))
        mz_90 = mz_inf * (2.0 / np.pi) * np.arctan(p[QCRP2] * p[R0] * abs(phit)) * g_yk
        size = abs(d_rp)
        share = mz_90 / size if size > _TINY_MOMENT else 0.0
        zeta7 = (2.0 / np.pi) * np.arccos(min(max(share, -1.0), 1.0))
        zeta8 = 1.0 + d_rp
    b_r = (p[QBZ9] * p[LKY] / lmuy + p[QBZ10] * by * p[PCY1] * p[LCY]) * zeta6
    d_r = (fz * p[R0] * ((p[QDZ6] + p[QDZ7] * dfz) * p[LRES] * zeta2
                         + ((p[QDZ8] + p[QDZ9] * dfz) * (1.0 + p[PPZ2] * p[DPI])
                            + (p[QDZ10] + p[QDZ11] * dfz) * abs(gamma_z))
                         * gamma_z * p[LKZC] * zeta0)
           * lmuy * np.cos(alpha) + zeta8 - 1.0)
    m_zr = d_r * np.cos(zeta7 * np.arctan(b_r * _equivalent(alpha_r, ratio)))
    arm = (p[R0] * (p[SSZ1] + p[SSZ2] * fy / p[FZN] + (p[SSZ3] + p[SSZ4] * dfz) * gamma_z)
           * p[LS])
    if p[V6] != 0.0:  # Fy' = Gyk Fy0 at zero camber ([P] 4.E74)
        fy_lever = g_yk * _lateral(p, fz, dfz, 0.0, alpha, 1.0, 1.0, 0.0, lmuy)[0]
    else:
        fy_lever = fy - sv_yk
    mz = -t * fy_lever + m_zr + arm * fx * p[COMBINED]
    # overturning moment ([Bd] 49) and rolling resistance ([5]; [B] A48)
    fnom = p[FNOMIN]
    r0 = p[R0]
    couple = (p[QSX1] * p[LVMX] - p[QSX2] * gamma * (1.0 + p[PPMX1] * p[DPI])
              + p[QSX3] * fy / fnom)
    if p[QSX4] != 0.0 or p[QSX10] != 0.0 or p[QSX12] != 0.0:  # terms 0 without them
        couple = (couple - p[QSX12] * gamma * abs(gamma)
                  + p[QSX4] * np.cos(p[QSX5] * np.arctan((p[QSX6] * fz / fnom) ** 2))
                  * np.sin(p[QSX7] * gamma + p[QSX8] * np.arctan(p[QSX9] * fy / fnom))
                  + p[QSX10] * np.arctan(p[QSX11] * fz / fnom) * gamma)
    mx = r0 * fz * p[LMX] * couple
    if p[QSX13] != 0.0 or p[QSX14] != 0.0:
        mx = mx + r0 * fy * p[LMX] * (p[QSX13] + p[QSX14] * abs(gamma))
    v_rel = vx / p[LONGVL] if p[LONGVL] > 0.0 else 0.0
    rolling = (p[QSY1] + p[QSY2] * fx / fnom + p[QSY3] * abs(v_rel)
               + p[QSY4] * v_rel ** 4)
    if p[V6] != 0.0:
        load = fz / fnom
        rolling = ((rolling + (p[QSY5] + p[QSY6] * load) * gamma * gamma)
                   * load ** p[QSY7] * p[PRATIO] ** p[QSY8] * fnom)
    else:
        rolling = rolling * fz
    my = -_signum(vx) * r0 * rolling * p[LMY]
    return (fx * p[FX_ON], fy * p[FY_ON], mx * p[FY_ON], my * p[FX_ON], mz * p[FY_ON])


@jit
def wheel_forces(p: np.ndarray, fz: float, kappa: float, alpha: float, gamma: float,
                 vx: float, mirror: float, phit: float, road_friction: float
                 ) -> tuple[float, float, float, float, float]:
    """
    (Fx, Fy, Mx, My, Mz) of one wheel: the kernel of :func:`combined_forces` (floats).

    ``mirror`` +1 as measured, -1 mirrored; ``road_friction`` (module doc,
    "Road friction"), 1 for the file's; 0 everything off the ground (Fz <= 0).
    """
    if not fz > 0.0:
        return 0.0, 0.0, 0.0, 0.0, 0.0
    fx, fy, mx, my, mz = _steady_state(p, fz, kappa, mirror * alpha, mirror * gamma, vx,
                                       mirror * phit, road_friction)
    return fx, mirror * fy, mirror * mx, my, mirror * mz


@jit
def four_wheel_forces(front: np.ndarray, rear: np.ndarray, fz: np.ndarray, kappa: np.ndarray,
                      alpha: np.ndarray, gamma: np.ndarray, vx: np.ndarray,
                      mirror: np.ndarray, road_friction: np.ndarray | float = 1.0) -> np.ndarray:
    """
    (5, 4) Fx, Fy, Mx, My, Mz of a car's wheels FL FR RL RR, ``front`` tire on FL FR.

    Inputs (4,) as :func:`wheel_forces` takes them per wheel (no turn slip); ``road_friction``
    per wheel or for all. The evaluation of the compiled vehicle step: one output array.
    """
    friction = np.empty(4)
    friction[:] = road_friction
    out = np.empty((5, 4))
    for w in range(4):
        p = front if w < 2 else rear
        out[0, w], out[1, w], out[2, w], out[3, w], out[4, w] = wheel_forces(
            p, fz[w], kappa[w], alpha[w], gamma[w], vx[w], mirror[w], 0.0, friction[w])
    return out


@jit
def four_wheel_springs(front: np.ndarray, rear: np.ndarray, deflection: np.ndarray,
                       gamma: np.ndarray, fx: np.ndarray, fy: np.ndarray, omega: np.ndarray,
                       mirror: np.ndarray) -> np.ndarray:
    """
    (4,) vertical tire forces of a car's wheels FL FR RL RR, N, ``front`` tire on FL FR.

    ``deflection`` = R0 - R_l (m), ``gamma`` rad, ``fx``, ``fy`` N (the forces of the 6.x
    stiffening, as :func:`four_wheel_forces` returns them), ``omega`` spin rad/s, ``mirror``
    per wheel. MF 6.x: the 6.x load-deflection curve (module doc, "Radii and vertical
    stiffness"); PAC2002 / MF 5.2: the linear C_z (1 + PFZ1 dpi). No damping.
    """
    out = np.empty(4)
    for w in range(4):
        p = front if w < 2 else rear
        s = mirror[w]
        out[w] = _tire_spring(p, deflection[w], s * gamma[w], fx[w], s * fy[w], omega[w])
    return out


# --- the same equations over arrays of wheels (the numpy interface) -----------------


@jit
def combined_forces(p: np.ndarray, fz: np.ndarray, kappa: np.ndarray, alpha: np.ndarray,
                    gamma: np.ndarray, vx: np.ndarray, mirror: np.ndarray, phit: np.ndarray,
                    road_friction: np.ndarray | float = 1.0
                    ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """
    (Fx, Fy, Mx, My, Mz) of :meth:`MagicFormula.steady_state` for coefficients ``p``.

    Arrays (n,); ``mirror`` +1 as measured, -1 mirrored, per element; ``road_friction`` per
    element or for all (module doc, "Road friction"); 0 off the ground.
    """
    n = fz.size
    friction = np.empty(n)
    friction[:] = road_friction
    fx, fy, mx = np.empty(n), np.empty(n), np.empty(n)
    my, mz = np.empty(n), np.empty(n)
    for i in range(n):
        fx[i], fy[i], mx[i], my[i], mz[i] = wheel_forces(
            p, fz[i], kappa[i], alpha[i], gamma[i], vx[i], mirror[i], phit[i], friction[i])
    return fx, fy, mx, my, mz


@jit
def _pure_lateral_at(p: np.ndarray, fz: np.ndarray, alpha: np.ndarray, gamma: np.ndarray,
                     s: float) -> np.ndarray:
    """Fy0 of :meth:`MagicFormula.fy` (mirrored by ``s``), (n,), 0 off the ground."""
    out = np.zeros(fz.size)
    for i in range(fz.size):
        if fz[i] > 0.0:
            out[i] = s * _pure_lateral(p, fz[i], s * alpha[i], s * gamma[i])
    return out


@jit
def _pure_longitudinal_at(p: np.ndarray, fz: np.ndarray, kappa: np.ndarray,
                          gamma: np.ndarray) -> np.ndarray:
    """Fx0 of :meth:`MagicFormula.fx`, (n,), 0 off the ground."""
    out = np.zeros(fz.size)
    for i in range(fz.size):
        if fz[i] > 0.0:
            out[i] = _longitudinal(p, fz[i], _dfz(p, fz[i]), gamma[i] * p[LGAX], kappa[i],
                                   1.0, p[LMUX])[0]
    return out


@jit
def _cornering_stiffness_at(p: np.ndarray, fz: np.ndarray, gamma: np.ndarray) -> np.ndarray:
    """dFy0/dalpha at alpha = 0, (n,), 0 off the ground."""
    out = np.zeros(fz.size)
    for i in range(fz.size):
        if fz[i] > 0.0:
            out[i] = _lateral_slope_at_zero(p, fz[i], gamma[i])
    return out


@jit
def _peak_lateral_friction_at(p: np.ndarray, fz: np.ndarray, gamma: np.ndarray) -> np.ndarray:
    """mu_y ([P] 4.E23), (n,)."""
    out = np.empty(fz.size)
    for i in range(fz.size):
        out[i] = _mu_y(p, _dfz(p, fz[i]), gamma[i] * p[LGAY], p[LMUY])
    return out


@jit
def _lateral_curvature_at(p: np.ndarray, fz: np.ndarray, gamma: np.ndarray,
                          sign: np.ndarray, s: float) -> np.ndarray:
    """E_y of :meth:`MagicFormula.lateral_curvature` (mirrored by ``s``), (n,)."""
    out = np.empty(fz.size)
    for i in range(fz.size):
        out[i] = _ey(p, _dfz(p, fz[i]), s * gamma[i] * p[LGAY], s * sign[i])
    return out


@jit
def _pneumatic_trail_at(p: np.ndarray, fz: np.ndarray, gamma_z: np.ndarray) -> np.ndarray:
    """Trail at alpha = 0 of :meth:`MagicFormula.pneumatic_trail`, (n,), 0 off the ground."""
    out = np.zeros(fz.size)
    for i in range(fz.size):
        if fz[i] > 0.0:
            bt, dt, sht, et = _trail_factors(p, fz[i], _dfz(p, fz[i]), gamma_z[i], 0.0, 1.0,
                                             p[LMUY])
            out[i] = _trail(p, bt, dt, et, sht, 0.0)
    return out


@jit
def _loaded_radius_at(p: np.ndarray, fz: np.ndarray, gamma: np.ndarray, fx: np.ndarray,
                      fy: np.ndarray, omega: np.ndarray) -> np.ndarray:
    """R_l of :meth:`MagicFormula.loaded_radius` (file frame), (n,), loads >= 0."""
    out = np.empty(fz.size)
    for i in range(fz.size):
        if p[V62] != 0.0 and (gamma[i] != 0.0 or fy[i] != 0.0):
            out[i] = _loaded_radius_62(p, fz[i], gamma[i], fx[i], fy[i], omega[i])
        else:
            out[i] = _loaded_radius(p, fz[i], omega[i], fx[i], fy[i])
    return out


@jit
def _vertical_force_at(p: np.ndarray, rho: np.ndarray, gamma: np.ndarray, fx: np.ndarray,
                       fy: np.ndarray, omega: np.ndarray) -> np.ndarray:
    """Fz of :meth:`MagicFormula.vertical_force` (file frame), (n,)."""
    out = np.empty(rho.size)
    for i in range(rho.size):
        out[i] = _vertical_force(p, rho[i], gamma[i], fx[i], fy[i], omega[i])
    return out


@jit
def _deflection_at(p: np.ndarray, fz: np.ndarray, omega: np.ndarray,
                   gamma: np.ndarray) -> np.ndarray:
    """R0 - R_l of :meth:`MagicFormula.deflection` (file frame), (n,), loads >= 0."""
    out = np.empty(fz.size)
    for i in range(fz.size):
        out[i] = _deflection(p, fz[i], omega[i], gamma[i])
    return out


@jit
def radii_at(p: np.ndarray, fz: np.ndarray,
             omega: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(R_l, R_e) of :meth:`MagicFormula.radii`, arrays (n,), m."""
    loaded, effective = np.empty(fz.size), np.empty(fz.size)
    for i in range(fz.size):
        fz_ = max(fz[i], 0.0)
        loaded[i] = _loaded_radius(p, fz_, omega[i], 0.0, 0.0)
        effective[i] = loaded[i] if p[RE_LINEAR] != 0.0 else _effective_radius(p, fz_, omega[i])
    return loaded, effective


@jit
def relaxation_at(p: np.ndarray, fz: np.ndarray,
                  gamma: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(sigma_kappa, sigma_alpha) of :meth:`MagicFormula.relaxation_lengths`, (n,), m."""
    sigma_k, sigma_a = np.zeros(fz.size), np.zeros(fz.size)
    for i in range(fz.size):
        if fz[i] > 0.0:
            sigma_k[i], sigma_a[i] = _relaxation(p, fz[i], gamma[i])
    return sigma_k, sigma_a


@jit
def slip_stiffness_at(p: np.ndarray, fz: np.ndarray) -> np.ndarray:
    """K_xk of :meth:`MagicFormula.slip_stiffness`, (n,), N."""
    out = np.zeros(fz.size)
    for i in range(fz.size):
        if fz[i] > 0.0:
            out[i] = _kxk(p, fz[i], _dfz(p, fz[i]))
    return out


def _flat(*values: ArrayLike) -> tuple[tuple[int, ...], tuple[np.ndarray, ...]]:
    """
    Return the broadcast shape of ``values`` and each as a contiguous float vector.

    The compiled equations then see one array type whatever the caller passes (scalars,
    broadcast grids); results are reshaped to the shape.
    """
    arrays = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in values))
    return arrays[0].shape, tuple(np.array(a, dtype=float, order='C').ravel() for a in arrays)
