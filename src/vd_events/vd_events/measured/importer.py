# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
``vd import FILE... [--map MAP.yaml] --bag DIR``: measured data into a vd bag.

Each file becomes an :class:`EventOutcome` with vd's channel names and SI units (model
``rig`` for a K&C rig measurement, ``test`` for a vehicle log; fidelity ``measured``;
the data hash is the source file's SHA-256), its provenance in the notes and in the
bag's metadata, and is written with the same messages and topics as a simulation
(:mod:`vd_events.bags.outcomes`). Every file is read and checked before the bag is
opened: bad input writes nothing.

A vehicle log is checked as it is read (:mod:`.checks`; docs/testdata.md): the logger's
sample interval, gaps, glitches (refused unless ``--repair glitches``), a time window
(``--from/--to`` or ``--window auto``, the manoeuvre found by its steering,
:mod:`.align`), the signs of yaw rate, lateral acceleration, steering-wheel angle and roll
against the GPS heading (``--yaw-sign``), and an IMU's lateral acceleration moved to the
CoG and roll-corrected (:mod:`.imu`, ``--imu-position``). Every finding is a note of the
result; nothing is repaired or reversed without being said.
"""
from __future__ import annotations

from collections.abc import Sequence
import dataclasses
from dataclasses import dataclass
import datetime as dt
import hashlib
import math
from pathlib import Path

import numpy as np

from vd_events.bags.bag import check_bag_path
from vd_events.bags.outcomes import write_outcomes
from vd_events.errors import InputError
from vd_events.measured import checks
from vd_events.measured.align import manoeuvre_window
from vd_events.measured.columns import VEHICLE_EVENTS, ColumnMap, load_map, normalise
from vd_events.measured.imu import to_cog
from vd_events.measured.table import Measured, read_table
from vd_events.measured.vbo import CANDIDATES, read_vbo
from vd_solvers import __version__
from vd_solvers.results import Channel, EventOutcome, Metric

MODELS = {'kc': 'rig', 'vehicle': 'test'}
FIDELITY = 'measured'
VBO_SUFFIXES = ('.vbo',)
TABLE_SUFFIXES = ('.csv', '.txt', '.dat', '.tsv', '.asc')
YAW_SIGNS = ('check', 'auto', 'reversed')
REPAIRS = ('glitches',)
WINDOWS = ('auto',)
#: how many glitches a refusal lists
LISTED = 6
#: lateral-acceleration channels measured by a body-fixed IMU (corrected, not the car's)
IMU_LATERAL = tuple(key for key, sensor in CANDIDATES['lateral_acceleration']
                    if sensor == 'IMU')


@dataclass(frozen=True)
class ImportOptions:
    """What the user asked of an import (docs/testdata.md); the defaults check and refuse."""

    repair: tuple[str, ...] = ()  # 'glitches'
    yaw_sign: str = 'check'  # check (refuse a reversed yaw rate) | auto | reversed
    start: float | None = None  # s from the log's first sample (--from)
    end: float | None = None  # (--to)
    window: str = ''  # 'auto': the manoeuvre found by its steering
    imu_position: tuple[float, float, float] | None = None  # m from the CoG, body axes
    event: str | None = None  # overrides the column map's

    def __post_init__(self) -> None:
        unknown = [r for r in self.repair if r not in REPAIRS]
        if unknown:
            raise InputError('--repair', f"unknown repair '{unknown[0]}' (known: "
                             f"{', '.join(REPAIRS)})")
        if self.yaw_sign not in YAW_SIGNS:
            raise InputError('--yaw-sign', f"must be one of {', '.join(YAW_SIGNS)}, found "
                             f'{self.yaw_sign!r}')
        if self.window and self.window not in WINDOWS:
            raise InputError('--window', f"must be {', '.join(WINDOWS)}, found "
                             f'{self.window!r}')
        if self.window and (self.start is not None or self.end is not None):
            raise InputError('--window', 'give either --window auto or --from/--to, not both')
        for name, value in (('--from', self.start), ('--to', self.end)):
            if value is not None and not (math.isfinite(value) and value >= 0.0):
                raise InputError(name, f'must be a time >= 0 s from the first sample, found '
                                 f'{value!r}')
        if self.start is not None and self.end is not None and not self.end > self.start:
            raise InputError('--to', f'{self.end:g} s is not after --from {self.start:g} s')
        if self.imu_position is not None and not (
                len(self.imu_position) == 3 and all(math.isfinite(v) and abs(v) < 10.0
                                                    for v in self.imu_position)):
            raise InputError('--imu-position', 'X,Y,Z in m from the CoG (x forward, y left, '
                             f'z up), each within 10 m; found {self.imu_position!r}')
        if self.event is not None and self.event not in VEHICLE_EVENTS:
            raise InputError('--event', f"must be one of {', '.join(VEHICLE_EVENTS)}, found "
                             f'{self.event!r}')


def sha256(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


def read_measurement(path: Path, cmap: ColumnMap | None,
                     options: ImportOptions | None = None) -> tuple[Measured, str]:
    """Read the file's channels and its kind (kc or vehicle); check a vehicle log."""
    options = options or ImportOptions()
    if not path.exists():
        raise InputError(path, 'no such file')
    suffix = path.suffix.lower()
    if suffix in VBO_SUFFIXES:
        if cmap is not None and cmap.kind != 'vehicle':
            raise InputError(path, f'a VBOX log is a vehicle log; the column map {cmap.path} '
                             f'is for kind {cmap.kind}')
        measured, kind = read_vbo(path, cmap), 'vehicle'
    elif suffix in TABLE_SUFFIXES:
        if cmap is None:
            raise InputError(path, 'a table needs a column map (--map COLUMNS.yaml; keys in '
                             'docs/testdata.md)')
        measured, kind = read_table(path, cmap), cmap.kind
    else:
        raise InputError(path, f"unknown file kind '{suffix}' (VBOX logs: .vbo; tables with a "
                         f"column map: {', '.join(TABLE_SUFFIXES)})")
    if kind == 'vehicle':
        event = options.event or (cmap.event if cmap is not None else 'vehicle_test')
        measured = check_log(path, measured, options, event)
    elif options != ImportOptions():
        raise InputError(path, 'a K&C rig measurement has no time axis: --repair, --yaw-sign, '
                         '--from/--to, --window, --imu-position and --event are for vehicle '
                         'logs')
    else:
        assert cmap is not None
        checks.check_rig(path, measured.channels, measured.units, measured.lines,
                         {c: (measured.positions[c], measured.columns[c])
                          for c in measured.channels}, cmap.event)
    return measured, kind


