# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The thesis' load-dependent simple tire (eqs. 6-9).

mu(Fz)   = mu0 * (1 - mu1 * (Fz - Fz0))                      (6)
C_Fa(Fz) = C0 * Fz * (1 - C1 * (Fz - Fz0))                     (7)
B        = C_Fa / (mu * C * Fz)                               (8)
Fy       = mu * Fz * sin(C * arctan(B a - E (B a - arctan(B a))))  (9)

All quantities SI: forces N, slip angle rad, C0 in 1/rad, C1 and mu1 in 1/N.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike


@dataclass(frozen=True)
class SimpleTire:
    """Parameters of eqs. 6-9 for one tire (one axle)."""

    mu0: float  # peak friction coefficient at the nominal load, -
    mu1: float  # friction load sensitivity, 1/N
    fz0: float  # nominal load, N
    c0: float  # cornering stiffness per unit load at fz0, 1/rad
    c1: float  # cornering stiffness load sensitivity, 1/N
    shape: float  # Magic Formula shape factor C, -
    curvature: float  # Magic Formula curvature factor E, -
    source: str = ''  # where the numbers came from (file, fit range)

    def friction(self, fz: ArrayLike) -> np.ndarray:
        """Peak friction coefficient at load ``fz`` (eq. 6)."""
        return self.mu0 * (1.0 - self.mu1 * (np.asarray(fz, dtype=float) - self.fz0))

    def cornering_stiffness(self, fz: ArrayLike) -> np.ndarray:
        """Cornering stiffness dFy/dalpha at zero slip, N/rad (eq. 7)."""
        fz = np.asarray(fz, dtype=float)
        return self.c0 * fz * (1.0 - self.c1 * (fz - self.fz0))

    def lateral_force(self, fz: ArrayLike, alpha: ArrayLike) -> np.ndarray:
        """
        Lateral force magnitude for slip angle ``alpha`` (rad), eqs. 8-9.

        Sign follows ``alpha``: a positive slip angle gives a positive force.
        """
        fz = np.asarray(fz, dtype=float)
        alpha = np.asarray(alpha, dtype=float)
        mu = self.friction(fz)
        b = self.cornering_stiffness(fz) / (mu * self.shape * fz)
        ba = b * alpha
        return mu * fz * np.sin(self.shape * np.arctan(ba - self.curvature * (ba - np.arctan(ba))))
