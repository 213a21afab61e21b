# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The numerical model of one axle on the K&C rig: state, equations, tangent.

A :class:`System` holds parts with poses (p, R), markers, primitives
(:mod:`.joints`), constraint rows g(q) = g_design + load offsets, and
potentials V(q) = sum_e V_e(y_e) on measures y = C x(q) - reference. It is
built by :mod:`.builder` from what :mod:`.assembly` makes of a template.

Both sides of the axle are modelled; the body is the ground (fixed, as on a
K&C rig). Per side the rig adds

* a wheel pad: the contact-point height is a constraint driven by the event
  (its multiplier is the vertical pad force at the contact point);
* applied loads: a force at the contact point (lateral, braking: the wheel is
  locked to the upright, so the brake reaction stays in it) and a force at
  the wheel centre (traction).

:meth:`System.evaluate` gives the residuals and the exact tangent of the
equilibrium ``grad V - Q + J^T lambda = 0, g = 0`` for a Newton step in
local pose coordinates (dp, dtheta) per part.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.sparse

from vd_solvers.compiled import jit
from vd_solvers.errors import SolverError
from vd_solvers.flex.component import Condensed

from .forces import EnergyLaw, MatrixLaw
from .joints import N_PAIRS, N_SLOTS, PAIRS, PARAM_WIDTH, PrimKind, primitives
from .model import SIDES, Side

_EYE = np.eye(3)


@dataclass(frozen=True)
class LoadCase:
    """
    Rig inputs of one step; index 0 = left, 1 = right wheel.

    ``pad``: contact-point height change from design (m); ``contact_force``:
    force on the tire at the contact point (N, vehicle axes); ``centre_force``:
    force at the wheel centre (N); ``rack``: commanded rack travel (m, +y);
    ``contact_moment``: moment on the tire at the contact point (N*m, vehicle
    axes; the aligning-torque rig test applies it about z).
    """

    pad: np.ndarray = field(default_factory=lambda: np.zeros(2))
    contact_force: np.ndarray = field(default_factory=lambda: np.zeros((2, 3)))
    centre_force: np.ndarray = field(default_factory=lambda: np.zeros((2, 3)))
    rack: float = 0.0
    contact_moment: np.ndarray = field(default_factory=lambda: np.zeros((2, 3)))

    def blend(self, other: LoadCase, t: float) -> LoadCase:
        """Return the load case a fraction ``t`` of the way from self to ``other``."""
        return LoadCase(
            pad=(1 - t) * self.pad + t * other.pad,
            contact_force=(1 - t) * self.contact_force + t * other.contact_force,
            centre_force=(1 - t) * self.centre_force + t * other.centre_force,
            rack=(1 - t) * self.rack + t * other.rack,
            contact_moment=(1 - t) * self.contact_moment + t * other.contact_moment,
        )


@dataclass
class State:
    """Poses of the moving parts, p (P, 3) and R (P, 3, 3), and multipliers (m,)."""

    p: np.ndarray
    R: np.ndarray
    lam: np.ndarray

    def copy(self) -> State:
        return State(self.p.copy(), self.R.copy(), self.lam.copy())


@dataclass(frozen=True)
class Wheel:
    """Per-side indices of the wheel: upright part, centre point, spin axis."""

    part: int
    centre: int  # point marker
    axis: int  # vector marker (outward spin axis)
    radius: float  # loaded radius, m


def _unset() -> np.ndarray:
    return np.full(2, -1, dtype=int)


