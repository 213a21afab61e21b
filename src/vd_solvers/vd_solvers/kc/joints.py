# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Kinematic primitives and the ideal joints built from them.

Every joint constraint and every elastic measure of the model is a linear
combination of five scalar *primitives* of markers -- points and unit vectors
fixed to parts (or to the ground, i.e. the vehicle body held by the rig):

======  =====================================  ===============================
kind    value                                  used for
======  =====================================  ===============================
COMP    c . (r_a - r_b), c a constant vector   spherical joints, gravity, rack
DOT     v_a . v_b                              axis alignment, bushing angles
DDOT    (r_b - r_a) . v_c                      in-line / sliding, bushing x y z
DIST    |r_a - r_b|                            links, springs, dampers
CPZ     r_z - rho * sqrt(1 - v_z^2)            contact-point height (pad)
======  =====================================  ===============================

For each primitive this module gives the value, the gradient with respect to
each marker's world quantity (3,) and the marker-level second derivatives.
The chain rule to part coordinates lives in :mod:`.assembly`.

Pose increments (Newton update): p <- p + dp, R <- exp([dth]x) R with a
world-frame rotation vector dth. A world point r = p + R s then moves as
dr = dp - [R s]x dth and a world vector v = R u as dv = -[v]x dth.
"""
from __future__ import annotations

from dataclasses import dataclass
from enum import Enum
from typing import Literal, Union

import numpy as np

from vd_solvers.compiled import jit
from vd_solvers.errors import SolverError

GROUND = 'body'  # the vehicle body: held by the rig, no degrees of freedom

JointKind = Literal[
    'spherical', 'inline', 'revolute', 'universal', 'cylindrical', 'translational', 'fixed'
]

# Two unit axes closer to parallel than this are treated as parallel when a
# perpendicular basis is built (|cos| of 0.81 deg).
_PARALLEL_COS = 0.9999


class PrimKind(Enum):
    """The scalar primitives; the order fixes their place in the state vector."""

    COMP = 0
    DOT = 1
    DDOT = 2
    DIST = 3
    CPZ = 4


MarkerType = Literal['p', 'v']

# Marker slots per primitive ("p" point, "v" unit vector) and the slot pairs
# with non-zero marker-level second derivatives.
SLOTS: dict[PrimKind, tuple[MarkerType, ...]] = {
    PrimKind.COMP: ('p', 'p'),
    PrimKind.DOT: ('v', 'v'),
    PrimKind.DDOT: ('p', 'p', 'v'),
    PrimKind.DIST: ('p', 'p'),
    PrimKind.CPZ: ('p', 'v'),
}
PAIRS: dict[PrimKind, tuple[tuple[int, int], ...]] = {
    PrimKind.COMP: (),
    PrimKind.DOT: ((0, 1), (1, 0)),
    PrimKind.DDOT: ((0, 2), (2, 0), (1, 2), (2, 1)),
    PrimKind.DIST: ((0, 0), (1, 1), (0, 1), (1, 0)),
    PrimKind.CPZ: ((1, 1),),
}


@dataclass(frozen=True)
class PointRef:
    """A point fixed to ``part``, at world position ``at`` (m) in the design pose."""

    part: str
    at: tuple[float, float, float]


@dataclass(frozen=True)
class VectorRef:
    """A unit vector fixed to ``part``, world ``direction`` in the design pose."""

    part: str
    direction: tuple[float, float, float]


Marker = Union[PointRef, VectorRef]


@dataclass(frozen=True)
class Primitive:
    """
    One scalar primitive.

    ``markers`` in the order of ``SLOTS[kind]``; ``param`` is c (3,) for COMP
    and (rho,) for CPZ, else empty.
    """

    kind: PrimKind
    markers: tuple[Marker, ...]
    param: tuple[float, ...] = ()


def point(part: str, at: np.ndarray) -> PointRef:
    """Marker helper: point ``at`` (3,) on ``part``."""
    x, y, z = (float(v) for v in at)
    return PointRef(part, (x, y, z))


def vector(part: str, direction: np.ndarray) -> VectorRef:
    """Marker helper: unit vector along ``direction`` (3,) on ``part``."""
    n = float(np.linalg.norm(direction))
    if n == 0.0:
        raise SolverError(f'zero-length axis on part {part!r}')
    x, y, z = (float(v) / n for v in direction)
    return VectorRef(part, (x, y, z))


def unit(v: np.ndarray, what: str) -> np.ndarray:
    """``v`` normalised; SolverError naming ``what`` if it has no length."""
    n = float(np.linalg.norm(v))
    if not n > 1e-12:
        raise SolverError(f'{what}: zero-length direction')
    return np.asarray(v, dtype=float) / n


def perpendicular_basis(axis: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """
    Two unit vectors n1, n2 with (n1, n2, axis) right-handed orthonormal.

    n1 is the vehicle axis least aligned with ``axis``, orthogonalised, so the
    basis is deterministic and well conditioned for any direction.
    """
    a = unit(axis, 'joint axis')
    ref = np.eye(3)[int(np.argmin(np.abs(a)))]
    n1 = unit(ref - (ref @ a) * a, 'joint axis basis')
    return n1, np.cross(a, n1)


def _comp(a: str, b: str, at: np.ndarray) -> list[Primitive]:
    pa, pb = point(a, at), point(b, at)
    return [Primitive(PrimKind.COMP, (pa, pb), tuple(np.eye(3)[k])) for k in range(3)]


def _perpendicular_dots(owner: str, other: str, axis: np.ndarray) -> list[Primitive]:
    """``axis`` fixed to ``other`` stays perpendicular to owner's normals (2 rows)."""
    n1, n2 = perpendicular_basis(axis)
    va = vector(other, axis)
    return [Primitive(PrimKind.DOT, (va, vector(owner, n))) for n in (n1, n2)]


