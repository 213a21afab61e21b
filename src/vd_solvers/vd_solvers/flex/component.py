# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
A flexible component as a frame of beam elements generated from hard points.

The frame is statically condensed to its attachment nodes.

Geometry is never drawn by hand: a component names its attachment points
(hard points, by name, with their current positions -- so a hard-point
override moves the FE model with it) and the *members* between them. A member
may bend through *shape points*, defined relative to the member's end points
(a fraction along it plus an offset), so they follow the hard points too.
Attachment points that lie off every member (a spring seat on a trailing link,
a drop-link mount on a lower arm) are joined by a *bracket* element from the
nearest point of the nearest member.

Condensation (Guyan; exact for static loads): with attachment DOFs m and
internal DOFs s, K_red = K_mm - K_ms K_ss^-1 K_sm. The result is the free-free
stiffness of the attachment nodes in vehicle axes (6 rigid-body modes in its
null space), plus the component's mass and centre of mass from the elements.
"""
from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np
import scipy.linalg

from vd_solvers.errors import SolverError

from .beam import element_mass, element_stiffness
from .section import Material, Section

#: an attachment point this close to a member lies on it (no bracket), m
ON_MEMBER = 1e-3
#: hard points this close share one node (a spring seat 2 mm from the damper eye), m
COINCIDENT = 5e-3
#: eigenvalues below this fraction of the largest count as rigid-body modes
RIGID_MODE_RATIO = 1e-10


@dataclass(frozen=True)
class ShapePoint:
    """A bend of member (``start``, ``end``): start + fraction (end - start) + offset."""

    start: str
    end: str
    fraction: float
    offset: tuple[float, float, float] = (0.0, 0.0, 0.0)  # m, left side

    def position(self, points: Mapping[str, np.ndarray]) -> np.ndarray:
        a, b = np.asarray(points[self.start], float), np.asarray(points[self.end], float)
        return a + self.fraction * (b - a) + np.asarray(self.offset, float)


@dataclass(frozen=True)
class Condensed:
    """
    A component reduced to its attachment nodes.

    ``stiffness`` (6n, 6n) acts on node DOFs (u_x, u_y, u_z, th_x, th_y, th_z)
    in vehicle axes, node order ``nodes``; ``positions`` (n, 3) m.
    """

    name: str
    nodes: tuple[str, ...]
    positions: np.ndarray
    stiffness: np.ndarray
    mass: float
    cog: np.ndarray
    elements: int = 0
    source: str = ''
    full: "Frame | None" = field(default=None, compare=False, repr=False)
    #: further hard-point names that coincide with a node (e.g. spring and damper seat)
    aliases: Mapping[str, str] = field(default_factory=dict)


@dataclass(frozen=True)
class Frame:
    """The un-condensed FE model (for checks and reports)."""

    positions: np.ndarray  # (N, 3)
    elements: tuple[tuple[int, int], ...]
    stiffness: np.ndarray  # (6N, 6N)
    attachment_nodes: tuple[int, ...]


def _foot(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, float]:
    d = b - a
    t = float(np.clip((p - a) @ d / (d @ d), 0.0, 1.0))
    return a + t * d, t


def build(name: str, points: Mapping[str, np.ndarray], members: Sequence[tuple[str, str]],
          material: Material, section: Section, *,
          attachments: Sequence[str] = (), shape_points: Sequence[ShapePoint] = (),
          elements_per_member: int = 1,
          member_sections: Mapping[tuple[str, str], Section] | None = None) -> Condensed:
    """
    FE frame of component ``name`` and its condensation.

    ``members``: pairs of point names joined by beams; ``attachments``: further
    point names that must be nodes (bracketed to the nearest member if off it).
    The attachment nodes are the member ends and ``attachments``, in order of
    first appearance. ``member_sections`` overrides the section per member.
    """
    if not members:
        raise SolverError(f"component '{name}': no members")
    if not (isinstance(elements_per_member, int) and 1 <= elements_per_member <= 50):
        raise SolverError(f"component '{name}': elements_per_member must be 1..50, "
                          f"got {elements_per_member!r}")
    order: list[str] = []
    for a, b in members:
        for n in (a, b):
            if n not in order:
                order.append(n)
    for n in attachments:
        if n not in order:
            order.append(n)
    for n in order:
        if n not in points:
            raise SolverError(f"component '{name}': hard point '{n}' is not given")
    # points that coincide share one node (the first name); a member between two of
    # them would have no length
    aliases: dict[str, str] = {}
    for i, a in enumerate(order):
        for b in order[:i]:
            if b not in aliases and np.linalg.norm(np.asarray(points[a], float)
                                                   - np.asarray(points[b], float)) <= COINCIDENT:
                aliases[a] = b
                break
    for a, b in members:
        if aliases.get(a, a) == aliases.get(b, b):
            raise SolverError(f"component '{name}': hard points '{a}' and '{b}' coincide "
                              "(a member needs length)")
    order = [n for n in order if n not in aliases]
    members = [(aliases.get(a, a), aliases.get(b, b)) for a, b in members]
    pos: list[np.ndarray] = [np.asarray(points[n], dtype=float) for n in order]
    index = {n: i for i, n in enumerate(order)}
    # legs: (node_i, node_j, section) of each straight piece of a member
    legs: list[tuple[int, int, Section, bool]] = []
    for a, b in members:
        sec = (member_sections or {}).get((a, b), section)
        bends = sorted((s for s in shape_points if (s.start, s.end) == (a, b)),
                       key=lambda s: s.fraction)
        chain = [index[a]]
        for s in bends:
            pos.append(s.position(points))
            chain.append(len(pos) - 1)
        chain.append(index[b])
        legs += [(i, j, sec, True) for i, j in zip(chain, chain[1:])]
    unknown = [s for s in shape_points
               if (aliases.get(s.start, s.start), aliases.get(s.end, s.end)) not in set(members)]
    if unknown:
        raise SolverError(f"component '{name}': shape point on '{unknown[0].start}'-"
                          f"'{unknown[0].end}', which is not one of its members")
    on_chain = {i for leg in legs for i in leg[:2]}
    for n in order:
        k = index[n]
        if k in on_chain:
            continue
        p = pos[k]
        best = min(range(len(legs)), key=lambda li: float(np.linalg.norm(
            p - _foot(p, pos[legs[li][0]], pos[legs[li][1]])[0])))
        i, j, sec, primary = legs[best]
        foot, t = _foot(p, pos[i], pos[j])
        if np.linalg.norm(p - foot) <= ON_MEMBER and 0.0 < t < 1.0:
            legs[best: best + 1] = [(i, k, sec, primary), (k, j, sec, primary)]
        else:
            pos.append(foot)
            f = len(pos) - 1
            if 0.0 < t < 1.0:
                legs[best: best + 1] = [(i, f, sec, primary), (f, j, sec, primary)]
            else:  # the foot is an end of the leg: bracket from that node
                pos.pop()
                f = i if t == 0.0 else j
            legs.append((f, k, section, False))
        on_chain.add(k)
    # subdivide the member legs
    elements: list[tuple[int, int, Section]] = []
    for i, j, sec, primary in legs:
        n_el = elements_per_member if primary else 1
        prev = i
        for e in range(1, n_el):
            pos.append(pos[i] + e / n_el * (pos[j] - pos[i]))
            elements.append((prev, len(pos) - 1, sec))
            prev = len(pos) - 1
        elements.append((prev, j, sec))
    xyz = np.array(pos)
    n = xyz.shape[0]
    k_full = np.zeros((6 * n, 6 * n))
    mass, moment = 0.0, np.zeros(3)
    for i, j, sec in elements:
        ke = element_stiffness(xyz[i], xyz[j], material, sec, f"component '{name}'")
        dofs = np.r_[6 * i: 6 * i + 6, 6 * j: 6 * j + 6]
        k_full[np.ix_(dofs, dofs)] += ke
        m, c = element_mass(xyz[i], xyz[j], material, sec)
        mass += m
        moment += m * c
    masters = np.arange(len(order))
    k_red = condense(k_full, masters, name)
    frame = Frame(xyz, tuple((i, j) for i, j, _ in elements), k_full, tuple(masters))
    cog = moment / mass if mass > 0.0 else xyz[: len(order)].mean(axis=0)
    return Condensed(name, tuple(order), xyz[: len(order)].copy(), k_red, mass, cog,
                     len(elements), f'beam frame of {len(elements)} elements', frame, aliases)


def condense(k_full: np.ndarray, master_nodes: np.ndarray, name: str = 'component') -> np.ndarray:
    """Guyan reduction of ``k_full`` (6N, 6N) to the DOFs of ``master_nodes``."""
    n = k_full.shape[0] // 6
    m = np.concatenate([np.arange(6 * i, 6 * i + 6) for i in master_nodes])
    s = np.setdiff1d(np.arange(6 * n), m)
    k_mm = k_full[np.ix_(m, m)]
    if s.size:
        k_ms = k_full[np.ix_(m, s)]
        try:
            factor = scipy.linalg.cho_factor(k_full[np.ix_(s, s)], check_finite=False)
        except scipy.linalg.LinAlgError:
            raise SolverError(f"component '{name}': its internal nodes are not held by the "
                              "attachment nodes (the frame is not connected)") from None
        k_mm = k_mm - k_ms @ scipy.linalg.cho_solve(factor, k_ms.T, check_finite=False)
    k_mm = 0.5 * (k_mm + k_mm.T)
    check_rigid_modes(k_mm, name)
    return k_mm


def check_rigid_modes(stiffness: np.ndarray, name: str) -> None:
    """Check that a connected free-free component has exactly six zero-energy modes."""
    values = np.linalg.eigvalsh(stiffness)
    top = float(np.max(np.abs(values)))
    zero = int(np.sum(np.abs(values) <= RIGID_MODE_RATIO * top))
    if not (np.all(np.isfinite(values)) and top > 0.0):
        raise SolverError(f"component '{name}': stiffness matrix is zero or not finite")
    if zero > 6:
        raise SolverError(f"component '{name}': {zero - 6} zero-stiffness deformation mode(s) "
                          "besides the 6 rigid-body modes (a mechanism: not connected)")
    if np.any(values < -1e-8 * top):
        raise SolverError(f"component '{name}': stiffness matrix is not positive semi-definite")


def clamped(stiffness: np.ndarray, reference: int = 0) -> np.ndarray:
    """
    Return the free-free node stiffness with node ``reference`` clamped: (6n-6, 6n-6).

    This is the stiffness the K&C model uses on deformations measured in the
    reference node's frame (exact for a matrix whose null space is the rigid modes).
    """
    keep = np.setdiff1d(np.arange(stiffness.shape[0]), np.arange(6 * reference, 6 * reference + 6))
    return stiffness[np.ix_(keep, keep)]
