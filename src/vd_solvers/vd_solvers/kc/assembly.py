"""
The numerical model of one axle on the K&C rig.

:func:`assemble` turns a :class:`~.model.SuspensionInput` and its template
into a :class:`System`: parts with poses (p, R), markers, primitives
(:mod:`.joints`), constraint rows g(q) = g_design + load offsets, and
potentials V(q) = sum_e V_e(y_e) on measures y = C x(q) - reference.

Both sides of the axle are modelled: the template's left corner and its
mirror image, the anti-roll bar and the rack coupling them. The body is the
ground (fixed, as on a K&C rig). Per side the rig adds

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

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Union

import numpy as np

from vd_solvers.errors import SolverError
from vd_solvers.flex.component import Condensed, build, clamped
from vd_solvers.flex.imported import mirror_stiffness

from .bushing import Measure, bushing_frame, bushing_measures, side_frame
from .forces import EnergyLaw, LinearLaw, MatrixLaw, StopLaw, TorsionLaw, spring_law, stiffness_law
from .joints import (
    GROUND,
    PAIRS,
    SLOTS,
    PointRef,
    Primitive,
    PrimKind,
    VectorRef,
    joint_constraints,
    kernel,
    perpendicular_basis,
    point,
    vector,
)
from .model import SIDES, FlexSpec, Side, SuspensionInput, mirror, validate
from .templates import (
    ARB_POINTS,
    STEERING,
    SUBFRAME_POINTS,
    TEMPLATES,
    LinkDef,
    PartDef,
    SuspensionTemplate,
    Topology,
)

GRAVITY = 9.80665  # m/s^2, standard gravity
RACK = 'rack'
BAR = 'anti_roll_bar'
SUBFRAME = 'subframe'
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
        """The load case a fraction ``t`` of the way from self to ``other``."""
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


@dataclass(frozen=True)
class Outputs:
    """Where the reported quantities live (indices per side where shaped (2,))."""

    wheels: tuple[Wheel, Wheel]
    pad_rows: np.ndarray  # constraint rows (2,)
    tracked: tuple[dict[str, int], dict[str, int]]  # hard point -> point marker
    spring: np.ndarray  # energy measure (2,)
    spring_length: np.ndarray  # primitive (2,)
    damper_length: np.ndarray  # primitive (2,)
    bump_stop: np.ndarray | None  # energy measure (2,)
    rebound_stop: np.ndarray | None
    bushings: dict[str, np.ndarray]  # name -> energy measures (2, 6)
    arb_twist: int | None  # energy measure
    arb_arms: np.ndarray | None  # parts (2,)
    droplink_rows: np.ndarray | None  # constraint rows (2,)
    rack_part: int | None
    rack_measure: int | None  # energy measure (compliant rack)
    rack_row: int | None  # constraint row (rigid rack)
    elastic: np.ndarray  # energy measures that store elastic energy
    steer_sign: float  # +1 if +y rack travel steers left
    components: tuple[Condensed, ...] = ()  # flexible components as built (left side, bar once)


@dataclass(frozen=True)
class _Batch:
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
        batches: list[_Batch],
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
        # products with them dominate an evaluation in dense form.
        import scipy.sparse

        self.c_g, self.c_e = scipy.sparse.csr_matrix(c_g), scipy.sparse.csr_matrix(c_e)
        self.laws = laws
        self.coupled = [(idx, law.matrix) for law, idx in laws if isinstance(law, MatrixLaw)]
        self.coupled_max = max((float(np.max(np.abs(k))) for _, k in self.coupled), default=0.0)
        self.outputs = outputs
        self.n_prim = c_g.shape[1]
        self.n_con = c_g.shape[0]
        self._build_scatter(pt_part, pt_local, vec_part, vec_local)
        # per coupled law: the DOFs its measures touch (its nodes' parts), so its
        # tangent block is assembled on those columns only
        self._coupled_cols = []
        for idx, _ in self.coupled:
            prims = np.unique(self.c_e[idx].indices)
            cols = np.unique(self._d_cols[np.isin(self._d_rows, prims)])
            cols = cols[cols < self.n_dof]
            self._coupled_cols.append((np.ix_(idx, cols), np.ix_(cols, cols)))
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
        World value (M, 3), rotation lever (M, 3) and pose Jacobian
        (M, 3, 6) of all markers: points first, then vectors.
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

    def _kernels(self, world: np.ndarray) -> tuple[np.ndarray, list[np.ndarray], list[np.ndarray]]:
        x = np.empty(self.n_prim)
        grads: list[np.ndarray] = []
        hess: list[np.ndarray] = []
        for b in self._batches:
            value, g, h = kernel(b.kind, [world[i] for i in b.slot_idx], b.param)
            x[b.offset : b.offset + value.shape[0]] = value
            grads.extend(g)
            hess.extend(h)
        return x, grads, hess

    def primitive_values(self, state: State) -> np.ndarray:
        """All primitive values x (n_prim,) in ``state``."""
        return self._kernels(self._markers(state)[0])[0]

    # -- static scatter indices ------------------------------------------------
    def _build_scatter(self, pt_part: np.ndarray, pt_local: np.ndarray,
                       vec_part: np.ndarray, vec_local: np.ndarray) -> None:
        """
        Combined marker table and the static indices that scatter slot
        gradients into D and second-order blocks into the tangent.
        """
        self._n_points = pt_part.shape[0]
        self._marker_part = np.concatenate((pt_part, vec_part))
        self._marker_local = np.concatenate((pt_local, vec_local)).reshape(-1, 3)
        self._is_point = np.concatenate((np.ones(pt_part.shape[0]), np.zeros(vec_part.shape[0])))
        self._jac_template = np.zeros((self._marker_part.shape[0], 3, 6))
        self._jac_template[: self._n_points, :, :3] = _EYE
        nc = 6 * (self.n_parts + 1)
        self._nc = nc
        slot_marker, slot_prim, pair_a, pair_b, pair_prim = [], [], [], [], []
        for b in self._batches:
            n = b.param.shape[0]
            rows = b.offset + np.arange(n)
            first = sum(len(m) for m in slot_marker)
            base = []
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

    # -- evaluation -------------------------------------------------------------
    def evaluate(self, state: State, load: LoadCase) -> Evaluation:
        """Residual ingredients and tangent pieces of the equilibrium in ``state``."""
        world, lever, jac = self._markers(state)
        x, grads, hess = self._kernels(world)
        g_slot = np.concatenate(grads)
        j_slot = jac[self._slot_marker]
        d_vals = np.einsum('si,sij->sj', g_slot, j_slot)
        import scipy.sparse

        d = scipy.sparse.csr_matrix((d_vals.ravel(), (self._d_rows, self._d_cols)),
                                    shape=(self.n_prim, self._nc))[:, : self.n_dof]
        if hess:
            ja = j_slot[self._pair_a]
            blocks = np.matmul(np.matmul(ja.transpose(0, 2, 1), np.concatenate(hess)), j_slot[self._pair_b])
        else:
            blocks = np.zeros((0, 6, 6))
        chart = _chart(g_slot, lever[self._slot_marker])
        so_vals = np.concatenate((blocks.ravel(), chart.ravel()))
        g = self.c_g @ x - self.g_design - self._constraint_offset(load)
        jacobian, measure_jacobian = (self.c_g @ d).toarray(), (self.c_e @ d).toarray()
        y = self.c_e @ x - self.e_design - self._energy_offset(load)
        energy, d1, d2 = (np.empty_like(y) for _ in range(3))
        for law, idx in self.laws:
            energy[idx], d1[idx], d2[idx] = law.evaluate(y[idx])
        n_pt = self._n_points
        q_ext, k_ext = self._applied(state, world[:n_pt], world[n_pt:], load)
        return Evaluation(
            self, x, jacobian, measure_jacobian, g, y, energy, d1, d2, q_ext, k_ext, so_vals
        )

    def second_order(self, so_vals: np.ndarray, weights: np.ndarray) -> np.ndarray:
        """
        sum_k weights_k * d2 x_k / dq2 (n_dof, n_dof) from the unweighted
        blocks ``so_vals`` of an evaluation and primitive weights (n_prim,).
        """
        nc = self._nc
        so = np.bincount(self._so_idx, so_vals * weights[self._so_prim], minlength=nc * nc)
        return so.reshape(nc, nc)[: self.n_dof, : self.n_dof]

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

    def _contact(self, world: np.ndarray, vec: np.ndarray) -> tuple[np.ndarray, ...]:
        wheels = self.outputs.wheels
        centre = np.array([world[w.centre] for w in wheels])
        axis = np.array([vec[w.axis] for w in wheels])
        radius = np.array([w.radius for w in wheels])
        return centre, axis, centre + radius[:, None] * contact_direction(axis)

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
        if not (np.any(load.contact_force) or np.any(load.centre_force)
                or np.any(load.contact_moment)):
            return q, k
        centre, _, contact = self._contact(world, vec)
        for s, wheel in enumerate(self.outputs.wheels):
            u = wheel.part
            # a pure moment, fixed in the vehicle axes: no lever, no tangent term
            q[6 * u + 3 : 6 * u + 6] += load.contact_moment[s]
            for at, force in ((contact[s], load.contact_force[s]), (centre[s], load.centre_force[s])):
                lever = at - state.p[u]
                q[6 * u : 6 * u + 3] += force
                q[6 * u + 3 : 6 * u + 6] += np.cross(lever, force)
                k[6 * u + 3 : 6 * u + 6, 6 * u + 3 : 6 * u + 6] += _chart(-force[None], lever[None])[0]
        return q, k


def contact_direction(axis: np.ndarray) -> np.ndarray:
    """
    Unit vector (n, 3) from wheel centre to contact point: the road normal
    (+z) projected into the wheel plane of spin axis ``axis`` (n, 3), negated.
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
    so_vals: np.ndarray  # unweighted second-order blocks of the primitives

    def force_residual(self, lam: np.ndarray) -> np.ndarray:
        """Grad V - Q + J^T lambda (n_dof,), N and N*m."""
        return self.measure_jacobian.T @ self.d1 - self.q_ext + self.jacobian.T @ lam

    def tangent(self, lam: np.ndarray) -> np.ndarray:
        """d(force residual)/dq (n_dof, n_dof) at fixed lambda."""
        s, e = self.system, self.measure_jacobian
        weights = s.c_e.T @ self.d1 + s.c_g.T @ lam
        stiff = np.nonzero(self.d2)[0]  # measures with a diagonal stiffness
        k = e[stiff].T @ (self.d2[stiff, None] * e[stiff])
        k += s.second_order(self.so_vals, weights) + self.k_ext
        for (_, matrix), (rows, square) in zip(s.coupled, s._coupled_cols):
            block = e[rows]
            k[square] += block.T @ matrix @ block
        return k


