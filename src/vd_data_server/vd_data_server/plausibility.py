# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Plausibility bounds of vehicle data (docs/data-format.md, "Plausibility bounds").

Two levels, both in SI after unit conversion:

* **errors** (:data:`LIMITS`): values no road vehicle can have - a hard point
  10 m from the origin, a sprung mass of 1e300 kg. Loading stops, as for any
  other bad value; the models never see such data.
* **warnings** (:data:`USUAL`): values that are possible but unusual for a car
  (a camber of 8 deg, a hard point 5 m from the origin). They are reported by
  ``vd data check`` and do not stop anything.

The bounds are generous on purpose: they catch typing and unit mistakes
(``mm`` read as ``m``, a missing exponent sign), not design choices.
"""
from __future__ import annotations

from collections.abc import Mapping
import math

from .errors import DataError
from .units import SI_UNITS

#: quantity -> (smallest magnitude of a non-zero value, largest magnitude), SI
LIMITS: Mapping[str, tuple[float, float]] = {
    'length': (0.0, 20.0),
    'road_length': (0.0, 1e5),  # along a road (its length, an obstacle's place)
    'angle': (0.0, math.pi),
    'force': (0.0, 1e7),
    'mass': (0.01, 1e5),  # a drop link or tie rod weighs under 1 kg
    'time': (0.0, 1e6),
    'velocity': (0.0, 1e3),
    'stiffness': (0.0, 1e10),
    'damping': (0.0, 1e8),
    'torsional_stiffness': (0.0, 1e9),
    'torsional_damping': (0.0, 1e8),
    'torque': (0.0, 1e7),
    'inertia': (0.0, 1e6),
    'pressure': (0.0, 1e12),
    'rack_ratio': (0.0, 1.0),
    'acceleration': (0.0, 1e4),
    'frequency': (0.0, 1e6),
    'angular_velocity': (0.0, 1e5),
    'dimensionless': (0.0, 1e6),
}
#: largest distance of a hard point or centre of gravity from the origin (m, per
#: coordinate): the origin is on the ground under the front axle centre
POINT_LIMIT = 8.0
#: quantity -> (lowest, highest) usual value for a car, SI; outside: a warning
USUAL: Mapping[str, tuple[float, float]] = {
    'angle': (-math.radians(10.0), math.radians(10.0)),
    'mass': (0.1, 2e4),
}
#: usual largest coordinate of a hard point, m
POINT_USUAL = 4.0


def check_scalar(si: float, quantity: str, *, file: str, key: str, raw: object) -> None:
    """Raise DataError for a value outside :data:`LIMITS` of its quantity."""
    low, high = LIMITS.get(quantity, (0.0, math.inf))
    size = abs(si)
    if size > high or (0.0 < size < low):
        bound = f'from {low:g} to {high:g}' if low > 0.0 else f'at most {high:g}'
        raise DataError(f'{_shown(raw)} is implausible: its size must be {bound} '
                        f'{_si(quantity)} (plausibility bound)', file=file, key=key)


def check_point(xyz: tuple[float, float, float], *, file: str, key: str, raw: object) -> None:
    """Raise DataError for a point with a coordinate beyond :data:`POINT_LIMIT`."""
    if any(abs(c) > POINT_LIMIT for c in xyz):
        raise DataError(f'{_shown(raw)} is implausible: every coordinate must be within '
                        f'{POINT_LIMIT:g} m of the origin (plausibility bound)', file=file,
                        key=key)


def unusual_scalar(si: float, quantity: str) -> str | None:
    """Return a warning text for a possible but unusual value, None if it is usual."""
    if quantity not in USUAL:
        return None
    low, high = USUAL[quantity]
    if low <= si <= high:
        return None
    return f'{si:g} {_si(quantity)} is unusual for a car (usual: {low:g} to {high:g})'


def unusual_point(xyz: tuple[float, float, float]) -> str | None:
    if all(abs(c) <= POINT_USUAL for c in xyz):
        return None
    return (f"[{', '.join(f'{c:g}' for c in xyz)}] m is unusual for a car (usual: within "
            f"{POINT_USUAL:g} m of the origin)")


def _si(quantity: str) -> str:
    return SI_UNITS.get(quantity, '') or '-'


def _shown(raw: object) -> str:
    text = repr(raw)
    return text if len(text) <= 60 else text[:57] + '...'
