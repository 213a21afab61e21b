# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Simulation vs test: per-channel errors, gradient errors, tolerance bands and verdicts.

``compare(sim, test)`` pairs two EventOutcomes of the same event (and axle) and compares
every channel both have, on the **test's points**:

* K&C (test model ``rig``): the simulation is interpolated linearly at the measured
  values of the event's swept channel (wheel travel, applied force or moment,
  steering-wheel angle; the simulation sorted by it); measured points outside the
  simulated range are left out and counted. The gradient error is the difference of
  the slopes at design (x = 0) of simulation and test, both from the same quadratic
  least-squares fit over the same window (``kc.metrics.slope_at`` with the K&C metrics'
  windows: 10 mm, 500 N, 25 N*m; 10 deg of steering-wheel angle): bump steer, camber
  gain, lateral compliance steer and the other slopes. It passes within
  GRADIENT_TOLERANCE of the measured slope plus two standard errors of that slope (a
  straight line through the window's measured points), so rig noise on a coarse sweep
  is not counted as model error.
* Vehicle (test model ``test``): the simulation is interpolated linearly at the log's
  times over the common time span. A simulation of a sine with dwell or a step steer
  (not a replay, which runs on the log's own time) is first put on the log's time axis by
  the manoeuvre (:mod:`.align`: BOS, the 50 % steering-wheel instant; for a simulated
  sine-with-dwell procedure its run nearest the log's amplitude and direction), and the
  notes state the shift. Where both are sampled at 20 Hz or more, both are low-passed
  first with the 12-pole phaseless Butterworth of the sine-with-dwell processing
  (``fmvss126.lowpass``, 6 Hz for responses, 10 Hz for the steering-wheel angle), each
  gap-free stretch on its own (the notes name the gaps), so sensor noise does not count
  as model error.
* Pairing (:func:`pair`): a replay (its note REPLAY_NOTE names the log's SHA-256) is
  compared with its own log only; any other simulation with every log of its event.

Per channel: RMS of (sim - test), max |sim - test|, bias (mean of sim - test), each in
the channel's SI unit, and the test signal's RMS for scale. A channel passes when every
metric is within its tolerance (:data:`TOLERANCES`, by SI unit; override per channel
with ``--tolerances``). Units: the test's values are converted to the simulation's unit
with pint before anything is compared.
"""
from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
import math
from pathlib import Path

import numpy as np
import yaml

from vd_events.bags.bag import read_bag
from vd_events.errors import InputError
from vd_events.measured.align import aligned
from vd_events.measured.checks import segments
from vd_events.measured.columns import KC_SWEEP, si_unit, unit_factor
from vd_solvers.constants import DEG
from vd_solvers.conversions import outcome_from_msg
from vd_solvers.kc.metrics import FORCE_WINDOW, TRAVEL_WINDOW, slope_at
from vd_solvers.results import EventOutcome
from vd_solvers.standards.fmvss126 import RESPONSE_CUTOFF, STEER_CUTOFF, ProcessingError, lowpass

#: half-width of the gradient window per swept channel (SI)
#: N*m of applied aligning torque: the half-width of that event's gradient window
MOMENT_WINDOW = 25.0
GRADIENT_WINDOWS = {'wheel_travel_left': TRAVEL_WINDOW, 'applied_force': FORCE_WINDOW,
                    'applied_moment': MOMENT_WINDOW, 'steering_wheel_angle': math.radians(10.0)}
#: low-pass cut-offs of the vehicle signals before comparison, Hz (fmvss126)
STEERING_CHANNELS = ('steering_wheel_angle',)
#: channels never compared (the axis itself and positions that drift with any error)
NOT_COMPARED = ('time', 'x', 'y', 'yaw')
#: default tolerance band by SI unit: rms, max, bias (SI) and relative gradient error
TOLERANCES: Mapping[str, Mapping[str, float]] = {
    'rad': {'rms': math.radians(0.1), 'max': math.radians(0.3), 'bias': math.radians(0.1)},
    'rad/s': {'rms': math.radians(1.0), 'max': math.radians(3.0), 'bias': math.radians(0.5)},
    'm/s^2': {'rms': 0.3, 'max': 1.0, 'bias': 0.2},
    'm/s': {'rms': 0.3, 'max': 1.0, 'bias': 0.3},
    'm': {'rms': 1e-3, 'max': 3e-3, 'bias': 1e-3},
    'N': {'rms': 100.0, 'max': 300.0, 'bias': 100.0},
    'N*m': {'rms': 10.0, 'max': 30.0, 'bias': 10.0},
}
GRADIENT_TOLERANCE = 0.10  # relative error of a slope at design
#: a simulation's note naming the channels it took from the test (a replay's inputs)
INPUTS_NOTE = 'inputs taken from the log: '
#: a replay's note naming the log it replays (its source's SHA-256)
REPLAY_NOTE = 'replay of the log with sha256: '
#: fewest samples of a stretch the low-pass filters
MIN_FILTERED = 30
#: how a unit is shown in tables (the values stay SI in JSON)
DISPLAY = {'rad': ('deg', 1.0 / DEG), 'rad/s': ('deg/s', 1.0 / DEG), 'm': ('mm', 1e3)}


@dataclass(frozen=True)
class ChannelError:
    channel: str
    unit: str  # SI
    points: int
    rms: float
    max: float
    bias: float
    test_rms: float
    gradient_sim: float | None = None
    gradient_test: float | None = None
    gradient_unit: str = ''
    tolerance: Mapping[str, float] = field(default_factory=dict)
    gradient_uncertainty: float = 0.0  # standard error of the measured slope

    @property
    def gradient_error(self) -> float | None:
        if self.gradient_sim is None or self.gradient_test is None:
            return None
        return self.gradient_sim - self.gradient_test

    @property
    def failures(self) -> list[str]:
        out = [k for k in ('rms', 'max', 'bias')
               if k in self.tolerance and abs(getattr(self, k)) > self.tolerance[k]]
        rel = self.tolerance.get('gradient')
        g = self.gradient_error
        if rel is not None and g is not None and self.gradient_test is not None:
            if abs(g) > rel * abs(self.gradient_test) + 2.0 * self.gradient_uncertainty:
                out.append('gradient')
        return out

    @property
    def verdict(self) -> str:
        if not self.tolerance:
            return 'no tolerance'
        return 'FAIL' if self.failures else 'PASS'

    def to_json(self) -> dict:
        return {'channel': self.channel, 'unit': self.unit, 'points': self.points,
                'rms': self.rms, 'max': self.max, 'bias': self.bias, 'test_rms': self.test_rms,
                'gradient_sim': self.gradient_sim, 'gradient_test': self.gradient_test,
                'gradient_error': self.gradient_error, 'gradient_unit': self.gradient_unit,
                'gradient_uncertainty': self.gradient_uncertainty,
                'tolerance': dict(self.tolerance), 'verdict': self.verdict,
                'failures': self.failures}


@dataclass(frozen=True)
class Comparison:
    sim: EventOutcome
    test: EventOutcome
    axis: str
    errors: list[ChannelError]
    notes: list[str]
    sim_x: dict[str, np.ndarray]  # channel -> simulation on the test's points (for plots)
    test_x: np.ndarray  # the test's axis values used

    @property
    def verdict(self) -> str:
        verdicts = {e.verdict for e in self.errors}
        if 'FAIL' in verdicts:
            return 'FAIL'
        return 'PASS' if 'PASS' in verdicts else 'no tolerance'

    @property
    def label(self) -> str:
        axle = f' {self.test.axle}' if self.test.axle else ''
        return (f'{self.test.event}{axle}: {self.sim.configuration} ({self.sim.model}, '
                f'{self.sim.fidelity}) vs {self.test.configuration} ({self.test.model})')

    def to_json(self) -> dict:
        return {'event': self.test.event, 'axle': self.test.axle,
                'sim': {'configuration': self.sim.configuration, 'model': self.sim.model,
                        'fidelity': self.sim.fidelity, 'data_hash': self.sim.data_hash},
                'test': {'configuration': self.test.configuration, 'model': self.test.model,
                         'source_sha256': self.test.data_hash},
                'axis': self.axis, 'verdict': self.verdict, 'notes': self.notes,
                'channels': [e.to_json() for e in self.errors]}


def _tolerance(channel: str, unit: str, overrides: Mapping[str, Mapping[str, float]],
               kc: bool) -> dict[str, float]:
    tol = dict(TOLERANCES.get(unit, {}))
    if kc and tol:
        tol['gradient'] = GRADIENT_TOLERANCE
    tol.update(overrides.get(channel, {}))
    return tol


def slope_uncertainty(x: np.ndarray, y: np.ndarray, half_width: float) -> float:
    """
    Return the standard error of the measured slope at x = 0.

    A straight line is fitted to the points of the gradient window (those ``slope_at``
    uses); its slope's standard error is the measurement noise in the slope.
    """
    distance = np.abs(x)
    mask = distance <= half_width + 1e-12
    if np.count_nonzero(mask) < 3:
        mask = distance <= np.sort(distance)[min(2, distance.size - 1)] + 1e-12
    xs, ys = x[mask], y[mask]
    if xs.size < 3:
        return 0.0
    b, a = np.polyfit(xs, ys, 1)
    spread = float(np.sum((xs - xs.mean()) ** 2))
    residual = float(np.sum((ys - a - b * xs) ** 2))
    return math.sqrt(residual / (xs.size - 2) / spread) if spread > 0.0 else 0.0


def replay_source(sim: EventOutcome) -> str | None:
    """Return the SHA-256 of the log a replay replays (None: not a replay)."""
    for note in sim.notes:
        if note.startswith(REPLAY_NOTE):
            return note[len(REPLAY_NOTE):].strip()
    return None


def lowpassed(t: np.ndarray, x: np.ndarray, channel: str) -> tuple[np.ndarray, int]:
    """``x`` low-passed per gap-free stretch; and how many samples were left unfiltered."""
    cutoff = STEER_CUTOFF if channel in STEERING_CHANNELS else RESPONSE_CUTOFF
    out = x.copy()
    left = 0
    for s in segments(t):
        try:
            if s.stop - s.start < MIN_FILTERED:
                raise ProcessingError('short')
            out[s] = lowpass(t[s], x[s], cutoff)
        except ProcessingError:
            left += s.stop - s.start
    return out, left


def compare(sim: EventOutcome, test: EventOutcome,
            overrides: Mapping[str, Mapping[str, float]] | None = None,
            inputs: Sequence[str] = ()) -> Comparison:
    """
    Compare ``sim`` with ``test`` on the test's points (module doc).

    ``inputs``: channels the simulation took from the test (a replay's steering and
    speed, also read from a sim note starting INPUTS_NOTE), named in the notes and not
    compared.
    """
    overrides = overrides or {}
    align_notes: list[str] = []
    if test.model == 'test' and replay_source(sim) is None:
        sim, align_notes = aligned(sim, test)
    inputs = tuple(inputs) + tuple(c.strip() for n in sim.notes if n.startswith(INPUTS_NOTE)
                                   for c in n[len(INPUTS_NOTE):].split(','))
    kc = test.model == 'rig'
    axis = KC_SWEEP.get(test.event, 'wheel_travel_left') if kc else 'time'
    notes: list[str] = list(align_notes)
    for who, o in (('simulation', sim), ('test', test)):
        if axis not in o.channels:
            raise InputError(who, f"{o.event}: no '{axis}' channel to compare on")
    to_test = unit_factor(sim.channels[axis].unit, test.channels[axis].unit)
    xs = sim.channels[axis].values * to_test[0] + to_test[1]
    xt = test.channels[axis].values
    order = np.argsort(xs, kind='stable')
    xs_sorted = xs[order]
    inside = (xt >= xs_sorted[0]) & (xt <= xs_sorted[-1])
    if np.count_nonzero(inside) < 2:
        raise InputError('comparison', f'{test.event}: the test and the simulation share '
                         f'fewer than two points of {axis}')
    if not np.all(inside):
        notes.append(f'{np.count_nonzero(~inside)} of {xt.size} test points lie outside '
                     f'the simulated {axis} range and are left out')
    notes.append(f"simulation interpolated linearly at the test's {axis} values")
    filter_both = (not kc and xt.size > 1 and xs_sorted.size > 1
                   and 1.0 / np.median(np.diff(xt)) >= 20.0
                   and 1.0 / np.median(np.diff(xs_sorted)) >= 20.0)
    if filter_both:
        stretches = [len(segments(xt)), len(segments(xs_sorted))]
        gaps = ('' if stretches == [1, 1] else
                f' (each gap-free stretch on its own: {stretches[0]} in the test, '
                f'{stretches[1]} in the simulation)')
        notes.append('both low-passed first: 12-pole phaseless Butterworth (fmvss126), '
                     f'6 Hz responses, 10 Hz steering-wheel angle{gaps}')
    elif not kc:
        notes.append('not low-passed: one of the two is sampled below 20 Hz')
    if inputs:
        notes.append(f"inputs of the simulation, taken from the test: "
                     f"{', '.join(dict.fromkeys(inputs))} (not compared)")
    errors, sim_x = [], {}
    for name in test.channels:
        if name == axis or name in NOT_COMPARED or name in inputs or name not in sim.channels:
            continue
        unit = sim.channels[name].unit
        try:
            factor, offset = unit_factor(test.channels[name].unit, unit)
        except ValueError:
            notes.append(f'{name}: units {test.channels[name].unit!r} and {unit!r} differ in '
                         'kind; not compared')
            continue
        y_test = test.channels[name].values * factor + offset
        y_sim_sorted = sim.channels[name].values[order]
        if not (np.all(np.isfinite(y_test)) and np.all(np.isfinite(y_sim_sorted))):
            notes.append(f'{name}: not finite in one of the two; not compared')
            continue
        if filter_both:
            y_test, left_test = lowpassed(xt, y_test, name)
            y_sim_sorted, left_sim = lowpassed(xs_sorted, y_sim_sorted, name)
            unfiltered = (f'{left_test} test and {left_sim} simulation samples in stretches '
                          f'shorter than {MIN_FILTERED} samples are not low-passed')
            if (left_test or left_sim) and unfiltered not in notes:
                notes.append(unfiltered)
        y_sim = np.interp(xt[inside], xs_sorted, y_sim_sorted)
        diff = y_sim - y_test[inside]
        sim_x[name] = y_sim
        grad_sim = grad_test = None
        grad_unit, grad_se = '', 0.0
        if kc and axis in GRADIENT_WINDOWS and xt[inside].min() < 0.0 < xt[inside].max():
            window = GRADIENT_WINDOWS[axis]
            grad_sim = float(slope_at(xs_sorted, y_sim_sorted, 0.0, window))
            grad_test = float(slope_at(xt, y_test, 0.0, window))
            grad_se = slope_uncertainty(xt, y_test, window)
            grad_unit = f'{unit}/{test.channels[axis].unit}'
        errors.append(ChannelError(
            channel=name, unit=unit, points=int(diff.size), rms=float(np.sqrt(np.mean(diff**2))),
            max=float(np.max(np.abs(diff))), bias=float(np.mean(diff)),
            test_rms=float(np.sqrt(np.mean(y_test[inside]**2))), gradient_sim=grad_sim,
            gradient_test=grad_test, gradient_unit=grad_unit, gradient_uncertainty=grad_se,
            tolerance=_tolerance(name, unit, overrides, kc)))
    if not errors:
        raise InputError('comparison', f'{test.event}: the test and the simulation have no '
                         'channel in common besides the axis')
    return Comparison(sim=sim, test=test, axis=axis, errors=errors, notes=notes,
                      sim_x=sim_x, test_x=xt[inside])


def load_outcomes(bag: Path) -> list[EventOutcome]:
    """Every EventOutcome in a finished bag (its ``*/result`` messages)."""
    return [outcome_from_msg(item.msg) for item in read_bag(bag)
            if item.topic.endswith('/result')]


def pair(sims: Sequence[EventOutcome], tests: Sequence[EventOutcome]
         ) -> list[tuple[EventOutcome, EventOutcome]]:
    """
    Every (simulation, test) of the same event and axle.

    A replay goes with the log it replays only (by the log's SHA-256, REPLAY_NOTE).
    """
    return [(s, t) for t in tests for s in sims
            if s.event == t.event and s.axle == t.axle and s.model not in ('rig', 'test')
            and replay_source(s) in (None, t.data_hash)]


def load_tolerances(path: Path | None) -> dict[str, dict[str, float]]:
    """``channel: {rms: '0.05 deg', max: ..., bias: ..., gradient: 0.1}`` -> SI values."""
    if path is None:
        return {}


    try:
        raw = yaml.safe_load(path.read_text(encoding='utf-8'))
    except (OSError, UnicodeDecodeError, yaml.YAMLError) as err:
        raise InputError(path, f'cannot read the tolerances: {err}') from None
    if not isinstance(raw, dict):
        raise InputError(path, 'a mapping channel -> {rms, max, bias, gradient}')
    out: dict[str, dict[str, float]] = {}
    for channel, spec in raw.items():
        target = si_unit('vehicle', channel) or si_unit('kc', channel)
        if target is None or not isinstance(spec, dict):
            raise InputError(path, f'{channel}: not a channel with a tolerance mapping')
        out[channel] = {}
        for key, value in spec.items():
            if key == 'gradient':
                out[channel][key] = float(value)
                continue
            if key not in ('rms', 'max', 'bias'):
                raise InputError(path, f'{channel}.{key}: unknown key (rms, max, bias, gradient)')
            number, _, unit = str(value).partition(' ')
            try:
                factor, _ = unit_factor(unit or target, target)
                out[channel][key] = float(number) * factor
            except ValueError as err:
                raise InputError(path, f'{channel}.{key}: {err}') from None
    return out


def compare_bags(sim_bag: Path, test_bag: Path,
                 tolerances: Mapping[str, Mapping[str, float]] | None = None
                 ) -> list[Comparison]:
    """Compare every matching pair of two bags (the page: ``reports.compare``)."""
    sims, tests = load_outcomes(sim_bag), load_outcomes(test_bag)
    tests = [t for t in tests if t.model in ('rig', 'test')]
    if not tests:
        raise InputError(test_bag, 'no measured results (model rig or test) in the bag '
                         '(vd import writes them)')
    pairs = pair(sims, tests)
    if not pairs:
        have = ', '.join(sorted({f'{s.event} {s.axle}'.strip() for s in sims})) or 'none'
        want = ', '.join(sorted({f'{t.event} {t.axle}'.strip() for t in tests}))
        raise InputError(sim_bag, f'no simulation of the measured events ({want}); the bag '
                         f'has: {have}')
    return [compare(s, t, tolerances) for s, t in pairs]


def shown(value: float | None, unit: str) -> str:
    if value is None or not math.isfinite(value):
        return '–'
    name, scale = DISPLAY.get(unit, (unit, 1.0))
    return f'{value * scale:.4g} {name}'.strip()


def gradient_shown(value: float | None, unit: str) -> str:
    if value is None:
        return '–'
    top, _, bottom = unit.partition('/')
    top_name, top_scale = DISPLAY.get(top, (top, 1.0))
    return f'{value * top_scale:.4g} {top_name}/{bottom}'


__all__ = ['compare', 'compare_bags', 'lowpassed', 'MIN_FILTERED', 'Comparison',
           'ChannelError', 'load_outcomes', 'pair',
           'replay_source', 'REPLAY_NOTE', 'INPUTS_NOTE',
           'TOLERANCES', 'shown', 'gradient_shown', 'DISPLAY', 'load_tolerances']
