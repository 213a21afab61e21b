# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Delimited tables (CSV, semicolon, tab or whitespace) read through a column map.

K&C rig exports (SPMM, ABD, MTS) and plain vehicle-test CSVs are tables: a header line of
column names, optionally a line of units, then one row per sample. The column map
(:mod:`.columns`) says which column is which channel, its unit and sign.
"""
from __future__ import annotations

import csv
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from vd_events.errors import InputError
from vd_events.measured.checks import Findings
from vd_events.measured.columns import ColumnMap, finite_number, si_unit, unit_factor


@dataclass(frozen=True)
class Measured:
    """Channels of one measured file in SI (ISO 8855 signs), and where they came from."""

    channels: dict[str, np.ndarray]
    units: dict[str, str]  # channel -> SI unit
    source_units: dict[str, str]  # channel -> the unit in the file (or the map)
    columns: dict[str, str]  # channel -> the file's column name
    skipped: tuple[str, ...]  # columns of the file not imported
    meta: dict[str, str]  # what the file says about itself (logger, date, ...)
    lines: tuple[int, ...] = ()  # the file line of each sample
    notes: tuple[str, ...] = ()  # what the reader and the checks say, one finding each
    positions: dict[str, int] = field(default_factory=dict)  # channel -> file column (1-based)
    findings: Findings | None = None  # what the import's checks found


#: largest measured file read (a 100 Hz VBOX log of 40 channels for an hour is ~60 MiB)
MAX_MEASURED_BYTES = 128 << 20


def read_text(path: Path) -> str:
    """
    Return the text: UTF-8 (with or without BOM), else Windows-1252; refuse binaries.

    A file over :data:`MAX_MEASURED_BYTES` is refused before it is read.
    """
    try:
        with path.open('rb') as stream:
            data = stream.read(MAX_MEASURED_BYTES + 1)
    except IsADirectoryError:
        raise InputError(path, 'is a folder, not a measured file') from None
    if len(data) > MAX_MEASURED_BYTES:
        raise InputError(path, f'exceeds the limit of {MAX_MEASURED_BYTES >> 20} MiB per '
                         'measured file (cut the log to its manoeuvres, or split it)')
    if b'\x00' in data[:4096]:
        raise InputError(path, 'not a text file (binary data)')
    try:
        return data.decode('utf-8-sig')
    except UnicodeDecodeError:
        return data.decode('cp1252', errors='replace')


def _split(line: str, delimiter: str | None) -> list[str]:
    if delimiter is None:
        return line.split()
    return [f.strip() for f in next(csv.reader([line], delimiter=delimiter))]


def read_table(path: Path, cmap: ColumnMap) -> Measured:
    """Read ``path`` as a table described by ``cmap`` (module doc)."""
    lines = read_text(path).splitlines()
    if len(lines) < cmap.header_line:
        raise InputError(path, f'the file has {len(lines)} lines, the column map expects the '
                         f'header on line {cmap.header_line} (truncated file?)')
    header = _split(lines[cmap.header_line - 1], cmap.delimiter)
    if len(header) < 2:
        raise InputError(path, f"the header has {len(header)} column(s) with delimiter "
                         f"{cmap.delimiter or 'whitespace'!r}: not a table of this column map",
                         line=cmap.header_line)
    index: dict[str, int] = {}
    for i, name in enumerate(header):
        if name in index:
            raise InputError(path, 'the column name appears twice', line=cmap.header_line,
                             column=i + 1, name=name)
        index[name] = i
    for i, name in enumerate(header):
        if name not in cmap.columns and name not in cmap.ignore:
            raise InputError(path, f'unknown column (not in the column map {cmap.path}; map '
                             "it or list it under 'ignore')", line=cmap.header_line,
                             column=i + 1, name=name)
    for name in cmap.columns:
        if name not in index:
            raise InputError(path, f"column '{name}' of the column map {cmap.path} is not in "
                             f"the file (columns: {', '.join(header)})", line=cmap.header_line)
    if cmap.kind == 'vehicle' and 'time' not in {s.channel for s in cmap.columns.values()}:
        raise InputError(cmap.path, "columns: a vehicle log table needs a column mapped to "
                         "'time'")
    file_units: list[str] | None = None
    if cmap.units_line is not None:
        if len(lines) < cmap.units_line:
            raise InputError(path, 'the file ends before its units line (truncated file?)',
                             line=cmap.units_line)
        file_units = _split(lines[cmap.units_line - 1], cmap.delimiter)
        if len(file_units) != len(header):
            raise InputError(path, f'{len(file_units)} units for {len(header)} columns',
                             line=cmap.units_line)
    factors: dict[str, tuple[float, float, float]] = {}
    source_units: dict[str, str] = {}
    for name, spec in cmap.columns.items():
        col = index[name]
        target = si_unit(cmap.kind, spec.channel) or ''
        given = file_units[col] if file_units is not None else None
        unit = _choose_unit(path, cmap, name, col, spec.unit, given, target)
        factor, offset = unit_factor(unit, target)
        factors[spec.channel] = (factor, offset, spec.sign)
        source_units[spec.channel] = unit
    first = cmap.data_line or (cmap.units_line or cmap.header_line) + 1
    rows: list[list[float]] = []
    numbers: list[int] = []
    wanted = [(index[name], spec.channel) for name, spec in cmap.columns.items()]
    for n, line in enumerate(lines[first - 1:], start=first):
        if not line.strip() or line.lstrip().startswith('#'):
            continue
        fields = _split(line, cmap.delimiter)
        if len(fields) != len(header):
            raise InputError(path, f'{len(fields)} fields, the header has {len(header)} '
                             '(truncated or malformed row)', line=n)
        rows.append([finite_number(path, fields[col], line=n, column=col + 1, name=header[col])
                     for col, _channel in wanted])
        numbers.append(n)
    if len(rows) < 2:
        raise InputError(path, f'{len(rows)} data row(s): a measurement needs at least two '
                         '(truncated file?)', line=first)
    data = np.array(rows)
    channels = {}
    for k, (col, channel) in enumerate(wanted):
        factor, offset, sign = factors[channel]
        channels[channel] = sign * (data[:, k] * factor + offset)
    if 'time' in channels:
        check_increasing(path, channels['time'], numbers, index[_name_of(cmap, 'time')] + 1,
                         _name_of(cmap, 'time'))
    return Measured(channels=channels,
                    units={c: si_unit(cmap.kind, c) or '' for c in channels},
                    source_units=source_units,
                    columns={spec.channel: name for name, spec in cmap.columns.items()},
                    skipped=tuple(n for n in header if n in cmap.ignore), meta={},
                    lines=tuple(numbers),
                    positions={spec.channel: index[name] + 1
                               for name, spec in cmap.columns.items()})


def _name_of(cmap: ColumnMap, channel: str) -> str:
    return next(name for name, spec in cmap.columns.items() if spec.channel == channel)


def _choose_unit(path: Path, cmap: ColumnMap, name: str, col: int, mapped: str | None,
                 given: str | None, target: str) -> str:
    """Choose the column's unit: the map's or the file's; both must agree where given."""
    if given is not None:
        try:
            unit_factor(given, target)
        except ValueError as err:
            raise InputError(path, f'unit mismatch: {err} (the unit of '
                             f'{cmap.columns[name].channel})', line=cmap.units_line,
                             column=col + 1, name=name) from None
    if mapped is not None and given is not None and given.strip():
        if unit_factor(mapped, target) != unit_factor(given, target):
            raise InputError(path, f"unit mismatch: the file says '{given}', the column map "
                             f"{cmap.path} says '{mapped}'", line=cmap.units_line,
                             column=col + 1, name=name)
    unit = mapped if mapped is not None else given
    if unit is None or (not unit.strip() and target):
        raise InputError(path, f"no unit for this column: give 'unit' in the column map "
                         f'{cmap.path} (the channel {cmap.columns[name].channel} is in '
                         f'{target})', column=col + 1, name=name)
    return unit


def check_increasing(path: Path, time: np.ndarray, lines: list[int], column: int,
                     name: str) -> None:
    """Refuse a time axis that does not strictly increase, naming the first bad row."""
    bad = np.nonzero(np.diff(time) <= 0.0)[0]
    if bad.size:
        i = int(bad[0]) + 1
        raise InputError(path, f'time does not increase ({time[i - 1]:.6g} s, then '
                         f'{time[i]:.6g} s)', line=lines[i], column=column, name=name)


__all__ = ['Measured', 'read_table', 'read_text', 'check_increasing', 'MAX_MEASURED_BYTES']
