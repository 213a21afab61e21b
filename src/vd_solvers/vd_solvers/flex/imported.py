# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Reduced stiffness matrices brought from an FE tool, and the mirror image of a node stiffness.

The FE tools are the thesis' "other solvers like Nastran".

Two formats, both describing one component's free-free stiffness on its
attachment nodes (6 DOFs each: u_x, u_y, u_z, th_x, th_y, th_z, vehicle axes,
left side):

* **plain** (YAML)::

      units: {length: mm, force: N, angle: rad}      # of the numbers below
      nodes: {lca_front: [260, 200, 199], lca_rear: [...], lca_outer: [...]}
      mass: 2.9          # kg (optional, default 0)
      cog: [0, 400, 200] # in the length unit (optional, default: node centroid)
      stiffness:         # 6n rows of 6n numbers, node order as in 'nodes'
        - [...]

  Entries are force/length, force/angle, force*length/length and
  force*length/angle by row and column kind.

* **Nastran punch DMIG** (``DMIG`` / ``DMIG*`` cards in small, large or free
  field, symmetric form IFO = 6 or square IFO = 1, real TIN = 1 or 2) of the
  matrix named in the mapping, e.g. ``KAAX`` from ``EXTSEOUT(DMIGPCH)``, with
  a ``grids: {GRID-ID: hard point}`` map and the model's length and force
  units. Node positions come from ``GRID`` cards in the same file when present
  (checked against the hard points), else from the hard points themselves.
