# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Measured-data readers: VBOX .vbo and column-mapped tables, units, signs, time axes.

Positions are checked against the standard series for the length of a degree of
latitude and longitude on WGS84 (111132.92 - 559.82 cos 2phi + 1.175 cos 4phi m and
111412.84 cos phi - 93.5 cos 3phi + 0.118 cos 5phi m), not against the reader's formula.
"""
from __future__ import annotations

import math
from pathlib import Path

from numpy.testing import assert_allclose
import pytest

from vd_events.errors import InputError
from vd_events.measured.columns import load_map
from vd_events.measured.table import read_table
from vd_events.measured.vbo import read_vbo

REPO = Path(__file__).resolve().parents[2]
SAMPLES = REPO / 'src' / 'vd_events' / 'samples'
G = 9.80665

VBO_HEAD = """File created on 20/11/2026 at 10:14:05

[header]
satellites
time
latitude
longitude
velocity kmh
heading
lat accel
Yaw Rate
Steering Angle

[channel units]
{units}
[comments]
made for the vd tests

[column names]
sats time lat long velocity heading latacc yaw_rate steer

[data]
"""


def vbo(tmp_path: Path, rows: list[str], units: str = '°/s\ndeg\n', name: str = 'log.vbo',
        encoding: str = 'cp1252') -> Path:
    path = tmp_path / name
    path.write_bytes((VBO_HEAD.format(units=units) + '\r\n'.join(rows) + '\r\n')
                     .encode(encoding))
    return path


def test_vbo_units_signs_and_time(tmp_path: Path) -> None:
    path = vbo(tmp_path, [
        '137 101405.00 +03120.00000 +00070.00000 072.000 090.00 +0.250 +1.000000E+01 +3.0E+01',
        '137 101405.05 +03120.00000 +00070.00000 072.000 000.00 -0.100 -5.000000E+00 -1.5E+01',
    ])
    m = read_vbo(path, None)
    assert_allclose(m.channels['time'], [0.0, 0.05], atol=1e-9)
    assert_allclose(m.channels['speed'], [20.0, 20.0])  # 72 km/h
    assert_allclose(m.channels['lateral_acceleration'], [0.25 * G, -0.1 * G])  # g, +left
    assert_allclose(m.channels['yaw_rate'], [math.radians(10.0), math.radians(-5.0)])
    # heading 90 deg (east) is yaw 0 in odom (x east); heading 0 (north) is yaw +90 deg
    assert_allclose(m.channels['yaw'], [0.0, math.pi / 2])
    assert 'steering_wheel_angle' not in m.channels  # a module channel needs a map
    assert 'Steering Angle' in m.skipped
    assert m.meta['start_utc'] == '2026-11-20T10:14:05+00:00'


def test_vbo_position_from_minutes_longitude_positive_west(tmp_path: Path) -> None:
    path = vbo(tmp_path, [
        '137 101405.00 +03120.00000 +00070.00000 072.000 090.00 +0.0 +0.0E+00 +0.0E+00',
        '137 101406.00 +03121.00000 +00070.00000 072.000 090.00 +0.0 +0.0E+00 +0.0E+00',
        '137 101407.00 +03121.00000 +00071.00000 072.000 090.00 +0.0 +0.0E+00 +0.0E+00',
    ])
    m = read_vbo(path, None)
    phi = math.radians(52.0)
    per_min_lat = (111132.92 - 559.82 * math.cos(2 * phi) + 1.175 * math.cos(4 * phi)) / 60
    per_min_lon = (111412.84 * math.cos(phi) - 93.5 * math.cos(3 * phi)
                   + 0.118 * math.cos(5 * phi)) / 60
    assert_allclose(m.channels['y'], [0.0, per_min_lat, per_min_lat], atol=0.05)
    # one minute more of longitude is one minute further WEST: x (east) decreases
    assert_allclose(m.channels['x'], [0.0, 0.0, -per_min_lon], atol=0.05)


def test_vbo_time_across_midnight(tmp_path: Path) -> None:
    path = vbo(tmp_path, [
        '137 235959.90 +03120.00000 +00070.00000 072.000 090.00 +0.0 +0.0E+00 +0.0E+00',
        '137 000000.00 +03120.00000 +00070.00000 072.000 090.00 +0.0 +0.0E+00 +0.0E+00',
    ])
    assert_allclose(read_vbo(path, None).channels['time'], [0.0, 0.1], atol=1e-9)


def test_vbo_map_adds_module_channel_with_sign(tmp_path: Path) -> None:
    path = vbo(tmp_path, [
        '137 101405.00 +03120.00000 +00070.00000 072.000 090.00 +0.0 +0.0E+00 +3.0E+01',
        '137 101405.05 +03120.00000 +00070.00000 072.000 090.00 +0.0 +0.0E+00 -1.5E+01',
    ])
    cmap = tmp_path / 'map.yaml'
    cmap.write_text('kind: vehicle\ncolumns:\n  steering angle: {channel: steering_wheel_angle,'
                    ' sign: -1}\n')
    m = read_vbo(path, load_map(cmap))
    assert_allclose(m.channels['steering_wheel_angle'], [math.radians(-30), math.radians(15)])


def test_vbo_without_channel_units(tmp_path: Path) -> None:
    """
    Read a log without [channel units].

    Racelogic's documented yaw-rate unit is assumed and noted; a steering unit is then
    the map's to give (and is refused without one).
    """
    text = vbo(tmp_path, [
        '137 101405.00 +03120.00000 +00070.00000 072.000 090.00 +0.0 +1.0E+01 +3.0E+01',
        '137 101405.05 +03120.00000 +00070.00000 072.000 090.00 +0.0 +1.0E+01 +3.0E+01',
    ]).read_text(encoding='cp1252')
    path = tmp_path / 'nounits.vbo'
    path.write_text(text.replace('[channel units]\n°/s\ndeg\n\n', ''), encoding='cp1252')
    m = read_vbo(path, None)
    assert_allclose(m.channels['yaw_rate'], math.radians(10.0))
    assert "'Yaw Rate': no unit in the file, Racelogic's documented deg/s assumed" in m.notes
    cmap = tmp_path / 'map.yaml'
    cmap.write_text('kind: vehicle\ncolumns:\n  Steering Angle: {channel: steering_wheel_angle}\n')
    with pytest.raises(InputError) as err:
        read_vbo(path, load_map(cmap))
    assert str(err.value) == (
        f"{path}: column 9 'Steering Angle': no unit for this channel in the file: give "
        "'unit' in a column map (--map; steering_wheel_angle is in rad)")
    cmap.write_text('kind: vehicle\ncolumns:\n  Steering Angle: {channel: steering_wheel_angle,'
                    ' unit: deg}\n')
    assert_allclose(read_vbo(path, load_map(cmap)).channels['steering_wheel_angle'],
                    math.radians(30.0))


def test_kc_csv_units_line_and_sign(tmp_path: Path) -> None:
    path = tmp_path / 'rig.csv'
    path.write_text('Travel LH,Toe LH,Note\nmm,deg,\n-10,0.5,a\n0,0.0,\n10,-0.5,\n')
    cmap = tmp_path / 'map.yaml'
    cmap.write_text('kind: kc\nevent: parallel_wheel_travel\naxle: front\nunits_line: 2\n'
                    'columns:\n  Travel LH: {channel: wheel_travel, side: left}\n'
                    '  Toe LH: {channel: toe, side: left, sign: -1}\nignore: [Note]\n')
    m = read_table(path, load_map(cmap))
    assert_allclose(m.channels['wheel_travel_left'], [-0.01, 0.0, 0.01])
    assert_allclose(m.channels['toe_left'], [math.radians(-0.5), 0.0, math.radians(0.5)])
    assert m.units == {'wheel_travel_left': 'm', 'toe_left': 'rad'}


def test_samples_read_with_their_maps() -> None:
    from vd_events.measured.importer import read_measurement

    for data, cmap, n in (('kc_spmm_bounce_front.csv', 'kc_spmm_bounce_front.map.yaml', 41),
                          ('kc_abd_lateral_front.txt', 'kc_abd_lateral_front.map.yaml', 21),
                          ('vbox_sine_steer.vbo', 'vbox_sine_steer.map.yaml', 161),
                          ('vehicle_log.csv', 'vehicle_log.map.yaml', 81)):
        measured, _kind = read_measurement(SAMPLES / data, load_map(SAMPLES / cmap))
        assert {len(v) for v in measured.channels.values()} == {n}, data
