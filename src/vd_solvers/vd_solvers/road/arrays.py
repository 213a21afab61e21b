# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
A road surface as the constant arrays of the compiled force evaluation.

:func:`road_grid` samples a surface's height on a regular grid over the earth plane (the
compiled evaluation interpolates it bilinearly and holds it beyond the border,
:func:`vd_solvers.vehicle.forces.grid_value`) and lays out the friction factor as a second
grid: uniform, or split along y = ``split_y`` (``friction_left`` for y above it, ISO 8855
y to the left) over a transition of SPLIT_TRANSITION m. ``fade_in`` blends the heights in
from zero over the first metres of the grid so that a vehicle set up on flat ground meets
the road without a step. :data:`FLAT` is the flat road of friction 1: every operation of
the contact then gives exactly the flat-road values.
"""
from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from .surface import Surface

#: width of the friction change of a split-friction road, m
SPLIT_TRANSITION = 0.05


class RoadGrid(NamedTuple):
    """The road of one run: grids, their axes (forces.ROAD_AXES) and what the road is."""

    axes: np.ndarray  # (8,)
    height: np.ndarray  # (nx, ny), m
    friction: np.ndarray  # (mx, my)
    description: str


def friction_grid(friction: float, friction_left: float | None = None,
                  split_y: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """(axes (4,), grid) of a uniform or a split friction factor."""
    if friction_left is None or friction_left == friction:
        return np.array([0.0, 0.0, 1.0, 1.0]), np.full((2, 2), float(friction))
    axes = np.array([0.0, split_y - 0.5 * SPLIT_TRANSITION, 1.0, SPLIT_TRANSITION])
    return axes, np.array([[friction, friction_left], [friction, friction_left]], dtype=float)


def road_grid(surface: Surface, x0: float, x1: float, y0: float, y1: float, dx: float,
              dy: float, friction_left: float | None = None, split_y: float = 0.0,
              fade_in: float = 0.0) -> RoadGrid:
    """Sample ``surface`` over [x0, x1] x [y0, y1] at spacings dx, dy (module doc)."""
    if not (x1 > x0 and y1 > y0 and dx > 0.0 and dy > 0.0):
        raise ValueError('a road grid needs x1 > x0, y1 > y0 and positive spacings')
    nx = max(2, int(math.ceil((x1 - x0) / dx)) + 1)
    ny = max(2, int(math.ceil((y1 - y0) / dy)) + 1)
    xs = x0 + dx * np.arange(nx)
    ys = y0 + dy * np.arange(ny)
    heights = np.asarray(surface.height(xs[:, None], ys[None, :]), dtype=float)
    if fade_in > 0.0:
        ramp = np.clip((xs - x0) / fade_in, 0.0, 1.0)
        heights = heights * (0.5 - 0.5 * np.cos(math.pi * ramp))[:, None]
    f_axes, f_grid = friction_grid(surface.friction, friction_left, split_y)
    axes = np.concatenate([[x0, y0, dx, dy], f_axes])
    return RoadGrid(np.ascontiguousarray(axes), np.ascontiguousarray(heights),
                    np.ascontiguousarray(f_grid), surface.description)


def flat(friction: float = 1.0, friction_left: float | None = None,
         split_y: float = 0.0) -> RoadGrid:
    """Return the flat road z = 0 with a uniform or split friction factor."""
    f_axes, f_grid = friction_grid(friction, friction_left, split_y)
    what = (f'flat road, friction {friction:g}' if f_grid[0, 0] == f_grid[0, 1] else
            f'flat road, friction {friction:g} right / {friction_left:g} left of y = '
            f'{split_y:g} m')
    return RoadGrid(np.concatenate([[0.0, 0.0, 1.0, 1.0], f_axes]), np.zeros((2, 2)),
                    f_grid, what)


#: the flat road of friction 1 (the tires as measured)
FLAT = flat()

__all__ = ['RoadGrid', 'road_grid', 'flat', 'friction_grid', 'FLAT', 'SPLIT_TRANSITION']
