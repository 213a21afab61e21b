"""Fit the thesis' simple tire (eqs. 6-9) to a PAC2002 Magic Formula.

Over ``n`` loads evenly spread across ``fz_range``, with the reference load
fz0 = the middle of the range (so the linear load terms are centred where the
fit is used, not at FNOMIN LFZO, which may lie outside it):

* mu0, mu1: least-squares line mu_y(Fz) = mu0 (1 - mu1 (Fz - fz0)) (eq. 6)
  through :meth:`MagicFormula.peak_lateral_friction` at zero camber. PAC2002's
  mu_y is linear in Fz, so this reproduces it exactly.
* c0, c1: least squares of the cornering stiffness, in N/rad,
  C(Fz) = c0 Fz (1 - c1 (Fz - fz0)) (eq. 7), which is linear in the unknowns
  (c0, c0 c1). The data are the slope of :meth:`MagicFormula.fy_iso` at zero
  slip (= -:meth:`MagicFormula.cornering_stiffness`), so c0 > 0 in the
  convention of :class:`SimpleTire`.
* shape = C_y = PCY1 LCY.
* curvature = E_y at fz0 and zero camber, the part even in the slip
  ((PEY1 + PEY2 dfz) LEY, the mean of both sgn(alpha) branches, since the
  simple tire is odd in alpha), clipped to <= 1.

The simple tire has no shifts: PHY*, PVY* and the PEY3/PEY4 asymmetry are
dropped by construction.
"""

from __future__ import annotations

from pathlib import Path
from typing import Final

import numpy as np

from vd_solvers.errors import SolverError
from vd_solvers.tire.magic_formula import MagicFormula
from vd_solvers.tire.simple import SimpleTire

__all__ = ["fit_simple_tire"]

# Two unknowns per fitted line need at least two loads.
_MIN_POINTS: Final[int] = 2


def fit_simple_tire(mf: MagicFormula, fz_range: tuple[float, float], n: int = 20) -> SimpleTire:
    """SimpleTire fitted to ``mf`` over loads ``fz_range`` = (low, high), N (see module doc)."""
    low, high = (float(v) for v in fz_range)
    if not 0.0 < low < high:
        raise ValueError(f"fz_range must satisfy 0 < low < high, got {fz_range!r}")
    if n < _MIN_POINTS:
        raise ValueError(f"n must be at least {_MIN_POINTS}, got {n}")
    fz = np.linspace(low, high, n)
    fz0 = 0.5 * (low + high)
    dfz = fz - fz0

    mu_slope, mu0 = np.polyfit(dfz, mf.peak_lateral_friction(fz), 1)

    stiffness = -mf.cornering_stiffness(fz)
    (c0, c0_c1), *_ = np.linalg.lstsq(np.column_stack((fz, fz * dfz)), stiffness, rcond=None)
    if c0 <= 0.0:
        raise SolverError(
            f"{mf.props.path}: cornering stiffness of fy_iso fitted as c0 = {c0:g} 1/rad, not > 0; "
            "the file's PKY1 should be negative (TYDEX convention)"
        )

    name = Path(mf.props.path).name
    return SimpleTire(
        mu0=float(mu0),
        mu1=float(-mu_slope / mu0),
        fz0=fz0,
        c0=float(c0),
        c1=float(-c0_c1 / c0),
        shape=mf.lateral_shape_factor,
        curvature=float(mf.lateral_curvature(fz0)),
        source=f"{name} ({mf.props.file_format}): least-squares fit over Fz {low:g}..{high:g} N, n={n}",
    )
