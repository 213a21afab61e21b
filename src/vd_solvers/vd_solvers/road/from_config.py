# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The road of a configuration: its ``road`` group (schema ``road``) as a surface and a grid.

Without a ``road`` group a configuration drives on the flat road of friction 1. The
straight roads (ISO 8608, obstacle) run along earth +x from x = 0, where the vehicle's
front axle starts; an OpenCRG road is where its file puts it. The grid covers the road's
length (an ISO 8608 road blended in from flat over its first FADE_IN m, so that the vehicle
set up on flat ground meets it without a step) and the lanes the vehicle can reach.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from vd_data_server.model import Configuration
from vd_solvers.vehicle_data import wheel_centres

from .arrays import RoadGrid, flat, road_grid
from .crg import CrgSurface, read_crg
from .iso8608 import random_road
from .obstacles import obstacle_road
from .surface import TrackProfile

#: m of an ISO 8608 road blended in from flat
FADE_IN = 10.0
#: grid spacing along the road (m) of the straight roads; obstacles finer
SPACING = 0.05
OBSTACLE_SPACING = 0.005
#: lateral half-width of the grid of a straight road beyond its tracks, m
MARGIN = 3.0


def road_surface(config: Configuration, data_root: Path | None = None
                 ) -> TrackProfile | CrgSurface | None:
    """Return the configuration's road surface (None: the flat road); DataError for a bad file."""
    if 'road' not in config.groups:
        return None
    g = config.group('road')
    kind = g.text('surface')
    friction = g.scalar('friction')
    track = float(abs(wheel_centres(config)[0, 1]) * 2.0)
    if kind == 'flat':
        return None
    if kind == 'iso8608':
        return random_road(g.text('road_class'), g.scalar('length'), track,
                           int(g.scalar('seed')), SPACING,
                           g.text('tracks') if g.has('tracks') else 'parallel', friction)
    if kind == 'obstacle':
        return obstacle_road(g.text('obstacle'), g.scalar('height'), g.scalar('obstacle_length'),
                             g.scalar('start'), g.scalar('length'), track,
                             g.text('side') if g.has('side') else 'both', OBSTACLE_SPACING,
                             friction)
    root = data_root if data_root is not None else _data_root(config)
    return read_crg(root / g.text('file'), friction)


def road_of(config: Configuration, data_root: Path | None = None) -> RoadGrid:
    """Return the configuration's road as the compiled evaluation's grids (module doc)."""
    g = config.group('road') if 'road' in config.groups else None
    friction = g.scalar('friction') if g is not None else 1.0
    left = g.scalar('friction_left') if g is not None and g.has('friction_left') else None
    surface = road_surface(config, data_root)
    if surface is None:
        return flat(friction, left)
    if isinstance(surface, CrgSurface):  # OpenCRG: its own extent and increments
        road = surface.road
        x0, x1, y0, y1 = _crg_box(road)
        step = min(float(road.u_inc), float(road.v_inc), 2.0 * SPACING)
        return road_grid(surface, x0, x1, y0, y1, step, step, left)
    length = float(surface.length)
    half = 0.5 * float(surface.track_width) + MARGIN
    spacing = OBSTACLE_SPACING if g is not None and g.text('surface') == 'obstacle' else SPACING
    fade = FADE_IN if g is not None and g.text('surface') == 'iso8608' else 0.0
    return road_grid(surface, 0.0, length, -half, half, spacing, 2.0 * half / 8.0, left,
                     fade_in=fade)


def _crg_box(road) -> tuple[float, float, float, float]:
    """Return the earth-frame bounding box of an OpenCRG road's grid, m."""
    u = np.linspace(float(road.u_start), float(road.u_end), 201)
    xs, ys = [], []
    for v in (float(road.v_min), float(road.v_max)):
        x, y = road.uv_to_xy(u, np.full_like(u, v))
        xs.append(np.asarray(x, dtype=float))
        ys.append(np.asarray(y, dtype=float))
    x_all, y_all = np.concatenate(xs), np.concatenate(ys)
    return float(x_all.min()), float(x_all.max()), float(y_all.min()), float(y_all.max())


def _data_root(config: Configuration) -> Path:
    """Return the data root of the configuration's master file (its study's ``data_root``)."""
    from vd_data_server.master import load_master  # noqa: PLC0415
    return load_master(Path(config.master_file)).data_root


__all__ = ['road_surface', 'road_of', 'FADE_IN', 'SPACING', 'OBSTACLE_SPACING']