def _skew(w: np.ndarray) -> np.ndarray:
    out = np.zeros(w.shape[:-1] + (3, 3))
    out[..., 0, 1], out[..., 0, 2] = -w[..., 2], w[..., 1]
    out[..., 1, 0], out[..., 1, 2] = w[..., 2], -w[..., 0]
    out[..., 2, 0], out[..., 2, 1] = -w[..., 1], w[..., 0]
    return out


def _chart(g: np.ndarray, w: np.ndarray) -> np.ndarray:
    """
    Second-order rotation term of G.(R s) in exponential coordinates:
    sym(G w^T) - (G.w) I, for G (n, 3) and w = R s (n, 3).
    """
    outer = g[:, :, None] * w[:, None, :]
    return 0.5 * (outer + outer.transpose(0, 2, 1)) - np.einsum('ni,ni->n', g, w)[:, None, None] * _EYE


# --- building ---------------------------------------------------------------

MeasureLike = Union[Measure, Primitive]


class _Builder:
    """Collects parts, markers, primitives, constraints and potentials."""

    def __init__(self) -> None:
        self.parts: dict[str, np.ndarray] = {}
        self._prims: dict[Primitive, int] = {}
        self.constraints: list[Measure] = []
        self.measures: list[Measure] = []
        self.laws: list[tuple[EnergyLaw, np.ndarray]] = []
        self.extra_points: list[PointRef] = []  # reported only

    def part(self, name: str, origin: np.ndarray) -> str:
        self.parts[name] = np.asarray(origin, dtype=float)
        return name

    def prim(self, p: Primitive) -> int:
        return self._prims.setdefault(p, len(self._prims))

    @staticmethod
    def _measure(m: MeasureLike) -> Measure:
        return [(m, 1.0)] if isinstance(m, Primitive) else m

    def constrain(self, m: MeasureLike) -> int:
        measure = self._measure(m)
        for p, _ in measure:
            self.prim(p)
        self.constraints.append(measure)
        return len(self.constraints) - 1

    def energy(self, ms: list[MeasureLike], law: EnergyLaw) -> np.ndarray:
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

    def build(self, outputs_factory: _OutputsFactory) -> System:
        names = list(self.parts)
        index = {n: i for i, n in enumerate(names)}
        ground = len(names)
        origins = np.array([self.parts[n] for n in names]).reshape(-1, 3)
        prims = list(self._prims)
        points: dict[PointRef, int] = {}
        vectors: dict[VectorRef, int] = {}
        for p in prims:
            for m in p.markers:
                table = points if isinstance(m, PointRef) else vectors
                table.setdefault(m, len(table))  # type: ignore[arg-type]
        for m in self.extra_points:
            points.setdefault(m, len(points))

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
        batches: list[_Batch] = []
        for kind in PrimKind:
            members = [i for i, p in enumerate(prims) if p.kind is kind]
            if not members:
                continue
            # Marker indices into the combined table: points, then vectors.
            slot_idx = tuple(
                np.array(
                    [
                        points[prims[i].markers[s]] if t == 'p'  # type: ignore[index]
                        else len(points) + vectors[prims[i].markers[s]]  # type: ignore[index]
                        for i in members
                    ],
                    dtype=int,
                )
                for s, t in enumerate(SLOTS[kind])
            )
            width = max(len(prims[i].param) for i in members)
            param = np.array([prims[i].param or (0.0,) * width for i in members]).reshape(len(members), -1)
            batches.append(_Batch(kind, len(order), slot_idx, param))
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
        prim_position = {p: int(position[i]) for i, p in enumerate(prims)}
        outputs = outputs_factory(index, points, vectors, prim_position)
        return System(
            names, origins, pt_part, pt_local, vec_part, vec_local, batches,
            matrix(self.constraints), matrix(self.measures), laws, outputs,
        )