"""
from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from vd_solvers.errors import SolverError

from .component import Condensed, check_rigid_modes

#: mirror y -> -y of one node's DOFs: translations (1, -1, 1), rotations (-1, 1, -1)
_NODE_MIRROR = np.array([1.0, -1.0, 1.0, -1.0, 1.0, -1.0])


def mirror_stiffness(stiffness: np.ndarray) -> np.ndarray:
    """Return the node stiffness of the mirror-image (right-side) component."""
    t = np.tile(_NODE_MIRROR, stiffness.shape[0] // 6)
    return stiffness * t[:, None] * t[None, :]


def dof_scales(n_nodes: int, length: float, force: float, angle: float) -> np.ndarray:
    """Factor per matrix entry to SI from file units (length, force, angle in SI)."""
    row = np.tile([force] * 3 + [force * length] * 3, n_nodes)
    col = np.tile([length] * 3 + [angle] * 3, n_nodes)
    return row[:, None] / col[None, :]


def _check_matrix(name: str, k: np.ndarray, what: str) -> np.ndarray:
    if not np.all(np.isfinite(k)):
        raise SolverError(f"{what}: stiffness of '{name}' holds non-finite numbers")
    if not np.allclose(k, k.T, rtol=1e-6, atol=1e-9 * float(np.max(np.abs(k)) or 1.0)):
        raise SolverError(f"{what}: stiffness of '{name}' is not symmetric")
    k = 0.5 * (k + k.T)
    check_rigid_modes(k, name)
    return k


def from_plain(name: str, raw: object, *, what: str, factors: Mapping[str, float]) -> Condensed:
    """
    Build a component from the plain format, already parsed to Python objects.

    ``factors``: SI factors of the file's units for length, force, angle, mass.
    """
    if not isinstance(raw, Mapping):
        raise SolverError(f'{what}: expected a mapping with nodes and stiffness')
    nodes = raw.get('nodes')
    if not isinstance(nodes, Mapping) or len(nodes) < 2:
        raise SolverError(f"{what}: 'nodes' must map at least two hard points to [x, y, z]")
    names = tuple(str(n) for n in nodes)
    try:
        xyz = np.array([[float(c) for c in nodes[n]] for n in nodes], dtype=float)
        k = np.array(raw.get('stiffness'), dtype=float)
    except (TypeError, ValueError):
        raise SolverError(f'{what}: nodes and stiffness must hold numbers') from None
    if xyz.shape != (len(names), 3):
        raise SolverError(f'{what}: every node needs three coordinates')
    size = 6 * len(names)
    if k.shape != (size, size):
        raise SolverError(f"{what}: stiffness must be {size} x {size} for {len(names)} nodes, "
                          f"found {'x'.join(str(d) for d in k.shape)}")
    length, force, angle = factors['length'], factors['force'], factors['angle']
    k = _check_matrix(name, k * dof_scales(len(names), length, force, angle), what)
    mass = float(raw.get('mass', 0.0)) * factors.get('mass', 1.0)
    if not (np.isfinite(mass) and mass >= 0.0):
        raise SolverError(f'{what}: mass must be >= 0')
    cog = np.array(raw['cog'], dtype=float) * length if 'cog' in raw else xyz.mean(axis=0) * length
    return Condensed(name, names, xyz * length, k, mass, cog, 0, f'imported {what}')


def _fields(line: str) -> list[str]:
    """Fields of one bulk-data line: free (commas), large (DMIG*, 16) or small (8)."""
    if ',' in line:
        return [f.strip() for f in line.split(',')]
    line = line.rstrip('\n')
    if line[:8].rstrip().endswith('*') or line.startswith('*'):
        return [line[:8].strip()] + [line[8 + 16 * i: 24 + 16 * i].strip() for i in range(4)]
    return [line[8 * i: 8 * i + 8].strip() for i in range(9)]


def _number(text: str, what: str) -> float:
    t = text.strip().upper().replace('D', 'E')
    if t and 'E' not in t and ('+' in t[1:] or '-' in t[1:]):  # Nastran 1.2-3 = 1.2E-3
        i = max(t.rfind('+', 1), t.rfind('-', 1))
        t = t[:i] + 'E' + t[i:]
    try:
        return float(t)
    except ValueError:
        raise SolverError(f"{what}: '{text.strip()}' is not a number") from None


def _cards(text: str) -> list[list[str]]:
    """Bulk-data cards with continuations joined (``+``/``*`` continuation lines)."""
    cards: list[list[str]] = []
    for raw in text.splitlines():
        if not raw.strip() or raw.lstrip().startswith('$'):
            continue
        fields = _fields(raw)
        head = fields[0]
        if head.startswith(('+', '*')) or head == '':
            if not cards:
                continue
            cards[-1].extend(fields[1:])
        else:
            cards.append([head.rstrip('*').upper()] + fields[1:])
    return cards


def from_dmig(name: str, text: str, *, matrix: str, grids: Mapping[int, str], what: str,
              factors: Mapping[str, float]) -> Condensed:
    """Build a component from a Nastran punch file's DMIG matrix ``matrix``."""
    cards = _cards(text)
    header = [c for c in cards if c[0] == 'DMIG' and c[1].upper() == matrix.upper()
              and c[2] in ('0', '')]
    if not header:
        found = sorted({c[1] for c in cards if c[0] == 'DMIG'})
        raise SolverError(
            f"{what}: no DMIG matrix '{matrix}' (found: {', '.join(found) or 'none'})"
        )
    try:
        ifo = int(header[0][3])
        tin = int(header[0][4])
    except (IndexError, ValueError):
        raise SolverError(f"{what}: malformed DMIG header of '{matrix}'") from None
    if ifo not in (1, 6) or tin not in (1, 2):
        raise SolverError(f"{what}: DMIG '{matrix}' must be real (TIN 1 or 2) and square "
                          f"or symmetric (IFO 1 or 6); found IFO {ifo}, TIN {tin}")
    order = list(grids)
    index = {g: i for i, g in enumerate(order)}
    size = 6 * len(order)
    k = np.zeros((size, size))
    seen = np.zeros((size, size), dtype=bool)

    def dof(grid_text: str, comp_text: str) -> int:
        try:
            grid, comp = int(grid_text), int(comp_text)
        except ValueError:
            raise SolverError(f"{what}: DMIG '{matrix}': bad grid/component "
                              f"'{grid_text} {comp_text}'") from None
        if grid not in index:
            raise SolverError(f"{what}: DMIG '{matrix}' uses GRID {grid}, which the mapping "
                              f"does not name (grids: {', '.join(map(str, order))})")
        if not 1 <= comp <= 6:
            raise SolverError(f"{what}: DMIG '{matrix}': component {comp} of GRID {grid} "
                              "is not 1..6")
        return 6 * index[grid] + comp - 1

    for c in cards:
        if c[0] != 'DMIG' or c[1].upper() != matrix.upper() or c[2] in ('0', ''):
            continue
        fields = list(c[2:])
        col = dof(fields[0], fields[1])
        # GJ CJ, then (G, C, A[, B]) per entry; B is blank for real matrices
        cells = [f for f in fields[2:] if f != '']
        if len(cells) % 3:
            raise SolverError(f"{what}: DMIG '{matrix}' column {fields[0]}-{fields[1]}: entries "
                              "must come as GRID, component, value")
        for g, comp, value in zip(cells[0::3], cells[1::3], cells[2::3]):
            row = dof(g, comp)
            k[row, col] = _number(value, what)
            seen[row, col] = True
    if ifo == 6:  # one triangle given: complete the other
        k = k + np.where((seen & ~seen.T).T, k.T, 0.0)
    k = _check_matrix(name, k * dof_scales(len(order), factors['length'], factors['force'],
                                           factors['angle']), what)
    positions = {}
    for c in cards:
        if c[0] == 'GRID':
            try:
                gid = int(c[1])
            except ValueError:
                continue
            if gid in index:
                positions[gid] = np.array([_number(v, what) for v in c[3:6]]) * factors['length']
    names = tuple(grids[g] for g in order)
    # without GRID cards the positions are unknown (NaN): the nodes then sit on their hard points
    xyz = np.array([positions.get(g, np.full(3, np.nan)) for g in order])
    cog = np.nanmean(xyz, axis=0) if np.any(np.isfinite(xyz)) else np.full(3, np.nan)
    return Condensed(name, names, xyz, k, 0.0, cog, 0, f"imported Nastran DMIG '{matrix}' {what}")
