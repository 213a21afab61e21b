# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
A second evaluation of the MF-Tyre 6.1 / 6.2 equations, one wheel at a time with ``math``.

Written from the published equations, not from vd's implementation: H. B. Pacejka, "Tire and
Vehicle Dynamics", 3rd ed. 2012, sec. 4.3.2 (4.E1-4.E78) and 4.3.3 (turn slip, 4.75-4.106);
I. J. M. Besselink et al., Vehicle System Dynamics 48 (S1), 2010 (A47, A48, A54-A60 and
eqs. 1-19); the draft of that paper, eq. (49), for Mx; and the forms MFeval 4.0 documents as
reproducing TNO MF-Tyre 6.1.2 where the book differs (E_t at the pure-slip alpha_t, Bt with
QBZ4 gamma + QBZ5 |gamma|, Dt with QDZ3 gamma, t times LFZO, s and Mx/My with FNOMIN).
Turn slip follows the spin definition of vd's module doc (camber thrust of the plain model
recovered at phit = 0). Coefficients absent from the file are 0, scaling factors 1, PKY4 2,
QSY7 1, Q_RE0 1.
"""
from __future__ import annotations

import math

from vd_data_server.tir import TireProperties

BLOCKS = ('LONGITUDINAL_COEFFICIENTS', 'LATERAL_COEFFICIENTS', 'ALIGNING_COEFFICIENTS',
          'OVERTURNING_COEFFICIENTS', 'ROLLING_COEFFICIENTS', 'TURNSLIP_COEFFICIENTS',
          'VERTICAL', 'STRUCTURAL', 'DIMENSION')
DEFAULTS = {'PKY4': 2.0, 'QSY7': 1.0, 'Q_RE0': 1.0}


def sgn(x: float) -> float:
    return 1.0 if x > 0 else (-1.0 if x < 0 else 0.0)


def mf(b: float, c: float, d: float, e: float, x: float) -> float:
    return d * math.sin(c * math.atan(b * x - e * (b * x - math.atan(b * x))))


def weight(b: float, c: float, e: float, x: float, sh: float) -> float:
    def cos_shape(u: float) -> float:
        return math.cos(c * math.atan(b * u - e * (b * u - math.atan(b * u))))
    return cos_shape(x + sh) / cos_shape(sh)


class Mf6:
    """The coefficients of one file and the equations of the module doc, scalar."""

    def __init__(self, props: TireProperties, pressure: float | None = None,
                 normalisation: str = 'mf-tyre', turn_slip: bool = False) -> None:
        self.props = props
        self.p0 = props.number('OPERATING_CONDITIONS', 'NOMPRES')
        self.p = pressure if pressure is not None else props.number('OPERATING_CONDITIONS',
                                                                    'INFLPRES')
        self.turn = turn_slip
        self.normalisation = normalisation
        self.version = props.file_format

    def c(self, key: str) -> float:
        for block in BLOCKS:
            if key in self.props.sections.get(block, {}):
                return float(self.props.sections[block][key])
        return DEFAULTS.get(key, 0.0)

    def lam(self, key: str) -> float:
        return float(self.props.sections['SCALING_COEFFICIENTS'].get(key, 1.0))

    def evaluate(self, fz: float, kappa: float, alpha: float, gamma: float, vx: float,
                 phit: float = 0.0, et_at_equivalent: bool = False) -> dict[str, float]:
        """Return the forces and moments; ``et_at_equivalent``: E_t at alpha_t,eq (not 4.E44)."""
        c, lam = self.c, self.lam
        r0 = c('UNLOADED_RADIUS')
        fz0 = c('FNOMIN')
        fz0p = fz0 * lam('LFZO')
        dfz = (fz - fz0p) / fz0p
        dpi = (self.p - self.p0) / self.p0
        fzn = fz0 if self.normalisation == 'mf-tyre' else fz0p

        # turn slip factors (4.77-4.106); 1 without turn slip
        z0 = z1 = z2 = z3 = z5 = z6 = z7 = z8 = 1.0
        shyp = 0.0
        phi = 0.0
        eps_g = 0.0
        kyg0 = fz * (c('PKY6') + c('PKY7') * dfz) * (1 + c('PPY5') * dpi) * lam('LKYC')

        def kya_of(g: float, zeta3: float) -> float:
            return (c('PKY1') * fz0p * (1 + c('PPY1') * dpi) * (1 - c('PKY3') * abs(g))
                    * math.sin(c('PKY4') * math.atan(
                        fz / ((c('PKY2') + c('PKY5') * g * g) * (1 + c('PPY2') * dpi) * fz0p)))
                    * zeta3 * lam('LKY'))

        if self.turn:
            eps_g = c('PECP1') * (1 + c('PECP2') * dfz)
            rho = fz / fz0
            cz = c('VERTICAL_STIFFNESS') * (1 + c('PFZ1') * dpi)
            r_e = r0 * c('Q_RE0') - fz0 / cz * (c('DREFF') * math.atan(c('BREFF') * rho)
                                                   + c('FREFF') * rho)
            phi = phit + (1 - eps_g) * math.sin(gamma) * (1 + kappa) * math.cos(alpha) / r_e
            z1 = math.cos(math.atan(c('PDXP1') * (1 + c('PDXP2') * dfz)
                                    * math.cos(math.atan(c('PDXP3') * kappa)) * r0 * phi))
            byp = c('PDYP1') * (1 + c('PDYP2') * dfz) * math.cos(math.atan(
                c('PDYP3') * math.tan(alpha)))
            z2 = math.cos(math.atan(byp * (r0 * abs(phi) + c('PDYP4') * math.sqrt(r0 * abs(phi)))))
            z3 = math.cos(math.atan(c('PKYP1') * r0 ** 2 * phi ** 2))
            chyp = c('PHYP1')
            dhyp = c('PHYP2') + c('PHYP3') * dfz
            ehyp = min(c('PHYP4'), 1.0)
            bhyp = kyg0 / (1 - eps_g) / (chyp * dhyp * kya_of(0.0, z3))
            shyp = mf(bhyp, chyp, dhyp, ehyp, r0 * phi)
            z0 = 0.0
            z5 = math.cos(math.atan(c('QDTP1') * r0 * phi))
            z6 = math.cos(math.atan(c('QBRP1') * r0 * phi))

        def lateral(g: float, zeta2: float, zeta3: float, zeta0: float, shift: float
                    ) -> tuple[float, float, float, float, float, float]:
            cy = c('PCY1') * lam('LCY')
            muy = ((c('PDY1') + c('PDY2') * dfz) * (1 + c('PPY3') * dpi + c('PPY4') * dpi ** 2)
                   * (1 - c('PDY3') * g ** 2) * lam('LMUY'))
            dy = muy * fz * zeta2
            kya = kya_of(g, zeta3)
            svyg = fz * (c('PVY3') + c('PVY4') * dfz) * g * lam('LKYC') * lam('LMUY') * zeta2
            zeta4 = 1 + shift - svyg / kya if zeta0 == 0.0 else 1.0
            shy = ((c('PHY1') + c('PHY2') * dfz) * lam('LHY')
                   + (kyg0 * g - svyg) / kya * zeta0 + zeta4 - 1)
            svy = fz * (c('PVY1') + c('PVY2') * dfz) * lam('LVY') * lam('LMUY') * zeta2 + svyg
            ay = alpha + shy
            ey = min((c('PEY1') + c('PEY2') * dfz)
                     * (1 + c('PEY5') * g ** 2 - (c('PEY3') + c('PEY4') * g) * sgn(ay))
                     * lam('LEY'), 1.0)
            by = kya / (cy * dy)
            return mf(by, cy, dy, ey, ay) + svy, muy, kya, by, shy, svy

        fy0, muy, kya, by, shy, svy = lateral(gamma, z2, z3, z0, shyp)
        # longitudinal (4.E9-4.E18)
        cx = c('PCX1') * lam('LCX')
        mux = ((c('PDX1') + c('PDX2') * dfz) * (1 + c('PPX3') * dpi + c('PPX4') * dpi ** 2)
               * (1 - c('PDX3') * gamma ** 2) * lam('LMUX'))
        dx = mux * fz * z1
        kxk = (fz * (c('PKX1') + c('PKX2') * dfz) * math.exp(c('PKX3') * dfz)
               * (1 + c('PPX1') * dpi + c('PPX2') * dpi ** 2) * lam('LKX'))
        kx = kappa + (c('PHX1') + c('PHX2') * dfz) * lam('LHX')
        ex = min((c('PEX1') + c('PEX2') * dfz + c('PEX3') * dfz ** 2)
                 * (1 - c('PEX4') * sgn(kx)) * lam('LEX'), 1.0)
        fx0 = mf(kxk / (cx * dx), cx, dx, ex, kx) + fz * (c('PVX1') + c('PVX2') * dfz) \
            * lam('LVX') * lam('LMUX') * z1
        # combined (4.E50-4.E67)
        bxa = (c('RBX1') + c('RBX3') * gamma ** 2) * math.cos(math.atan(c('RBX2') * kappa)) \
            * lam('LXAL')
        fx = weight(bxa, c('RCX1'), min(c('REX1') + c('REX2') * dfz, 1.0), alpha,
                    c('RHX1')) * fx0
        byk = (c('RBY1') + c('RBY4') * gamma ** 2) * math.cos(
            math.atan(c('RBY2') * (alpha - c('RBY3')))) * lam('LYKA')
        gyk = weight(byk, c('RCY1'), min(c('REY1') + c('REY2') * dfz, 1.0), kappa,
                     c('RHY1') + c('RHY2') * dfz)
        svyk = (muy * fz * (c('RVY1') + c('RVY2') * dfz + c('RVY3') * gamma)
                * math.cos(math.atan(c('RVY4') * alpha)) * z2
                * math.sin(c('RVY5') * math.atan(c('RVY6') * kappa)) * lam('LVYKA'))
        fy = gyk * fy0 + svyk
        # aligning moment (4.E31-4.E49, 4.E71-4.E78, A54-A60)
        sht = c('QHZ1') + c('QHZ2') * dfz + (c('QHZ3') + c('QHZ4') * dfz) * gamma
        at = alpha + sht
        bt = ((c('QBZ1') + c('QBZ2') * dfz + c('QBZ3') * dfz ** 2)
              * (1 + c('QBZ4') * gamma + c('QBZ5') * abs(gamma)) * lam('LKY') / lam('LMUY'))
        ct = c('QCZ1')
        dt = ((c('QDZ1') + c('QDZ2') * dfz) * (1 - c('PPZ1') * dpi)
              * (1 + c('QDZ3') * gamma + c('QDZ4') * gamma ** 2) * fz * (r0 / fzn) * lam('LTR')
              * z5)
        k_ratio = kxk / kya
        at_eq = math.atan(math.sqrt(math.tan(at) ** 2 + (k_ratio * kappa) ** 2)) \
            * (-1.0 if at < 0 else 1.0)
        et = min((c('QEZ1') + c('QEZ2') * dfz + c('QEZ3') * dfz ** 2)
                 * (1 + (c('QEZ4') + c('QEZ5') * gamma) * (2 / math.pi)
                    * math.atan(bt * ct * (at_eq if et_at_equivalent else at))), 1.0)
        t = (dt * math.cos(ct * math.atan(bt * at_eq - et * (bt * at_eq - math.atan(bt * at_eq))))
             * math.cos(alpha))
        ar = alpha + shy + svy / kya
        ar_eq = math.atan(math.sqrt(math.tan(ar) ** 2 + (k_ratio * kappa) ** 2)) \
            * (-1.0 if ar < 0 else 1.0)
        if self.turn:
            mzp_inf = abs(c('QCRP1') * abs(muy) * r0 * fz * math.sqrt(fz / fz0p) * lam('LMP'))
            cdrp = c('QDRP1')
            ddrp = mzp_inf / math.sin(0.5 * math.pi * cdrp)
            kzgr0 = fz * r0 * (c('QDZ8') + c('QDZ9') * dfz) * (1 + c('PPZ2') * dpi) \
                * lam('LKZC')
            bdrp = kzgr0 / (cdrp * ddrp * (1 - eps_g))
            drp = ddrp * math.sin(cdrp * math.atan(bdrp * r0 * phi))
            mzp90 = mzp_inf * (2 / math.pi) * math.atan(c('QCRP2') * r0 * abs(phit)) * gyk
            ratio = mzp90 / abs(drp) if abs(drp) > 1e-12 else 0.0
            z7 = (2 / math.pi) * math.acos(max(-1.0, min(1.0, ratio)))
            z8 = 1 + drp
        br = (c('QBZ9') * lam('LKY') / lam('LMUY') + c('QBZ10') * by * c('PCY1') * lam('LCY')) \
            * z6
        dr = (fz * r0 * ((c('QDZ6') + c('QDZ7') * dfz) * lam('LRES') * z2
                         + ((c('QDZ8') + c('QDZ9') * dfz) * (1 + c('PPZ2') * dpi)
                            + (c('QDZ10') + c('QDZ11') * dfz) * abs(gamma))
                         * gamma * lam('LKZC') * z0)
              * lam('LMUY') * math.cos(alpha) + z8 - 1)
        mzr = dr * math.cos(z7 * math.atan(br * ar_eq))
        fy0_flat = lateral(0.0, 1.0, 1.0, 1.0, 0.0)[0]
        s = r0 * (c('SSZ1') + c('SSZ2') * fy / fzn + (c('SSZ3') + c('SSZ4') * dfz) * gamma) \
            * lam('LS')
        mz = -t * gyk * fy0_flat + mzr + s * fx
        # overturning moment (draft eq. 49) and rolling resistance (A48)
        mx = (r0 * fz * lam('LMX') * (
            c('QSX1') * lam('LVMX') - c('QSX2') * gamma * (1 + c('PPMX1') * dpi)
            - c('QSX12') * gamma * abs(gamma) + c('QSX3') * fy / fz0
            + c('QSX4') * math.cos(c('QSX5') * math.atan((c('QSX6') * fz / fz0) ** 2))
            * math.sin(c('QSX7') * gamma + c('QSX8') * math.atan(c('QSX9') * fy / fz0))
            + c('QSX10') * math.atan(c('QSX11') * fz / fz0) * gamma)
            + r0 * fy * lam('LMX') * (c('QSX13') + c('QSX14') * abs(gamma)))
        v0 = self.props.number('MODEL', 'LONGVL')
        my = -sgn(vx) * r0 * fz0 * lam('LMY') * (
            c('QSY1') + c('QSY2') * fx / fz0 + c('QSY3') * abs(vx / v0)
            + c('QSY4') * (vx / v0) ** 4 + (c('QSY5') + c('QSY6') * fz / fz0) * gamma ** 2) \
            * (fz / fz0) ** c('QSY7') * (self.p / self.p0) ** c('QSY8')
        return {'fx': fx, 'fy': fy, 'mx': mx, 'my': my, 'mz': mz}

    def loaded_radius(self, fz: float, omega: float = 0.0, fx: float = 0.0,
                      fy: float = 0.0) -> float:
        """R_omega - rho, rho from the quadratic load-deflection curve of [B] eq. 4 (6.1)."""
        c = self.c
        r0, fz0 = c('UNLOADED_RADIUS'), c('FNOMIN')
        dpi = (self.p - self.p0) / self.p0
        v0 = self.props.number('MODEL', 'LONGVL')
        q2 = c('Q_FZ2')
        q1 = math.sqrt((c('VERTICAL_STIFFNESS') * r0 / fz0) ** 2 - 4 * q2)
        fc = ((1 + c('Q_V2') * r0 / v0 * abs(omega) - (c('Q_FCX') * fx / fz0) ** 2
               - (c('Q_FCY') * fy / fz0) ** 2) * (1 + c('PFZ1') * dpi))
        target = fz / (fc * fz0)
        x = (-q1 + math.sqrt(q1 ** 2 + 4 * q2 * target)) / (2 * q2) if q2 else target / q1
        return r0 * (c('Q_RE0') + c('Q_V1') * (omega * r0 / v0) ** 2) - x * r0

    def effective_radius(self, fz: float, omega: float = 0.0) -> float:
        """[B] eq. 7 with the pressure-corrected C_z of eq. 5."""
        c = self.c
        r0, fz0 = c('UNLOADED_RADIUS'), c('FNOMIN')
        dpi = (self.p - self.p0) / self.p0
        v0 = self.props.number('MODEL', 'LONGVL')
        cz = c('VERTICAL_STIFFNESS') * (1 + c('PFZ1') * dpi)
        r_omega = r0 * (c('Q_RE0') + c('Q_V1') * (omega * r0 / v0) ** 2)
        return r_omega - fz0 / cz * (c('DREFF') * math.atan(c('BREFF') * fz / fz0)
                                     + c('FREFF') * fz / fz0)

    def relaxation(self, fz: float, gamma: float) -> tuple[float, float]:
        """|Kxk| / Cx and |Kya| / Cy ([B] eqs. 17-19)."""
        c, lam = self.c, self.lam
        fz0p = c('FNOMIN') * lam('LFZO')
        dfz = (fz - fz0p) / fz0p
        dpi = (self.p - self.p0) / self.p0
        kxk = (fz * (c('PKX1') + c('PKX2') * dfz) * math.exp(c('PKX3') * dfz)
               * (1 + c('PPX1') * dpi + c('PPX2') * dpi ** 2) * lam('LKX'))
        kya = (c('PKY1') * fz0p * (1 + c('PPY1') * dpi) * (1 - c('PKY3') * abs(gamma))
               * math.sin(c('PKY4') * math.atan(
                   fz / ((c('PKY2') + c('PKY5') * gamma ** 2) * (1 + c('PPY2') * dpi) * fz0p)))
               * lam('LKY'))
        cx = c('LONGITUDINAL_STIFFNESS') * (1 + c('PCFX1') * dfz + c('PCFX2') * dfz ** 2) \
            * (1 + c('PCFX3') * dpi)
        cy = c('LATERAL_STIFFNESS') * (1 + c('PCFY1') * dfz + c('PCFY2') * dfz ** 2) \
            * (1 + c('PCFY3') * dpi)
        return abs(kxk) / cx, abs(kya) / cy