def _cut(m: Measured, keep: np.ndarray) -> Measured:
    """Keep the samples ``keep`` of every channel and line, time from the first kept sample."""
    channels = {k: v[keep] for k, v in m.channels.items()}
    shift = float(channels['time'][0])
    channels['time'] = channels['time'] - shift
    meta = dict(m.meta)
    if meta.get('start_utc'):
        meta['start_utc'] = (dt.datetime.fromisoformat(meta['start_utc'])
                             + dt.timedelta(seconds=shift)).isoformat()
    lines = tuple(np.asarray(m.lines)[keep]) if m.lines else ()
    return dataclasses.replace(m, channels=channels, meta=meta,
                               lines=tuple(int(n) for n in lines))


def check_log(path: Path, m: Measured, options: ImportOptions, event: str) -> Measured:
    """Run the checks of a vehicle log (module doc); InputError names what is refused."""
    if 'time' not in m.channels:
        return m
    notes = list(m.notes)
    t = m.channels['time']
    lines = list(m.lines)
    interval = checks.sample_interval(t)
    log_rate = float(m.meta['log_rate']) if m.meta.get('log_rate') else None
    rate_note = f"sample rate {1.0 / interval:.4g} Hz: the logger's interval {interval:.4g} s"
    if log_rate:
        rate_note += f' (the file states a log rate of {log_rate:g} Hz)'
    notes.append(rate_note)
    glitches = [g for c in m.channels if c not in ('time', 'x', 'y', 'yaw')
                for g in checks.find_glitches(c, m.columns.get(c, c), t, m.channels[c],
                                              m.units[c], lines)]
    # the window: cut first, so a glitch or a gap outside it does not matter
    t_end = float(t[-1])
    if options.window:
        clean = {c: checks.repair(t, v, [g for g in glitches if g.channel == c])
                 for c, v in m.channels.items()}
        start, end, how = manoeuvre_window(path, event, t, clean)
        how = f'window: {start:.2f} s to {end:.2f} s of the log ({how})'
    elif options.start is not None or options.end is not None:
        start = options.start if options.start is not None else 0.0
        end = options.end if options.end is not None else t_end
        if start >= t_end:
            raise InputError(path, f'--from {start:g} s is beyond the end of the log '
                             f'({t_end:.2f} s)')
        how = f'window: {start:.2f} s to {min(end, t_end):.2f} s of the log (--from/--to)'
    else:
        start, end, how = 0.0, t_end, ''
    if how:
        keep = (t >= start - 1e-9) & (t <= end + 1e-9)
        if np.count_nonzero(keep) < 2:
            raise InputError(path, f'{how}: fewer than two samples')
        first = int(np.argmax(keep))
        glitches = [dataclasses.replace(g, first=g.first - first, last=g.last - first)
                    for g in glitches if keep[g.first]]
        m = _cut(m, keep)
        notes.append(how)
        t, lines = m.channels['time'], list(m.lines)
    gaps = checks.find_gaps(t, interval, lines)
    notes += [g.describe() for g in gaps]
    if glitches and 'glitches' not in options.repair:
        g = glitches[0]
        rest = '; '.join(x.describe() for x in glitches[1:LISTED])
        more = f' and {len(glitches) - LISTED} more' if len(glitches) > LISTED else ''
        raise InputError(path, f"{len(glitches)} glitch{'es' if len(glitches) > 1 else ''} in "
                         f'the imported channels: {g.describe(with_line=False)}'
                         f"{'; ' + rest if rest else ''}{more}; repair them with --repair "
                         'glitches (linear between the neighbouring samples) or leave them out '
                         'with --from/--to', line=g.line, column=m.positions.get(g.channel),
                         name=g.column)
    channels = dict(m.channels)
    for g in glitches:
        channels[g.channel] = checks.repair(t, channels[g.channel], [g])
        notes.append(f'glitch repaired: {g.describe()} -> linear between the samples around it')
    m = dataclasses.replace(m, channels=channels)
    m, sign_notes = _check_signs(path, m, options, interval)
    notes += sign_notes
    m, imu_notes = _lateral_at_cog(m, options, interval)
    notes += imu_notes
    findings = checks.Findings(interval=interval, gaps=tuple(gaps), glitches=tuple(glitches),
                               repaired=bool(glitches), window=(start, min(end, t_end)),
                               log_rate=log_rate)
    return dataclasses.replace(m, notes=tuple(notes), findings=findings)


