# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The brakes, driveline and aero groups: units at the boundary, consistency, exact refusals.

Reference values are worked by hand from the sample files (rpm to rad/s: 2 pi / 60; bar to
Pa: 1e5) and from the Chrono sources the files name.
"""
from __future__ import annotations

import math
from pathlib import Path
import textwrap

import pytest

from vd_data_server.datafile import load_group_file
from vd_data_server.errors import DataError, DataErrors
from vd_data_server.master import with_overrides
from vd_data_server.study import load_study

STUDIES = Path(__file__).resolve().parents[2] / 'src' / 'vd_data_server' / 'data' / 'studies'

DRIVELINE = """\
    kind: driveline
    units: {torque: N*m}
    data:
      layout: FWD
      engine_torque: {x_unit: rpm, x: [1000, 6000], y: [200, 300]}
      gears: {x: [1, 2], y: [3.0, 1.5]}
      final_drive: 4.0
"""
BRAKES = """\
    kind: brakes
    units: {length: mm, force: N, pressure: bar}
    data:
      front: {piston_diameter: 57, pad_friction: 0.4, effective_radius: 125}
      rear: {piston_diameter: 38, pad_friction: 0.38, effective_radius: 115}
      master_cylinder_diameter: 23.81
      pedal_ratio: 3.5
