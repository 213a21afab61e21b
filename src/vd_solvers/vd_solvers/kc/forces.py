# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Elastic force elements as potentials of one scalar deflection.

Each element contributes V(delta) with delta = measure - reference, where
the measure is a length (springs, stops), a coordinate (gravity, rack), a
bushing deflection or the sine of the bar twist. The solver needs V, V' (the
element's generalised force) and V'' (its tangent stiffness); all are exact,
so the quasi-static equilibrium is a true stationary point and the elastic
energy can be checked against the work of the applied loads.

Conventions: a spring's or bump stop's *compression* force is positive;
``V' = dV/dL`` is then minus that force. Curves are piecewise linear
(:class:`~.model.Curve`), so V is exactly their integral.
"""
from __future__ import annotations

from dataclasses import dataclass
import functools
from typing import Protocol

import numpy as np

from vd_solvers.errors import SolverError

from .model import Curve, SpringSpec, Stiffness

Triple = tuple[np.ndarray, np.ndarray, np.ndarray]

# The sine of the bar twist is kept below this, i.e. twist below ~84 deg; a
# bar twisted further is far outside any suspension's travel.
_MAX_TWIST_SINE = 0.995


class EnergyLaw(Protocol):
    """Potential of ``size`` independent scalar deflections."""

    @property
    def size(self) -> int:
        """Return the number of deflections."""
        ...

    def evaluate(self, delta: np.ndarray) -> Triple:
        """V, dV/d(delta), d2V/d(delta)^2, each shaped like ``delta`` (size,)."""
        ...


@dataclass(frozen=True)
class LinearLaw:
    """
    V = f*delta + k*delta^2/2 for arrays ``stiffness`` k and ``force`` f.

    Gravity is k = 0, f = m*g on the height of a centre of mass; a preloaded
    linear element has f = its force at the reference.
    """

    stiffness: np.ndarray
    force: np.ndarray

    @property
    def size(self) -> int:
        return int(np.asarray(self.stiffness).size)

    def evaluate(self, delta: np.ndarray) -> Triple:
        k, f = self.stiffness, self.force
        return f * delta + 0.5 * k * delta * delta, f + k * delta, np.broadcast_to(k, delta.shape)


@dataclass(frozen=True)
class CurveLaw:
    """V = integral of ``curve`` from 0 to delta (non-linear bushing direction)."""

    curve: Curve
    size: int = 1

    def evaluate(self, delta: np.ndarray) -> Triple:
        return self.curve.evaluate(delta)


@dataclass(frozen=True)
class SpringLaw:
    """
    Coil spring on its length L; delta = L - L_design.

    The compression from the free length is c = c_design - delta and the
    compression force F(c) = rate*c or ``curve``(c).
    """

    design_compression: float
    rate: float | None = None
    curve: Curve | None = None
    size: int = 1

    def force(self, compression: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Compression force (N) and its slope dF/dc (N/m)."""
        if self.curve is not None:
            return self.curve.value(compression), self.curve.slope(compression)
        rate = self._rate()
        return rate * compression, np.full_like(compression, rate)

    def _work(self, compression: np.ndarray) -> np.ndarray:
        if self.curve is not None:
            return self.curve.integral(compression)
        return 0.5 * self._rate() * compression * compression

    def _rate(self) -> float:
        if self.rate is None:
            raise SolverError('internal: a spring law needs a rate or a curve')
        return float(self.rate)

    def evaluate(self, delta: np.ndarray) -> Triple:
        c = self.design_compression - delta
        if self.curve is not None:
            work, force, slope = self.curve.evaluate(c)  # one segment search for all three
        else:
            force, slope = self.force(c)
            work = self._work(c)
        return work - self._design_work, -force, slope

    @functools.cached_property
    def _design_work(self) -> np.ndarray:
        return self._work(np.array(self.design_compression))


