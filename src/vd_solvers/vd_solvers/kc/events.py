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

from .assembly import assemble
from .metrics import channels, wheel_angles
from .model import Axle, SuspensionInput, without_bar
from .solver import solve_path, solve_static
from .system import LoadCase, State, System
from .templates import TEMPLATES

DEFAULT_STEPS = 101
# Spring-preload trim: secant iterations and relative tolerance on the pad load.
MAX_TRIM_ITERATIONS = 8
TRIM_TOL = 1e-9
# Loaded alignment: fixed-point iterations and tolerance on toe and camber, rad.
MAX_ALIGN_ITERATIONS = 12
ALIGN_TOL = 1e-10


@dataclass(frozen=True)
class EventResult:
    """
    One event's per-step channels (see :func:`.metrics.channels`) and the
    parameters it ran with (SI).
    """

    event: str
    axle: Axle
    label: str
    params: Mapping[str, float]
    channels: Mapping[str, np.ndarray]

    @property
    def steps(self) -> int:
        """Number of steps."""
        return int(self.channels['wheel_travel'].shape[0])


@dataclass(frozen=True)
class _Plan:
    """Load cases of an event and the swept quantity that names its steps."""

    cases: list[LoadCase]
    sweep: np.ndarray
    quantity: str
    unit: str
    params: dict[str, float]


def _sweep(low: float, high: float, steps: int, what: str) -> np.ndarray:
    if not (isinstance(steps, int) and steps >= 3):
        raise SolverError(f'{what}: steps must be an integer >= 3, got {steps!r}')
    if not (np.isfinite(low) and np.isfinite(high) and low < high):
        raise SolverError(f'{what}: need a finite range low < high, got {low!r}..{high!r}')
    return np.linspace(low, high, steps)


def parallel_wheel_travel(
    inp: SuspensionInput, travel_min: float = -0.08, travel_max: float = 0.08, steps: int = DEFAULT_STEPS
) -> _Plan:
    """Both pads from ``travel_min`` to ``travel_max`` (m, + = bump)."""
    z = _sweep(travel_min, travel_max, steps, 'parallel_wheel_travel')
    cases = [LoadCase(pad=np.array([t, t])) for t in z]
    params = {'travel_min': travel_min, 'travel_max': travel_max, 'steps': steps}
    return _Plan(cases, z, 'pad travel', 'm', params)


def opposite_wheel_travel(
    inp: SuspensionInput, amplitude: float = 0.08, steps: int = DEFAULT_STEPS
) -> _Plan:
    """Left pad t, right pad -t for t from -``amplitude`` to ``amplitude`` (m)."""
    z = _sweep(-amplitude, amplitude, steps, 'opposite_wheel_travel')
    cases = [LoadCase(pad=np.array([t, -t])) for t in z]
    return _Plan(cases, z, 'left pad travel', 'm', {'amplitude': amplitude, 'steps': steps})


def lateral_force(
    inp: SuspensionInput, force_min: float = -4000.0, force_max: float = 4000.0, steps: int = DEFAULT_STEPS
) -> _Plan:
    """Force along +y (N) at both contact points, pads at design height."""
    f = _sweep(force_min, force_max, steps, 'lateral_force')
    cases = []
    for v in f:
        force = np.zeros((2, 3))
        force[:, 1] = v
        cases.append(LoadCase(contact_force=force))
    params = {'force_min': force_min, 'force_max': force_max, 'steps': steps}
    return _Plan(cases, f, 'lateral force', 'N', params)


def longitudinal_force(
    inp: SuspensionInput, force_min: float = -4000.0, force_max: float = 4000.0, steps: int = DEFAULT_STEPS
) -> _Plan:
    """
    Force along +x (N) on both wheels: negative = braking at the contact
    point (wheel locked), positive = traction at the wheel centre.
    """
    f = _sweep(force_min, force_max, steps, 'longitudinal_force')
    cases = []
    for v in f:
        at_contact, at_centre = np.zeros((2, 3)), np.zeros((2, 3))
        (at_contact if v < 0.0 else at_centre)[:, 0] = v
        cases.append(LoadCase(contact_force=at_contact, centre_force=at_centre))
    params = {'force_min': force_min, 'force_max': force_max, 'steps': steps}
    return _Plan(cases, f, 'longitudinal force', 'N', params)


