# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The K&C rig events of thesis ch. 3 and their runner.

* ``parallel_wheel_travel``: both wheel pads move up together.
* ``opposite_wheel_travel``: left pad up, right pad down (body roll).
* ``lateral_force``: force along +y at both contact points, pads held.
* ``longitudinal_force``: braking (force < 0) at the contact point with the
  wheel locked, traction (force > 0) at the wheel centre; pads held.
* ``steering``: rack swept lock to lock (or to a steering-wheel angle).
* ``aligning_torque``: moment about +z at both contact points, pads held
  (the K&C rig's aligning-torque compliance test).

Pads move the contact-point height (m, from design); the wheel is locked to
the upright throughout (its rotation reacts in the upright), the steering is
held except in ``steering``, the body is fixed. Pads float horizontally:
the only horizontal loads are the applied ones.
"""
from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, replace

import numpy as np

from vd_solvers.errors import SolverError
from vd_solvers.event_params import Param

from .assembly import assemble
from .channels import SOLVER_CHANNELS, TRAVEL_EVENTS, channels, wheel_angles
from .model import SuspensionInput, without_bar
from .result import EventResult
from .solver import (
    Convergence,
    Sensitivity,
    Solution,
    moved,
    sensitivity,
    solve_path,
    solve_static,
)
from .system import Evaluation, LoadCase, State, System
from .templates import TEMPLATES

# Spring-preload trim: secant iterations and relative tolerance on the pad load.
MAX_TRIM_ITERATIONS = 8
TRIM_TOL = 1e-9
# Loaded alignment: fixed-point iterations and tolerance on toe and camber, rad.
MAX_ALIGN_ITERATIONS = 12
ALIGN_TOL = 1e-10
#: step of the output-map derivative at design, as a fraction of the sweep's reach
RATE_STEP = 1e-3

_STEPS = Param('integer', 101, 'steps', minimum=3, maximum=2001)

#: event -> its parameters (SI) with their defaults: the one table of them, used by
#: :meth:`KCModel.run` and by ``vd run --param`` (:mod:`.from_config`)
EVENT_PARAMS: Mapping[str, Mapping[str, Param]] = {
    'parallel_wheel_travel': {
        'travel_min': Param('length', -0.08, 'lowest pad travel (rebound)', maximum=0.0),
        'travel_max': Param('length', 0.08, 'highest pad travel (bump)', minimum=0.0),
        'steps': _STEPS,
    },
    'opposite_wheel_travel': {
        'amplitude': Param('length', 0.08, 'left pad +a..-a, right pad opposite', minimum=0.001),
        'steps': _STEPS,
    },
    'lateral_force': {
        'force_min': Param('force', -4000.0, 'lowest force along +y at both contact patches',
                           maximum=0.0),
        'force_max': Param('force', 4000.0, 'highest force', minimum=0.0),
        'steps': _STEPS,
    },
    'longitudinal_force': {
        'force_min': Param('force', -4000.0, 'braking force at the contact patch (negative)',
                           maximum=0.0),
        'force_max': Param('force', 4000.0, 'traction force at the wheel centre', minimum=0.0),
        'steps': _STEPS,
    },
    'steering': {
        'steering_wheel_angle': Param('angle', 0.0, 'sweep +-angle; 0 = lock to lock',
                                      minimum=0.0),
        'steps': _STEPS,
    },
    'aligning_torque': {
        'moment_min': Param('torque', -200.0, 'lowest moment about +z at both contact patches',
                            maximum=0.0),
        'moment_max': Param('torque', 200.0, 'highest moment', minimum=0.0),
        'steps': _STEPS,
    },
}


@dataclass(frozen=True)
class _Plan:
    """The load of an event as a function of its swept quantity, and the sweep."""

    load: Callable[[float], LoadCase]
    sweep: np.ndarray
    quantity: str  # channel-style name of the swept quantity
    unit: str
    params: dict[str, float]


def _sweep(low: float, high: float, steps: int, what: str) -> np.ndarray:
    if not (isinstance(steps, int) and steps >= 3):
        raise SolverError(f'{what}: steps must be an integer >= 3, got {steps!r}')
    if not (np.isfinite(low) and np.isfinite(high) and low < high):
        raise SolverError(f'{what}: need a finite range low < high, got {low!r}..{high!r}')
    return np.linspace(low, high, steps)


def parallel_wheel_travel(inp: SuspensionInput, *, travel_min: float, travel_max: float,
                          steps: int) -> _Plan:
    """Both pads from ``travel_min`` to ``travel_max`` (m, + = bump)."""
    z = _sweep(travel_min, travel_max, steps, 'parallel_wheel_travel')
    params = {'travel_min': travel_min, 'travel_max': travel_max, 'steps': steps}
    return _Plan(lambda t: LoadCase(pad=np.array([t, t])), z, 'pad_travel', 'm', params)


def opposite_wheel_travel(inp: SuspensionInput, *, amplitude: float, steps: int) -> _Plan:
    """Left pad t, right pad -t for t from -``amplitude`` to ``amplitude`` (m)."""
    z = _sweep(-amplitude, amplitude, steps, 'opposite_wheel_travel')
    return _Plan(lambda t: LoadCase(pad=np.array([t, -t])), z, 'pad_travel_left', 'm',
                 {'amplitude': amplitude, 'steps': steps})


def _on_both(value: float, component: int) -> np.ndarray:
    out = np.zeros((2, 3))
    out[:, component] = value
    return out


def lateral_force(inp: SuspensionInput, *, force_min: float, force_max: float,
                  steps: int) -> _Plan:
    """Force along +y (N) at both contact points, pads at design height."""
    f = _sweep(force_min, force_max, steps, 'lateral_force')
    params = {'force_min': force_min, 'force_max': force_max, 'steps': steps}
    return _Plan(lambda v: LoadCase(contact_force=_on_both(v, 1)), f, 'lateral_force', 'N',
                 params)


def longitudinal_force(inp: SuspensionInput, *, force_min: float, force_max: float,
                       steps: int) -> _Plan:
    """
    Apply a force along +x (N) on both wheels.

    Negative = braking at the contact point (wheel locked), positive =
    traction at the wheel centre.
    """
    f = _sweep(force_min, force_max, steps, 'longitudinal_force')

    def load(v: float) -> LoadCase:
        if v < 0.0:
            return LoadCase(contact_force=_on_both(v, 0))
        return LoadCase(centre_force=_on_both(v, 0))

    params = {'force_min': force_min, 'force_max': force_max, 'steps': steps}
    return _Plan(load, f, 'longitudinal_force', 'N', params)


def steering(inp: SuspensionInput, *, steering_wheel_angle: float | None, steps: int) -> _Plan:
    """
    Sweep the steering wheel from -a to +a (rad, + = left), pads at design height.

    ``steering_wheel_angle`` None or 0: lock to lock (the rack travel limit).
    """
    spec = inp.steering
    if spec is None:
        raise SolverError('steering event: the axle has no steering (front axle with rack only)')
    limit = spec.rack_travel_limit / spec.rack_ratio
    amplitude = limit if not steering_wheel_angle else float(steering_wheel_angle)
    if amplitude > limit * (1.0 + 1e-12):
        raise SolverError(
            f'steering event: steering-wheel angle {np.degrees(amplitude):.1f} deg needs '
            f'{amplitude * spec.rack_ratio * 1e3:.1f} mm of rack travel, beyond the '
            f'{spec.rack_travel_limit * 1e3:.1f} mm limit'
        )
    swa = _sweep(-amplitude, amplitude, steps, 'steering')
    ratio = spec.rack_ratio
    return _Plan(
        lambda a: LoadCase(rack=float(a * ratio)),  # sign applied by the model
        swa,
        'steering_wheel_angle',
        'rad',
        {'steering_wheel_angle': amplitude, 'rack_ratio': spec.rack_ratio, 'steps': steps},
    )


def aligning_torque(inp: SuspensionInput, *, moment_min: float, moment_max: float,
                    steps: int) -> _Plan:
    """
    Apply a moment about +z (N*m, counter-clockwise from above) at both contact points.

    Pads at design height, steering held.
    """
    mz = _sweep(moment_min, moment_max, steps, 'aligning_torque')
    params = {'moment_min': moment_min, 'moment_max': moment_max, 'steps': steps}
    return _Plan(lambda v: LoadCase(contact_moment=_on_both(v, 2)), mz, 'aligning_torque',
                 'N*m', params)


EVENTS: dict[str, Callable[..., _Plan]] = {
    'parallel_wheel_travel': parallel_wheel_travel,
    'opposite_wheel_travel': opposite_wheel_travel,
    'lateral_force': lateral_force,
    'longitudinal_force': longitudinal_force,
    'steering': steering,
    'aligning_torque': aligning_torque,
}


def event_defaults(event: str) -> dict[str, float]:
    """Return the default parameters of ``event`` (SI; ``steps`` an int)."""
    return {k: (int(p.default) if p.quantity == 'integer' else p.default)
            for k, p in EVENT_PARAMS[event].items()}


class KCModel:
    """
    An axle assembled once and run through any number of events.

    ``label`` (e.g. the configuration name) prefixes every error message.
    ``inp`` is the input as solved: with the trimmed spring preload if the
    spring had neither free length nor preload, and with the toe and camber
    the wheel is assembled with solved so that the loaded axle at design
    height has the specified alignment (:meth:`_aligned`). ``solved=True``
    takes ``inp`` as already solved (e.g. a model's ``inp`` without its bar).
    """

    def __init__(self, inp: SuspensionInput, label: str = '', solved: bool = False) -> None:
        self.inp = inp
        self.label = label
        try:
            if not solved:
                aligned = self._aligned(inp)
                trimmed = self._trimmed(aligned)
                # the trim moves the design state a little: align again to the specification
                self.inp = aligned if trimmed is aligned else self._aligned(trimmed, inp)
            self.system: System = assemble(self.inp)
        except SolverError as err:
            raise SolverError(f'{self._prefix()}{err}') from None
        self.template = TEMPLATES[inp.template]

    def _prefix(self) -> str:
        return f'{self.label}: ' if self.label else ''

    def run(self, event: str, on_step: Callable[[int, int], None] | None = None,
            **params: float) -> EventResult:
        """
        Run ``event`` with ``params`` (defaults: :data:`EVENT_PARAMS`).

        ``on_step(done, total)`` reports progress. Besides the per-step
        channels the result holds every channel at the design state and its
        exact rates there (:class:`.result.EventResult`); the travel events
        also carry the kinematic channels of :func:`.channels.instant_centres`.
        """
        plan_of = EVENTS.get(event)
        if plan_of is None:
            raise SolverError(f'{self._prefix()}unknown event {event!r}; known: {sorted(EVENTS)}')
        unknown = sorted(set(params) - set(EVENT_PARAMS[event]))
        if unknown:
            known = ', '.join(EVENT_PARAMS[event])
            raise SolverError(f'{self._prefix()}event {event!r}: unknown parameter(s) '
                              f'{", ".join(unknown)} (parameters: {known})')
        try:
            plan = plan_of(self.inp, **{**event_defaults(event), **params})
        except SolverError as err:
            raise SolverError(f'{self._prefix()}{err}') from None
        sign = self.system.outputs.steer_sign

        def load(value: float) -> LoadCase:
            case = plan.load(value)
            return replace(case, rack=sign * case.rack)

        cases = [load(v) for v in plan.sweep]
        n = len(cases)

        def describe(i: int) -> str:
            return (
                f'{self._prefix()}event {event!r}, step {i} of 0..{n - 1} '
                f"({plan.quantity.replace('_', ' ')} = {plan.sweep[i]:.6g} {plan.unit})"
            )

        start = int(np.argmin(np.abs(plan.sweep)))
        solution = solve_path(self.system, cases, start, describe, on_step)
        ratio = self.inp.steering.rack_ratio if self.inp.steering is not None else None
        step = RATE_STEP * float(np.max(np.abs(plan.sweep)))
        travel = event in TRAVEL_EVENTS
        per_step = None
        if travel:
            per_step = [sensitivity(self.system, st, c, load(v + step), step, ev)
                        for st, c, v, ev in zip(solution.states, cases, plan.sweep,
                                                solution.evaluations)]
        ch = channels(self.system, self.template, solution, cases, ratio, per_step)
        design, rate_up, rate_down = self._design_rates(event, load, step, ratio, travel)
        return EventResult(event, self.inp.axle, self.label, dict(plan.params), ch,
                           plan.quantity, plan.unit, design, rate_up, rate_down)

    def _design_rates(self, event: str, load: Callable[[float], LoadCase], step: float,
                      ratio: float | None, travel: bool):
        """
        Return the channels at design and their exact rates there (up, down).

        The state's rate is exact (:func:`.solver.sensitivity`); each
        channel's rate follows by the chain rule as the directional derivative
        of the channel map along it: a Richardson-extrapolated central
        difference over +-``step``, +-2 ``step`` of an explicit smooth map
        (truncation O(step^4), about 1e-12 relative at RATE_STEP).
        """
        system = self.system
        design = LoadCase()
        state, ev, conv = solve_static(system, design, f'{self._prefix()}event {event!r}, design')
        rates: list[tuple[Sensitivity, Callable[[float], LoadCase]]] = []
        for sign in (1.0, -1.0):
            ahead = load(sign * step)
            rate = sensitivity(system, state, design, ahead, sign * step, ev)

            def toward(t: float, a: LoadCase = ahead, h: float = sign * step) -> LoadCase:
                return design.blend(a, t / h)
            rates.append((rate, toward))
        up = rates[0][0]
        at = channels(system, self.template, Solution((state,), (ev,), (conv,)), [design], ratio,
                      [up] if travel else None)
        values = {k: v[0] for k, v in at.items()}
        out = []
        for rate, line in rates:
            out.append(self._channel_rates(state, rate, line, step, ratio, values))
        return values, out[0], out[1]

    def _channel_rates(self, state: State, rate: Sensitivity, line: Callable[[float], LoadCase],
                       step: float, ratio: float | None,
                       values: Mapping[str, np.ndarray]) -> dict[str, np.ndarray]:
        offsets = (-2.0 * step, -step, step, 2.0 * step)
        states = tuple(moved(state, rate, t) for t in offsets)
        loads = [line(t) for t in offsets]
        evals: tuple[Evaluation, ...] = tuple(
            self.system.evaluate(st, c) for st, c in zip(states, loads))
        idle = tuple(Convergence(0, 0.0, 0.0) for _ in offsets)
        ch = channels(self.system, self.template, Solution(states, evals, idle), loads, ratio)
        return {k: (8.0 * (v[2] - v[1]) - (v[3] - v[0])) / (12.0 * step)
                for k, v in ch.items() if k in values and k not in SOLVER_CHANNELS}

    @staticmethod
    def _aligned(inp: SuspensionInput, spec: SuspensionInput | None = None) -> SuspensionInput:
        """
        Solve the toe and camber the wheel is assembled with.

        Returns ``inp`` with them, chosen so that under the static corner load at design
        height (pads at design, bushings deflected) the left wheel has the toe and
        camber of ``spec`` (default ``inp``): alignment is specified for the loaded car.
        Without bushings the linkage does not deflect and ``inp`` is returned. Fixed-
        point iteration on the deflection, to ALIGN_TOL.
        """
        spec = inp if spec is None else spec
        if not inp.bushings:
            return inp
        target = np.array([spec.toe, spec.camber])
        x = np.array([inp.toe, inp.camber])
        last: State | None = None
        for _ in range(MAX_ALIGN_ITERATIONS):
            trial = replace(inp, toe=float(x[0]), camber=float(x[1]))
            system = assemble(trial)
            last, _, _ = solve_static(system, LoadCase(), 'loaded alignment', last)
            _, axis, _ = system.contact_points(last)
            angles = wheel_angles(axis)
            error = np.array([angles['toe'][0], angles['camber'][0]]) - target
            if np.max(np.abs(error)) <= ALIGN_TOL:
                return trial
            x = x - error
        raise SolverError(
            f'loaded alignment: toe and camber {np.degrees(error)} deg off the specified values '
            f'after {MAX_ALIGN_ITERATIONS} iterations')

    @staticmethod
    def _trimmed(inp: SuspensionInput) -> SuspensionInput:
        """
        Trim the spring preload to the corner load.

        Returns ``inp`` with the spring preload found, if neither free length
        nor preload is given, so that the design pad load equals the corner load
        (secant on the preload; exact in one step for a rigid linkage).
        """
        spring = inp.spring
        if spring.free_length is not None or spring.preload is not None:
            return inp

        last: list[State] = []  # the previous iterate's solution: a warm start

        def pad_load(preload: float) -> float:
            trial = replace(inp, spring=replace(spring, preload=preload))
            system = assemble(trial)
            state, _, _ = solve_static(system, LoadCase(), 'spring preload trim',
                                       last[-1] if last else None)
            last.append(state)
            return float(-state.lam[system.outputs.pad_rows].mean())

        target = inp.corner_load
        p0, p1 = 0.0, target
        f0, f1 = pad_load(p0), pad_load(p1)
        for _ in range(MAX_TRIM_ITERATIONS):
            if abs(f1 - target) <= TRIM_TOL * target:
                return replace(inp, spring=replace(spring, preload=p1))
            if f1 == f0:
                raise SolverError('spring preload trim: the pad load does not respond to the '
                                  'spring preload')
            p0, p1, f0 = p1, p1 + (target - f1) * (p1 - p0) / (f1 - f0), f1
            f1 = pad_load(p1)
        raise SolverError(
            f'spring preload trim: pad load {f1:.1f} N after {MAX_TRIM_ITERATIONS} secant steps, '
            f'corner load {target:.1f} N'
        )


def run_event(inp: SuspensionInput, event: str, label: str = '', **params: float) -> EventResult:
    """Assemble ``inp`` and run one ``event`` with ``params``."""
    return KCModel(inp, label).run(event, None, **params)


def run_suite(
    inp: SuspensionInput,
    label: str = '',
    params: Mapping[str, Mapping[str, float]] | None = None,
) -> dict[str, EventResult]:
    """
    Run all events that apply to ``inp`` (steering on a steered axle only).

    Plus ``opposite_wheel_travel_no_bar`` when the axle has an anti-roll bar.
    ``params``: per-event keyword arguments.
    """
    params = params or {}
    model = KCModel(inp, label)
    names = [e for e in EVENTS if e != 'steering' or inp.steering is not None]
    results = {e: model.run(e, None, **params.get(e, {})) for e in names}
    if inp.stabilizer is not None:
        bare = KCModel(without_bar(model.inp), label, solved=True)
        results['opposite_wheel_travel_no_bar'] = bare.run(
            'opposite_wheel_travel', None, **params.get('opposite_wheel_travel', {})
        )
    return results
