# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Six-direction bushings: frame, deflection measures and mirroring.

A bushing joins part a (inboard, usually the body) and part b at one hard
point. Its frame (e1, e2, e3) is fixed to a; b carries a copy (f1, f2, f3)
that coincides with it in the design pose. Deflections, in the bushing frame:

* translation  d_k = (r_b - r_a) . e_k                       (m)
* rotation     phi_1 = (e3.f2 - e2.f3)/2, cyclic              (rad)

The rotation measure is the small-angle relative rotation vector (exact to
O(phi^3): 0.1 % at 3 deg), as in Adams' BUSHING element. Each direction has
its own potential (linear rate or force-deflection curve), so a linear bushing
stores V = sum(k_i * d_i^2)/2.

Frame: the vehicle axes by default; with an axial direction the bushing's
local z is that axis (Adams convention) and local x the vehicle axis least
aligned with it, orthogonalised.

Right side: the frame is mirrored into a right-handed one
(M e1, -M e2, M e3) with M = diag(1, -1, 1). Measured deflections are then
multiplied by ``MIRROR_SIGNS`` so a mirror-symmetric motion gives equal
left and right channels (and non-symmetric curves act mirror-symmetrically).
"""
from __future__ import annotations

import numpy as np

from .joints import Primitive, PrimKind, perpendicular_basis, point, unit, vector
from .model import Side, mirror

MIRROR_SIGNS = np.array([1.0, -1.0, 1.0, -1.0, 1.0, -1.0])

# Small-angle rotation about e_i: (e_k . f_j - e_j . f_k)/2 with (i, j, k) cyclic.
_ROTATION_PAIRS = ((0, 1, 2), (1, 2, 0), (2, 0, 1))

Measure = list[tuple[Primitive, float]]


def bushing_frame(axial: np.ndarray | None) -> np.ndarray:
    """Left-side bushing frame, columns (e1, e2, e3) in the vehicle frame (3, 3)."""
    if axial is None:
        return np.eye(3)
    e3 = unit(np.asarray(axial, dtype=float), 'bushing axial direction')
    e1, e2 = perpendicular_basis(e3)
    return np.column_stack((e1, e2, e3))


def side_frame(left_frame: np.ndarray, side: Side) -> tuple[np.ndarray, np.ndarray]:
    """Frame (3, 3) and measure signs (6,) of the bushing on ``side``."""
    if side == 'left':
        return left_frame, np.ones(6)
    e1, e2, e3 = (mirror(left_frame[:, k], 'right') for k in range(3))
    return np.column_stack((e1, -e2, e3)), MIRROR_SIGNS


def bushing_measures(
    part_a: str, part_b: str, at: np.ndarray, frame: np.ndarray, signs: np.ndarray
) -> list[Measure]:
    """Return the six deflection measures (x, y, z, rx, ry, rz) as primitive combinations."""
    ra, rb = point(part_a, at), point(part_b, at)
    e = [vector(part_a, frame[:, k]) for k in range(3)]
    f = [vector(part_b, frame[:, k]) for k in range(3)]
    measures: list[Measure] = [
        [(Primitive(PrimKind.DDOT, (ra, rb, e[k])), float(signs[k]))] for k in range(3)
    ]
    for i, j, k in _ROTATION_PAIRS:
        s = 0.5 * float(signs[3 + i])
        measures.append(
            [
                (Primitive(PrimKind.DOT, (e[k], f[j])), s),
                (Primitive(PrimKind.DOT, (e[j], f[k])), -s),
            ]
        )
    return measures
