# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Racelogic VBOX ``.vbo`` logs, read as the loggers write them.

The format (Racelogic's "VBO file structure" and the VBOX user guides): a ``File created
on DD/MM/YYYY at HH:MM:SS`` line (older loggers write ``@ HH:MM``), then sections, each
a ``[name]`` line (case varies; loggers add sections such as ``[avifile]`` or
``[laptiming]``, which are skipped):

* ``[header]``: one channel name a line; names may contain spaces and dots, some carry
  their unit (``velocity kmh``, ``velocity knots``);
* ``[channel units]``: the units of the *non-standard* channels (module and CAN
  channels), one a line in header order; blank lines are channels without a unit; the
  section may be missing or empty, and older software writes the degree sign in
  Windows-1252;
* ``[comments]``, ``[module information]``: free text;
* ``[column names]``: the short names of the data columns, space separated, one per
  header channel;
* ``[data]``: space-separated rows with explicit signs and exponents
  (``+03119.09973``, ``1.234567E-02``).

Standard channels and their fixed units: satellites; time as UTC HHMMSS.SS (a log
across midnight wraps to 000000.00); latitude in minutes, positive north; longitude in
minutes, positive **west**; velocity in km/h (knots or mph when the name says so);
heading in degrees clockwise from north; height in m; vertical velocity in km/h (m/s
when named so); long and lat accel in g (positive forward and to the left); yaw rate of
the Racelogic IMU or yaw sensor in deg/s, positive anti-clockwise (Racelogic's signing
conventions): the same signs as ISO 8855.

Into vd channels (REP 105 ``odom``: x east, y north, from the first fix; ISO 8855):
x, y from latitude and longitude on the local tangent plane at the first sample (WGS84
radii of curvature); yaw = 90 deg - heading, unwrapped; speed, accelerations and yaw rate
as they are, in SI; time in s from the first sample (the UTC start is the bag's stamp).
Loggers add ``*_raw`` copies of the GPS channels (``latitude_raw``, ``velocity_raw``
...): standard channels too, with the units of their twins and no ``[channel units]`` line.

**Channel choice by quality** (:data:`CANDIDATES`): where a log has several channels of
one quantity, the best sensor is taken and the notes say which and why, with the noise
of each (:func:`.checks.noise`): the IMU's yaw rate (``YawRate``, ``Yaw Rate``) over the
slip module's (``Yaw_Rate``); the IMU's lateral acceleration (``Y_Accel``, measured at the
IMU, corrected by the import when the roll angle and the IMU position are known) over the
logger's GPS-derived ``lat accel``; the slip module's roll angle. Other channels (steering
angle, slip angle, CAN channels) come in through a column map (:mod:`.columns`) that names
them, their unit if the file has none, and their sign; a mapped channel replaces the
choice.
"""
from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
import datetime as dt
import math
from pathlib import Path
import re

import numpy as np

from vd_events.errors import InputError
from vd_events.measured.checks import noise, shown
from vd_events.measured.columns import ColumnMap, finite_number, normalise, si_unit, unit_factor
from vd_events.measured.table import Measured, check_increasing, read_text

#: WGS84 semi-major axis, m, and first eccentricity squared
WGS84_A = 6378137.0
WGS84_E2 = 6.69437999014e-3

#: standard channels (normalised header name) -> unit; these have no [channel units] line
STANDARD_UNITS: Mapping[str, str] = {
    'satellites': '', 'time': 'HHMMSS', 'latitude': 'min', 'longitude': 'min',
    'velocity': 'km/h', 'velocity kmh': 'km/h', 'velocity knots': 'knot',
    'velocity mph': 'mph', 'heading': 'deg', 'height': 'm',
    'vertical velocity': 'km/h', 'vertical velocity kmh': 'km/h',
    'vertical velocity m/s': 'm/s', 'vertical velocity mph': 'mph',
    'long accel': 'g', 'lat accel': 'g', 'longitudinal acceleration': 'g',
    'lateral acceleration': 'g', 'solution type': '', 'event 1 time': 's',
    'event 2 time': 's', 'trigger event time': 's', 'avifileindex': '', 'avisynctime': 's',
    'glonass_sats': '', 'gps_sats': '', 'distance': 'm',
}
#: module channels whose unit Racelogic documents, used when the file gives none (noted)
DOCUMENTED_UNITS: Mapping[str, str] = {
    'yaw rate': 'deg/s', 'yaw_rate': 'deg/s', 'slip angle': 'deg', 'roll angle': 'deg',
    'pitch angle': 'deg', 'roll_imu': 'deg', 'pitch_imu': 'deg', 'yawrate': 'deg/s',
    'roll_angle': 'deg', 'y_accel': 'g',
}
RAW_SUFFIX = '_raw'
#: the channels vd takes from a .vbo without a column map, best first:
#: channel -> ((normalised name, sensor), ...)
CANDIDATES: Mapping[str, tuple[tuple[str, str], ...]] = {
    'speed': (('velocity kmh', 'GPS'), ('velocity', 'GPS'), ('velocity knots', 'GPS'),
              ('velocity mph', 'GPS')),
    'longitudinal_acceleration': (('long accel', 'GPS'),
                                  ('longitudinal acceleration', 'GPS')),
    'lateral_acceleration': (('y_accel', 'IMU'), ('lat accel', 'GPS'),
                             ('lateral acceleration', 'GPS')),
    'yaw_rate': (('yawrate', 'IMU'), ('yaw rate', 'IMU'), ('yaw_rate', 'slip module')),
    'roll': (('roll_angle', 'slip module'), ('roll angle', 'slip module'),
             ('roll_imu', 'IMU')),
}
#: why one sensor is taken over another
WHY = {'IMU': "the IMU's is the better sensor where both are logged",
       'GPS': "the logger's own channel"}
_LOG_RATE = re.compile(r'log rate\s*\(hz\)\s*:\s*([0-9.]+)', re.IGNORECASE)
_SECTION = re.compile(r'^\s*\[([^\]]+)\]\s*$')
_CREATED = re.compile(r'file created on\s+(\d{1,2})/(\d{1,2})/(\d{4})\s*(?:@|at)?\s*'
                      r'(\d{1,2}):(\d{2})(?::(\d{2}))?', re.IGNORECASE)


@dataclass(frozen=True)
class VboFile:
    """The sections of a .vbo file as written (names, units, rows)."""

    path: Path
    created: dt.datetime | None
    names: list[str]  # [header], as written
    columns: list[str]  # [column names]
    units: dict[str, str | None]  # normalised name -> unit string, None if not known
    data: np.ndarray  # (n, len(names))
    lines: list[int]  # file line of each data row
    comments: list[str]
    notes: list[str]

    @property
    def log_rate(self) -> float | None:
        """The rate the comments state ('Log Rate (Hz) : 100.00'), Hz."""
        for c in self.comments:
            m = _LOG_RATE.search(c)
            if m:
                return float(m.group(1))
        return None


def parse_vbo(path: Path) -> VboFile:
    """Read the sections of ``path`` (module doc); InputError names file, line and column."""
    lines = read_text(path).splitlines()
    sections: dict[str, tuple[int, list[tuple[int, str]]]] = {}
    current: str | None = None
    created = None
    for n, line in enumerate(lines, start=1):
        match = _SECTION.match(line)
        if match:
            current = match.group(1).strip().lower()
            if current in sections:
                raise InputError(path, f'section [{current}] appears twice', line=n)
            sections[current] = (n, [])
        elif current is not None:
            sections[current][1].append((n, line))
        elif line.strip() and created is None:
            m = _CREATED.search(line)
            if m:
                day, month, year, hour, minute = (int(g) for g in m.groups()[:5])
                try:
                    created = dt.datetime(year, month, day, hour, minute, int(m.group(6) or 0),
                                          tzinfo=dt.timezone.utc)
                except ValueError:
                    raise InputError(path, f'invalid creation date {m.group(0)!r}',
                                     line=n) from None
    if 'header' not in sections:
        raise InputError(path, 'not a VBOX .vbo file: no [header] section')
    for needed in ('column names', 'data'):
        if needed not in sections:
            raise InputError(path, f'no [{needed}] section (truncated file, or not a VBOX '
                             '.vbo log)')
    names = [t.strip() for _, t in sections['header'][1] if t.strip()]
    col_lines = [(n, t) for n, t in sections['column names'][1] if t.strip()]
    if not col_lines:
        raise InputError(path, '[column names] is empty', line=sections['column names'][0])
    col_line, col_text = col_lines[0]
    columns = col_text.split()
    if len(columns) != len(names):
        raise InputError(path, f'[column names] has {len(columns)} names, [header] '
                         f'{len(names)} channels', line=col_line)
    notes: list[str] = []
    units = _units(path, names, sections.get('channel units'), notes)
    rows, numbers = [], []
    for n, text in sections['data'][1]:
        if not text.strip():
            continue
        fields = text.split()
        if len(fields) != len(columns):
            raise InputError(path, f'{len(fields)} values, [column names] has '
                             f'{len(columns)} (truncated or malformed row)', line=n)
        rows.append([finite_number(path, field, line=n, column=c + 1, name=names[c])
                     for c, field in enumerate(fields)])
        numbers.append(n)
    if len(rows) < 2:
        raise InputError(path, f'{len(rows)} data row(s) (truncated file?)',
                         line=sections['data'][0])
    comments = [t.strip() for _, t in sections.get('comments', (0, []))[1] if t.strip()]
    return VboFile(path=path, created=created, names=names, columns=columns, units=units,
                   data=np.array(rows), lines=numbers, comments=comments, notes=notes)


def standard_unit(key: str) -> str | None:
    """Return the unit of a standard channel or of its ``*_raw`` twin (None: not standard)."""
    if key in STANDARD_UNITS:
        return STANDARD_UNITS[key]
    if key.endswith(RAW_SUFFIX):
        return STANDARD_UNITS.get(key[:-len(RAW_SUFFIX)])
    return None


def _units(path: Path, names: list[str], section, notes: list[str]) -> dict[str, str | None]:
    """Normalised channel name -> unit (standard table, [channel units], or None)."""
    units: dict[str, str | None] = {}
    others = [normalise(n) for n in names if standard_unit(normalise(n)) is None]
    given = [t.strip() for _, t in section[1]] if section else []
    while len(given) > len(others) and not given[-1]:
        given.pop()  # the blank line that ends the section
    if section is None or not any(given):
        if others:
            notes.append('no [channel units]: the units of ' + ', '.join(others) +
                         ' are not in the file')
        given = [''] * len(others)
    elif len(given) != len(others):
        notes.append(f'[channel units] has {len(given)} lines for {len(others)} '
                     f"non-standard channels ({', '.join(others)}): their units are not "
                     'taken from the file')
        given = [''] * len(others)
    lookup = dict(zip(others, given))
    for name in names:
        key = normalise(name)
        if standard_unit(key) is not None:
            units[key] = standard_unit(key)
        elif lookup.get(key):
            units[key] = lookup[key]
        elif key in DOCUMENTED_UNITS:
            units[key] = DOCUMENTED_UNITS[key]
            notes.append(f"'{name}': no unit in the file, Racelogic's documented "
                         f'{DOCUMENTED_UNITS[key]} assumed')
        else:
            units[key] = None
    return units


def hhmmss_seconds(path: Path, values: np.ndarray, lines: list[int], column: int) -> np.ndarray:
    """UTC HHMMSS.SS -> seconds from the first sample (a log across midnight wraps)."""
    hours = np.floor(values / 10000.0)
    minutes = np.floor((values - hours * 10000.0) / 100.0)
    seconds = values - hours * 10000.0 - minutes * 100.0
    bad = np.nonzero((values < 0) | (hours > 23) | (minutes > 59) | (seconds >= 60.0))[0]
    if bad.size:
        i = int(bad[0])
        raise InputError(path, f'time {values[i]!r} is not UTC HHMMSS.SS', line=lines[i],
                         column=column, name='time')
    t = hours * 3600.0 + minutes * 60.0 + seconds
    wrapped = np.concatenate(([0.0], np.cumsum(np.diff(t) < -43200.0) * 86400.0))
    return t + wrapped


def local_plane(lat_deg: np.ndarray, lon_east_deg: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """East and north (m) from the first fix on its tangent plane (WGS84 radii)."""
    phi0 = math.radians(float(lat_deg[0]))
    s2 = math.sin(phi0) ** 2
    r_n = WGS84_A / math.sqrt(1.0 - WGS84_E2 * s2)  # prime vertical
    r_m = WGS84_A * (1.0 - WGS84_E2) / (1.0 - WGS84_E2 * s2) ** 1.5  # meridian
    east = np.radians(lon_east_deg - lon_east_deg[0]) * r_n * math.cos(phi0)
    north = np.radians(lat_deg - lat_deg[0]) * r_m
    return east, north


def read_vbo(path: Path, cmap: ColumnMap | None) -> Measured:
    """Read a .vbo log as vehicle channels (module doc); ``cmap`` adds or overrides."""
    vbo = parse_vbo(path)
    index = {normalise(n): i for i, n in enumerate(vbo.names)}
    short = {normalise(c): i for i, c in enumerate(vbo.columns)}
    if 'time' not in index:
        raise InputError(path, "no 'time' channel in [header]", line=None)
    col_time = index['time']
    t = hhmmss_seconds(path, vbo.data[:, col_time], vbo.lines, col_time + 1)
    check_increasing(path, t - t[0], vbo.lines, col_time + 1, vbo.names[col_time])
    channels: dict[str, np.ndarray] = {'time': t - t[0]}
    source_units = {'time': 'UTC HHMMSS.SS'}
    columns = {'time': vbo.names[col_time]}
    positions = {'time': col_time + 1}
    notes = list(vbo.notes)
    if 'latitude' in index and 'longitude' in index:
        lat = vbo.data[:, index['latitude']] / 60.0
        lon_east = -vbo.data[:, index['longitude']] / 60.0  # the file's longitude is +west
        channels['x'], channels['y'] = local_plane(lat, lon_east)
        source_units['x'] = source_units['y'] = 'min (lat +N, long +W)'
        columns['x'], columns['y'] = vbo.names[index['longitude']], vbo.names[index['latitude']]
    if 'heading' in index:
        heading = np.radians(vbo.data[:, index['heading']])
        channels['yaw'] = np.unwrap(math.pi / 2.0 - heading)
        source_units['yaw'] = 'deg clockwise from north'
        columns['yaw'] = vbo.names[index['heading']]
        positions['yaw'] = index['heading'] + 1
    mapped: dict[str, tuple[int, str | None, float]] = {}
    if cmap is not None:
        for name, spec in cmap.columns.items():
            key = normalise(name)
            col = index.get(key, short.get(key))
            if col is None:
                raise InputError(path, f"channel '{name}' of the column map {cmap.path} is not "
                                 f"in the file ([header]: {', '.join(vbo.names)})")
            if spec.channel in ('time', 'x', 'y', 'yaw'):
                raise InputError(cmap.path, f"columns.{name}: '{spec.channel}' comes from the "
                                 "log's time, latitude/longitude and heading; it cannot be mapped")
            mapped[spec.channel] = (col, spec.unit, spec.sign)
    for channel, (col, unit, sign) in mapped.items():
        channels[channel], source_units[channel] = _convert(path, vbo, col, channel, unit,
                                                            sign)
        columns[channel], positions[channel] = vbo.names[col], col + 1
        notes.append(f"{channel} <- '{vbo.names[col]}' (column map)")
    for channel, candidates in CANDIDATES.items():
        if channel in mapped:
            continue
        found = [(index[key], sensor) for key, sensor in candidates if key in index]
        if not found:
            continue
        converted = [(col, sensor, *_convert(path, vbo, col, channel, None, 1.0))
                     for col, sensor in found]
        col, sensor, values, unit = converted[0]
        channels[channel], source_units[channel] = values, unit
        columns[channel], positions[channel] = vbo.names[col], col + 1
        notes.append(_choice_note(channel, vbo.names, converted))
    used = set(columns.values())
    start = ''
    if vbo.created is not None:
        midnight = vbo.created.replace(hour=0, minute=0, second=0)
        start = (midnight + dt.timedelta(seconds=float(t[0]))).isoformat()
    meta = {'logger': ' / '.join(vbo.comments[:2]) or 'VBOX', 'start_utc': start,
            'file_created': vbo.created.isoformat() if vbo.created else '',
            'log_rate': f'{vbo.log_rate:g}' if vbo.log_rate else ''}
    return Measured(channels=channels, units={c: si_unit('vehicle', c) or '' for c in channels},
                    source_units=source_units, columns=columns,
                    skipped=tuple(n for n in vbo.names if n not in used and
                                  normalise(n) not in ('latitude', 'longitude')),
                    meta=meta, lines=tuple(vbo.lines), notes=tuple(notes),
                    positions=positions)


def _convert(path: Path, vbo: VboFile, col: int, channel: str, mapped: str | None,
             sign: float) -> tuple[np.ndarray, str]:
    """One column in the channel's SI unit (the map's unit, else the file's), with its sign."""
    name = vbo.names[col]
    target = si_unit('vehicle', channel) or ''
    in_file = vbo.units.get(normalise(name))
    unit = mapped if mapped is not None else in_file
    if unit is None:
        raise InputError(path, f"no unit for this channel in the file: give 'unit' in "
                         f'a column map (--map; {channel} is in {target})',
                         column=col + 1, name=name)
    if mapped is not None and in_file and normalise(name) not in DOCUMENTED_UNITS:
        try:
            same = unit_factor(in_file, target) == unit_factor(mapped, target)
        except ValueError:
            same = False
        if not same:
            raise InputError(path, f"unit mismatch: the file says '{in_file}', the "
                             f"column map says '{mapped}'", column=col + 1, name=name)
    try:
        factor, offset = unit_factor(unit, target)
    except ValueError as err:
        raise InputError(path, f'unit mismatch: {err} (the unit of {channel})',
                         column=col + 1, name=name) from None
    return (sign * (vbo.data[:, col] * factor + offset),
            unit + (' (sign reversed)' if sign < 0 else ''))


def _choice_note(channel: str, names: list[str], converted) -> str:
    """Which of the candidates was taken and why, with the noise of each."""
    unit = si_unit('vehicle', channel) or ''

    def label(col: int, sensor: str, values: np.ndarray) -> str:
        return f"{sensor} '{names[col]}' (noise {shown(noise(values), unit, 2)})"

    col, sensor, values, _ = converted[0]
    text = f'{channel} <- {label(col, sensor, values)}'
    others = [label(c, s, v) for c, s, v, _ in converted[1:]]
    if others:
        text += f", preferred over the {', '.join(others)}: {WHY.get(sensor, 'listed first')}"
    return text


__all__ = ['parse_vbo', 'read_vbo', 'hhmmss_seconds', 'local_plane', 'VboFile', 'CANDIDATES',
           'standard_unit']