def _inline(owner: str, other: str, at: np.ndarray, axis: np.ndarray) -> list[Primitive]:
    """Point ``at`` of ``other`` stays on owner's line through ``at`` along axis (2 rows)."""
    n1, n2 = perpendicular_basis(axis)
    pa, pb = point(owner, at), point(other, at)
    return [Primitive(PrimKind.DDOT, (pa, pb, vector(owner, n))) for n in (n1, n2)]


def joint_constraints(
    kind: JointKind,
    part_a: str,
    part_b: str,
    at: np.ndarray,
    axis: np.ndarray | None = None,
    cross: tuple[np.ndarray, np.ndarray] | None = None,
) -> list[Primitive]:
    """
    Constraint rows of an ideal joint between ``part_a`` and ``part_b``.

    Each returned primitive must keep its design value. ``axis`` (3,) is the
    joint axis (in-line, revolute, cylindrical, translational); ``cross`` the
    universal joint's cross axes (on a, on b), perpendicular at design.
    Row counts: spherical 3, inline 2, revolute 5, universal 4,
    cylindrical 4, translational 5, fixed 6.
    """
    if kind == 'spherical':
        return _comp(part_a, part_b, at)
    if kind == 'fixed':
        e = np.eye(3)
        rot = [
            Primitive(PrimKind.DOT, (vector(part_a, e[i]), vector(part_b, e[(i + 1) % 3])))
            for i in range(3)
        ]
        return _comp(part_a, part_b, at) + rot
    if kind == 'universal':
        if cross is None:
            raise SolverError('universal joint needs its cross axes')
        ca, cb = unit(cross[0], 'universal axis'), unit(cross[1], 'universal axis')
        if abs(ca @ cb) > 1e-6:
            raise SolverError('universal joint cross axes must be perpendicular')
        return _comp(part_a, part_b, at) + [
            Primitive(PrimKind.DOT, (vector(part_a, ca), vector(part_b, cb)))
        ]
    if axis is None:
        raise SolverError(f'{kind} joint needs an axis')
    if kind == 'inline':
        return _inline(part_a, part_b, at, axis)
    if kind == 'revolute':
        return _comp(part_a, part_b, at) + _perpendicular_dots(part_a, part_b, axis)
    cylinder = _perpendicular_dots(part_a, part_b, axis) + _inline(part_a, part_b, at, axis)
    if kind == 'cylindrical':
        return cylinder
    if kind == 'translational':
        n1, n2 = perpendicular_basis(axis)
        return cylinder + [Primitive(PrimKind.DOT, (vector(part_a, n1), vector(part_b, n2)))]
    raise SolverError(f'unknown joint kind {kind!r}')


# --- primitive kernels ------------------------------------------------------
# The value of every primitive, the gradients with respect to its slots' world quantities
# and the second-derivative blocks of its slot pairs (in the order of PAIRS[kind]), all
# primitives of a model in one compiled pass (:func:`primitives`); :func:`kernel` is the
# same for the primitives of one kind, stacked.

#: slots and slot pairs per kind, indexed by the kind's value
N_SLOTS = np.array([len(SLOTS[k]) for k in PrimKind])
N_PAIRS = np.array([len(PAIRS[k]) for k in PrimKind])
#: parameters per primitive, at most (COMP: the vector c; CPZ: rho)
PARAM_WIDTH = 3
#: a link or spring shorter than this (m) has collapsed: its direction is undefined
COLLAPSED_LENGTH = 1e-9


