# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Single obstacles on an otherwise flat straight road: bump, pothole, kerb.

Shapes along the road (x from the obstacle's start, m):

* ``bump``: a cosine bump z = h (1 - cos(2 pi x / l)) / 2 over its length l (zero slope at
  both ends);
* ``pothole``: the same shape downwards, depth d (z = -d (1 - cos(2 pi x / l)) / 2);
* ``kerb``: a step up of height h reached by a straight ramp of length l (l = 0 is a sharp
  step over one sample spacing, which a point-contact tire meets as a jump; give the ramp
  the tire's contact-patch length or more).

``side`` puts the obstacle under both wheel tracks, the left or the right one.
"""
from __future__ import annotations

import math

import numpy as np

from .surface import TrackProfile

KINDS = ('bump', 'pothole', 'kerb')
SIDES = ('both', 'left', 'right')


def shape(kind: str, x: np.ndarray, height: float, length: float) -> np.ndarray:
    """Return the obstacle's height at x (m from its start)."""
    x = np.asarray(x, dtype=float)
    if kind in ('bump', 'pothole'):
        if not length > 0.0:
            raise ValueError(f'a {kind} needs a positive length (got {length} m)')
        inside = (x >= 0.0) & (x <= length)
        z = np.where(inside, 0.5 * height * (1.0 - np.cos(2.0 * math.pi * x / length)), 0.0)
        return -z if kind == 'pothole' else z
    if kind == 'kerb':
        if length < 0.0:
            raise ValueError(f'a kerb ramp cannot be negative (got {length} m)')
        if length == 0.0:
            return np.where(x >= 0.0, height, 0.0)
        return height * np.clip(x / length, 0.0, 1.0)
    raise ValueError(f"unknown obstacle '{kind}' (one of {', '.join(KINDS)})")


def obstacle_road(kind: str, height: float, length: float, start: float, road_length: float,
                  track_width: float, side: str = 'both', spacing: float = 0.005,
                  friction: float = 1.0) -> TrackProfile:
    """Build a flat straight road of ``road_length`` m with one obstacle from ``start`` m."""
    if side not in SIDES:
        raise ValueError(f"unknown obstacle side '{side}' (one of {', '.join(SIDES)})")
    if not height > 0.0:
        raise ValueError(f'an obstacle height (depth) must be positive (got {height} m)')
    if not 0.0 <= start < road_length:
        raise ValueError(f'the obstacle start ({start} m) must lie on the road '
                         f'(0..{road_length} m)')
    x = np.union1d(np.arange(0.0, road_length + 0.5 * spacing, spacing),
                   [start, start + length])
    x = x[x <= road_length]
    z = shape(kind, x - start, height, length)
    flat = np.zeros_like(z)
    left = z if side in ('both', 'left') else flat
    right = z if side in ('both', 'right') else flat
    what = 'depth' if kind == 'pothole' else 'height'
    return TrackProfile(x, left, right, track_width, friction,
                        f'{kind} of {what} {height:g} m and length {length:g} m at {start:g} m, '
                        f'{side} track{"s" if side == "both" else ""}')


__all__ = ['KINDS', 'SIDES', 'shape', 'obstacle_road']
