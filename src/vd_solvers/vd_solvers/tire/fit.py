# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Fit the thesis' simple tire (eqs. 6-9) to a PAC2002 Magic Formula.

Over ``n`` loads evenly spread across ``fz_range``, with the reference load
fz0 = the middle of the range (so the linear load terms are centred where the
fit is used, not at FNOMIN LFZO, which may lie outside it):

Both lines pass exactly through the Magic Formula's values at fz0 (the
static wheel load where the bicycle model uses the tire); only the slopes are
fitted over the range:

* mu0, mu1: mu0 = :meth:`MagicFormula.peak_lateral_friction` at fz0 and zero
  camber; mu1 from the least-squares slope of mu_y(Fz) = mu0 (1 - mu1 (Fz -
  fz0)) (eq. 6) through that point. PAC2002's mu_y is linear in Fz, so the
  line reproduces it everywhere.
* c0, c1: c0 fz0 = the Magic Formula's cornering stiffness at fz0, in N/rad;
  c1 from least squares of C(Fz) = c0 Fz (1 - c1 (Fz - fz0)) (eq. 7), linear in
  c0 c1 once c0 is fixed. The data are the slope of :meth:`MagicFormula.fy_iso`
  at zero slip (= -:meth:`MagicFormula.cornering_stiffness`), so c0 > 0 in the
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

__all__ = ['fit_simple_tire']

# Two unknowns per fitted line need at least two loads.
_MIN_POINTS: Final[int] = 2


def fit_simple_tire(mf: MagicFormula, fz_range: tuple[float, float], n: int = 20) -> SimpleTire:
    """SimpleTire fitted to ``mf`` over loads ``fz_range`` = (low, high), N (see module doc)."""
    low, high = (float(v) for v in fz_range)
    if not 0.0 < low < high:
        raise ValueError(f'fz_range must satisfy 0 < low < high, got {fz_range!r}')
    if n < _MIN_POINTS:
        raise ValueError(f'n must be at least {_MIN_POINTS}, got {n}')
    fz = np.linspace(low, high, n)
    fz0 = 0.5 * (low + high)
    dfz = fz - fz0

    mu0 = float(mf.peak_lateral_friction(fz0))
    mu_slope = _slope_through(dfz, mf.peak_lateral_friction(fz) - mu0)

    c0 = float(-mf.cornering_stiffness(fz0)) / fz0
    # C(Fz) - c0 Fz = -(c0 c1) Fz dfz
    c0_c1 = -_slope_through(fz * dfz, -mf.cornering_stiffness(fz) - c0 * fz)
    if c0 <= 0.0:
        raise SolverError(
            f'{mf.props.path}: cornering stiffness of fy_iso fitted as c0 = {c0:g} 1/rad, '
            "not > 0; the file's PKY1 should be negative (TYDEX convention)"
        )

    name = Path(mf.props.path).name
    return SimpleTire(
        mu0=float(mu0),
        mu1=float(-mu_slope / mu0),
        fz0=fz0,
        c0=float(c0),
        c1=float(c0_c1 / c0),
        shape=mf.lateral_shape_factor,
        curvature=float(mf.lateral_curvature(fz0)),
        source=f'{name} ({mf.props.file_format}): exact at Fz {fz0:g} N, slopes fitted over '
        f'{low:g}..{high:g} N, n={n}',
    )


def _slope_through(x: np.ndarray, y: np.ndarray) -> float:
    """Least-squares slope k of y = k x (a line through the origin)."""
    return float(np.dot(x, y) / np.dot(x, x))