@jit
def primitives(world: np.ndarray, kinds: np.ndarray, offsets: np.ndarray,
               counts: np.ndarray, slot_base: np.ndarray, pair_base: np.ndarray,
               slot_marker: np.ndarray, param: np.ndarray, x: np.ndarray,
               g_slot: np.ndarray, hess: np.ndarray) -> bool:
    """
    Evaluate the primitives of every batch; return False if a link collapsed.

    Batch b holds ``counts[b]`` primitives of kind ``kinds[b]`` (PrimKind value), whose
    values go to ``x[offsets[b] + i]`` (n_prim,). Slot k of its primitive i is the marker
    ``slot_marker[slot_base[b] + k counts[b] + i]`` of ``world`` (M, 3) and its gradient
    goes to the same row of ``g_slot`` (S, 3); the block of its slot pair t (PAIRS order)
    to ``hess[pair_base[b] + t counts[b] + i]`` (P, 3, 3). ``param`` (n_prim,
    PARAM_WIDTH): COMP's c, CPZ's rho in column 0.
    """
    for b in range(kinds.shape[0]):
        kind, n, sb, pb = kinds[b], counts[b], slot_base[b], pair_base[b]
        for i in range(n):
            row = offsets[b] + i
            q0 = world[slot_marker[sb + i]]
            q1 = world[slot_marker[sb + n + i]]
            g0, g1 = g_slot[sb + i], g_slot[sb + n + i]
            if kind == 0:  # COMP: c . (r_a - r_b)
                value = 0.0
                for c in range(3):
                    value += param[row, c] * (q0[c] - q1[c])
                    g0[c] = param[row, c]
                    g1[c] = -param[row, c]
            elif kind == 1:  # DOT: v_a . v_b
                value = 0.0
                for c in range(3):
                    value += q0[c] * q1[c]
                    g0[c] = q1[c]
                    g1[c] = q0[c]
                for t in range(2):
                    h = hess[pb + t * n + i]
                    h[:] = 0.0
                    for c in range(3):
                        h[c, c] = 1.0
            elif kind == 2:  # DDOT: (r_b - r_a) . v_c
                q2 = world[slot_marker[sb + 2 * n + i]]
                g2 = g_slot[sb + 2 * n + i]
                value = 0.0
                for c in range(3):
                    d = q1[c] - q0[c]
                    value += d * q2[c]
                    g0[c] = -q2[c]
                    g1[c] = q2[c]
                    g2[c] = d
                for t in range(4):
                    h = hess[pb + t * n + i]
                    h[:] = 0.0
                    for c in range(3):
                        h[c, c] = -1.0 if t < 2 else 1.0
            elif kind == 3:  # DIST: |r_a - r_b|
                square = 0.0
                for c in range(3):
                    square += (q0[c] - q1[c]) * (q0[c] - q1[c])
                value = np.sqrt(square)
                if value < COLLAPSED_LENGTH:
                    return False
                h0 = hess[pb + i]
                for c in range(3):
                    g0[c] = (q0[c] - q1[c]) / value
                    g1[c] = -g0[c]
                for r in range(3):
                    for c in range(3):
                        h0[r, c] = ((1.0 if r == c else 0.0) - g0[r] * g0[c]) / value
                hess[pb + n + i] = h0
                for r in range(3):
                    for c in range(3):
                        hess[pb + 2 * n + i, r, c] = -h0[r, c]
                        hess[pb + 3 * n + i, r, c] = -h0[r, c]
            else:  # CPZ: r_z - rho sqrt(1 - v_z^2)
                rho, vz = param[row, 0], q1[2]
                root = np.sqrt(max(1.0 - vz * vz, 1e-12))
                value = q0[2] - rho * root
                g0[:] = 0.0
                g0[2] = 1.0
                g1[:] = 0.0
                g1[2] = rho * vz / root
                h = hess[pb + i]
                h[:] = 0.0
                h[2, 2] = rho / (root * root * root)
            x[row] = value
    return True


def kernel(
    kind: PrimKind, q: list[np.ndarray], param: np.ndarray
) -> tuple[np.ndarray, list[np.ndarray], list[np.ndarray]]:
    """
    Value, slot gradients and pair Hessians of ``kind`` for slot data ``q``.

    ``q``: the world quantities of the slots, each (n, 3); ``param`` (n, w), w <= 3.
    Returns the values (n,), the slot gradients [(n, 3)] and the second-derivative blocks
    [(n, 3, 3)] in the order of PAIRS[kind] (:func:`primitives`).
    """
    n, slots, pairs = q[0].shape[0], N_SLOTS[kind.value], N_PAIRS[kind.value]
    padded = np.zeros((n, PARAM_WIDTH))
    padded[:, : param.shape[1]] = param
    x, g, h = np.empty(n), np.empty((slots * n, 3)), np.empty((pairs * n, 3, 3))
    zero = np.zeros(1, dtype=np.int64)
    if not primitives(np.ascontiguousarray(np.concatenate(q), dtype=float),
                      np.array([kind.value]), zero, np.array([n]), zero, zero,
                      np.arange(slots * n), padded, x, g, h):
        raise SolverError('a link or spring collapsed to zero length')
    return x, [g[k * n:(k + 1) * n] for k in range(slots)], [h[t * n:(t + 1) * n]
                                                             for t in range(pairs)]
