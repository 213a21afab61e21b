# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The builder of a :class:`~.system.System`: numbering and matrices.

:mod:`.assembly` walks a template and hands the builder parts, primitives,
constraints and potentials; the builder numbers them as they come (parts,
point and vector markers, constraint rows, energy measures: the indices an
:class:`~.system.Outputs` records) and, in :meth:`Builder.build`, orders the
primitives kind-major, forms the combination matrices C_g and C_e and merges
the linear laws into one vectorised law.
"""
from __future__ import annotations

from collections.abc import Sequence
from typing import Union

import numpy as np

from vd_solvers.errors import SolverError

from .bushing import Measure
from .forces import EnergyLaw, LinearLaw
from .joints import GROUND, SLOTS, PointRef, Primitive, PrimKind, VectorRef
from .system import Batch, Outputs, System

MeasureLike = Union[Measure, Primitive]


class Builder:
    """Collects parts, markers, primitives, constraints and potentials."""

    def __init__(self) -> None:
        self.parts: dict[str, np.ndarray] = {}
        self._prims: dict[Primitive, int] = {}
        self._points: dict[PointRef, int] = {}
        self._vectors: dict[VectorRef, int] = {}
        self.constraints: list[Measure] = []
        self.measures: list[Measure] = []
        self.laws: list[tuple[EnergyLaw, np.ndarray]] = []

    def part(self, name: str, origin: np.ndarray) -> str:
        self.parts[name] = np.asarray(origin, dtype=float)
        return name

    def part_index(self, name: str) -> int:
        """Return the index of the moving part ``name`` (its pose is block ``name`` of q)."""
        for i, known in enumerate(self.parts):
            if known == name:
                return i
        raise SolverError(f'internal: unknown part {name!r}')

    def prim(self, p: Primitive) -> int:
        """Return the index of primitive ``p`` in creation order (renumbered at build)."""
        if p not in self._prims:
            self._prims[p] = len(self._prims)
            for m in p.markers:
                self.marker(m)
        return self._prims[p]

    def marker(self, m: PointRef | VectorRef) -> int:
        """Return the index of point or vector marker ``m`` among markers of its kind."""
        if isinstance(m, PointRef):
            return self._points.setdefault(m, len(self._points))
        return self._vectors.setdefault(m, len(self._vectors))

    @staticmethod
    def _measure(m: MeasureLike) -> Measure:
        return [(m, 1.0)] if isinstance(m, Primitive) else m

    def constrain(self, m: MeasureLike) -> int:
        measure = self._measure(m)
        for p, _ in measure:
            self.prim(p)
        self.constraints.append(measure)
        return len(self.constraints) - 1

    def energy(self, ms: Sequence[MeasureLike], law: EnergyLaw) -> np.ndarray:
        if len(ms) != law.size:
            raise SolverError('internal: law size does not match its measures')
        first = len(self.measures)
        for m in ms:
            measure = self._measure(m)
            for p, _ in measure:
                self.prim(p)
            self.measures.append(measure)
        idx = np.arange(first, first + len(ms))
        self.laws.append((law, idx))
        return idx

    def build(self, outputs: Outputs) -> System:
        """Return the system; renumbers the primitive indices of ``outputs`` in place."""
        outputs.check()
        names = list(self.parts)
        index = {n: i for i, n in enumerate(names)}
        ground = len(names)
        origins = np.array([self.parts[n] for n in names]).reshape(-1, 3)
        prims = list(self._prims)
        points, vectors = self._points, self._vectors

        def part_of(name: str) -> int:
            if name == GROUND:
                return ground
            if name not in index:
                raise SolverError(f'internal: unknown part {name!r}')
            return index[name]

        pt_part = np.array([part_of(m.part) for m in points], dtype=int)
        pt_local = np.array(
            [np.array(m.at) - (origins[pt_part[i]] if pt_part[i] < ground else 0.0)
             for i, m in enumerate(points)]
        ).reshape(-1, 3)
        vec_part = np.array([part_of(m.part) for m in vectors], dtype=int)
        vec_local = np.array([m.direction for m in vectors], dtype=float).reshape(-1, 3)
        # Group primitives by kind: the state vector x is kind-major.
        order: list[int] = []
        batches: list[Batch] = []
        for kind in PrimKind:
            members = [i for i, p in enumerate(prims) if p.kind is kind]
            if not members:
                continue
            # Marker indices into the combined table: points, then vectors.
            slot_idx = tuple(
                np.array([self._slot(prims[i].markers[s], t) for i in members], dtype=int)
                for s, t in enumerate(SLOTS[kind])
            )
            width = max(len(prims[i].param) for i in members)
            param = np.array([prims[i].param or (0.0,) * width for i in members])
            batches.append(Batch(kind, len(order), slot_idx, param.reshape(len(members), -1)))
            order.extend(members)
        position = np.empty(len(prims), dtype=int)
        position[np.array(order, dtype=int)] = np.arange(len(order))

        def matrix(rows: list[Measure]) -> np.ndarray:
            out = np.zeros((len(rows), len(prims)))
            for r, measure in enumerate(rows):
                for p, coef in measure:
                    out[r, position[self._prims[p]]] += coef
            return out

        # One vectorised law for all linear elements (gravity, rates, rack).
        linear = [(law, idx) for law, idx in self.laws if isinstance(law, LinearLaw)]
        laws = [(law, idx) for law, idx in self.laws if not isinstance(law, LinearLaw)]
        if linear:
            merged = LinearLaw(
                np.concatenate([np.asarray(law.stiffness) for law, _ in linear]),
                np.concatenate([np.asarray(law.force) for law, _ in linear]),
            )
            laws.append((merged, np.concatenate([idx for _, idx in linear])))
        outputs.spring_length = position[outputs.spring_length]
        outputs.damper_length = position[outputs.damper_length]
        return System(
            names, origins, pt_part, pt_local, vec_part, vec_local, batches,
            matrix(self.constraints), matrix(self.measures), laws, outputs,
        )

    def _slot(self, m: PointRef | VectorRef, kind: str) -> int:
        """Return the combined-table index of marker ``m`` in a slot of ``kind`` ('p', 'v')."""
        if kind == 'p' and isinstance(m, PointRef):
            return self._points[m]
        if kind == 'v' and isinstance(m, VectorRef):
            return len(self._points) + self._vectors[m]
        raise SolverError(f'internal: a {type(m).__name__} in a {kind!r} slot')