class _OutputsFactory:
    """Deferred :class:`Outputs`: marker and part indices exist only after build."""

    def __init__(self) -> None:
        self.wheels: dict[Side, tuple[str, PointRef, VectorRef, float]] = {}
        self.pad_rows: dict[Side, int] = {}
        self.tracked: dict[Side, dict[str, PointRef]] = {'left': {}, 'right': {}}
        self.spring: dict[Side, int] = {}
        self.spring_length: dict[Side, Primitive] = {}
        self.damper: dict[Side, Primitive] = {}
        self.bump: dict[Side, int] = {}
        self.rebound: dict[Side, int] = {}
        self.bushings: dict[str, dict[Side, np.ndarray]] = {}
        self.arb_twist: int | None = None
        self.arb_arms: dict[Side, str] = {}
        self.droplink_rows: dict[Side, int] = {}
        self.rack_measure: int | None = None
        self.rack_row: int | None = None
        self.elastic: list[int] = []
        self.steer_sign = 1.0
        self.components: list[Condensed] = []

    def __call__(
        self,
        parts: Mapping[str, int],
        points: Mapping[PointRef, int],
        vectors: Mapping[VectorRef, int],
        prim_pos: Mapping[Primitive, int],
    ) -> Outputs:
        def pair(d: Mapping[Side, int]) -> np.ndarray:
            return np.array([d[s] for s in SIDES], dtype=int)

        wheels = tuple(
            Wheel(parts[part], points[c], vectors[a], r)
            for part, c, a, r in (self.wheels[s] for s in SIDES)
        )
        return Outputs(
            wheels=wheels,  # type: ignore[arg-type]
            pad_rows=pair(self.pad_rows),
            tracked=tuple({k: points[v] for k, v in self.tracked[s].items()} for s in SIDES),  # type: ignore[arg-type]
            spring=pair(self.spring),
            spring_length=np.array([prim_pos[self.spring_length[s]] for s in SIDES], dtype=int),
            damper_length=np.array([prim_pos[self.damper[s]] for s in SIDES], dtype=int),
            bump_stop=pair(self.bump) if self.bump else None,
            rebound_stop=pair(self.rebound) if self.rebound else None,
            bushings={n: np.array([d[s] for s in SIDES]) for n, d in self.bushings.items()},
            arb_twist=self.arb_twist,
            arb_arms=np.array([parts[self.arb_arms[s]] for s in SIDES]) if self.arb_arms else None,
            droplink_rows=pair(self.droplink_rows) if self.droplink_rows else None,
            rack_part=parts.get(RACK),
            rack_measure=self.rack_measure,
            rack_row=self.rack_row,
            elastic=np.array(self.elastic, dtype=int),
            steer_sign=self.steer_sign,
            components=tuple(self.components),
        )


