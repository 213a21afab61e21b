# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
``vd import`` on bad input: one message naming file, line and column, exit 2, no bag.

One test per class: unknown column, unit mismatch, non-monotonic time, truncated file,
a file of the wrong kind, a value that is not a number, a bad column map.
"""
from __future__ import annotations

from pathlib import Path

import pytest

from vd_events.cli.main import main

KC_MAP = """kind: kc
event: parallel_wheel_travel
axle: front
units_line: 2
columns:
  Travel LH: {channel: wheel_travel, side: left}
  Toe LH: {channel: toe, side: left}
"""
LOG_MAP = """kind: vehicle
columns:
  Time: {channel: time, unit: s}
  Speed: {channel: speed, unit: km/h}
"""
VBO = """File created on 20/11/2026 at 10:14:05

[header]
satellites
time
latitude
longitude
velocity kmh

[channel units]

[column names]
sats time lat long velocity

[data]
137 101405.00 +03120.00000 +00070.00000 072.000
137 101405.05 +03120.00000 +00070.00000 072.000
137 101405.10 +03120.00000 +00070.00000 072.000
"""


def files(tmp_path: Path, name: str, text: str | bytes, cmap: str | None = KC_MAP):
    data = tmp_path / name
    if isinstance(text, bytes):
        data.write_bytes(text)
    else:
        data.write_text(text, encoding='utf-8')
    mpath = None
    if cmap is not None:
        mpath = tmp_path / 'map.yaml'
        mpath.write_text(cmap)
    return data, mpath


def refused(capsys, tmp_path: Path, data: Path, cmap: Path | None) -> str:
    """Run ``vd import``; assert exit 2, nothing on stdout, no bag; return the message."""
    before = sorted(p.name for p in tmp_path.iterdir())
    argv = ['import', str(data), '--bag', str(tmp_path / 'bag')]
    if cmap is not None:
        argv += ['--map', str(cmap)]
    rc = main(argv)
    out, err = capsys.readouterr()
    assert (rc, out) == (2, '')
    assert sorted(p.name for p in tmp_path.iterdir()) == before  # no bag, no .partial
    return err.strip()


def test_unknown_column(capsys, tmp_path: Path) -> None:
    data, cmap = files(tmp_path, 'rig.csv', 'Travel LH,Toe LH,Extra\nmm,deg,-\n0,0,1\n1,0,1\n')
    assert refused(capsys, tmp_path, data, cmap) == (
        f"{data}: line 1, column 3 'Extra': unknown column (not in the column map {cmap}; "
        "map it or list it under 'ignore')")


def test_mapped_column_missing_from_file(capsys, tmp_path: Path) -> None:
    data, cmap = files(tmp_path, 'rig.csv', 'Travel LH,Camber LH\nmm,deg\n0,0\n1,0\n',
                       KC_MAP + 'ignore: [Camber LH]\n')
    assert refused(capsys, tmp_path, data, cmap) == (
        f"{data}: line 1: column 'Toe LH' of the column map {cmap} is not in the file "
        '(columns: Travel LH, Camber LH)')


def test_unit_of_the_wrong_kind(capsys, tmp_path: Path) -> None:
    data, cmap = files(tmp_path, 'rig.csv', 'Travel LH,Toe LH\nmm,N\n0,0\n1,0\n')
    assert refused(capsys, tmp_path, data, cmap) == (
        f"{data}: line 2, column 2 'Toe LH': unit mismatch: unit 'N' cannot be converted "
        "to 'rad' (the unit of toe_left)")


def test_unit_file_and_map_disagree(capsys, tmp_path: Path) -> None:
    data, cmap = files(tmp_path, 'rig.csv', 'Travel LH,Toe LH\nmm,deg\n0,0\n1,0\n',
                       KC_MAP.replace('toe, side: left}', 'toe, side: left, unit: rad}'))
    assert refused(capsys, tmp_path, data, cmap) == (
        f"{data}: line 2, column 2 'Toe LH': unit mismatch: the file says 'deg', the "
        f"column map {cmap} says 'rad'")


def test_time_not_increasing(capsys, tmp_path: Path) -> None:
    data, cmap = files(tmp_path, 'log.csv', 'Time,Speed\n0.0,80\n0.1,80\n0.1,81\n', LOG_MAP)
    assert refused(capsys, tmp_path, data, cmap) == (
        f"{data}: line 4, column 1 'Time': time does not increase (0.1 s, then 0.1 s)")


def test_vbo_time_not_increasing(capsys, tmp_path: Path) -> None:
    data, _ = files(tmp_path, 'log.vbo', VBO.replace('101405.10', '101405.00'), None)
    assert refused(capsys, tmp_path, data, None) == (
        f"{data}: line 18, column 2 'time': time does not increase (0.05 s, then 0 s)")


def test_truncated_table_row(capsys, tmp_path: Path) -> None:
    data, cmap = files(tmp_path, 'rig.csv', 'Travel LH,Toe LH\nmm,deg\n0,0\n1\n')
    assert refused(capsys, tmp_path, data, cmap) == (
        f'{data}: line 4: 1 fields, the header has 2 (truncated or malformed row)')


def test_truncated_vbo_row(capsys, tmp_path: Path) -> None:
    data, _ = files(tmp_path, 'log.vbo', VBO[:-20], None)
    assert refused(capsys, tmp_path, data, None) == (
        f'{data}: line 18: 4 values, [column names] has 5 (truncated or malformed row)')


def test_vbo_cut_before_its_data(capsys, tmp_path: Path) -> None:
    data, _ = files(tmp_path, 'log.vbo', VBO.split('[column names]')[0], None)
    assert refused(capsys, tmp_path, data, None) == (
        f'{data}: no [column names] section (truncated file, or not a VBOX .vbo log)')


def test_csv_named_vbo(capsys, tmp_path: Path) -> None:
    data, _ = files(tmp_path, 'log.vbo', 'Time,Speed\n0.0,80\n0.1,80\n', None)
    assert refused(capsys, tmp_path, data, None) == (
        f'{data}: not a VBOX .vbo file: no [header] section')


def test_binary_file(capsys, tmp_path: Path) -> None:
    data, cmap = files(tmp_path, 'rig.csv', b'\x89PNG\r\n\x1a\n\x00\x00\x00\rIHDR')
    assert refused(capsys, tmp_path, data, cmap) == f'{data}: not a text file (binary data)'


def test_unknown_file_kind(capsys, tmp_path: Path) -> None:
    data, cmap = files(tmp_path, 'rig.xlsx', 'x')
    assert refused(capsys, tmp_path, data, cmap) == (
        f"{data}: unknown file kind '.xlsx' (VBOX logs: .vbo; tables with a column map: "
        '.csv, .txt, .dat, .tsv, .asc)')


def test_kc_map_for_a_vehicle_log(capsys, tmp_path: Path) -> None:
    data, cmap = files(tmp_path, 'log.vbo', VBO)
    assert refused(capsys, tmp_path, data, cmap) == (
        f'{data}: a VBOX log is a vehicle log; the column map {cmap} is for kind kc')


def test_table_without_a_map(capsys, tmp_path: Path) -> None:
    data, _ = files(tmp_path, 'rig.csv', 'a,b\n1,2\n', None)
    assert refused(capsys, tmp_path, data, None) == (
        f'{data}: a table needs a column map (--map COLUMNS.yaml; keys in docs/testdata.md)')


def test_not_a_number(capsys, tmp_path: Path) -> None:
    data, cmap = files(tmp_path, 'rig.csv', 'Travel LH,Toe LH\nmm,deg\n0,0\n1,abc\n')
    assert refused(capsys, tmp_path, data, cmap) == (
        f"{data}: line 4, column 2 'Toe LH': not a number: 'abc'")


@pytest.mark.parametrize(('edit', 'message'), [
    (('kind: kc', 'kind: kc\nrate: 5'),
     'rate: unknown key (known: kind, event, axle, delimiter, header_line, units_line, '
     'data_line, rig, logger, vehicle, configuration, date, columns, ignore, comment)'),
    (('channel: toe,', 'channel: toes,'),
     "columns.Toe LH.channel: 'toes_left' is not a kc channel (known: "),
    (('side: left}\n', 'side: left, unit: N}\n'),
     "columns.Travel LH.unit: unit 'N' cannot be converted to 'm' (the unit of "
     'wheel_travel_left)'),
    (('axle: front', 'axle: middle'),
     "axle: a K&C measurement needs axle front or rear, found 'middle'"),
])
def test_bad_column_map(capsys, tmp_path: Path, edit, message) -> None:
    data, cmap = files(tmp_path, 'rig.csv', 'Travel LH,Toe LH\nmm,deg\n0,0\n1,0\n',
                       KC_MAP.replace(*edit, 1))
    assert refused(capsys, tmp_path, data, cmap).startswith(f'{cmap}: {message}')


RIG = 'Travel LH,Toe LH\nmm,deg\n' + ''.join(f'{x},0.0{i}\n' for i, x in
                                            enumerate((-20, -10, 0, 10, 20)))


@pytest.mark.parametrize(('text', 'message'), [
    (RIG.replace('-20,', '1e308,'), "line 3, column 1 'Travel LH': wheel_travel_left 1e+305 m "
     'is implausible (beyond 2 m)'),
    (RIG.replace('0,0.02', '30,0.02'), "line 6, column 1 'Travel LH': wheel_travel_left does "
     'not run one way (0.03 m, then 0.01 m): import each sweep of a loop as a file of its own'),
    (RIG.replace('\n-10,', '\n-20,'), "line 4, column 1 'Travel LH': wheel_travel_left does "
     'not run one way (-0.02 m, then -0.02 m): import each sweep of a loop as a file of its '
     'own'),
    ('Travel LH,Toe LH\nmm,deg\n' + '5,0.01\n' * 5,
     "column 1 'Travel LH': wheel_travel_left does not change (0.005 m throughout): nothing "
     'was swept'),
    ('Travel LH,Toe LH\nmm,deg\n0,0\n1,0\n', 'line 3: 2 steps: a K&C rig measurement needs '
     'at least 5 (truncated file?)'),
    (RIG.replace('0,0.02', ',0.02'), "line 5, column 1 'Travel LH': not a number: ''"),
    (RIG.replace('0,0.02', 'nan,0.02'), "line 5, column 1 'Travel LH': not a finite number: "
     "'nan'"),
    (RIG.replace('0,0.02', 'inf,0.02'), "line 5, column 1 'Travel LH': not a finite number: "
     "'inf'"),
])
def test_rig_tables_the_comparison_cannot_use(capsys, tmp_path: Path, text: str,
                                              message: str) -> None:
    data, cmap = files(tmp_path, 'rig.csv', text)
    assert refused(capsys, tmp_path, data, cmap) == f'{data}: {message}'


def test_rig_table_with_a_duplicate_column(capsys, tmp_path: Path) -> None:
    data, cmap = files(tmp_path, 'rig.csv', RIG.replace('Toe LH', 'Travel LH', 1))
    assert refused(capsys, tmp_path, data, cmap) == (
        f"{data}: line 1, column 2 'Travel LH': the column name appears twice")


def test_log_with_a_duplicate_time_column(capsys, tmp_path: Path) -> None:
    data, cmap = files(tmp_path, 'log.csv', 'Time,Time\n0.0,0.0\n0.1,0.1\n0.2,0.2\n', LOG_MAP)
    assert refused(capsys, tmp_path, data, cmap) == (
        f"{data}: line 1, column 2 'Time': the column name appears twice")


def test_measured_file_over_the_size_limit(capsys, tmp_path: Path, monkeypatch) -> None:
    from vd_events.measured import table

    monkeypatch.setattr(table, 'MAX_MEASURED_BYTES', 1 << 20)
    data, _ = files(tmp_path, 'log.vbo', VBO + '137 101405.15 +03120.00000 +00070.00000 '
                    '072.000\n' * 30000, None)
    assert refused(capsys, tmp_path, data, None) == (
        f'{data}: exceeds the limit of 1 MiB per measured file (cut the log to its '
        'manoeuvres, or split it)')