def steering(
    inp: SuspensionInput, steering_wheel_angle: float | None = None, steps: int = DEFAULT_STEPS
) -> _Plan:
    """
    Steering wheel from -a to +a (rad, + = left); default lock to lock
    (the rack travel limit). Pads at design height.
    """
    spec = inp.steering
    if spec is None:
        raise SolverError('steering event: the axle has no steering (front axle with rack only)')
    limit = spec.rack_travel_limit / spec.rack_ratio
    amplitude = limit if steering_wheel_angle is None else float(steering_wheel_angle)
    if amplitude > limit * (1.0 + 1e-12):
        raise SolverError(
            f'steering event: steering-wheel angle {np.degrees(amplitude):.1f} deg needs '
            f'{amplitude * spec.rack_ratio * 1e3:.1f} mm of rack travel, beyond the '
            f'{spec.rack_travel_limit * 1e3:.1f} mm limit'
        )
    swa = _sweep(-amplitude, amplitude, steps, 'steering')
    return _Plan(
        [LoadCase(rack=float(a * spec.rack_ratio)) for a in swa],  # sign applied by the model
        swa,
        'steering-wheel angle',
        'rad',
        {'steering_wheel_angle': amplitude, 'rack_ratio': spec.rack_ratio, 'steps': steps},
    )


def aligning_torque(
    inp: SuspensionInput, moment_min: float = -200.0, moment_max: float = 200.0,
    steps: int = DEFAULT_STEPS,
) -> _Plan:
    """
    Moment about +z (N*m, counter-clockwise from above) at both contact
    points, pads at design height, steering held.
    """
    mz = _sweep(moment_min, moment_max, steps, 'aligning_torque')
    cases = []
    for v in mz:
        moment = np.zeros((2, 3))
        moment[:, 2] = v
        cases.append(LoadCase(contact_moment=moment))
    params = {'moment_min': moment_min, 'moment_max': moment_max, 'steps': steps}
    return _Plan(cases, mz, 'aligning torque', 'N*m', params)


EVENTS: dict[str, Callable[..., _Plan]] = {
    'parallel_wheel_travel': parallel_wheel_travel,
    'opposite_wheel_travel': opposite_wheel_travel,
    'lateral_force': lateral_force,
    'longitudinal_force': longitudinal_force,
    'steering': steering,
    'aligning_torque': aligning_torque,
}


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
        Run ``event`` with ``params`` (see the event functions' defaults);
        ``on_step(done, total)`` reports progress.
        """
        plan_of = EVENTS.get(event)
        if plan_of is None:
            raise SolverError(f'{self._prefix()}unknown event {event!r}; known: {sorted(EVENTS)}')
        try:
            plan = plan_of(self.inp, **params)
        except TypeError as err:
            raise SolverError(f'{self._prefix()}event {event!r}: {err}') from None
        except SolverError as err:
            raise SolverError(f'{self._prefix()}{err}') from None
        sign = self.system.outputs.steer_sign
        cases = [replace(c, rack=sign * c.rack) for c in plan.cases]
        n = len(cases)

        def describe(i: int) -> str:
            return (
                f'{self._prefix()}event {event!r}, step {i} of 0..{n - 1} '
                f'({plan.quantity} = {plan.sweep[i]:.6g} {plan.unit})'
            )

        start = int(np.argmin(np.abs(plan.sweep)))
        solution = solve_path(self.system, cases, start, describe, on_step)
        ratio = self.inp.steering.rack_ratio if self.inp.steering is not None else None
        ch = channels(self.system, self.template, solution, cases, ratio)
        return EventResult(event, self.inp.axle, self.label, dict(plan.params), ch)

    @staticmethod
    def _aligned(inp: SuspensionInput, spec: SuspensionInput | None = None) -> SuspensionInput:
        """
        ``inp`` with the toe and camber the wheel is assembled with solved so
        that under the static corner load at design height (pads at design,
        bushings deflected) the left wheel has the toe and camber of ``spec``
        (default ``inp``): alignment is specified for the loaded car. Without
        bushings the linkage does not deflect and ``inp`` is returned.
        Fixed-point iteration on the deflection, to ALIGN_TOL.
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
        ``inp`` with the spring preload found, if neither free length nor
        preload is given, so that the design pad load equals the corner load
        (secant on the preload; exact in one step for a rigid linkage).
        """
        spring = inp.spring
        if spring.free_length is not None or spring.preload is not None:
            return inp

        last: list[State] = []  # the previous iterate's solution: a warm start

        def pad_load(preload: float) -> float:
            trial = replace(inp, spring=replace(spring, preload=preload))
            system = assemble(trial)
            state, _, _ = solve_static(system, LoadCase(), 'spring preload trim', last[-1] if last else None)
            last.append(state)
            return float(-state.lam[system.outputs.pad_rows].mean())

        target = inp.corner_load
        p0, p1 = 0.0, target
        f0, f1 = pad_load(p0), pad_load(p1)
        for _ in range(MAX_TRIM_ITERATIONS):
            if abs(f1 - target) <= TRIM_TOL * target:
                return replace(inp, spring=replace(spring, preload=p1))
            if f1 == f0:
                raise SolverError('spring preload trim: the pad load does not respond to the spring preload')
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
    All events that apply to ``inp`` (steering on a steered axle only),
    plus ``opposite_wheel_travel_no_bar`` when the axle has an anti-roll bar.
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