def assemble(inp: SuspensionInput) -> System:
    """The axle model of ``inp``; SolverError on any unusable input."""
    validate(inp)
    template = TEMPLATES.get(inp.template)
    if template is None:
        raise SolverError(
            f'unknown suspension template {inp.template!r}; known: {sorted(TEMPLATES)}'
        )
    required = template.required_points + (ARB_POINTS if inp.stabilizer is not None else ()) \
        + (SUBFRAME_POINTS if SUBFRAME in inp.flexible else ())
    for name in required:
        if name not in inp.hardpoints:
            raise SolverError(f'template {template.name!r}: hard point {name!r} is missing')
        value = np.asarray(inp.hardpoints[name], dtype=float)
        if value.shape != (3,) or not np.all(np.isfinite(value)):
            raise SolverError(f'hard point {name!r} must be 3 finite coordinates (m)')
    topo = template.topology()
    _check_keys(inp, topo)
    return _Assembly(inp, template, topo).run()


def _check_keys(inp: SuspensionInput, topo: Topology) -> None:
    """Bushings, masses and joint axes must name something the template has."""
    connections = {j.point for j in topo.joints} | {
        p for link in topo.links for p in (link.inboard_point, link.outboard_point)
    }
    for name in inp.bushings:
        if name not in connections:
            raise SolverError(
                f'bushing {name!r} does not name a connection; known: {sorted(connections)}'
            )
    masses = {p.name for p in topo.parts} | {link.name for link in topo.links} | {'wheel'}
    for name in inp.masses:
        if name not in masses:
            raise SolverError(f'mass {name!r} names no part; known: {sorted(masses)}')
    known = topo.flexible_components(inp.stabilizer is not None)
    for name in inp.flexible:
        if name not in known:
            raise SolverError(f"unknown flexible component {name!r} (components of template "
                              f"{inp.template!r}: {', '.join(known)})")
    universals = {j.point for j in topo.joints if j.kind == 'universal'}
    for name in inp.joint_axes:
        if name not in universals:
            raise SolverError(f'joint_axes {name!r} is not a universal joint; known: {sorted(universals)}')


