# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Column maps: which column of a measured file is which vd channel, in which unit and sign.

A column map is a YAML file (``vd import FILE --map MAP.yaml``; keys in docs/testdata.md)::

    kind: kc                      # kc (a K&C rig export) or vehicle (a vehicle test log)
    event: parallel_wheel_travel  # the vd event the measurement corresponds to
    axle: front                   # kc only
    delimiter: ','                # ',', ';', 'tab' or 'whitespace' (tables only)
    header_line: 1                # line of the column names (tables only)
    units_line: 2                 # optional line of the units (tables only)
    rig: ABD SPMM                 # provenance: rig or logger, vehicle, date
    vehicle: sample sedan
    date: '2026-11-20'
    columns:
      Wheel Travel LH: {channel: wheel_travel, side: left, unit: mm}
      Toe RH: {channel: toe, side: right, unit: deg, sign: -1}
    ignore: [Comment]

Every column of the file must be mapped or ignored; every mapped column must be in the
file. Units are converted with pint to the channel's SI unit (``g`` for an acceleration is
standard gravity, not the gram); ``sign: -1`` maps a rig's convention to ISO 8855.
"""
from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
import math
from pathlib import Path
import re
from typing import Any, cast

import yaml

from vd_data_server.units import parse_unit, ureg
from vd_events.errors import InputError
from vd_solvers.kc.channels import UNITS as KC_BASE_UNITS

KINDS = ('kc', 'vehicle')
SIDES = ('left', 'right')
#: full-vehicle channels a vehicle log can carry, with their SI units (the VehicleState
#: fields of vd_solvers.conversions)
VEHICLE_UNITS: Mapping[str, str] = {
    'time': 's', 'x': 'm', 'y': 'm', 'yaw': 'rad', 'roll': 'rad', 'pitch': 'rad',
    'yaw_rate': 'rad/s', 'speed': 'm/s', 'sideslip': 'rad', 'steering_wheel_angle': 'rad',
    'lateral_acceleration': 'm/s^2', 'longitudinal_acceleration': 'm/s^2',
    'wheel_torque': 'N*m',
}
#: K&C channels a rig measures per wheel (with ``side``) and per axle
KC_WHEEL = ('wheel_travel', 'pad_travel', 'toe', 'camber', 'steer_angle', 'caster',
            'kingpin_inclination', 'scrub_radius', 'mechanical_trail', 'pad_force',
            'spring_force')
KC_VECTORS = ('wheel_centre', 'contact_point')  # per wheel, with a _x/_y/_z component
KC_AXLE: Mapping[str, str] = {
    'track': 'm', 'applied_force': 'N', 'applied_moment': 'N*m', 'steering_wheel_angle': 'rad',
    'rack_travel': 'm', 'rack_force': 'N',
}
#: the channel each K&C event is swept over (the comparison's x axis)
KC_SWEEP: Mapping[str, str] = {
    'parallel_wheel_travel': 'wheel_travel_left', 'opposite_wheel_travel': 'wheel_travel_left',
    'lateral_force': 'applied_force', 'longitudinal_force': 'applied_force',
    'aligning_torque': 'applied_moment', 'steering': 'steering_wheel_angle',
}
VEHICLE_EVENTS = ('step_steer', 'constant_radius_turn', 'sine_with_dwell',
                  'slowly_increasing_steer', 'vehicle_test')
DELIMITERS: Mapping[str, str | None] = {',': ',', ';': ';', 'tab': '\t', 'whitespace': None}
MAP_KEYS = ('kind', 'event', 'axle', 'delimiter', 'header_line', 'units_line', 'data_line',
            'rig', 'logger', 'vehicle', 'configuration', 'date', 'columns', 'ignore', 'comment')
COLUMN_KEYS = ('channel', 'side', 'component', 'unit', 'sign')
#: unit spellings of loggers and rigs that pint does not read as meant
_UNIT_ALIASES = {'°': 'deg', 'degrees': 'deg', 'kmh': 'km/h', 'kph': 'km/h', 'g': 'g0',
                 'G': 'g0', 'secs': 's', 'sec': 's', 'metres': 'm', 'meters': 'm',
                 'nm': 'N*m', 'Nm': 'N*m', '-': '', '': ''}




def finite_number(file: str | Path, text: str, *, line: int, column: int, name: str) -> float:
    """Return the measured value ``text`` as a finite float, or raise InputError naming it."""
    try:
        value = float(text)
    except ValueError:
        raise InputError(file, f'not a number: {text!r}', line=line, column=column,
                         name=name) from None
    if not math.isfinite(value):
        raise InputError(file, f'not a finite number: {text!r}', line=line, column=column,
                         name=name)
    return value


@dataclass(frozen=True)
class ColumnSpec:
    """One mapped column: vd channel, the file's unit and the sign to ISO 8855."""

    channel: str  # the vd channel name (with _left/_right, _x/_y/_z)
    unit: str | None  # None: take the unit from the file
    sign: float = 1.0