"""


def _load(tmp_path: Path, group: str, text: str):
    path = tmp_path / 'X.yaml'
    path.write_text(textwrap.dedent(text), encoding='utf-8')
    return load_group_file(path, display=f'sedan/{group}/X.yaml', group=group, variant='X')


def _messages(tmp_path: Path, group: str, text: str) -> list[str]:
    with pytest.raises((DataError, DataErrors)) as info:
        _load(tmp_path, group, text)
    err = info.value
    return [str(e) for e in err.errors] if isinstance(err, DataErrors) else [str(err)]


@pytest.fixture(scope='module')
def sedan():
    return load_study(STUDIES / 'sedan_longitudinal.yaml')


def test_sample_groups_convert_to_si(sedan) -> None:
    config = sedan.configurations['abs']
    line = config.group('driveline')
    speeds, torques = line.values['engine_torque'].si
    assert speeds[0] == pytest.approx(1000.0 * 2.0 * math.pi / 60.0, rel=1e-12)
    assert max(torques) == pytest.approx(370.0)  # Sedan_EngineSimpleMap.cpp
    assert line.scalar('shift_speed') == pytest.approx(4500.0 * math.pi / 30.0, rel=1e-12)
    assert line.values['gears'].si[1] == pytest.approx((3.778, 2.045, 1.276, 0.941, 0.784,
                                                         0.667))
    brakes = config.group('brakes')
    assert brakes.scalar('knee_pressure') == pytest.approx(40e5)
    assert brakes.scalar('front.piston_diameter') == pytest.approx(0.057)
    assert brakes.scalar('rear.pistons') == 1.0
    assert brakes.scalar('abs_dump_slip') == 0.15  # the default
    aero = config.group('aero')
    assert aero.scalar('air_density') == pytest.approx(1.204)  # the default
    assert aero.scalar('drag_coefficient') * aero.scalar('frontal_area') == pytest.approx(0.66)


def test_the_configurations_differ_where_the_master_file_says(sedan) -> None:
    configs = sedan.configurations
    assert configs['abs'].group('brakes').text('anti_lock') == 'all_wheels'
    assert configs['no_abs'].group('brakes').text('anti_lock') == 'none'
    assert configs['open_differential'].group('driveline').text(
        'front_differential.type') == 'open'
    hmmwv = load_study(STUDIES / 'hmmwv_longitudinal.yaml').configurations
    assert hmmwv['no_abs'].group('brakes').text('anti_lock') == 'none'
    assert hmmwv['abs'].group('driveline').text('layout') == 'AWD'


def test_a_valid_minimal_driveline_takes_its_defaults(tmp_path: Path) -> None:
    line = _load(tmp_path, 'driveline', DRIVELINE)
    assert line.scalar('efficiency') == 0.92
    assert not line.has('front_differential.type')  # open by default


@pytest.mark.parametrize('edit, message', [
    ('      front_share: 0.5\n',
     'front_share: front_share 0.5 contradicts layout FWD (front_share 1); leave it out or '
     'make them agree'),
    ('      rear_differential: {type: open}\n',
     'rear_differential.type: the rear axle is not driven (layout FWD): it has no '
     'differential'),
    ('      front_differential: {type: limited_slip}\n',
     'front_differential.locking_torque: a limited_slip differential needs a positive '
     'locking_torque'),
    ('      shift_speed: 7000 rpm\n',
     'shift_speed: shift_speed 733 rad/s lies beyond the engine_torque curve (up to 628.3 '
     'rad/s)'),
])
def test_a_driveline_that_contradicts_itself_is_refused(tmp_path, edit, message) -> None:
    assert _messages(tmp_path, 'driveline', DRIVELINE + edit) == [
        f'sedan/driveline/X.yaml: {message}']


def test_awd_needs_its_share_and_gears_are_numbered(tmp_path: Path) -> None:
    text = DRIVELINE.replace('layout: FWD', 'layout: AWD').replace('x: [1, 2]', 'x: [1, 3]')
    assert _messages(tmp_path, 'driveline', text) == [
        "sedan/driveline/X.yaml: front_share: required with layout AWD (the front axle's "
        'share of the drive torque)',
        'sedan/driveline/X.yaml: gears: gears x must number the gears 1, 2, 3, ... (found '
        '1, 3)']


def test_a_negative_engine_torque_and_an_unknown_layout_are_refused(tmp_path: Path) -> None:
    text = DRIVELINE.replace('y: [200, 300]', 'y: [-20, 300]')
    assert _messages(tmp_path, 'driveline', text) == [
        'sedan/driveline/X.yaml: engine_torque: curve y must be >= 0 (line 5)']
    text = DRIVELINE.replace('layout: FWD', 'layout: 4WD')
    assert _messages(tmp_path, 'driveline', text) == [
        "sedan/driveline/X.yaml: layout: '4WD' is not one of: FWD, RWD, AWD (line 4)"]


def test_brake_ranges_and_anti_lock_slips(tmp_path: Path) -> None:
    assert _load(tmp_path, 'brakes', BRAKES).scalar('booster_gain') == 1.0
    text = BRAKES + '      abs_dump_slip: 0.05\n'
    assert _messages(tmp_path, 'brakes', text) == [
        'sedan/brakes/X.yaml: abs_build_slip: abs_build_slip 0.08 must lie below '
        'abs_dump_slip 0.05']
    text = BRAKES.replace('pad_friction: 0.4,', 'pad_friction: 1.4,')
    assert _messages(tmp_path, 'brakes', text) == [
        'sedan/brakes/X.yaml: front.pad_friction: must be <= 1, found 1.4 (line 4)']


def test_overrides_are_checked_like_the_file(sedan) -> None:
    config = sedan.configurations['abs']
    with pytest.raises(DataError) as info:
        with_overrides(config, {'driveline.layout': 'RWD'})
    assert str(info.value) == (
        'sedan/driveline/X.yaml: front_differential.type: the front axle is not driven '
        '(layout RWD): it has no differential')
    with pytest.raises(DataError) as info:
        with_overrides(config, {'brakes.anti_lock': 'front_only'})
    assert str(info.value) == "--set: brakes.anti_lock: 'front_only' is not one of: " \
                              'all_wheels, none'


def test_a_brake_larger_than_the_rim_is_refused(sedan) -> None:
    """The sedan's tire file has RIM_RADIUS 0.2286 m (a 9 in rim radius): 240 mm is outside."""
    with pytest.raises(DataError) as info:
        with_overrides(sedan.configurations['abs'], {'brakes.front.effective_radius': '240 mm'})
    assert str(info.value) == (
        'sedan/brakes/X.yaml: front.effective_radius: front.effective_radius 240 mm does not '
        'fit inside the rim: sedan/front_tire/X.yaml -> tires/Sedan_Pac02Tire.tir RIM_RADIUS '
        'is 228.6 mm (the pads work inside the wheel); lower it or fit a larger rim')