class _Assembly:
    """One pass over the template for both sides."""

    def __init__(self, inp: SuspensionInput, template: SuspensionTemplate, topo: Topology) -> None:
        self.inp, self.template, self.topo = inp, template, topo
        self.b = _Builder()
        self.out = _OutputsFactory()
        self.steered = inp.steering is not None
        #: (component, side) -> hard point -> node part, for flexible components
        self.nodes: dict[tuple[str, Side], dict[str, str]] = {}
        self._condensed: dict[str, Condensed] = {}

    def run(self) -> System:
        inp = self.inp
        if self.steered:
            self._rack()
        if SUBFRAME in inp.flexible:
            self._flex_subframe()
        for side in SIDES:
            self._corner(side)
        if inp.stabilizer is not None:
            if BAR in inp.flexible:
                self._flex_bar()
            else:
                self._bar_torsion()
        for side in SIDES:
            self._tracking(side)
        return self.b.build(self.out)

    # -- helpers ---------------------------------------------------------------
    def hp(self, name: str, side: Side) -> np.ndarray:
        return mirror(self.inp.hardpoints[name], side)

    def at(self, part: str, point_name: str, side: Side) -> str:
        """
        The part that carries hard point ``point_name`` of ``part``: the part
        itself, or the node of a flexible component at that point (its
        reference node if the point is no node of it).
        """
        resolved = self.resolve(part, side)
        if resolved == GROUND:
            carried = self.nodes.get((SUBFRAME, 'left'), {})
            return carried.get(f'{point_name}.{side}', GROUND)
        nodes = self.nodes.get((part, side))
        if nodes is None:
            return resolved
        return nodes.get(point_name, next(iter(nodes.values())))

    def resolve(self, part: str, side: Side) -> str:
        if part == GROUND:
            return GROUND
        if part == STEERING:
            return RACK if self.steered else GROUND
        return f'{part}.{side}'

    def _gravity(self, part: str, at: np.ndarray, mass: float) -> None:
        if part == GROUND or mass == 0.0:
            return
        prim = Primitive(PrimKind.COMP, (point(part, at), point(GROUND, np.zeros(3))), (0.0, 0.0, 1.0))
        self.b.energy([prim], LinearLaw(np.zeros(1), np.array([mass * GRAVITY])))

    def _connection(
        self, kind: str, name: str, a: str, b: str, at: np.ndarray, side: Side,
        axis: np.ndarray | None = None, cross: tuple[np.ndarray, np.ndarray] | None = None,
    ) -> None:
        """Ideal joint, or the input's bushing keyed by ``name``."""
        bushing = self.inp.bushings.get(name)
        if bushing is None:
            for prim in joint_constraints(kind, a, b, at, axis, cross):  # type: ignore[arg-type]
                self.b.constrain(prim)
            return
        frame, signs = side_frame(bushing_frame(bushing.axial), side)
        measures = bushing_measures(a, b, at, frame, signs)
        idx = [
            self.b.energy([m], stiffness_law(k))[0] for m, k in zip(measures, bushing.stiffness)
        ]
        self.out.bushings.setdefault(name, {})[side] = np.array(idx)
        self.out.elastic.extend(idx)

    # -- pieces ---------------------------------------------------------------
    def _rack(self) -> None:
        inp = self.inp
        steering = inp.steering
        assert steering is not None
        inner = self.hp('tierod_inner', 'left')
        centre = np.array([inner[0], 0.0, inner[2]])
        self.b.part(RACK, centre)
        y = np.array([0.0, 1.0, 0.0])
        for prim in joint_constraints('translational', GROUND, RACK, centre, y):
            self.b.constrain(prim)
        travel = Primitive(PrimKind.COMP, (point(RACK, centre), point(GROUND, centre)), (0.0, 1.0, 0.0))
        compliance = steering.rack_compliance()
        if compliance == 0.0:
            self.out.rack_row = self.b.constrain(travel)
        else:
            law = LinearLaw(np.array([1.0 / compliance]), np.zeros(1))
            self.out.rack_measure = int(self.b.energy([travel], law)[0])
            self.out.elastic.append(self.out.rack_measure)
        # A rack ahead of the wheel centre steers left when moving left.
        ahead = inp.hardpoints['tierod_outer'][0] > inp.hardpoints['wheel_centre'][0]
        self.out.steer_sign = 1.0 if ahead else -1.0

    def _corner(self, side: Side) -> None:
        inp, topo, b = self.inp, self.topo, self.b
        masses = inp.masses
        for part in topo.parts:
            if part.name in inp.flexible:
                self._flex_part(part, side)
                continue
            at = np.mean([self.hp(n, side) for n in part.points], axis=0)
            name = b.part(self.resolve(part.name, side), at)
            self._gravity(name, at, masses.get(part.name, 0.0))
        for j in topo.joints:
            a, c = self.at(j.inboard, j.point, side), self.at(j.outboard, j.point, side)
            at = self.hp(j.point, side)
            axis = cross = None
            if j.axis is not None:
                axis = self.hp(j.axis[1], side) - self.hp(j.axis[0], side)
            if j.kind == 'universal':
                given = inp.joint_axes.get(j.point)
                if given is not None:
                    cross = (mirror(given[0], side), mirror(given[1], side))
                else:
                    # Both cross axes perpendicular to the link: the joint then
                    # only stops the link's spin about its own axis.
                    cross = perpendicular_basis(axis)  # type: ignore[arg-type]
            kind = j.kind
            if kind == 'inline' and (j.inboard in inp.flexible or j.outboard in inp.flexible):
                # The in-line rear pivot only avoids a redundant constraint on a rigid arm;
                # a flexible arm needs its pivot held in place, as its bushing sleeve is.
                kind = 'spherical'
            self._connection(kind, j.point, a, c, at, side, axis, cross)
        for link in topo.links:
            self._link(link, side)
        self._wheel(side)
        self._force_lines(side)
        if inp.stabilizer is not None and BAR not in inp.flexible:
            self._bar_arm(side)

    def _link(self, link: LinkDef, side: Side) -> None:
        """
        Distance constraint, or a rigid link part when an end has a bushing
        (its spin about its own axis is then held by the bushing).
        """
        inp, b = self.inp, self.b
        a = self.at(link.inboard, link.inboard_point, side)
        c = self.at(link.outboard, link.outboard_point, side)
        pa, pc = self.hp(link.inboard_point, side), self.hp(link.outboard_point, side)
        if link.name in inp.flexible:
            self._flex_link(link, side, a, c, pa, pc)
            return
        mass = inp.masses.get(link.name, 0.0)
        # A link's mass is split between its two ends (two-force member).
        self._gravity(a, pa, 0.5 * mass)
        self._gravity(c, pc, 0.5 * mass)
        ends = ((link.inboard_point, a, pa), (link.outboard_point, c, pc))
        if not any(name in inp.bushings for name, _, _ in ends):
            b.constrain(Primitive(PrimKind.DIST, (point(a, pa), point(c, pc))))
            return
        body = b.part(f'{link.name}.{side}', 0.5 * (pa + pc))
        for name, part, at in ends:
            self._connection('spherical', name, part, body, at, side)

    def _wheel(self, side: Side) -> None:
        inp, b = self.inp, self.b
        upright = self.at(self.topo.wheel_part, 'wheel_centre', side)
        centre = self.hp('wheel_centre', side)
        toe, camber = inp.toe, inp.camber
        # Outward spin axis from ISO toe (+ = toe-in) and camber (+ = top out).
        left = np.array([np.sin(toe) * np.cos(camber), np.cos(toe) * np.cos(camber), -np.sin(camber)])
        axis = mirror(left, side)
        pc, va = point(upright, centre), vector(upright, axis)
        row = b.constrain(Primitive(PrimKind.CPZ, (pc, va), (inp.tire_radius,)))
        self.out.pad_rows[side] = row
        self.out.wheels[side] = (upright, pc, va, inp.tire_radius)
        self._gravity(upright, centre, inp.masses.get('wheel', 0.0))

    def _force_lines(self, side: Side) -> None:
        inp, topo, b = self.inp, self.topo, self.b
        sp = topo.spring
        upper, lower = self.hp(sp.upper, side), self.hp(sp.lower, side)
        length = Primitive(PrimKind.DIST, (point(GROUND, upper), point(self.at(sp.part, sp.lower, side), lower)))
        design = float(np.linalg.norm(upper - lower))
        self.out.spring[side] = int(b.energy([length], spring_law(inp.spring, design))[0])
        self.out.spring_length[side] = length
        self.out.elastic.append(self.out.spring[side])
        dp = topo.damper
        upper, lower = self.hp(dp.upper, side), self.hp(dp.lower, side)
        damper = Primitive(PrimKind.DIST, (point(GROUND, upper), point(self.at(dp.part, dp.lower, side), lower)))
        b.prim(damper)
        self.out.damper[side] = damper
        for stop, direction, store in (
            (inp.bump_stop, -1.0, self.out.bump),
            (inp.rebound_stop, 1.0, self.out.rebound),
        ):
            if stop is not None:
                law = StopLaw(stop.curve, stop.clearance, direction)
                store[side] = int(b.energy([damper], law)[0])
                self.out.elastic.append(store[side])

    def _bar_arm(self, side: Side) -> None:
        b = self.b
        pivot = self.hp('arb_pivot', side)
        upper = self.hp('arb_link_upper', side)
        arm = b.part(f'arb_arm.{side}', pivot)
        for prim in joint_constraints('revolute', GROUND, arm, pivot, np.array([0.0, 1.0, 0.0])):
            b.constrain(prim)
        lower_part = self.at(self.topo.arb_part, 'arb_link_lower', side)
        lower = self.hp('arb_link_lower', side)
        row = b.constrain(Primitive(PrimKind.DIST, (point(lower_part, lower), point(arm, upper))))
        self.out.droplink_rows[side] = row
        self.out.arb_arms[side] = arm

    def _bar_torsion(self) -> None:
        stab = self.inp.stabilizer
        assert stab is not None
        # sin(psi_left - psi_right) for rotations psi about y of the two arms.
        twist = Primitive(
            PrimKind.DOT,
            (vector('arb_arm.left', np.array([0.0, 0.0, 1.0])), vector('arb_arm.right', np.array([1.0, 0.0, 0.0]))),
        )
        self.out.arb_twist = int(self.b.energy([twist], TorsionLaw(stab.torsional_stiffness))[0])
        self.out.elastic.append(self.out.arb_twist)

    def _tracking(self, side: Side) -> None:
        """A point marker per hard point on the part whose motion it follows."""
        topo, inp = self.topo, self.inp
        owner: dict[str, str] = {}
        for part in topo.parts:
            for n in part.points:
                owner.setdefault(n, part.name)
        for j in topo.joints:
            owner.setdefault(j.point, j.inboard)
        for link in topo.links:
            owner.setdefault(link.inboard_point, link.inboard)
            owner.setdefault(link.outboard_point, link.outboard)
        owner.setdefault(topo.spring.lower, topo.spring.part)
        owner.setdefault(topo.damper.lower, topo.damper.part)
        owner.update(topo.tracked)
        if inp.stabilizer is not None:
            owner['arb_link_lower'] = topo.arb_part
        tracked = self.out.tracked[side]
        for name in inp.hardpoints:
            part = owner.get(name, GROUND)
            if name == 'arb_link_upper' and inp.stabilizer is not None:
                resolved = (self.nodes[(BAR, 'left')][f'arb_link_upper.{side}']
                            if BAR in inp.flexible else f'arb_arm.{side}')
            else:
                resolved = self.at(part, name, side)
            ref = point(resolved, self.hp(name, side))
            self.b.extra_points.append(ref)
            tracked[name] = ref

    # -- flexible components ------------------------------------------------------
    def _attachments(self, part: str) -> list[str]:
        """
        Hard points of other elements that act on ``part`` (spring and damper
        seats, the drop-link mount): they must be nodes of its FE frame.
        """
        topo, out = self.topo, []
        for line in (topo.spring, topo.damper):
            if line.part == part:
                out.append(line.lower)
        if self.inp.stabilizer is not None and topo.arb_part == part:
            out.append('arb_link_lower')
        return out

    def _component(self, name: str, points: list[str], members, attachments=()) -> Condensed:
        """The left-side condensed component ``name`` (built once)."""
        if name in self._condensed:
            return self._condensed[name]
        spec: FlexSpec = self.inp.flexible[name]
        hp = {n: np.asarray(self.inp.hardpoints[n], dtype=float) for n in points}
        if spec.imported is not None:
            comp = _check_imported(name, spec.imported, hp)
        else:
            comp = build(name, hp, members, spec.material, spec.section,  # type: ignore[arg-type]
                         attachments=attachments, shape_points=spec.shape_points,
                         elements_per_member=spec.elements_per_member)
        self._condensed[name] = comp
        self.out.components.append(comp)
        return comp

    def _embed(self, comp: Condensed, side: Side, key: tuple[str, Side],
               positions: np.ndarray, stiffness: np.ndarray, cog: np.ndarray) -> dict[str, str]:
        """
        Node parts of a condensed component and its co-rotational potential.

        Deformations are measured in the frame of the first node (the
        reference): per other node, its displacement relative to the point of
        the reference frame it coincided with, and its small-angle rotation
        relative to that frame (the six bushing measures). Rigid motions of all
        nodes leave every measure at zero, so the potential is objective; the
        stiffness on these measures is the condensed one with the reference
        node clamped (exact for a matrix whose null space is the rigid modes).
        """
        b = self.b
        nodes = {n: b.part(f'{key[0]}.{key[1]}@{n}', positions[i])
                 for i, n in enumerate(comp.nodes)}
        ref = nodes[comp.nodes[0]]
        measures = []
        for i, n in enumerate(comp.nodes[1:], start=1):
            measures += bushing_measures(ref, nodes[n], positions[i], np.eye(3), np.ones(6))
        idx = b.energy(measures, MatrixLaw(clamped(stiffness)))
        self.out.elastic.extend(int(i) for i in idx)
        self._gravity(ref, cog, comp.mass)
        for alias, target in comp.aliases.items():
            nodes[alias] = nodes[target]
        self.nodes[key] = nodes
        return nodes

    def _flex_part(self, part: PartDef, side: Side) -> None:
        members = self.topo.frames.get(part.name)
        if members is None:
            raise SolverError(f'template {self.template.name!r} has no beam frame for part '
                              f'{part.name!r}; it cannot be made flexible')
        extra = [p for p in part.points + tuple(self._attachments(part.name))
                 if p not in {n for m in members for n in m}]
        points = list(dict.fromkeys([n for m in members for n in m] + extra))
        comp = self._component(part.name, points, members, extra)
        self._place(comp, part.name, side)

    def _place(self, comp: Condensed, name: str, side: Side) -> dict[str, str]:
        positions = np.array([mirror(p, side) for p in comp.positions])
        stiffness = comp.stiffness if side == 'left' else mirror_stiffness(comp.stiffness)
        return self._embed(comp, side, (name, side), positions, stiffness, mirror(comp.cog, side))

    def _flex_link(self, link: LinkDef, side: Side, a: str, c: str,
                   pa: np.ndarray, pc: np.ndarray) -> None:
        """
        A flexible two-force link: a beam between its ball joints. Ideal ball
        joints at both ends would leave its spin about its own axis free, so the
        inboard joint is a universal joint whose cross is normal to the link (it
        only stops the spin, which carries no load).
        """
        comp = self._component(link.name, [link.inboard_point, link.outboard_point],
                               [(link.inboard_point, link.outboard_point)])
        nodes = self._place(comp, link.name, side)
        inner, outer = nodes[link.inboard_point], nodes[link.outboard_point]
        axis = pc - pa
        self._connection('universal', link.inboard_point, a, inner, pa, side, axis,
                         perpendicular_basis(axis))
        self._connection('spherical', link.outboard_point, outer, c, pc, side)

    def _flex_subframe(self) -> None:
        """
        A subframe carrying the template's body-side pivots of both sides: per side a
        rail from the front mount through the carried points to the rear mount, and
        cross-members joining each carried point to its mirror image. The mounts are
        bolted to the body (fixed joints); the carried joints and bushings attach to the
        subframe's nodes instead of the body.
        """
        spec = self.inp.flexible[SUBFRAME]
        if spec.imported is not None:
            raise SolverError('subframe: an imported stiffness is not supported for the subframe')
        carried = self.topo.subframe_points
        chain = ('subframe_front',) + carried + ('subframe_rear',)
        points = {f'{n}.{s}': mirror(self.inp.hardpoints[n], s) for s in SIDES for n in chain}
        members = [(f'{a}.{s}', f'{b}.{s}') for s in SIDES for a, b in zip(chain, chain[1:])]
        members += [(f'{n}.left', f'{n}.right') for n in carried]
        comp = build(SUBFRAME, points, members, spec.material, spec.section,  # type: ignore[arg-type]
                     elements_per_member=spec.elements_per_member)
        self.out.components.append(comp)
        nodes = self._embed(comp, 'left', (SUBFRAME, 'left'), comp.positions, comp.stiffness,
                            comp.cog)
        for s in SIDES:
            for mount in ('subframe_front', 'subframe_rear'):
                name = f'{mount}.{s}'
                for prim in joint_constraints('fixed', GROUND, nodes[name], points[name]):
                    self.b.constrain(prim)

    def _flex_bar(self) -> None:
        """
        The anti-roll bar as a beam frame: drop-link end, arm, body mount
        (pivot), torsion part across to the other side. The mounts are ball
        joints on the body; the drop links are distance constraints.
        """
        spec = self.inp.flexible[BAR]
        names = {s: (f'arb_link_upper.{s}', f'arb_pivot.{s}') for s in SIDES}
        points = {f'{n}.{s}': mirror(self.inp.hardpoints[n], s) for s in SIDES
                  for n in ('arb_link_upper', 'arb_pivot')}
        members = [names['left'], (names['left'][1], names['right'][1]),
                   (names['right'][1], names['right'][0])]
        if spec.imported is not None:
            raise SolverError('anti_roll_bar: an imported stiffness is not supported for the bar')
        shapes = []
        for sp in spec.shape_points:
            if (sp.start, sp.end) != ('arb_link_upper', 'arb_pivot'):
                raise SolverError('anti_roll_bar: shape points lie on the arm, from '
                                  'arb_link_upper to arb_pivot')
            shapes.append(type(sp)(names['left'][0], names['left'][1], sp.fraction, sp.offset))
            shapes.append(type(sp)(names['right'][1], names['right'][0], 1.0 - sp.fraction,
                                   tuple(mirror(np.asarray(sp.offset), 'right'))))
        arm = spec.arm_section or spec.section
        comp = build(BAR, points, members, spec.material, spec.section,  # type: ignore[arg-type]
                     shape_points=shapes, elements_per_member=spec.elements_per_member,
                     member_sections={names['left']: arm, members[2]: arm})
        self.out.components.append(comp)
        nodes = self._embed(comp, 'left', (BAR, 'left'), comp.positions, comp.stiffness, comp.cog)
        for side in SIDES:
            upper, pivot = names[side]
            for prim in joint_constraints('spherical', GROUND, nodes[pivot], points[pivot]):
                self.b.constrain(prim)
            lower = self.hp('arb_link_lower', side)
            lower_part = self.at(self.topo.arb_part, 'arb_link_lower', side)
            row = self.b.constrain(Primitive(PrimKind.DIST, (point(lower_part, lower),
                                                             point(nodes[upper], points[upper]))))
            self.out.droplink_rows[side] = row
            self.out.arb_arms[side] = nodes[upper]


