"""PAC2002 (MF-Tyre 5.2) steady-state pure-slip Magic Formula.

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

Coefficients absent from the file are 0 and scaling factors 1, as in MF-Tyre.
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
from typing import Final

import numpy as np
from numpy.typing import ArrayLike

from vd_data_server.errors import DataError
from vd_data_server.tir import TireProperties
from vd_solvers.errors import SolverError

__all__ = ["MagicFormula"]

# Formats whose pure-slip equations are the PAC2002 ones above.
_SUPPORTED_FORMATS: Final[frozenset[str]] = frozenset({"PAC2002", "MF52"})
# Coefficients used here, per block; absent ones are 0 (MF-Tyre default).
_COEFFICIENTS: Final[Mapping[str, tuple[str, ...]]] = MappingProxyType(
    {
        "LONGITUDINAL_COEFFICIENTS": (
            "PCX1", "PDX1", "PDX2", "PDX3", "PEX1", "PEX2", "PEX3", "PEX4",
            "PKX1", "PKX2", "PKX3", "PHX1", "PHX2", "PVX1", "PVX2",
        ),
        "LATERAL_COEFFICIENTS": (
            "PCY1", "PDY1", "PDY2", "PDY3", "PEY1", "PEY2", "PEY3", "PEY4",
            "PKY1", "PKY2", "PKY3", "PHY1", "PHY2", "PHY3", "PVY1", "PVY2", "PVY3", "PVY4",
        ),
    }
)  # fmt: skip
# Scaling factors used here; absent ones are 1 (MF-Tyre default).
_SCALING_FACTORS: Final[tuple[str, ...]] = (
    "LFZO", "LCX", "LMUX", "LEX", "LKX", "LHX", "LVX", "LGAX",
    "LCY", "LMUY", "LEY", "LKY", "LHY", "LVY", "LGAY",
)  # fmt: skip
# E <= 1 (Pacejka 4.E14, 4.E24): beyond it B x - E (B x - atan B x) falls again
# at large x and the curve loses its single peak.
_MAX_CURVATURE: Final[float] = 1.0
_SIDES: Final[tuple[str, ...]] = ("LEFT", "RIGHT")
# Loads (x the scaled nominal load) and slips at which a tire must give finite forces.
_CHECK_LOADS: Final[tuple[float, ...]] = (0.1, 0.5, 1.0, 2.0, 3.0)
_CHECK_SLIPS: Final[tuple[float, ...]] = (-0.5, -0.05, 0.0, 0.05, 0.5)


@dataclass(frozen=True)
class _Curve:
    """Factors of one pure-slip curve F(x) = D sin(C atan(B x - E (B x - atan B x))) + SV.

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
    """Steady-state pure-slip PAC2002 forces of one tire (see module doc).

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
                f"{props.path}: MagicFormula evaluates PAC2002 / MF 5.2 files, this one is {props.file_format}"
            )
        coefficients = {
            name: props.number(block, name, 0.0) for block, names in _COEFFICIENTS.items() for name in names
        }
        coefficients.update({name: props.number("SCALING_COEFFICIENTS", name, 1.0) for name in _SCALING_FACTORS})
        # LFZO > 0 and the divisors != 0 are checked where the properties are read
        # (vd_data_server.tir.check_values), so `vd data check` refuses what a run would
        coefficients["FZ0_PRIME"] = props.fnomin * coefficients["LFZO"]
        # Frozen dataclass: derived fields are set once, here.
        object.__setattr__(self, "_c", MappingProxyType(coefficients))
        object.__setattr__(self, "_mirror", -1.0 if self._mirrored() else 1.0)
        self._check_finite()

    def _check_finite(self) -> None:
        """Forces and stiffness must be finite over the working range: coefficients that
        are finite one by one can still overflow together (PKX3 = 3000 in exp(PKX3 dfz))."""
        fz = self.nominal_load * np.array(_CHECK_LOADS)
        slip = np.array(_CHECK_SLIPS)[:, None]
        with np.errstate(all="ignore"):
            values = (self.fy(fz, slip), self.fx(fz, slip), self.cornering_stiffness(fz))
        for name, value in zip(("Fy", "Fx", "cornering stiffness"), values):
            if not np.all(np.isfinite(value)):
                raise DataError(
                    f"the Magic Formula gives a non-finite {name} within {_CHECK_LOADS[0]:g}.."
                    f"{_CHECK_LOADS[-1]:g} x the nominal load: coefficients out of range",
                    file=self.props.path,
                )

    def _mirrored(self) -> bool:
        """True if the tire is mounted on the side opposite to TYRESIDE."""
        if self.side is None:
            return False
        wanted = self.side.upper()
        if wanted not in _SIDES:
            raise ValueError(f"side must be 'LEFT' or 'RIGHT', got {self.side!r}")
        measured = self.props.get("MODEL", "TYRESIDE")
        if not isinstance(measured, str) or measured.upper() not in _SIDES:
            raise DataError(
                f"key 'TYRESIDE' in block [MODEL] must be 'LEFT' or 'RIGHT', found {measured!r}",
                file=self.props.path,
                key="TYRESIDE",
            )
        return wanted != measured.upper()

    @property
    def nominal_load(self) -> float:
        """Scaled nominal load Fz0' = FNOMIN LFZO, N."""
        return self._c["FZ0_PRIME"]

    @property
    def lateral_shape_factor(self) -> float:
        """C_y = PCY1 LCY, -."""
        return self._c["PCY1"] * self._c["LCY"]

    def fy(self, fz: ArrayLike, alpha: ArrayLike, gamma: ArrayLike = 0.0) -> np.ndarray:
        """Pure-slip lateral force Fy0, N, file (TYDEX) convention: alpha > 0 gives Fy < 0."""
        fz_, alpha_, gamma_ = _arrays(fz, alpha, gamma)
        s = self._mirror
        loaded, fz_eval = self._loaded(fz_)
        force = s * self._lateral(fz_eval, s * gamma_).force(s * alpha_)
        return np.where(loaded, force, 0.0)

    def fy_iso(self, fz: ArrayLike, alpha: ArrayLike, gamma: ArrayLike = 0.0) -> np.ndarray:
        """Lateral force, N, for the vehicle-dynamics slip angle alpha = -alpha_TYDEX.

        Positive alpha gives positive Fy (ISO y, left), as in SimpleTire.
        """
        return self.fy(fz, -np.asarray(alpha, dtype=float), gamma)

    def fx(self, fz: ArrayLike, kappa: ArrayLike, gamma: ArrayLike = 0.0) -> np.ndarray:
        """Pure-slip longitudinal force Fx0, N; kappa > 0 (driving) gives Fx > 0."""
        fz_, kappa_, gamma_ = _arrays(fz, kappa, gamma)
        loaded, fz_eval = self._loaded(fz_)
        return np.where(loaded, self._longitudinal(fz_eval, gamma_).force(kappa_), 0.0)

    def cornering_stiffness(self, fz: ArrayLike, gamma: ArrayLike = 0.0) -> np.ndarray:
        """dFy/dalpha at alpha = 0, N/rad, file convention (negative for PKY1 < 0).

        Exact derivative of :meth:`fy`, so it includes the horizontal shift SH_y;
        where SH_y = 0 it equals K_y = B C D of the Magic Formula.
        """
        fz_, gamma_ = _arrays(fz, gamma)
        loaded, fz_eval = self._loaded(fz_)
        # d/dalpha [s F(s alpha, s gamma)] = s^2 F'(s alpha, s gamma), and s^2 = 1.
        slope = self._lateral(fz_eval, self._mirror * gamma_).slope_at_zero_slip()
        return np.where(loaded, slope, 0.0)

    def peak_lateral_friction(self, fz: ArrayLike, gamma: ArrayLike = 0.0) -> np.ndarray:
        """mu_y = D_y / Fz, -: the peak of |Fy - SV_y| over alpha (reached for C_y > 1, E_y < 1) per load."""
        fz_, gamma_ = _arrays(fz, gamma)
        c = self._c
        dfz = (fz_ - c["FZ0_PRIME"]) / c["FZ0_PRIME"]
        gamma_y = gamma_ * c["LGAY"]
        return (c["PDY1"] + c["PDY2"] * dfz) * (1.0 - c["PDY3"] * gamma_y**2) * c["LMUY"]

    def lateral_curvature(self, fz: ArrayLike, gamma: ArrayLike = 0.0, slip_sign: ArrayLike = 0.0) -> np.ndarray:
        """Curvature factor E_y, -, for sgn(alpha_y) = ``slip_sign`` (file convention).

        ``slip_sign = 0`` gives the part even in the slip, (PEY1 + PEY2 dfz) LEY:
        the mean of the two branches, used for a symmetric (odd) fit.
        """
        fz_, gamma_, sign_ = _arrays(fz, gamma, slip_sign)
        s = self._mirror
        e_even, e_odd = self._lateral_curvature_terms(fz_, s * gamma_)
        return _curvature(e_even, e_odd, s * sign_)

    def _loaded(self, fz: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Mask of wheels on the ground, and loads safe to evaluate (no 0/0 off the ground)."""
        loaded = fz > 0.0
        return loaded, np.where(loaded, fz, self._c["FZ0_PRIME"])

    def _lateral(self, fz: np.ndarray, gamma: np.ndarray) -> _Curve:
        """Lateral factors as measured (PAC2002, Pacejka 4.E19-4.E30)."""
        c = self._c
        fz0 = c["FZ0_PRIME"]
        dfz = (fz - fz0) / fz0
        gamma_y = gamma * c["LGAY"]
        shape = c["PCY1"] * c["LCY"]
        peak = self.peak_lateral_friction(fz, gamma) * fz
        stiffness = (
            c["PKY1"] * fz0 * np.sin(2.0 * np.arctan(fz / (c["PKY2"] * fz0)))
            * (1.0 - c["PKY3"] * np.abs(gamma_y)) * c["LKY"]
        )  # fmt: skip
        e_even, e_odd = self._lateral_curvature_terms(fz, gamma)
        return _Curve(
            b=stiffness / (shape * peak),
            c=shape,
            d=peak,
            e_even=e_even,
            e_odd=e_odd,
            sh=(c["PHY1"] + c["PHY2"] * dfz) * c["LHY"] + c["PHY3"] * gamma_y,
            sv=fz * ((c["PVY1"] + c["PVY2"] * dfz) * c["LVY"] + (c["PVY3"] + c["PVY4"] * dfz) * gamma_y) * c["LMUY"],
        )

    def _lateral_curvature_terms(self, fz: np.ndarray, gamma: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """E_y = min(e_even (1 - e_odd sgn(alpha_y)), 1): returns (e_even, e_odd)."""
        c = self._c
        dfz = (fz - c["FZ0_PRIME"]) / c["FZ0_PRIME"]
        return (c["PEY1"] + c["PEY2"] * dfz) * c["LEY"], c["PEY3"] + c["PEY4"] * gamma * c["LGAY"]

    def _longitudinal(self, fz: np.ndarray, gamma: np.ndarray) -> _Curve:
        """Longitudinal factors (PAC2002, Pacejka 4.E9-4.E18)."""
        c = self._c
        fz0 = c["FZ0_PRIME"]
        dfz = (fz - fz0) / fz0
        gamma_x = gamma * c["LGAX"]
        shape = c["PCX1"] * c["LCX"]
        peak = (c["PDX1"] + c["PDX2"] * dfz) * (1.0 - c["PDX3"] * gamma_x**2) * c["LMUX"] * fz
        stiffness = fz * (c["PKX1"] + c["PKX2"] * dfz) * np.exp(c["PKX3"] * dfz) * c["LKX"]
        return _Curve(
            b=stiffness / (shape * peak),
            c=shape,
            d=peak,
            e_even=(c["PEX1"] + c["PEX2"] * dfz + c["PEX3"] * dfz**2) * c["LEX"],
            e_odd=np.full_like(fz, c["PEX4"]),
            sh=(c["PHX1"] + c["PHX2"] * dfz) * c["LHX"],
            sv=fz * (c["PVX1"] + c["PVX2"] * dfz) * c["LVX"] * c["LMUX"],
        )


def _curvature(e_even: np.ndarray, e_odd: np.ndarray, x: np.ndarray) -> np.ndarray:
    """E = min(e_even (1 - e_odd sgn(x)), 1)."""
    return np.minimum(e_even * (1.0 - e_odd * np.sign(x)), _MAX_CURVATURE)


def _arrays(*values: ArrayLike) -> tuple[np.ndarray, ...]:
    """Float arrays broadcast to one shape."""
    return tuple(np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in values)))
