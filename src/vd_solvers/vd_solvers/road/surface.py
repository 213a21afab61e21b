# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The surface protocol, the flat road and the straight road of two wheel-track profiles.

``TrackProfile`` is a straight road along the earth x axis: a height profile under the
left wheel track (y = +track_width / 2, ISO 8855 y to the left) and one under the right
(y = -track_width / 2), linear in x between samples and linear across between the tracks
(constant beyond them). Before its first and after its last sample the profile keeps its
end heights; ``length`` says how far the road reaches.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Protocol

import numpy as np
from numpy.typing import ArrayLike


class Surface(Protocol):
    """What a tire needs of the road: the ground height at (x, y) and the friction scale."""

    @property
    def friction(self) -> float:
        """Friction factor of the road (1: the tires as measured)."""
        ...

    @property
    def description(self) -> str:
        """What the road is (class and seed, obstacle, file and hash)."""
        ...

    def height(self, x: ArrayLike, y: ArrayLike) -> np.ndarray:
        """Ground height z (m) at earth-frame points (x, y) (m)."""
        ...


@dataclass(frozen=True)
class Flat:
    """The flat road z = 0 (``friction`` scales the tires' friction; 1 = as measured)."""

    friction: float = 1.0
    description: str = 'flat road'

    def height(self, x: ArrayLike, y: ArrayLike) -> np.ndarray:
        """Zero everywhere, in the broadcast shape of x and y."""
        return np.zeros(np.broadcast(np.asarray(x), np.asarray(y)).shape)


@dataclass(frozen=True)
class TrackProfile:
    """A straight road along +x with a height profile under each wheel track."""

    x: np.ndarray
    left: np.ndarray
    right: np.ndarray
    track_width: float
    friction: float = 1.0
    description: str = field(default='track profile')

    def __post_init__(self) -> None:
        x = np.asarray(self.x, dtype=float)
        left = np.asarray(self.left, dtype=float)
        right = np.asarray(self.right, dtype=float)
        if x.ndim != 1 or x.size < 2 or left.shape != x.shape or right.shape != x.shape:
            raise ValueError('a track profile needs x, left and right heights of one length '
                             '(at least two samples)')
        if not np.all(np.isfinite(x)) or not np.all(np.diff(x) > 0.0):
            raise ValueError('the profile positions x must be finite and increasing')
        if not (np.all(np.isfinite(left)) and np.all(np.isfinite(right))):
            raise ValueError('the profile heights must be finite')
        if not self.track_width > 0.0:
            raise ValueError(f'the track width must be positive (got {self.track_width} m)')
        if not self.friction > 0.0:
            raise ValueError(f'the road friction scale must be positive (got {self.friction})')
        object.__setattr__(self, 'x', x)
        object.__setattr__(self, 'left', left)
        object.__setattr__(self, 'right', right)

    @property
    def length(self) -> float:
        """Length of road the profile covers, m."""
        return float(self.x[-1] - self.x[0])

    def height(self, x: ArrayLike, y: ArrayLike) -> np.ndarray:
        """Height at (x, y): each track's profile at x, interpolated across in y."""
        xs, ys = np.broadcast_arrays(np.asarray(x, dtype=float), np.asarray(y, dtype=float))
        z_left = np.interp(xs, self.x, self.left)
        z_right = np.interp(xs, self.x, self.right)
        w = np.clip((ys + 0.5 * self.track_width) / self.track_width, 0.0, 1.0)
        return z_right + w * (z_left - z_right)


__all__ = ['Surface', 'Flat', 'TrackProfile']