def _check_signs(path: Path, m: Measured, options: ImportOptions,
                 interval: float) -> tuple[Measured, list[str]]:
    """Signs of yaw rate, lateral acceleration, steering and roll (checks module doc)."""
    ch = dict(m.channels)
    notes: list[str] = []
    t = ch['time']
    speed = ch.get('speed')
    moving = speed > checks.MIN_SPEED if speed is not None else np.ones(t.size, dtype=bool)

    def refuse(channel: str, message: str) -> InputError:
        return InputError(path, message, column=m.positions.get(channel),
                          name=m.columns.get(channel, channel))

    heading = None
    if 'yaw' in ch:
        heading = checks.heading_rate(t, ch['yaw'], interval)
        turning = moving & (np.abs(heading) > checks.TURN_RATE)
    if 'yaw_rate' in ch and options.yaw_sign == 'reversed':
        ch['yaw_rate'] = -ch['yaw_rate']
        notes.append(f"yaw_rate reversed (--yaw-sign reversed): '{m.columns['yaw_rate']}' "
                     'taken as positive clockwise')
    if 'yaw_rate' in ch:
        r = ch['yaw_rate']
        by_heading = checks.agreement(r, heading, turning) if heading is not None else None
        by_ay = None
        if 'lateral_acceleration' in ch and speed is not None:
            ay_v = np.where(moving, ch['lateral_acceleration'] / np.maximum(speed, 1.0), 0.0)
            by_ay = checks.agreement(r, ay_v, moving & (np.abs(ay_v) > checks.TURN_RATE))
        said = ' and '.join(f'{what} ({a.describe()})' for what, a in
                         (('the heading rate', by_heading),
                          ('the lateral acceleration / speed', by_ay)) if a is not None)
        opposes = by_heading.opposes if by_heading is not None and by_heading.decided else (
            by_ay.opposes if by_ay is not None and by_heading is None else False)
        agrees = by_heading.agrees if by_heading is not None and by_heading.decided else (
            by_ay.agrees if by_ay is not None and by_heading is None else False)
        name = m.columns['yaw_rate']
        if opposes and options.yaw_sign == 'auto':
            ch['yaw_rate'] = -r
            notes.append(f"yaw_rate reversed (--yaw-sign auto): '{name}' is positive clockwise: "
                         f'it opposes {said}')
        elif opposes and options.yaw_sign == 'reversed':
            raise refuse('yaw_rate', f'--yaw-sign reversed makes the yaw rate oppose {said}: '
                         "the log's yaw rate is positive anticlockwise (ISO 8855) already; "
                         'import without --yaw-sign')
        elif opposes:
            raise refuse('yaw_rate', f'the yaw rate is positive clockwise: it opposes {said}; '
                         'ISO 8855 yaw rate is positive anticlockwise: import with --yaw-sign '
                         'reversed (or --yaw-sign auto)')
        elif agrees:
            notes.append(f'sign check: yaw_rate agrees with {said}')
        else:
            said = said or 'no heading, no lateral acceleration'
            notes.append(f'sign check: yaw_rate not decided ({said}); kept as logged')
    if heading is None:
        notes.append('sign check: no GPS heading; lateral acceleration, steering and roll '
                     'not checked')
        return dataclasses.replace(m, channels=ch), notes
    for channel, reference, what, hint in (
            ('lateral_acceleration', heading * (speed if speed is not None else 1.0),
             'the lateral acceleration is positive to the right: it opposes speed x heading '
             'rate', 'ISO 8855 lateral acceleration is positive to the left'),
            ('steering_wheel_angle', heading, 'the steering-wheel angle turns against the '
             'heading rate', 'ISO 8855 steering-wheel angle is positive anticlockwise')):
        if channel not in ch:
            continue
        a = checks.agreement(ch[channel], reference, turning)
        if a.opposes:
            raise refuse(channel, f'{what} ({a.describe()}); {hint}: give sign: -1 in the '
                         'column map (--map)')
        notes.append(f"sign check: {channel} {'agrees with' if a.agrees else 'not decided by'}"
                     f' the heading rate ({a.describe()})')
    if 'roll' in ch and 'lateral_acceleration' in ch:
        ay = ch['lateral_acceleration']
        a = checks.agreement(ch['roll'], ay, moving & (np.abs(ay) > 1.0))
        if a.opposes:
            raise refuse('roll', f'the roll angle is positive in right turns ({a.describe()} '
                         'with the lateral acceleration); ISO 8855 roll is positive left side '
                         'up, as a car rolls in a left turn: give sign: -1 in the column map '
                         '(--map)')
        notes.append(f"sign check: roll {'agrees with' if a.agrees else 'not decided by'} the "
                     f'lateral acceleration ({a.describe()})')
    return dataclasses.replace(m, channels=ch), notes


