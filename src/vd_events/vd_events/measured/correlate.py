# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Model correlation by the validation methods of ISO 19364, ISO 19365 and ISO 22140.

``correlate(sims, tests, method, bands)``: a tolerance band is built around the
simulation of each manoeuvre, and every repeated test run of that manoeuvre must lie
inside it, channel by channel (the band widths: :class:`BandSet`, the versioned file
``data/correlation_bands.yaml`` or the user's own, each number with its source).

* ``iso19364`` (steady-state circular driving): the channels over **lateral
  acceleration**, simulation and test on the same abscissa -- the simulated curve
  (sorted by lateral acceleration) is interpolated at each measured point's lateral
  acceleration; measured points outside the simulated range are left out and counted.
* ``iso19365`` (sine with dwell) and ``iso22140`` (lateral transient response): the
  channels over **time**, the simulation put on the test's time axis by the
  manoeuvre's start (:func:`.align.aligned`: BOS of FMVSS 126 S7.11.6, the 50 %
  steering-wheel instant of ISO 7401), over the method's window around that instant;
  a replay (which runs on its log's own time) over the time the two share.

The band at an abscissa point x is ``[min sim(x') - w, max sim(x') + w]`` over
``|x' - x| <= shift`` with ``w = absolute + relative * scale``; ``scale`` is ``|sim(x)|``
on a steady-state abscissa and the largest ``|sim|`` of the window on a transient one.
A point on the edge is inside. Both signals are low-passed first where both are sampled
at 20 Hz or more (:func:`.compare.lowpassed`, as ``vd compare`` does). Pairing is
``vd compare``'s (:func:`.compare.pair`): a replay goes with its own log only.

Verdicts: a channel of a run passes when the fraction of its points inside the band is
at least the method's ``inside``; a manoeuvre (test event and axle) passes when every
channel of every run passes. The methods ask for repeated runs: a manoeuvre with fewer
than ``min_runs`` test runs is refused (:class:`~vd_events.errors.InputError`) unless
forced, and a forced verdict says so.
"""
from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field, replace
import math
from pathlib import Path
from typing import Any

import numpy as np
import yaml

from vd_events.errors import InputError
from vd_events.measured.align import ALIGNED, aligned, reference_time
from vd_events.measured.columns import si_unit, unit_factor
from vd_events.measured.compare import INPUTS_NOTE, lowpassed, pair, replay_source
from vd_solvers.results import EventOutcome
from vd_solvers.standards.fmvss126 import ProcessingError

METHODS = ('iso19364', 'iso19365', 'iso22140')
#: the band file shipped with vd
DEFAULT_BANDS = Path(__file__).with_name('data') / 'correlation_bands.yaml'
ABSCISSAE = ('time', 'lateral_acceleration')
FILE_KEYS = ('version', 'name', 'methods')
METHOD_KEYS = ('title', 'abscissa', 'tests', 'simulations', 'window', 'window_source',
               'min_runs', 'min_runs_source', 'inside', 'inside_source', 'channels')
BAND_KEYS = ('absolute', 'relative', 'shift', 'source')
#: low-pass only where both signals are sampled at least this fast, Hz (as vd compare)
FILTER_RATE = 20.0
MEASURED = ('test',)


@dataclass(frozen=True)
class Band:
    """The band of one channel: widths in SI (the abscissa's unit for ``shift``)."""

    channel: str
    unit: str
    absolute: float
    relative: float
    shift: float
    source: str

    def to_json(self) -> dict:
        return {'channel': self.channel, 'unit': self.unit, 'absolute': self.absolute,
                'relative': self.relative, 'shift': self.shift, 'source': self.source}


@dataclass(frozen=True)
class MethodBands:
    """One method's bands and rules (module doc)."""

    method: str
    title: str
    abscissa: str
    tests: tuple[str, ...]
    simulations: tuple[str, ...]
    window: tuple[float, float] | None  # s around the manoeuvre's instant
    min_runs: int
    inside: float
    channels: Mapping[str, Band]
    sources: Mapping[str, str] = field(default_factory=dict)


@dataclass(frozen=True)
class BandSet:
    path: Path
    version: int
    name: str
    methods: Mapping[str, MethodBands]


def _quantity(path: Path, key: str, raw: Any, unit: str) -> float:
    """``'2 deg'`` or a bare number (in ``unit``) -> SI of ``unit``."""
    if isinstance(raw, bool):
        raise InputError(path, f'{key}: expected a number with a unit, found {raw!r}')
    if isinstance(raw, (int, float)):
        value = float(raw)
    else:
        number, _, given = str(raw).strip().partition(' ')
        try:
            factor, offset = unit_factor(given.strip() or unit, unit)
            value = float(number) * factor + offset
        except ValueError as err:
            raise InputError(path, f'{key}: {err} (expected {unit})') from None
    if not (math.isfinite(value) and value >= 0.0):
        raise InputError(path, f'{key}: expected a finite width >= 0, found {raw!r}')
    return value


def load_bands(path: Path | None = None) -> BandSet:
    """Read and check a band file (the shipped one when ``path`` is None)."""
    path = Path(path) if path is not None else DEFAULT_BANDS
    try:
        raw = yaml.safe_load(path.read_text(encoding='utf-8'))
    except (OSError, UnicodeDecodeError, yaml.YAMLError) as err:
        raise InputError(path, f'cannot read the band file: {err}') from None
    if not isinstance(raw, dict) or not isinstance(raw.get('methods'), dict):
        raise InputError(path, 'a band file is a mapping with version, name and methods')
    unknown = [k for k in raw if k not in FILE_KEYS]
    if unknown:
        raise InputError(path, f"unknown key '{unknown[0]}' (keys: {', '.join(FILE_KEYS)})")
    version = raw.get('version')
    if not isinstance(version, int) or isinstance(version, bool):
        raise InputError(path, f'version: expected an integer, found {version!r}')
    methods = {}
    for method, spec in raw['methods'].items():
        where = f'methods.{method}'
        if method not in METHODS:
            raise InputError(path, f"{where}: unknown method (methods: {', '.join(METHODS)})")
        if not isinstance(spec, dict):
            raise InputError(path, f'{where}: expected a mapping')
        bad = [k for k in spec if k not in METHOD_KEYS]
        if bad:
            raise InputError(path, f"{where}.{bad[0]}: unknown key (keys: "
                             f"{', '.join(METHOD_KEYS)})")
        abscissa = spec.get('abscissa')
        if abscissa not in ABSCISSAE:
            raise InputError(path, f"{where}.abscissa: one of {', '.join(ABSCISSAE)}, found "
                             f'{abscissa!r}')
        x_unit = si_unit('vehicle', abscissa) or ''
        window = None
        if spec.get('window') is not None:
            w = spec['window']
            if not (isinstance(w, list) and len(w) == 2):
                raise InputError(path, f'{where}.window: expected [before, after] in s')
            before = _signed(path, f'{where}.window', w[0])
            after = _signed(path, f'{where}.window', w[1])
            if not before < after:
                raise InputError(path, f'{where}.window: the start must come before the end')
            window = (before, after)
        min_runs = spec.get('min_runs', 2)
        if not isinstance(min_runs, int) or isinstance(min_runs, bool) or min_runs < 1:
            raise InputError(path, f'{where}.min_runs: expected an integer >= 1, found '
                             f'{min_runs!r}')
        inside = spec.get('inside', 1.0)
        if isinstance(inside, bool) or not isinstance(inside, (int, float)) \
                or not 0.0 < inside <= 1.0:
            raise InputError(path, f'{where}.inside: a fraction in (0, 1], found {inside!r}')
        channels = {}
        if not isinstance(spec.get('channels'), dict) or not spec['channels']:
            raise InputError(path, f'{where}.channels: expected channel: {{absolute, '
                             'relative, shift, source}')
        for channel, band in spec['channels'].items():
            key = f'{where}.channels.{channel}'
            unit = si_unit('vehicle', channel)
            if unit is None or not isinstance(band, dict):
                raise InputError(path, f'{key}: not a vehicle channel with a band mapping')
            bad = [k for k in band if k not in BAND_KEYS]
            if bad:
                raise InputError(path, f"{key}.{bad[0]}: unknown key (keys: "
                                 f"{', '.join(BAND_KEYS)})")
            if not str(band.get('source', '')).strip():
                raise InputError(path, f'{key}.source: every width says where it comes from')
            channels[channel] = Band(
                channel=channel, unit=unit,
                absolute=_quantity(path, f'{key}.absolute', band.get('absolute', 0.0), unit),
                relative=_quantity(path, f'{key}.relative', band.get('relative', 0.0), ''),
                shift=_quantity(path, f'{key}.shift', band.get('shift', 0.0), x_unit),
                source=' '.join(str(band['source']).split()))
        methods[method] = MethodBands(
            method=method, title=str(spec.get('title', method)), abscissa=abscissa,
            tests=tuple(spec.get('tests') or ()), simulations=tuple(spec.get('simulations')
                                                                    or ()),
            window=window, min_runs=min_runs, inside=float(inside), channels=channels,
            sources={k: ' '.join(str(spec[k]).split()) for k in
                     ('window_source', 'min_runs_source', 'inside_source') if k in spec})
    return BandSet(path=path, version=version, name=str(raw.get('name', path.stem)),
                   methods=methods)


def _signed(path: Path, key: str, raw: Any) -> float:
    text = str(raw).strip()
    sign = -1.0 if text.startswith('-') else 1.0
    return sign * _quantity(path, key, text.lstrip('+-').strip(), 's')


def band_edges(x_sim: np.ndarray, y_sim: np.ndarray, x: np.ndarray, band: Band,
               scale: np.ndarray | float) -> tuple[np.ndarray, np.ndarray]:
    """
    Lower and upper edge of ``band`` at the points ``x`` (module doc).

    ``x_sim`` ascending; ``scale`` what ``relative`` multiplies (per point or one value).
    """
    centre = np.interp(x, x_sim, y_sim)
    low, high = centre.copy(), centre.copy()
    if band.shift > 0.0:
        for i, xi in enumerate(x):
            a, b = xi - band.shift, xi + band.shift
            inner = y_sim[(x_sim >= a) & (x_sim <= b)]
            ends = np.interp([a, b], x_sim, y_sim)
            low[i] = min(float(np.min(inner, initial=np.inf)), float(ends.min()), low[i])
            high[i] = max(float(np.max(inner, initial=-np.inf)), float(ends.max()), high[i])
    width = band.absolute + band.relative * np.abs(scale)
    return low - width, high + width


@dataclass(frozen=True)
class ChannelBand:
    """One channel of one test run against its band."""

    channel: str
    unit: str
    run: str
    x: np.ndarray  # abscissa of the test points used (SI)
    test: np.ndarray
    sim: np.ndarray  # the simulation at x
    low: np.ndarray
    high: np.ndarray
    required: float  # fraction of points that must be inside

    @property
    def inside(self) -> np.ndarray:
        return (self.test >= self.low) & (self.test <= self.high)

    @property
    def fraction(self) -> float:
        return float(np.mean(self.inside)) if self.test.size else 0.0

    @property
    def excess(self) -> float:
        """Largest distance of a point outside the band, SI (0: all inside)."""
        out = np.maximum(self.low - self.test, self.test - self.high)
        return float(max(0.0, np.max(out, initial=0.0)))

    @property
    def verdict(self) -> str:
        return 'PASS' if self.test.size and self.fraction >= self.required else 'FAIL'

    def to_json(self) -> dict:
        return {'channel': self.channel, 'unit': self.unit, 'run': self.run,
                'points': int(self.test.size), 'inside': int(np.count_nonzero(self.inside)),
                'fraction_inside': self.fraction, 'required': self.required,
                'largest_excess': self.excess, 'verdict': self.verdict}


@dataclass
class Manoeuvre:
    """The correlation of one manoeuvre: its test runs, every channel's band, the verdict."""

    event: str
    axle: str
    method: str
    runs: list[str]
    simulations: list[str]
    channels: list[ChannelBand]
    min_runs: int
    forced: bool
    notes: list[str]

    @property
    def label(self) -> str:
        return f"{self.event}{' ' + self.axle if self.axle else ''}"

    @property
    def verdict(self) -> str:
        return 'PASS' if self.channels and all(c.verdict == 'PASS' for c in self.channels) \
            else 'FAIL'

    @property
    def verdict_text(self) -> str:
        if not self.forced:
            return self.verdict
        return (f'{self.verdict} (forced: {len(self.runs)} test run; the method asks for '
                f'{self.min_runs})')

    def channel_verdicts(self) -> dict[str, str]:
        out: dict[str, str] = {}
        for c in self.channels:
            out[c.channel] = 'FAIL' if 'FAIL' in (out.get(c.channel), c.verdict) else 'PASS'
        return out

    def to_json(self) -> dict:
        return {'event': self.event, 'axle': self.axle, 'method': self.method,
                'verdict': self.verdict, 'verdict_text': self.verdict_text,
                'forced': self.forced, 'test_runs': self.runs, 'min_runs': self.min_runs,
                'simulations': self.simulations, 'channel_verdicts': self.channel_verdicts(),
                'channels': [c.to_json() for c in self.channels], 'notes': self.notes}


@dataclass
class Correlation:
    method: MethodBands
    bands: BandSet
    manoeuvres: list[Manoeuvre]

    @property
    def verdict(self) -> str:
        return 'PASS' if all(m.verdict == 'PASS' for m in self.manoeuvres) else 'FAIL'

    def to_json(self) -> dict:
        return {'method': self.method.method, 'title': self.method.title,
                'bands': {'file': str(self.bands.path), 'version': self.bands.version,
                          'name': self.bands.name,
                          'channels': [b.to_json() for b in self.method.channels.values()]},
                'verdict': self.verdict, 'manoeuvres': [m.to_json() for m in self.manoeuvres]}


def run_label(o: EventOutcome) -> str:
    """Return a test run's name: its source file, else its configuration and hash."""
    source = next((n[len('source: '):] for n in o.notes if n.startswith('source: ')), '')
    return Path(source).name if source else f'{o.configuration} ({o.data_hash[:12]})'


def sim_label(o: EventOutcome) -> str:
    return f'{o.configuration} ({o.model})'


def _si(o: EventOutcome, name: str, unit: str) -> np.ndarray:
    ch = o.channels[name]
    factor, offset = unit_factor(ch.unit, unit)
    return np.asarray(ch.values, dtype=float) * factor + offset


def _rate(x: np.ndarray) -> float:
    d = np.diff(x)
    d = d[d > 0]
    return 1.0 / float(np.median(d)) if d.size else 0.0


def correlate_pair(sim: EventOutcome, test: EventOutcome, spec: MethodBands
                   ) -> tuple[list[ChannelBand], list[str]]:
    """Every band channel both have, of one test run against its simulation (module doc)."""
    notes: list[str] = []
    label = run_label(test)
    if spec.abscissa == 'time' and replay_source(sim) is None and test.event in ALIGNED:
        sim, notes = aligned(sim, test)
    inputs = {c.strip() for n in sim.notes if n.startswith(INPUTS_NOTE)
              for c in n[len(INPUTS_NOTE):].split(',')}
    for who, o in (('simulation', sim), ('test', test)):
        for name in ('time', spec.abscissa):
            if name not in o.channels:
                raise InputError(who, f"{o.event} ({sim_label(o)}): no '{name}' channel to "
                                 f'correlate on by {spec.title}')
    t_test, t_sim = _si(test, 'time', 's'), _si(sim, 'time', 's')
    filtering = _rate(t_test) >= FILTER_RATE and _rate(t_sim) >= FILTER_RATE
    notes.append('both low-passed first (12-pole phaseless Butterworth, 6 Hz responses)'
                 if filtering else 'not low-passed: one of the two is sampled below 20 Hz')

    def signal(o: EventOutcome, t: np.ndarray, name: str, unit: str) -> np.ndarray:
        y = _si(o, name, unit)
        # a model without a value at some points (a steady state not solved there) is
        # taken as it is: a filter would spread the gaps
        return lowpassed(t, y, name)[0] if filtering and np.all(np.isfinite(y)) else y

    keep = np.ones(t_test.size, dtype=bool)
    if spec.abscissa == 'time':
        x_test, x_sim = t_test, t_sim
        if spec.window is not None and test.event in ALIGNED:
            try:
                t0 = reference_time(test.event, t_test, _si(test, 'steering_wheel_angle',
                                                               'rad'))
            except (ProcessingError, KeyError) as err:
                raise InputError(label, f'{test.event}: cannot find {ALIGNED[test.event]}: '
                                 f'{err}') from None
            keep &= (t_test >= t0 + spec.window[0]) & (t_test <= t0 + spec.window[1])
            notes.append(f'window {spec.window[0]:+g} s to {spec.window[1]:+g} s around '
                         f'{ALIGNED[test.event]} at {t0:.3f} s')
        else:
            notes.append('over the time the simulation and the log share')
        keep &= (t_test >= t_sim.min()) & (t_test <= t_sim.max())
    else:
        x_test = signal(test, t_test, spec.abscissa, 'm/s^2')
        x_sim = signal(sim, t_sim, spec.abscissa, 'm/s^2')
        inside = (x_test >= x_sim.min()) & (x_test <= x_sim.max())
        if not np.all(inside):
            notes.append(f'{np.count_nonzero(~inside)} of {inside.size} test points lie '
                         'outside the simulated lateral-acceleration range and are left out')
        keep &= inside
    if np.count_nonzero(keep) < 2:
        raise InputError(label, f'{test.event}: the test run and the simulation share fewer '
                         f'than two points of {spec.abscissa}')
    order = np.argsort(x_sim, kind='stable')
    out = []
    for name, band in spec.channels.items():
        if name not in test.channels or name not in sim.channels or name in inputs:
            continue
        y_sim = signal(sim, t_sim, name, band.unit)[order]
        y_test = signal(test, t_test, name, band.unit)[keep]
        xs = x_sim[order]
        x = x_test[keep]
        # a model without a value at a point (a steady state not solved there) leaves it out
        known = np.isfinite(y_sim) & np.isfinite(xs)
        xs, y_sim = xs[known], y_sim[known]
        if xs.size < 2:
            continue
        usable = np.isfinite(y_test) & (x >= xs[0]) & (x <= xs[-1])
        x, y_test = x[usable], y_test[usable]
        centre = np.interp(x, xs, y_sim)
        scale: np.ndarray | float = (np.abs(centre) if spec.abscissa != 'time'
                                     else float(np.max(np.abs(centre))))
        low, high = band_edges(xs, y_sim, x, band, scale)
        out.append(ChannelBand(channel=name, unit=band.unit, run=label, x=x, test=y_test,
                               sim=centre, low=low, high=high, required=spec.inside))
    if inputs:
        notes.append(f"inputs of the simulation, taken from the test: "
                     f"{', '.join(sorted(inputs))} (not correlated)")
    return out, notes


def correlate(sims: Sequence[EventOutcome], tests: Sequence[EventOutcome], method: str,
              bands: BandSet | None = None, force: bool = False) -> Correlation:
    """Correlate the simulations with the test runs by ``method`` (module doc)."""
    bands = bands or load_bands()
    if method not in bands.methods:
        raise InputError(bands.path, f"no bands for method '{method}' (the file has: "
                         f"{', '.join(bands.methods) or 'none'})")
    spec = bands.methods[method]
    tests = [t for t in tests if t.model in MEASURED]
    if not tests:
        raise InputError('TEST_BAGS', 'no vehicle log (model test) among the test results '
                         '(vd import writes them)')
    wrong = sorted({t.event for t in tests if t.event not in spec.tests})
    if wrong:
        raise InputError('TEST_BAGS', f"{spec.title} correlates {', '.join(spec.tests)}; the "
                         f"test runs hold {', '.join(wrong)} (--method picks another method)")
    groups: dict[tuple[str, str], list[EventOutcome]] = {}
    for t in tests:
        groups.setdefault((t.event, t.axle), []).append(t)
    short = {k: v for k, v in groups.items() if len(v) < spec.min_runs}
    if short and not force:
        (event, axle), runs = next(iter(short.items()))
        raise InputError('TEST_BAGS', f"{event}{' ' + axle if axle else ''}: "
                         f"{len(runs)} test run ({', '.join(run_label(r) for r in runs)}); "
                         f'{spec.title} validates against repeated runs (at least '
                         f'{spec.min_runs}: min_runs of {bands.path.name}); give the other '
                         'runs, or --force to correlate anyway (the verdict says so)')
    manoeuvres = []
    for (event, axle), runs in groups.items():
        candidates = [s for s in sims if s.model not in ('rig', 'test')
                      and s.event in spec.simulations and s.axle == axle]
        pairs = pair([_as_event(s, event) for s in candidates], runs) \
            if spec.abscissa != 'time' else pair(candidates, runs)
        if not pairs:
            have = ', '.join(sorted({s.event for s in sims})) or 'none'
            raise InputError('SIM_BAGS', f"no simulation of {event} (accepted: "
                             f"{', '.join(spec.simulations)}); the simulation bags hold: "
                             f'{have}')
        channels: list[ChannelBand] = []
        notes: list[str] = []
        for sim, test in pairs:
            found, pair_notes = correlate_pair(sim, test, spec)
            channels += found
            notes += [f'{run_label(test)}: {n}' for n in pair_notes]
        if not channels:
            raise InputError('SIM_BAGS', f'{event}: the simulation and the test runs have no '
                             f"channel of the bands in common ({', '.join(spec.channels)})")
        forced = (event, axle) in short
        if forced:
            notes.append(f'{len(runs)} test run, forced (--force): {spec.title} asks for '
                         f'repeated runs (at least {spec.min_runs})')
        manoeuvres.append(Manoeuvre(
            event=event, axle=axle, method=method, runs=[run_label(r) for r in runs],
            simulations=sorted({sim_label(s) for s, _ in pairs}), channels=channels,
            min_runs=spec.min_runs, forced=forced, notes=notes))
    return Correlation(method=spec, bands=bands, manoeuvres=manoeuvres)


def _as_event(sim: EventOutcome, event: str) -> EventOutcome:
    """Return a steady-state simulation as one of the test's event (same curve over a_y)."""
    return replace(sim, event=event)


__all__ = ['correlate', 'correlate_pair', 'load_bands', 'band_edges', 'Band', 'BandSet',
           'MethodBands', 'ChannelBand', 'Manoeuvre', 'Correlation', 'METHODS',
           'DEFAULT_BANDS', 'run_label']