@dataclass
class Outputs:
    """
    Where the reported quantities live in a :class:`System`.

    Indices into its parts, point and vector markers, primitives, energy measures and
    constraint rows; per side (0 = left, 1 = right) where shaped (2,). The assembly fills
    one while it builds, with the indices the builder hands out; the builder renumbers the
    primitive indices once it has ordered the primitives (``Builder.build``).
    """

    wheels: list[Wheel] = field(default_factory=lambda: [Wheel(-1, -1, -1, 0.0)] * 2)
    pad_rows: np.ndarray = field(default_factory=_unset)  # constraint rows (2,)
    #: per side, hard point -> point marker
    tracked: tuple[dict[str, int], dict[str, int]] = field(default_factory=lambda: ({}, {}))
    spring: np.ndarray = field(default_factory=_unset)  # energy measure (2,)
    spring_length: np.ndarray = field(default_factory=_unset)  # primitive (2,)
    damper_length: np.ndarray = field(default_factory=_unset)  # primitive (2,)
    bump_stop: np.ndarray | None = None  # energy measure (2,)
    rebound_stop: np.ndarray | None = None
    bushings: dict[str, np.ndarray] = field(default_factory=dict)  # name -> measures (2, 6)
    arb_twist: int | None = None  # energy measure
    arb_arms: np.ndarray | None = None  # parts (2,)
    droplink_rows: np.ndarray | None = None  # constraint rows (2,)
    rack_part: int | None = None
    rack_measure: int | None = None  # energy measure (compliant rack)
    rack_row: int | None = None  # constraint row (rigid rack)
    elastic: list[int] = field(default_factory=list)  # measures that store elastic energy
    steer_sign: float = 1.0  # +1 if +y rack travel steers left
    #: flexible components as built (left side, bar and subframe once)
    components: list[Condensed] = field(default_factory=list)

    def put(self, name: str, side: Side, index: int) -> None:
        """Set the ``side`` entry of the per-side index pair ``name``."""
        pair = getattr(self, name)
        if pair is None:
            pair = _unset()
            setattr(self, name, pair)
        pair[SIDES.index(side)] = index

    def check(self) -> None:
        """Raise SolverError if a quantity every axle reports was never placed."""
        required = (self.pad_rows, self.spring, self.spring_length, self.damper_length,
                    np.array([w.part for w in self.wheels]))
        optional = (self.bump_stop, self.rebound_stop, self.arb_arms, self.droplink_rows)
        placed = required + tuple(p for p in optional if p is not None) + tuple(
            self.bushings.values())
        if any(np.any(p < 0) for p in placed):
            raise SolverError('internal: an output of the axle model was not placed')


@dataclass(frozen=True)
class Batch:
    """All primitives of one kind: combined-marker index per slot, parameters."""

    kind: PrimKind
    offset: int
    slot_idx: tuple[np.ndarray, ...]
    param: np.ndarray