def _lateral_at_cog(m: Measured, options: ImportOptions,
                    interval: float) -> tuple[Measured, list[str]]:
    """Move an IMU's lateral acceleration to the CoG, roll-correct it (:mod:`.imu`)."""
    ch = m.channels
    if 'lateral_acceleration' not in ch:
        return m, []
    name = m.columns['lateral_acceleration']
    body_fixed = normalise(name) in IMU_LATERAL or options.imu_position is not None
    if not body_fixed:
        return m, []
    roll = ch.get('roll')
    position = options.imu_position
    if roll is None and position is None:
        return m, [f"lateral_acceleration: '{name}' is measured by the IMU, at the IMU: not "
                   'roll-corrected, not moved to the CoG (give --imu-position X,Y,Z and a '
                   'roll angle)']
    if 'yaw_rate' not in ch and position is not None:
        raise InputError(m.columns.get('time', 'log'), '--imu-position needs a yaw rate in '
                         'the log (the lever-arm terms)')
    corrected = to_cog(ch['time'], ch['lateral_acceleration'],
                       ch.get('yaw_rate', np.zeros_like(ch['time'])), roll, position, interval)
    done = []
    if position is not None:
        done.append('moved from the IMU at (' + ', '.join(f'{v:g}' for v in position)
                    + ') m to the CoG')
    if roll is not None:
        done.append(f"roll-corrected with '{m.columns['roll']}'")
    missing = ('; not roll-corrected (no roll angle)' if roll is None else
               '; not moved to the CoG (no --imu-position)' if position is None else '')
    at_cog = "a_P,y - r' x_P + p' z_P + (p^2 + r^2) y_P" if position is not None else 'a_P,y'
    formula = f'({at_cog} - g sin(phi)) / cos(phi)' if roll is not None else at_cog
    note = f"lateral_acceleration: '{name}' {' and '.join(done)}: a_y = {formula}{missing}"
    return dataclasses.replace(m, channels={**ch, 'lateral_acceleration': corrected}), [note]