@dataclass(frozen=True)
class ColumnMap:
    """A parsed column map (module doc)."""

    path: str
    kind: str
    event: str
    axle: str = ''
    delimiter: str | None = ','
    header_line: int = 1
    units_line: int | None = None
    data_line: int | None = None
    provenance: Mapping[str, str] = field(default_factory=dict)
    columns: Mapping[str, ColumnSpec] = field(default_factory=dict)
    ignore: tuple[str, ...] = ()
    text: str = ''  # the map as written, for the bag's provenance

    @property
    def configuration(self) -> str:
        return self.provenance.get('configuration') or self.provenance.get('vehicle') or 'test'


def si_unit(kind: str, channel: str) -> str | None:
    """Return the SI unit of a vd channel of ``kind`` (None: ``kind`` has no such channel)."""
    if kind == 'vehicle':
        return VEHICLE_UNITS.get(channel)
    if channel in KC_AXLE:
        return KC_AXLE[channel]
    base, _, side = channel.rpartition('_')
    if side not in SIDES:
        return None
    if base in KC_WHEEL:
        return KC_BASE_UNITS[base]
    stem, _, comp = base.rpartition('_')
    if stem in KC_VECTORS and comp in ('x', 'y', 'z'):
        return KC_BASE_UNITS[stem]
    return None


def known_channels(kind: str) -> list[str]:
    if kind == 'vehicle':
        return list(VEHICLE_UNITS)
    wheel = [f'{c}_{s}' for c in KC_WHEEL for s in SIDES]
    vectors = [f'{c}_{k}_{s}' for c in KC_VECTORS for k in 'xyz' for s in SIDES]
    return [*KC_AXLE, *wheel, *vectors]


def unit_factor(unit: str, target: str) -> tuple[float, float]:
    """
    (factor, offset) converting a value in ``unit`` to ``target`` (SI) with pint.

    Raises ValueError for an unknown unit or one of another dimension (angles are told
    from dimensionless units by their power of the radian).
    """
    text = _UNIT_ALIASES.get(unit.strip(), unit.strip())
    text = text.replace('°', 'deg').replace('²', '^2').replace('³', '^3')
    src = parse_unit(text) if text else ureg().dimensionless
    dst = parse_unit(target) if target else ureg().dimensionless
    if _radian_power(src) != _radian_power(dst):
        raise ValueError(f"unit '{unit}' cannot be converted to '{target or '-'}'")
    try:
        zero = float(ureg().Quantity(0.0, src).to(dst).magnitude)
        one = float(ureg().Quantity(1.0, src).to(dst).magnitude)
    except Exception as err:  # noqa: BLE001 - pint's DimensionalityError and offset errors
        raise ValueError(f"unit '{unit}' cannot be converted to '{target or '-'}'") from err
    if not (math.isfinite(one) and math.isfinite(zero)) or one == zero:
        raise ValueError(f"invalid unit '{unit}'")
    return one - zero, zero


def _radian_power(unit) -> int:
    return cast(int, dict(ureg().Quantity(1.0, unit).to_root_units().unit_items()).get(
        'radian', 0))


def load_map(path: str | Path) -> ColumnMap:
    """Read and validate a column map; InputError names the map's file and key."""
    path = Path(path)
    try:
        text = path.read_text(encoding='utf-8')
        raw = yaml.safe_load(text)
    except UnicodeDecodeError:
        raise InputError(path, 'not a text file (a column map is YAML)') from None
    except yaml.YAMLError as err:
        mark = getattr(err, 'problem_mark', None)
        raise InputError(path, f'not valid YAML: {getattr(err, "problem", err)}',
                         line=mark.line + 1 if mark else None) from None
    if not isinstance(raw, dict):
        raise InputError(path, 'a column map is a YAML mapping (kind, event, columns, ...)')
    return parse_map(raw, str(path), text)