class System:
    """Numerical axle model; see the module docstring for the equations."""

    def __init__(
        self,
        part_names: list[str],
        origins: np.ndarray,
        pt_part: np.ndarray,
        pt_local: np.ndarray,
        vec_part: np.ndarray,
        vec_local: np.ndarray,
        batches: list[Batch],
        c_g: np.ndarray,
        c_e: np.ndarray,
        laws: list[tuple[EnergyLaw, np.ndarray]],
        outputs: Outputs,
    ) -> None:
        self.part_names = part_names
        self.origins = origins
        self.n_parts = len(part_names)
        self.n_dof = 6 * self.n_parts
        self._batches = batches
        # The primitive-combination matrices are very sparse (a few entries per row):
        # they are kept sparse for the index work below, dense for the products with
        # vectors; the products with the primitives' Jacobian D are scattered directly
        # into dense Jacobians (:meth:`_build_products`), with no sparse matrix built per
        # evaluation (that construction cost more than the rest of an evaluation).
        self.c_g, self.c_e = scipy.sparse.csr_matrix(c_g), scipy.sparse.csr_matrix(c_e)
        self._c_g_dense = np.ascontiguousarray(c_g, dtype=float)
        self._c_e_dense = np.ascontiguousarray(c_e, dtype=float)
        self.laws = laws
        self.coupled = [(idx, law.matrix) for law, idx in laws if isinstance(law, MatrixLaw)]
        self.coupled_max = max((float(np.max(np.abs(k))) for _, k in self.coupled), default=0.0)
        self.outputs = outputs
        wheels = outputs.wheels
        self._upright = np.array([w.part for w in wheels])
        self._wheel_centre = np.array([w.centre for w in wheels])
        self._wheel_axis = np.array([w.axis for w in wheels])
        self._wheel_radius = np.array([w.radius for w in wheels])
        self.n_prim = c_g.shape[1]
        self.n_con = c_g.shape[0]
        self._build_scatter(pt_part, pt_local, vec_part, vec_local)
        self._g_product = self._build_product(self.c_g)
        self._e_product = self._build_product(self.c_e)
        # per coupled law: the DOFs its measures touch (its nodes' parts), so its
        # tangent block is assembled on those columns only
        # (slices where the rows and columns are contiguous, as the builder numbers them:
        # views instead of fancy-index copies)
        self._coupled_cols = []
        for idx, _ in self.coupled:
            prims = np.unique(self.c_e[idx].indices)
            cols = np.unique(self._d_cols[np.isin(self._d_rows, prims)])
            cols = cols[cols < self.n_dof]
            self._coupled_cols.append((_block(idx, cols), _block(cols, cols)))
        x0 = self.primitive_values(self.design_state())
        self.g_design = c_g @ x0
        self.e_design = c_e @ x0

    # -- poses -------------------------------------------------------------
    def design_state(self) -> State:
        """All parts in the design pose, zero multipliers."""
        return State(
            self.origins.copy(), np.repeat(_EYE[None], self.n_parts, axis=0), np.zeros(self.n_con)
        )

    def _markers(self, state: State) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """
        Return world value, rotation lever and pose Jacobian of all markers.

        Shapes (M, 3), (M, 3) and (M, 3, 6); points first, then vectors.
        """
        # The ground is an extra part n_parts in the identity pose; its
        # columns are dropped after assembly.
        p = np.vstack((state.p, np.zeros((1, 3))))
        R = np.concatenate((state.R, _EYE[None]))
        lever = np.einsum('nij,nj->ni', R[self._marker_part], self._marker_local)
        world = lever + self._is_point[:, None] * p[self._marker_part]
        jac = self._jac_template.copy()
        jac[:, :, 3:] = -_skew(lever)
        return world, lever, jac

    def marker_world(self, state: State) -> tuple[np.ndarray, np.ndarray]:
        """World positions of all point markers (Mp, 3) and vector markers (Mv, 3)."""
        world = self._markers(state)[0]
        return world[: self._n_points], world[self._n_points :]

    def _kernels(self, world: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """
        Return the primitives' values, slot gradients and pair Hessians at ``world``.

        Shapes (n_prim,), (S, 3) and (P, 3, 3), from the markers' world quantities
        ``world`` (M, 3) (:func:`.joints.primitives`).
        """
        x = np.empty(self.n_prim)
        grads = np.empty((self._slot_marker.shape[0], 3))
        hess = np.empty((self._pair_a.shape[0], 3, 3))
        if not primitives(world, self._kinds, self._offsets, self._counts, self._slot_base,
                          self._pair_base, self._slot_marker, self._param, x, grads, hess):
            raise SolverError('a link or spring collapsed to zero length')
        return x, grads, hess

    def primitive_values(self, state: State) -> np.ndarray:
        """All primitive values x (n_prim,) in ``state``."""
        return self._kernels(self._markers(state)[0])[0]

    # -- static scatter indices ------------------------------------------------
    def _build_scatter(self, pt_part: np.ndarray, pt_local: np.ndarray,
                       vec_part: np.ndarray, vec_local: np.ndarray) -> None:
        """
        Build the combined marker table and the static scatter indices.

        The indices scatter slot gradients into D and second-order blocks into
        the tangent.
        """
        self._n_points = pt_part.shape[0]
        self._marker_part = np.concatenate((pt_part, vec_part))
        self._marker_local = np.concatenate((pt_local, vec_local)).reshape(-1, 3)
        self._is_point = np.concatenate((np.ones(pt_part.shape[0]), np.zeros(vec_part.shape[0])))
        self._jac_template = np.zeros((self._marker_part.shape[0], 3, 6))
        self._jac_template[: self._n_points, :, :3] = _EYE
        nc = 6 * (self.n_parts + 1)
        self._nc = nc
        slot_marker: list[np.ndarray] = []
        slot_prim: list[np.ndarray] = []
        pair_a: list[np.ndarray] = []
        pair_b: list[np.ndarray] = []
        pair_prim: list[np.ndarray] = []
        for b in self._batches:
            n = b.param.shape[0]
            rows = b.offset + np.arange(n)
            first = sum(len(m) for m in slot_marker)
            base: list[int] = []
            for idx in b.slot_idx:
                base.append(first)
                first += n
                slot_marker.append(idx)
                slot_prim.append(rows)
            for i, j in PAIRS[b.kind]:
                pair_a.append(base[i] + np.arange(n))
                pair_b.append(base[j] + np.arange(n))
                pair_prim.append(rows)
        self._slot_marker = np.concatenate(slot_marker)
        # the batches as :func:`.joints.primitives` walks them
        batches = self._batches
        self._kinds = np.array([b.kind.value for b in batches], dtype=np.int64)
        self._offsets = np.array([b.offset for b in batches], dtype=np.int64)
        self._counts = np.array([b.param.shape[0] for b in batches], dtype=np.int64)
        sizes = self._counts * N_SLOTS[self._kinds]
        self._slot_base = np.concatenate(([0], np.cumsum(sizes)[:-1])).astype(np.int64)
        sizes = self._counts * N_PAIRS[self._kinds]
        self._pair_base = np.concatenate(([0], np.cumsum(sizes)[:-1])).astype(np.int64)
        self._param = np.zeros((self.n_prim, PARAM_WIDTH))
        for b in batches:
            self._param[b.offset: b.offset + b.param.shape[0], : b.param.shape[1]] = b.param
        self._pair_a = np.concatenate(pair_a) if pair_a else np.zeros(0, dtype=int)
        self._pair_b = np.concatenate(pair_b) if pair_b else np.zeros(0, dtype=int)
        parts = self._marker_part[self._slot_marker]
        prims = np.concatenate(slot_prim)
        six, three = np.arange(6), np.arange(3)
        self._d_rows = np.repeat(prims, 6)
        self._d_cols = (6 * parts[:, None] + six).ravel()
        pa, pb = parts[self._pair_a], parts[self._pair_b]
        pair_idx = (6 * pa[:, None, None] + six[None, :, None]) * nc + 6 * pb[:, None, None] + six
        chart_idx = (6 * parts[:, None, None] + 3 + three[None, :, None]) * nc + (
            6 * parts[:, None, None] + 3 + three
        )
        self._so_idx = np.concatenate((pair_idx.ravel(), chart_idx.ravel()))
        self._so_prim = np.concatenate(
            (np.repeat(prims[self._pair_a], 36), np.repeat(prims, 9))
        )

    def _build_product(self, c: scipy.sparse.csr_matrix
                       ) -> tuple[np.ndarray, np.ndarray, np.ndarray, tuple[int, int]]:
        """
        Return the scatter of the product C D into a dense (rows, n_dof) array.

        D holds the entries ``d_vals`` at (``_d_rows``, ``_d_cols``); entry t contributes
        C[r, d_rows[t]] d_vals[t] to (r, d_cols[t]) for every nonzero of C's column
        d_rows[t] (ground columns, >= n_dof, dropped). Returned: flat target index, the
        entry t of each contribution, its coefficient, and the product's shape.
        """
        csc = c.tocsc()
        keep = np.nonzero(self._d_cols < self.n_dof)[0]
        column = self._d_rows[keep]
        counts = np.diff(csc.indptr)[column]
        entry = np.repeat(keep, counts)
        first = np.repeat(csc.indptr[column] - np.cumsum(counts) + counts, counts)
        pos = first + np.arange(entry.size)
        target = csc.indices[pos] * self.n_dof + self._d_cols[entry]
        return target, entry, csc.data[pos].astype(float), (c.shape[0], self.n_dof)

    @staticmethod
    def _product(scatter: tuple[np.ndarray, np.ndarray, np.ndarray, tuple[int, int]],
                 d_flat: np.ndarray) -> np.ndarray:
        """Return C D (dense) from the scatter of :meth:`_build_product` and D's entries."""
        target, entry, coef, shape = scatter
        return np.bincount(target, coef * d_flat[entry],
                           minlength=shape[0] * shape[1]).reshape(shape)

    # -- evaluation -------------------------------------------------------------
    def evaluate(self, state: State, load: LoadCase) -> Evaluation:
        """Residual ingredients and tangent pieces of the equilibrium in ``state``."""
        world, lever, jac = self._markers(state)
        x, g_slot, hess = self._kernels(world)
        j_slot = jac[self._slot_marker]
        d_vals = np.einsum('si,sij->sj', g_slot, j_slot)

        d_flat = d_vals.ravel()
        g = self._c_g_dense @ x - self.g_design - self._constraint_offset(load)
        jacobian = self._product(self._g_product, d_flat)
        measure_jacobian = self._product(self._e_product, d_flat)
        y = self._c_e_dense @ x - self.e_design - self._energy_offset(load)
        energy, d1, d2 = (np.empty_like(y) for _ in range(3))
        for law, idx in self.laws:
            energy[idx], d1[idx], d2[idx] = law.evaluate(y[idx])
        n_pt = self._n_points
        q_ext, k_ext = self._applied(state, world[:n_pt], world[n_pt:], load)
        return Evaluation(self, x, jacobian, measure_jacobian, g, y, energy, d1, d2, q_ext, k_ext,
                          (g_slot, j_slot, hess, lever))

    def second_order(self, slots: tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray],
                     weights: np.ndarray) -> np.ndarray:
        """
        Return sum_k weights_k * d2 x_k / dq2 (n_dof, n_dof).

        From an evaluation's ``slots`` -- the slot gradients (S, 3), the slots' marker pose
        Jacobians (S, 3, 6), the pair Hessians of the kernels and the markers' rotation
        levers (M, 3) -- and primitive weights (n_prim,) (:func:`second_order_sum`).
        """
        g_slot, j_slot, hess, lever = slots
        so = second_order_sum(j_slot, hess, self._pair_a, self._pair_b, g_slot,
                              np.ascontiguousarray(lever[self._slot_marker]), self._so_idx,
                              self._so_prim, weights, self._nc)
        return so[: self.n_dof, : self.n_dof]

    def _constraint_offset(self, load: LoadCase) -> np.ndarray:
        off = np.zeros(self.n_con)
        off[self.outputs.pad_rows] = load.pad
        if self.outputs.rack_row is not None:
            off[self.outputs.rack_row] = load.rack
        return off

    def _energy_offset(self, load: LoadCase) -> np.ndarray:
        off = np.zeros(self.c_e.shape[0])
        if self.outputs.rack_measure is not None:
            off[self.outputs.rack_measure] = load.rack
        return off

    def contact_points(self, state: State) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Wheel centres, outward spin axes and contact points, each (2, 3)."""
        world, vec = self.marker_world(state)
        return self._contact(world, vec)

    def _contact(self, world: np.ndarray,
                 vec: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        centre, axis = world[self._wheel_centre], vec[self._wheel_axis]
        return centre, axis, centre + self._wheel_radius[:, None] * contact_direction(axis)

    def _applied(
        self, state: State, world: np.ndarray, vec: np.ndarray, load: LoadCase
    ) -> tuple[np.ndarray, np.ndarray]:
        """
        Generalised applied force Q (n_dof,) and the tangent of -Q.

        Forces act on the upright at the current contact point and wheel
        centre. The tangent treats both as material points (exact for the
        wheel centre; the contact point's rolling along the tread is a small
        second-order term that only slows convergence).
        """
        q = np.zeros(self.n_dof)
        k = np.zeros((self.n_dof, self.n_dof))
        if not (load.contact_force.any() or load.centre_force.any()
                or load.contact_moment.any()):
            return q, k
        centre, _, contact = self._contact(world, vec)
        # both sides at once: (side, point of application: contact, centre)
        upright = self._upright
        at = np.stack((contact, centre), axis=1)
        force = np.stack((load.contact_force, load.centre_force), axis=1)
        lever = at - state.p[upright][:, None, :]
        moment = _cross(lever, force)
        chart = _chart(-force.reshape(-1, 3), lever.reshape(-1, 3)).reshape(2, 2, 3, 3)
        # a pure moment, fixed in the vehicle axes: no lever, no tangent term
        rot = load.contact_moment + moment[:, 0] + moment[:, 1]
        for s, u in enumerate(upright):
            q[6 * u : 6 * u + 3] += force[s, 0] + force[s, 1]
            q[6 * u + 3 : 6 * u + 6] += rot[s]
            k[6 * u + 3 : 6 * u + 6, 6 * u + 3 : 6 * u + 6] += chart[s, 0] + chart[s, 1]
        return q, k


def contact_direction(axis: np.ndarray) -> np.ndarray:
    """
    Return the unit vectors (n, 3) from wheel centre to contact point.

    The road normal (+z) projected into the wheel plane of spin axis ``axis``
    (n, 3), negated.
    """
    up = np.array([0.0, 0.0, 1.0]) - axis[:, 2:3] * axis
    return -up / np.linalg.norm(up, axis=1, keepdims=True)


@dataclass
class Evaluation:
    """Everything one Newton iteration needs, in state q for loads."""

    system: System
    x: np.ndarray  # primitive values (n_prim,)
    jacobian: np.ndarray  # constraint Jacobian J (m, n_dof)
    measure_jacobian: np.ndarray  # energy-measure Jacobian (n_e, n_dof)
    g: np.ndarray  # constraint residuals (m,)
    y: np.ndarray  # energy deflections (n_e,)
    energy: np.ndarray  # V_e (n_e,), J
    d1: np.ndarray  # V_e' (n_e,), N or N*m (generalised force of the element)
    d2: np.ndarray  # V_e'' (n_e,)
    q_ext: np.ndarray  # applied generalised force (n_dof,)
    k_ext: np.ndarray  # tangent of -q_ext (n_dof, n_dof)
    #: what the primitives' second-order blocks are formed from, when a tangent is asked for
    #: (an evaluation that only checks convergence never needs them)
    slots: tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]

    def force_residual(self, lam: np.ndarray) -> np.ndarray:
        """Grad V - Q + J^T lambda (n_dof,), N and N*m."""
        return self.measure_jacobian.T @ self.d1 - self.q_ext + self.jacobian.T @ lam

    def tangent(self, lam: np.ndarray) -> np.ndarray:
        """d(force residual)/dq (n_dof, n_dof) at fixed lambda."""
        s, e = self.system, self.measure_jacobian
        weights = self.d1 @ s._c_e_dense + lam @ s._c_g_dense
        stiff = np.nonzero(self.d2)[0]  # measures with a diagonal stiffness
        k = e[stiff].T @ (self.d2[stiff, None] * e[stiff])
        k += s.second_order(self.slots, weights) + self.k_ext
        for (_, matrix), (rows, square) in zip(s.coupled, s._coupled_cols):
            block = e[rows]
            k[square] += block.T @ matrix @ block
        return k


Block = tuple[slice | np.ndarray, slice | np.ndarray]


def _block(rows: np.ndarray, cols: np.ndarray) -> Block:
    """Index of the block (rows, cols) of a matrix: slices where both are contiguous."""
    def ranged(i: np.ndarray) -> slice | None:
        contiguous = i.size > 0 and np.array_equal(i, np.arange(i[0], i[0] + i.size))
        return slice(int(i[0]), int(i[0]) + i.size) if contiguous else None
    r, c = ranged(rows), ranged(cols)
    if r is not None and c is not None:
        return r, c
    open_rows, open_cols = np.ix_(rows, cols)
    return open_rows, open_cols


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Cross products of stacked 3-vectors (..., 3), written out (no np.cross overhead)."""
    out = np.empty(np.broadcast_shapes(a.shape, b.shape))
    out[..., 0] = a[..., 1] * b[..., 2] - a[..., 2] * b[..., 1]
    out[..., 1] = a[..., 2] * b[..., 0] - a[..., 0] * b[..., 2]
    out[..., 2] = a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]
    return out