def to_outcome(path: Path, measured: Measured, kind: str, cmap: ColumnMap | None,
               event: str | None = None) -> EventOutcome:
    """Make the measurement an EventOutcome with its provenance (module doc)."""
    digest = sha256(path)
    provenance = dict(cmap.provenance) if cmap is not None else {}
    if kind == 'vehicle' and 'logger' not in provenance and measured.meta.get('logger'):
        provenance['logger'] = measured.meta['logger']
    if 'date' not in provenance and measured.meta.get('start_utc'):
        provenance['date'] = measured.meta['start_utc']
    event = event or (cmap.event if cmap is not None else 'vehicle_test')
    configuration = cmap.configuration if cmap is not None else 'test'
    channels = {name: Channel(measured.units[name], values)
                for name, values in measured.channels.items()}
    metrics = {'samples': Metric(float(len(next(iter(measured.channels.values())))), '-')}
    if 'time' in measured.channels:
        t = measured.channels['time']
        metrics['duration'] = Metric(float(t[-1] - t[0]), 's')
        f = measured.findings
        interval = f.interval if f is not None else float(np.median(np.diff(t)))
        metrics['sample_rate'] = Metric(1.0 / interval, 'Hz', "the logger's interval")
        if f is not None:
            metrics['gaps'] = Metric(float(len(f.gaps)), '-')
            metrics['gap_time'] = Metric(float(sum(g.length for g in f.gaps)), 's')
            metrics['glitches_repaired'] = Metric(float(len(f.glitches)), '-')
    notes = [f'measured: {path.name} ({kind} {"rig" if kind == "kc" else "log"})',
             f'source: {path}', f'source_sha256: {digest}',
             *(f'{k}: {v}' for k, v in provenance.items()),
             f"column map: {cmap.path if cmap is not None else 'the VBOX defaults'}",
             *(f'channel {c} <- {measured.columns[c]!r} [{measured.source_units[c]}]'
               for c in measured.channels)]
    if measured.skipped:
        notes.append('not imported: ' + ', '.join(measured.skipped))
    notes += measured.notes
    return EventOutcome(event=event, configuration=configuration, model=MODELS[kind],
                        fidelity=FIDELITY, axle=cmap.axle if cmap is not None else '',
                        data_hash=digest, metrics=metrics, channels=channels,
                        notes=tuple(notes))


def start_stamp(measured: Measured) -> int:
    """Nanoseconds of the log's first sample (its UTC start where the file says it)."""
    start = measured.meta.get('start_utc')
    if start:
        return int(dt.datetime.fromisoformat(start).timestamp() * 1e9)
    return int(dt.datetime.now(dt.timezone.utc).timestamp()) * 1_000_000_000


def import_files(files: Sequence[Path], map_path: Path | None, bag: Path,
                 options: ImportOptions | None = None) -> tuple[Path, list]:
    """Read and check every file, then write one bag with all of them; return it."""
    check_bag_path(bag)
    options = options or ImportOptions()
    cmap = load_map(map_path) if map_path is not None else None
    items = []
    for path in files:
        measured, kind = read_measurement(Path(path), cmap, options)
        outcome = to_outcome(Path(path), measured, kind, cmap, options.event)
        items.append((outcome, start_stamp(measured)))
    first = items[0][0]
    custom = {'vd.kind': 'measurement', 'vd.model': first.model, 'vd.fidelity': FIDELITY,
              'vd.event': ' '.join(dict.fromkeys(o.event for o, _ in items)),
              'vd.configuration': first.configuration,
              'vd.sources': ' '.join(str(Path(f)) for f in files),
              'vd.source_sha256': ' '.join(o.data_hash for o, _ in items),
              'vd.column_map': cmap.text if cmap is not None else 'VBOX defaults',
              'vd.software_version': __version__}
    if cmap is not None:
        custom.update({f'vd.{k}': v for k, v in cmap.provenance.items()})
    path = write_outcomes(bag, items, custom, master_file=' '.join(str(f) for f in files))
    return path, [o for o, _ in items]


__all__ = ['import_files', 'read_measurement', 'to_outcome', 'check_log', 'ImportOptions',
           'MODELS', 'FIDELITY', 'YAW_SIGNS', 'REPAIRS', 'WINDOWS']