def spring_law(spec: SpringSpec, design_length: float) -> SpringLaw:
    """
    Return the spring's law, its design compression found from free length or preload.

    Raises SolverError when a curve cannot deliver the requested preload.
    """
    if spec.free_length is not None:
        c_design = spec.free_length - design_length
    elif spec.rate is not None:
        c_design = (spec.preload or 0.0) / spec.rate
    else:
        curve = spec.curve
        assert curve is not None  # validated: exactly one of rate and curve
        preload = spec.preload or 0.0
        if np.any(np.diff(curve.y) <= 0.0):
            raise SolverError('spring curve must be strictly increasing to place a preload')
        # Invert the polyline (linear extrapolation beyond the ends, as value()).
        y, x = curve.y, curve.x
        i = int(np.clip(np.searchsorted(y, preload) - 1, 0, y.size - 2))
        c_design = float(x[i] + (preload - y[i]) * (x[i + 1] - x[i]) / (y[i + 1] - y[i]))
    return SpringLaw(c_design, spec.rate, spec.curve)


@dataclass(frozen=True)
class StopLaw:
    """
    Bump (``direction`` = -1) or rebound (+1) stop on a length, delta = L - L_design.

    The stop engages when direction*delta exceeds ``clearance``; its own
    compression s = direction*delta - clearance carries the force curve(s).
    A curve that starts beyond s = 0 is joined to (0, 0) by a straight line,
    so the force rises from zero at contact instead of being extrapolated.
    """

    curve: Curve
    clearance: float
    direction: float
    size: int = 1

    def __post_init__(self) -> None:
        c = self.curve
        if c.x[0] > 0.0:
            object.__setattr__(self, 'curve', Curve(np.r_[0.0, c.x], np.r_[0.0, c.y]))

    def evaluate(self, delta: np.ndarray) -> Triple:
        s = self.direction * delta - self.clearance
        engaged = s > 0.0
        if not np.any(engaged):
            zero = np.zeros_like(delta)
            return zero, zero, zero
        work, force, slope = self.curve.evaluate(np.where(engaged, s, 0.0))
        work, force, slope = (np.where(engaged, v, 0.0) for v in (work, force, slope))
        return work, self.direction * force, slope


@dataclass(frozen=True)
class TorsionLaw:
    """Torsion bar: delta = sin(twist), V = k*twist^2/2 with k in N*m/rad."""

    stiffness: float
    size: int = 1

    def evaluate(self, delta: np.ndarray) -> Triple:
        if np.any(np.abs(delta) > _MAX_TWIST_SINE):
            raise SolverError('anti-roll bar twisted beyond its range')
        k = self.stiffness
        twist = np.arcsin(delta)
        c2 = 1.0 - delta * delta
        d1 = k * twist / np.sqrt(c2)
        d2 = k * (1.0 / c2 + twist * delta / c2**1.5)
        return 0.5 * k * twist * twist, d1, d2


@dataclass(frozen=True, eq=False)
class MatrixLaw:
    """
    V = delta^T K delta / 2 with a full symmetric ``matrix`` K (n, n).

    The condensed stiffness of a flexible component on its deformation
    measures. ``evaluate`` returns the per-measure split delta_i (K delta)_i / 2
    of V (they sum to V), the exact gradient K delta and a zero diagonal: the
    coupled tangent K enters the Newton matrix through :attr:`matrix`.
    """

    matrix: np.ndarray

    @property
    def size(self) -> int:
        return int(self.matrix.shape[0])

    def evaluate(self, delta: np.ndarray) -> Triple:
        force = self.matrix @ delta
        return 0.5 * delta * force, force, np.zeros_like(delta)


def stiffness_law(stiffness: Stiffness) -> EnergyLaw:
    """Law of one bushing direction: linear rate or force-deflection curve."""
    if isinstance(stiffness, Curve):
        return CurveLaw(stiffness)
    return LinearLaw(np.array([float(stiffness)]), np.zeros(1))
