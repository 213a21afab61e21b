# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
ASAM OpenCRG road surfaces (``.crg``), read with ``pyopencrg``.

OpenCRG describes a road as a reference line (x, y, heading, slope, banking along u) and a
regular grid of heights over (u, v), v to the left of the line; heights between grid
points are bilinear. ``pyopencrg`` reads every OpenCRG data format (KRBI, KDBI, LRFI,
LDFI), checks the file's consistency and maps earth (x, y) to (u, v) and the height.
Outside the grid the surface keeps its border heights (OpenCRG's default extension).

A file that cannot be read or fails the reader's checks is a ``DataError`` naming the
file. The surface names itself by file name and content hash (``description``).
"""
from __future__ import annotations

from dataclasses import dataclass
import hashlib
from pathlib import Path
from typing import Any
import warnings

import numpy as np
from numpy.typing import ArrayLike
import pyopencrg

from vd_data_server.errors import DataError


@dataclass(frozen=True)
class CrgSurface:
    """An OpenCRG road: height at earth (x, y) and the road's friction scale."""

    road: Any  # pyopencrg.CrgRoad
    friction: float
    description: str

    def height(self, x: ArrayLike, y: ArrayLike) -> np.ndarray:
        """Height z (m) at earth-frame points (x, y) (m)."""
        xs, ys = np.broadcast_arrays(np.asarray(x, dtype=float), np.asarray(y, dtype=float))
        return np.asarray(self.road.xy_to_z(xs, ys), dtype=float).reshape(xs.shape)

    @property
    def length(self) -> float:
        """Length of the reference line, m."""
        return float(self.road.length)


def read_crg(path: str | Path, friction: float = 1.0) -> CrgSurface:
    """Read an OpenCRG file; a DataError naming the file when it is not a valid one."""
    path = Path(path)
    try:
        content = path.read_bytes()
    except OSError as err:
        raise DataError(f'cannot read the road file: {err.strerror or err}',
                        file=str(path)) from None
    if not friction > 0.0:
        raise DataError(f'the road friction scale must be positive (got {friction})',
                        file=str(path))
    with warnings.catch_warnings():
        warnings.simplefilter('error', pyopencrg.CrgCheckWarning)
        try:
            road = pyopencrg.read(str(path), check=True)
        except Exception as err:  # noqa: BLE001 - the reader's errors on a foreign file
            reason = str(err).strip().splitlines()[0] if str(err).strip() else type(err).__name__
            raise DataError(f'not a valid OpenCRG road file: {reason}', file=str(path)) from None
    z = np.asarray(road.z, dtype=float)
    if np.isinf(z).any() or not np.isfinite(z).any():
        raise DataError('not a valid OpenCRG road file: no finite heights', file=str(path))
    digest = hashlib.sha256(content).hexdigest()[:16]
    return CrgSurface(road, float(friction),
                      f'OpenCRG {path.name} (sha256 {digest}), {float(road.length):g} m')


__all__ = ['CrgSurface', 'read_crg']
