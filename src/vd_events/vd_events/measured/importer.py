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
"""
from __future__ import annotations

from collections.abc import Sequence
import datetime as dt
import hashlib
from pathlib import Path

from vd_events.bags.bag import check_bag_path
from vd_events.bags.outcomes import write_outcomes
from vd_events.errors import InputError
from vd_events.measured.columns import ColumnMap, load_map
from vd_events.measured.table import Measured, read_table
from vd_events.measured.vbo import read_vbo
from vd_solvers import __version__
from vd_solvers.results import Channel, EventOutcome, Metric

MODELS = {'kc': 'rig', 'vehicle': 'test'}
FIDELITY = 'measured'
VBO_SUFFIXES = ('.vbo',)
TABLE_SUFFIXES = ('.csv', '.txt', '.dat', '.tsv', '.asc')


def sha256(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


def read_measurement(path: Path, cmap: ColumnMap | None) -> tuple[Measured, str]:
    """Read the file's channels and its kind (kc or vehicle), by the file's format."""
    if not path.exists():
        raise InputError(path, 'no such file')
    suffix = path.suffix.lower()
    if suffix in VBO_SUFFIXES:
        if cmap is not None and cmap.kind != 'vehicle':
            raise InputError(path, f'a VBOX log is a vehicle log; the column map {cmap.path} '
                             f'is for kind {cmap.kind}')
        return read_vbo(path, cmap), 'vehicle'
    if suffix in TABLE_SUFFIXES:
        if cmap is None:
            raise InputError(path, 'a table needs a column map (--map COLUMNS.yaml; keys in '
                             'docs/testdata.md)')
        return read_table(path, cmap), cmap.kind
    raise InputError(path, f"unknown file kind '{suffix}' (VBOX logs: .vbo; tables with a "
                     f"column map: {', '.join(TABLE_SUFFIXES)})")


def to_outcome(path: Path, measured: Measured, kind: str, cmap: ColumnMap | None) -> EventOutcome:
    """Make the measurement an EventOutcome with its provenance (module doc)."""
    digest = sha256(path)
    provenance = dict(cmap.provenance) if cmap is not None else {}
    if kind == 'vehicle' and 'logger' not in provenance and measured.meta.get('logger'):
        provenance['logger'] = measured.meta['logger']
    if 'date' not in provenance and measured.meta.get('start_utc'):
        provenance['date'] = measured.meta['start_utc']
    event = cmap.event if cmap is not None else 'vehicle_test'
    configuration = cmap.configuration if cmap is not None else 'test'
    channels = {name: Channel(measured.units[name], values)
                for name, values in measured.channels.items()}
    metrics = {'samples': Metric(float(len(next(iter(measured.channels.values())))), '-')}
    if 'time' in measured.channels:
        t = measured.channels['time']
        metrics['duration'] = Metric(float(t[-1] - t[0]), 's')
        metrics['sample_rate'] = Metric(float((len(t) - 1) / (t[-1] - t[0])), 'Hz')
    notes = [f'measured: {path.name} ({kind} {"rig" if kind == "kc" else "log"})',
             f'source: {path}', f'source_sha256: {digest}',
             *(f'{k}: {v}' for k, v in provenance.items()),
             f"column map: {cmap.path if cmap is not None else 'the VBOX defaults'}",
             *(f'channel {c} <- {measured.columns[c]!r} [{measured.source_units[c]}]'
               for c in measured.channels)]
    if measured.skipped:
        notes.append('not imported: ' + ', '.join(measured.skipped))
    if measured.meta.get('notes'):
        notes.append(measured.meta['notes'])
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


def import_files(files: Sequence[Path], map_path: Path | None, bag: Path) -> tuple[Path, list]:
    """Read and check every file, then write one bag with all of them; return it."""
    check_bag_path(bag)
    cmap = load_map(map_path) if map_path is not None else None
    items = []
    for path in files:
        measured, kind = read_measurement(Path(path), cmap)
        outcome = to_outcome(Path(path), measured, kind, cmap)
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


__all__ = ['import_files', 'read_measurement', 'to_outcome', 'MODELS', 'FIDELITY']