def _skew(w: np.ndarray) -> np.ndarray:
    out = np.zeros(w.shape[:-1] + (3, 3))
    out[..., 0, 1], out[..., 0, 2] = -w[..., 2], w[..., 1]
    out[..., 1, 0], out[..., 1, 2] = w[..., 2], -w[..., 0]
    out[..., 2, 0], out[..., 2, 1] = -w[..., 1], w[..., 0]
    return out


@jit
def second_order_sum(j_slot: np.ndarray, hess: np.ndarray, pair_a: np.ndarray,
                     pair_b: np.ndarray, g_slot: np.ndarray, lever: np.ndarray,
                     so_idx: np.ndarray, so_prim: np.ndarray, weights: np.ndarray,
                     nc: int) -> np.ndarray:
    """
    Return the weighted second derivatives of the primitives, (nc, nc) with the ground.

    Two kinds of terms, each scaled by its primitive's weight and summed into the flat
    index ``so_idx`` (pose DOFs of both parts, rows and columns):

    * per slot pair t of a kernel, ``J_a^T H_t J_b`` (6, 6): the kernel's Hessian
      ``hess[t]`` (3, 3) between slots a = ``pair_a[t]`` and b = ``pair_b[t]`` through the
      slots' marker pose Jacobians ``j_slot`` (S, 3, 6);
    * per slot s, the rotation chart's own second-order term ``sym(G w^T) - (G.w) I``
      (:func:`_chart`) of its gradient ``g_slot[s]`` and rotation lever ``lever[s]``.

    ``so_prim`` gives the primitive (index into ``weights``) of every entry.
    """
    out = np.zeros(nc * nc)
    tmp = np.empty((6, 3))
    t = 0
    for p in range(pair_a.shape[0]):
        a, b = pair_a[p], pair_b[p]
        for r in range(6):
            for k in range(3):
                acc = 0.0
                for i in range(3):
                    acc += j_slot[a, i, r] * hess[p, i, k]
                tmp[r, k] = acc
        for r in range(6):
            for c in range(6):
                acc = 0.0
                for k in range(3):
                    acc += tmp[r, k] * j_slot[b, k, c]
                out[so_idx[t]] += acc * weights[so_prim[t]]
                t += 1
    for q in range(g_slot.shape[0]):
        dot = 0.0
        for i in range(3):
            dot += g_slot[q, i] * lever[q, i]
        for r in range(3):
            for c in range(3):
                v = 0.5 * (g_slot[q, r] * lever[q, c] + g_slot[q, c] * lever[q, r])
                if r == c:
                    v -= dot
                out[so_idx[t]] += v * weights[so_prim[t]]
                t += 1
    return out.reshape(nc, nc)


def _chart(g: np.ndarray, w: np.ndarray) -> np.ndarray:
    """
    Return the second-order rotation term of G.(R s) in exponential coordinates.

    sym(G w^T) - (G.w) I, for G (n, 3) and w = R s (n, 3).
    """
    outer = g[:, :, None] * w[:, None, :]
    dot = np.einsum('ni,ni->n', g, w)
    return 0.5 * (outer + outer.transpose(0, 2, 1)) - dot[:, None, None] * _EYE

