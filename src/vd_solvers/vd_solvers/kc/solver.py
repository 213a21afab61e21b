# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Static equilibrium of the axle on the K&C rig: Newton on the KKT system.

For a load case the rig imposes (pad heights, applied forces, rack travel)
find poses q and multipliers lambda with

    grad V(q) - Q(q) + J(q)^T lambda = 0        (force balance, N and N*m)
    g(q) = 0                                    (joints, pads, rack; m)

Each Newton step solves

    [ K   s J^T ] [ dq ]   [ -(grad V - Q) ]
    [ s J   0   ] [ mu ] = [ -s g          ],   lambda_new = s mu,

with K the exact tangent (potentials, constraint curvature weighted by
lambda, applied-load stiffness) and s the largest entry of K, which puts both
blocks on one scale so that the LU pivots reveal a singular (locked or
unrestrained) mechanism. Poses update as p += dp, R <- exp([dtheta]x) R.

Along an event the previous solution is the initial guess (continuation); a
step that fails is halved up to ``MAX_SUBDIVISIONS`` times before the event
fails with a :class:`~vd_solvers.errors.SolverError` naming event and step.
"""
from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
import scipy.linalg.lapack

from vd_solvers.errors import SolverError

from .system import Evaluation, LoadCase, State, System

CONSTRAINT_TOL = 1e-9  # m; angular rows (dot products) in rad, i.e. m at 1 m lever
FORCE_TOL = 1e-6  # N and N*m, absolute ...
# ... or, if larger, the force of the stiffest element at a position error of
# this size (~50 ulp of 1 m): the round-off floor of very stiff bushings.
ROUNDOFF_LENGTH = 1e-14  # m
MAX_NEWTON_ITERATIONS = 30
MAX_SUBDIVISIONS = 8  # halvings of one event step (1/256 of the step)
MAX_TRANSLATION_STEP = 0.05  # m per Newton iteration and part
MAX_ROTATION_STEP = 0.2  # rad per Newton iteration and part
MAX_STEP_ROTATION = 0.15  # rad of any part between converged neighbours: guards branch jumps
SINGULAR_PIVOT_RATIO = 1e-13  # smallest/largest LU pivot of the scaled KKT matrix

_GETRF, _GETRS = scipy.linalg.lapack.get_lapack_funcs(('getrf', 'getrs'), (np.zeros(1),))


@dataclass(frozen=True)
class Convergence:
    """
    How one load case converged.

    Newton iterations, max |g| (m) and max force-balance residual (N or N*m).
    """

    iterations: int
    constraint_residual: float
    force_residual: float


class _StepFailure(Exception):
    """A load case did not converge from the given start (may be retried)."""


def rotation_vectors_to_matrices(theta: np.ndarray) -> np.ndarray:
    """exp([theta]x) for rotation vectors ``theta`` (n, 3) -> (n, 3, 3)."""
    angle = np.linalg.norm(theta, axis=1)
    small = angle < 1e-8
    safe = np.where(small, 1.0, angle)
    # sin(a)/a and (1 - cos a)/a^2 with their series near zero.
    a = np.where(small, 1.0 - angle**2 / 6.0, np.sin(safe) / safe)
    b = np.where(small, 0.5 - angle**2 / 24.0, (1.0 - np.cos(safe)) / safe**2)
    k = np.zeros((theta.shape[0], 3, 3))
    k[:, 0, 1], k[:, 0, 2] = -theta[:, 2], theta[:, 1]
    k[:, 1, 0], k[:, 1, 2] = theta[:, 2], -theta[:, 0]
    k[:, 2, 0], k[:, 2, 1] = -theta[:, 1], theta[:, 0]
    return np.eye(3) + a[:, None, None] * k + b[:, None, None] * (k @ k)


def _rotation_angle(r_new: np.ndarray, r_old: np.ndarray) -> float:
    """Largest rotation angle (rad) between two pose sets (n, 3, 3)."""
    if r_new.shape[0] == 0:
        return 0.0
    rel = np.einsum('nij,nkj->nik', r_new, r_old)
    cos = np.clip((np.trace(rel, axis1=1, axis2=2) - 1.0) / 2.0, -1.0, 1.0)
    return float(np.max(np.arccos(cos)))


def newton(system: System, state: State, load: LoadCase) -> tuple[State, Evaluation, Convergence]:
    """
    Equilibrium for ``load`` from the initial guess ``state`` (not modified).

    Raises _StepFailure with the reason when it does not converge.
    """
    state = state.copy()
    for iteration in range(MAX_NEWTON_ITERATIONS + 1):
        try:
            ev = system.evaluate(state, load)
        except SolverError as err:  # e.g. a link collapsed on a wild iterate
            raise _StepFailure(str(err)) from err
        residual = ev.force_residual(state.lam)
        c_res = float(np.max(np.abs(ev.g), initial=0.0))
        f_res = float(np.max(np.abs(residual), initial=0.0))
        stiffest = max(float(np.max(np.abs(ev.d2), initial=0.0)), system.coupled_max) * float(
            np.max(np.abs(ev.measure_jacobian), initial=0.0)
        ) ** 2
        if c_res <= CONSTRAINT_TOL and f_res <= max(FORCE_TOL, ROUNDOFF_LENGTH * stiffest):
            return state, ev, Convergence(iteration, c_res, f_res)
        if iteration == MAX_NEWTON_ITERATIONS:
            break
        j = ev.jacobian
        factors = _kkt(ev.tangent(state.lam), j)
        if factors is None:
            raise _StepFailure(
                'singular equilibrium equations: the mechanism is locked (at a '
                'singular position) or a part is unrestrained'
            )
        s = factors[2]
        n = j.shape[1]
        rhs = np.concatenate((-(residual - j.T @ state.lam), -s * ev.g))
        sol = _lu_solve(factors, rhs)
        dq = sol[:n].reshape(-1, 6)
        longest = max(
            float(np.max(np.linalg.norm(dq[:, :3], axis=1), initial=0.0)) / MAX_TRANSLATION_STEP,
            float(np.max(np.linalg.norm(dq[:, 3:], axis=1), initial=0.0)) / MAX_ROTATION_STEP,
            1.0,
        )
        dq = dq / longest
        state.p = state.p + dq[:, :3]
        state.R = np.einsum('nij,njk->nik', rotation_vectors_to_matrices(dq[:, 3:]), state.R)
        state.lam = s * sol[n:]
    raise _StepFailure(
        f"no equilibrium after {MAX_NEWTON_ITERATIONS} Newton iterations (max |g| = "
        f"{c_res:.3g} m, force residual {f_res:.3g} N); the step may be outside the "
        "mechanism's range"
    )


def solve_static(
    system: System, load: LoadCase, describe: str, start: State | None = None
) -> tuple[State, Evaluation, Convergence]:
    """
    Solve the equilibrium for ``load`` from ``start`` (default: the design pose).

    Raises SolverError prefixed with ``describe`` when there is none.
    """
    try:
        return newton(system, system.design_state() if start is None else start, load)
    except _StepFailure as failure:
        raise SolverError(f'{describe}: {failure}') from None


@dataclass(frozen=True)
class Solution:
    """Converged states of an event, in step order, with their evaluations."""

    states: tuple[State, ...]
    evaluations: tuple[Evaluation, ...]
    convergence: tuple[Convergence, ...]


def solve_path(
    system: System,
    cases: Sequence[LoadCase],
    start: int,
    describe: Callable[[int], str],
    on_step: Callable[[int, int], None] | None = None,
) -> Solution:
    """
    Equilibria of ``cases`` by continuation from the design state.

    The walk starts at ``cases[start]`` (the one nearest the design load) and
    runs outward in both directions. ``describe(i)`` names step i in errors;
    ``on_step(done, total)`` is called after each solved step (progress; it may
    raise to abandon the event).
    """
    n = len(cases)
    states: list[State | None] = [None] * n
    evals: list[Evaluation | None] = [None] * n
    conv: list[Convergence | None] = [None] * n
    design = LoadCase()
    state, _, _ = _advance(system, system.design_state(), None, design, design, 0, start, describe)
    for walk in (range(start, n), range(start - 1, -1, -1)):
        if walk.start == start:
            previous, before = design, None
        else:
            state, previous, before = states[start], cases[start], None  # type: ignore[assignment]
        for i in walk:
            # Events step uniformly, so the last increment predicts the next.
            guess: State | None = _extrapolate(before, state) if before is not None else None
            new, evals[i], conv[i] = _advance(system, state, guess, previous, cases[i], 0, i,
                                              describe)
            before, state, previous = state, new, cases[i]
            states[i] = state
            if on_step is not None:
                on_step(sum(st is not None for st in states), n)
    return Solution(tuple(states), tuple(evals), tuple(conv))  # type: ignore[arg-type]


def _extrapolate(before: State, state: State) -> State:
    """Linear predictor: repeat the increment from ``before`` to ``state``."""
    turn = np.einsum('nij,nkj->nik', state.R, before.R)  # world-frame increments
    # Project back onto rotations: repeated products would otherwise grow
    # round-off away from orthonormality (a Newton step that converges at
    # once keeps its guess).
    u, _, vt = np.linalg.svd(np.einsum('nij,njk->nik', turn, state.R))
    return State(2.0 * state.p - before.p, u @ vt, 2.0 * state.lam - before.lam)


def _advance(
    system: System,
    state: State,
    guess: State | None,
    previous: LoadCase,
    target: LoadCase,
    depth: int,
    step: int,
    describe: Callable[[int], str],
) -> tuple[State, Evaluation, Convergence]:
    """
    Solve ``target`` from the solution ``state`` of ``previous``.

    First from the predicted ``guess`` if any; the load step is halved on failure.
    """
    for start in (guess, state):
        if start is None:
            continue
        try:
            new, ev, c = newton(system, start, target)
        except _StepFailure as failure:
            reason = str(failure)
            continue
        if _rotation_angle(new.R, state.R) <= MAX_STEP_ROTATION:
            return new, ev, c
        reason = 'a part rotated too far in one step (possible branch jump)'
    if depth >= MAX_SUBDIVISIONS:
        raise SolverError(f'{describe(step)}: {reason}')
    middle = previous.blend(target, 0.5)
    half, _, _ = _advance(system, state, None, previous, middle, depth + 1, step, describe)
    return _advance(system, half, None, middle, target, depth + 1, step, describe)


@dataclass(frozen=True)
class Sensitivity:
    """
    Rates of an equilibrium along a load parameter p (per unit of p).

    ``dq`` (P, 6): dp (m) and d theta (rad) of every part, in the chart of the
    Newton update; ``dlam`` (m,): the multipliers' rates.
    """

    dq: np.ndarray
    dlam: np.ndarray


def sensitivity(system: System, state: State, load: LoadCase, ahead: LoadCase,
                step: float, evaluation: Evaluation | None = None) -> Sensitivity:
    """
    Exact rates of the equilibrium ``state`` of ``load`` along a load path.

    The load path runs from ``load`` to ``ahead``, which is ``step`` units of
    the parameter p further on. The residual F(q, lambda; p) = [grad V - Q +
    J^T lambda; g] is affine in the rig inputs (pad heights and rack command
    offset g and the rack measure linearly, applied loads enter Q linearly),
    so dF/dp = (F(q; ahead) - F(q; load)) / step exactly; the implicit
    function theorem gives

        [ K  J^T ] [ dq   ]     [ dF_force/dp ]
        [ J   0  ] [ dlam ] = - [ dg/dp       ]

    with K the tangent at the converged state (scaled as in :func:`newton`).
    ``evaluation``: the evaluation of ``state`` under ``load`` if at hand.
    Raises SolverError when the equations are singular there.
    """
    ev = system.evaluate(state, load) if evaluation is None else evaluation
    if _pads_only(load, ahead):
        # the pads offset their constraint rows only: no second evaluation needed
        d_force = np.zeros(ev.jacobian.shape[1])
        d_g = -(system._constraint_offset(ahead) - system._constraint_offset(load)) / step
    else:
        further = system.evaluate(state, ahead)
        d_force = (further.force_residual(state.lam) - ev.force_residual(state.lam)) / step
        d_g = (further.g - ev.g) / step
    factors = _kkt(ev.tangent(state.lam), ev.jacobian)
    if factors is None:
        raise SolverError('sensitivity: singular equilibrium equations at the state')
    s = factors[2]
    n = ev.jacobian.shape[1]
    sol = _lu_solve(factors, -np.concatenate((d_force, s * d_g)))
    return Sensitivity(sol[:n].reshape(-1, 6), s * sol[n:])


def _kkt(k: np.ndarray, j: np.ndarray) -> tuple[np.ndarray, np.ndarray, float] | None:
    """
    Return the LU factors of the scaled KKT matrix [[K, s Jᵀ], [s J, 0]] and the scale s.

    The constraint blocks are scaled by s = max |K| (at least 1) so that the pivots of
    both blocks are of one size and a small pivot reveals a singular system: None when
    the smallest pivot is below SINGULAR_PIVOT_RATIO of the largest (a locked or
    unrestrained mechanism). Used by Newton and by the sensitivities alike.
    """
    s = max(float(np.max(np.abs(k))), 1.0)
    n, m = k.shape[0], j.shape[0]
    # Fortran order: LAPACK factors it in place, with no copy
    kkt = np.zeros((n + m, n + m), order='F')
    kkt[:n, :n] = k
    kkt[:n, n:] = s * j.T
    kkt[n:, :n] = s * j
    # getrf directly (the inputs are finite): scipy's lu_factor only adds checks around it
    lu, piv, _ = _GETRF(kkt, overwrite_a=True)
    pivots = np.abs(np.diag(lu))
    if not np.all(np.isfinite(pivots)) or pivots.min() < SINGULAR_PIVOT_RATIO * pivots.max():
        return None
    return lu, piv, s


def _lu_solve(factors: tuple[np.ndarray, np.ndarray, float], rhs: np.ndarray) -> np.ndarray:
    """Solve the scaled KKT system factored by :func:`_kkt` for ``rhs`` (getrs)."""
    x, info = _GETRS(factors[0], factors[1], rhs)
    if info != 0:
        raise SolverError(f'internal: getrs rejected its argument {-info}')
    return x


def _pads_only(load: LoadCase, other: LoadCase) -> bool:
    """Whether two load cases differ in their pad heights only."""
    return (load.rack == other.rack and np.array_equal(load.contact_force, other.contact_force)
            and np.array_equal(load.centre_force, other.centre_force)
            and np.array_equal(load.contact_moment, other.contact_moment))


def moved(state: State, rate: Sensitivity, t: float) -> State:
    """``state`` moved by ``t`` along ``rate`` in the Newton chart (first order)."""
    return State(state.p + t * rate.dq[:, :3],
                 np.einsum('nij,njk->nik', rotation_vectors_to_matrices(t * rate.dq[:, 3:]),
                           state.R),
                 state.lam + t * rate.dlam)