def parse_map(raw: Mapping[str, Any], path: str, text: str = '') -> ColumnMap:
    """Validate a column map given as a mapping (``load_map`` reads it from YAML)."""
    def fail(key: str, message: str) -> InputError:
        return InputError(path, f'{key}: {message}')

    unknown = [k for k in raw if k not in MAP_KEYS]
    if unknown:
        raise fail(str(unknown[0]), f"unknown key (known: {', '.join(MAP_KEYS)})")
    kind = raw.get('kind')
    if kind not in KINDS:
        raise fail('kind', f"must be one of {', '.join(KINDS)}, found {kind!r}")
    event = str(raw.get('event') or ('vehicle_test' if kind == 'vehicle' else ''))
    events = KC_SWEEP if kind == 'kc' else VEHICLE_EVENTS
    if event not in events:
        raise fail('event', f"must be one of {', '.join(events)} for kind {kind}, "
                   f'found {event!r}')
    axle = str(raw.get('axle') or '')
    if kind == 'kc' and axle not in ('front', 'rear'):
        raise fail('axle', f'a K&C measurement needs axle front or rear, found {axle!r}')
    if kind == 'vehicle' and axle:
        raise fail('axle', 'a vehicle log has no axle')
    delimiter = raw.get('delimiter', ',')
    if delimiter not in DELIMITERS:
        raise fail('delimiter', f"must be one of {', '.join(map(repr, DELIMITERS))}, "
                   f'found {delimiter!r}')
    lines = {}
    for key in ('header_line', 'units_line', 'data_line'):
        value = raw.get(key)
        if value is None:
            continue
        if not isinstance(value, int) or isinstance(value, bool) or value < 1:
            raise fail(key, f'must be a line number >= 1, found {value!r}')
        lines[key] = value
    header = lines.get('header_line', 1)
    for key in ('units_line', 'data_line'):
        if key in lines and lines[key] <= header:
            raise fail(key, f'must come after header_line {header}, found {lines[key]}')
    columns = raw.get('columns')
    if not isinstance(columns, dict) or not columns:
        raise fail('columns', 'a mapping of file column name -> {channel, unit, side, sign}')
    specs: dict[str, ColumnSpec] = {}
    seen: dict[str, str] = {}
    for name, spec in columns.items():
        specs[str(name)] = _column(spec, str(name), kind, fail)
        channel = specs[str(name)].channel
        if channel in seen:
            raise fail(f'columns.{name}', f"channel '{channel}' is also given by column "
                       f"'{seen[channel]}'")
        seen[channel] = str(name)
    if kind == 'kc' and KC_SWEEP[event] not in seen:
        raise fail('columns', f"event {event} is swept over '{KC_SWEEP[event]}': map a "
                   'column to it')
    ignore = raw.get('ignore') or []
    if not isinstance(ignore, list) or not all(isinstance(i, str) for i in ignore):
        raise fail('ignore', 'a list of column names')
    provenance = {k: str(raw[k]) for k in ('rig', 'logger', 'vehicle', 'configuration', 'date',
                                             'comment') if raw.get(k) is not None}
    return ColumnMap(path=path, kind=kind, event=event, axle=axle,
                     delimiter=DELIMITERS[delimiter], header_line=header,
                     units_line=lines.get('units_line'), data_line=lines.get('data_line'),
                     provenance=provenance, columns=specs, ignore=tuple(ignore), text=text)


def _column(spec: Any, name: str, kind: str, fail) -> ColumnSpec:
    key = f'columns.{name}'
    if isinstance(spec, str):
        spec = {'channel': spec}
    if not isinstance(spec, dict):
        raise fail(key, 'a mapping {channel, unit, side, sign} or a channel name')
    unknown = [k for k in spec if k not in COLUMN_KEYS]
    if unknown:
        raise fail(f'{key}.{unknown[0]}', f"unknown key (known: {', '.join(COLUMN_KEYS)})")
    channel = str(spec.get('channel') or '')
    if spec.get('component') is not None:
        if spec['component'] not in ('x', 'y', 'z'):
            raise fail(f'{key}.component', f"must be x, y or z, found {spec['component']!r}")
        channel = f"{channel}_{spec['component']}"
    if spec.get('side') is not None:
        if spec['side'] not in SIDES:
            raise fail(f'{key}.side', f"must be left or right, found {spec['side']!r}")
        channel = f"{channel}_{spec['side']}"
    target = si_unit(kind, channel)
    if target is None:
        raise fail(f'{key}.channel', f"'{channel}' is not a {kind} channel (known: "
                   f"{', '.join(known_channels(kind))})")
    sign = spec.get('sign', 1)
    if sign not in (1, -1) or isinstance(sign, bool):
        raise fail(f'{key}.sign', f'must be 1 or -1, found {sign!r}')
    unit = spec.get('unit')
    if unit is not None:
        unit = str(unit)
        try:
            unit_factor(unit, target)
        except ValueError as err:
            raise fail(f'{key}.unit', f'{err} (the unit of {channel})') from None
    return ColumnSpec(channel=channel, unit=unit, sign=float(sign))


def normalise(name: str) -> str:
    """Fold case and runs of blanks, which loggers vary, out of a channel name."""
    return re.sub(r'\s+', ' ', name.strip()).lower()


__all__ = ['ColumnMap', 'ColumnSpec', 'InputError', 'load_map', 'parse_map', 'unit_factor',
           'si_unit', 'known_channels', 'KC_SWEEP', 'VEHICLE_UNITS', 'VEHICLE_EVENTS', 'normalise']