def _check_imported(name: str, comp: Condensed, hardpoints: dict[str, np.ndarray]) -> Condensed:
    """An imported reduced stiffness must have its nodes on the component's hard points."""
    missing = [n for n in hardpoints if n not in comp.nodes]
    if missing:
        raise SolverError(f"flexible component {name!r}: the imported stiffness has no node "
                          f"for hard point(s) {', '.join(missing)} (nodes: {', '.join(comp.nodes)})")
    order = [comp.nodes.index(n) for n in hardpoints]
    extra = [n for n in comp.nodes if n not in hardpoints]
    if extra:
        raise SolverError(f"flexible component {name!r}: imported node(s) {', '.join(extra)} are "
                          f"not attachment points of this component ({', '.join(hardpoints)})")
    for i, n in zip(order, hardpoints):
        gap = float(np.linalg.norm(comp.positions[i] - hardpoints[n]))
        if np.isfinite(gap) and gap > IMPORT_POSITION_TOL:
            raise SolverError(f'flexible component {name!r}: imported node {n} lies '
                              f'{gap * 1e3:.1f} mm from the hard point (more than '
                              f'{IMPORT_POSITION_TOL * 1e3:g} mm): the stiffness belongs to '
                              'other geometry')
    dofs = np.concatenate([np.arange(6 * i, 6 * i + 6) for i in order])
    positions = np.array([hardpoints[n] for n in hardpoints])
    cog = comp.cog if np.all(np.isfinite(comp.cog)) else positions.mean(axis=0)
    return Condensed(name, tuple(hardpoints), positions, comp.stiffness[np.ix_(dofs, dofs)],
                     comp.mass, cog, 0, comp.source)


#: how far an imported node may lie from its hard point, m
IMPORT_POSITION_TOL = 0.002
