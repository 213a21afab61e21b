# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Master files: configurations, variants, overrides, and the data-root boundary.

Every test edits a private copy of the bundled data root (``sample_root``) and, for bad
input, checks the exact message and that nothing under the root was written.
"""
from __future__ import annotations

import os
from pathlib import Path
import re
import shutil

from numpy.testing import assert_allclose
import pytest

from vd_data_server import schema
from vd_data_server.errors import DataError
from vd_data_server.master import load_master, resolve
from vd_data_server.study import load_study
from vdtest import line_no, replace_once, tree_snapshot

RTOL = 1e-12


def refused(root: Path, master: Path) -> list[str]:
    """Return the error lines of loading ``master``; nothing under ``root`` is written."""
    before = tree_snapshot(root)
    with pytest.raises(DataError) as info:
        load_study(master)
    assert tree_snapshot(root) == before
    return str(info.value).splitlines()


def sport_override(master: Path, line: str) -> None:
    """Replace the sport configuration's camber override by ``line``."""
    replace_once(master, 'front_alignment.camber: -1.5 deg', line)


# --- the master file itself -------------------------------------------------------------------

def test_master_file_not_found(tmp_path: Path) -> None:
    missing = tmp_path / 'none.yaml'
    with pytest.raises(DataError) as info:
        load_study(missing)
    assert str(info.value) == f'{missing}: file not found'
    assert list(tmp_path.iterdir()) == []


def test_unknown_top_level_key_is_refused(sample_root: Path, sedan_master: Path) -> None:
    replace_once(sedan_master, 'defaults:', 'plots: true\ndefaults:')
    assert refused(sample_root, sedan_master) == [
        f"{sedan_master}: plots: unknown key (expected one of: study, defaults, configurations) "
        f"(line {line_no(sedan_master, 'plots:')})"]


def test_unknown_study_key_is_refused(sample_root: Path, sedan_master: Path) -> None:
    replace_once(sedan_master, '  vehicle: sedan\n', '  vehicle: sedan\n  owner: chassis team\n')
    assert refused(sample_root, sedan_master) == [
        f"{sedan_master}: study.owner: unknown key (expected one of: name, description, vehicle, "
        f"data_root) (line {line_no(sedan_master, '  owner:')})"]


def test_unknown_configuration_key_is_refused(sample_root: Path, sedan_master: Path) -> None:
    replace_once(sedan_master, '    variants:\n      front_spring: Y',
                 '    variant:\n      front_spring: Y')
    lines = refused(sample_root, sedan_master)
    line = line_no(sedan_master, '    variant:')
    assert [(f'{sedan_master}: configurations.sport.variant: unknown key (expected one of: '
             'description, variants, overrides, flexible, flexible_components) '
             f'(line {line})')] == lines


def test_variant_that_does_not_exist_lists_the_available_ones(sample_root: Path,
                                                              sedan_master: Path) -> None:
    replace_once(sedan_master, '      front_spring: Y', '      front_spring: Z')
    assert refused(sample_root, sedan_master) == [
        f"{sedan_master}: variant 'Z' of group 'front_spring' does not exist (no file "
        "sedan/front_spring/Z.yaml; available: X, Y)"]


def test_a_group_without_a_variant_is_refused_for_every_configuration(
        sample_root: Path, sedan_master: Path) -> None:
    replace_once(sedan_master, '  front_damper: X\n', '')
    message = ("no variant chosen (neither in 'defaults' nor in the configuration)")
    assert refused(sample_root, sedan_master) == [
        f"{sedan_master}: configurations.{name}.variants.front_damper: {message} "
        f"(line {line_no(sedan_master, f'  {name}:')})"
        for name in ('baseline', 'stiff_rear', 'sport')]


def test_unknown_group_is_refused(sample_root: Path, sedan_master: Path) -> None:
    replace_once(sedan_master, '      front_spring: Y', '      front_sprung: Y')
    assert refused(sample_root, sedan_master) == [
        f"{sedan_master}: configurations.sport.variants.front_sprung: unknown input group "
        f"(expected one of: {', '.join(schema.all_group_names())}) "
        f"(line {line_no(sedan_master, '      front_sprung:')})"]


@pytest.mark.parametrize('variant', ['../X', 'sub/X', '..', '/etc/X'])
def test_variant_names_must_be_plain_names(sample_root: Path, sedan_master: Path,
                                           variant: str) -> None:
    replace_once(sedan_master, '      front_spring: Y', f"      front_spring: '{variant}'")
    assert refused(sample_root, sedan_master) == [
        f"{sedan_master}: configurations.sport.variants.front_spring: variant must be a plain "
        f"name, found '{variant}' (line {line_no(sedan_master, '      front_spring:')})"]


def test_default_variant_names_must_be_plain_names(sample_root: Path, sedan_master: Path) -> None:
    replace_once(sedan_master, '  front_damper: X\n', '  front_damper: ../../X\n')
    assert refused(sample_root, sedan_master) == [
        f"{sedan_master}: defaults.front_damper: variant must be a plain name, found '../../X' "
        f"(line {line_no(sedan_master, '  front_damper:')})"]


def test_vehicle_must_be_a_plain_folder_name(sample_root: Path, sedan_master: Path) -> None:
    replace_once(sedan_master, '  vehicle: sedan\n', '  vehicle: ../sedan\n')
    assert refused(sample_root, sedan_master) == [
        f"{sedan_master}: study.vehicle: '../sedan' is not a plain folder name "
        f"(line {line_no(sedan_master, '  vehicle:')})"]


def test_configuration_names_must_be_plain(sample_root: Path, sedan_master: Path) -> None:
    replace_once(sedan_master, '  sport:\n', '  sport car:\n')
    assert refused(sample_root, sedan_master) == [
        f"{sedan_master}: configurations.sport car: configuration names may hold letters, "
        f"digits, '_', '-' and '.' (line {line_no(sedan_master, '  sport car:')})"]


def test_flexible_must_be_a_switch_or_a_list(sample_root: Path, sedan_master: Path) -> None:
    replace_once(sedan_master, '    flexible_components: [lca, strut, upright]\n',
                 '    flexible: 3\n')
    assert refused(sample_root, sedan_master) == [
        f'{sedan_master}: configurations.sport.flexible: expected true, false or a list of '
        f"component names, found 3 (line {line_no(sedan_master, '    flexible: 3')})"]


def test_flexible_components_are_kept(sedan_master: Path) -> None:
    replace_once(sedan_master, '    flexible_components: [lca, strut, upright]\n',
                 '    flexible: [lca]\n')
    master = load_master(sedan_master)
    assert master.configurations['sport'].flexible is True
    assert master.configurations['sport'].flexible_components == ('lca',)
    assert master.configurations['baseline'].flexible is False


def test_flexible_components_key_switches_a_subset_on(sedan_master: Path) -> None:
    replace_once(sedan_master, '    flexible_components: [lca, strut, upright]\n',
                 '    flexible_components: [lca, trailing_link]\n')
    study = load_study(sedan_master)
    sport = study.configurations['sport']
    assert sport.flexible and sport.flexible_components == ('lca', 'trailing_link')
    assert sport.data_hash != load_study(sedan_master).configurations['baseline'].data_hash


def test_unknown_flexible_component_is_refused(sample_root: Path, sedan_master: Path) -> None:
    replace_once(sedan_master, '    flexible_components: [lca, strut, upright]\n',
                 '    flexible_components: [lca, crossmember]\n')
    assert refused(sample_root, sedan_master) == [
        f"{sedan_master}: configurations.sport.flexible_components: flexible component "
        "'crossmember' is not defined in the configuration's flex data (defined: anti_roll_bar, "
        "lateral_link, lca, strut, subframe, tierod, trailing_link, upper_arm, upright)"]


def test_unknown_configuration_is_refused(sedan_master: Path) -> None:
    master = load_master(sedan_master)
    with pytest.raises(DataError) as info:
        resolve(master, 'rally')
    assert str(info.value) == (f"{sedan_master}: configuration 'rally' does not exist "
                               "(available: baseline, stiff_rear, sport)")


# --- overrides --------------------------------------------------------------------------------

def test_override_of_a_key_that_does_not_exist(sample_root: Path, sedan_master: Path) -> None:
    sport_override(sedan_master, 'front_alignment.caster: 7 deg')
    assert refused(sample_root, sedan_master) == [
        f"{sedan_master}: configurations.sport.overrides.front_alignment.caster: key 'caster' "
        "does not exist in group 'front_alignment' (sedan/front_alignment/X.yaml); keys: "
        "camber, toe"]


def test_override_of_a_group_that_does_not_exist(sample_root: Path, sedan_master: Path) -> None:
    sport_override(sedan_master, 'front_alignmnt.camber: -1.5 deg')
    groups = load_master(sedan_master).configurations['sport'].variants
    assert refused(sample_root, sedan_master) == [
        f"{sedan_master}: configurations.sport.overrides.front_alignmnt.camber: override of "
        f"unknown group 'front_alignmnt' (groups: {', '.join(groups)}); write GROUP.KEY"]


def test_override_without_a_unit_is_refused(sample_root: Path, sedan_master: Path) -> None:
    sport_override(sedan_master, 'front_alignment.camber: -1.5')
    assert refused(sample_root, sedan_master) == [
        f"{sedan_master}: configurations.sport.overrides.front_alignment.camber: override -1.5 "
        "needs a unit (e.g. '-1.5 deg')"]


def test_override_with_the_wrong_dimension_is_refused(sample_root: Path,
                                                      sedan_master: Path) -> None:
    sport_override(sedan_master, 'front_alignment.camber: -1.5 mm')
    assert refused(sample_root, sedan_master) == [
        f"{sedan_master}: configurations.sport.overrides.front_alignment.camber: unit 'mm' is "
        "not an angle unit (expected e.g. 'rad')"]


def test_override_making_a_stiffness_negative_is_refused(sample_root: Path,
                                                         sedan_master: Path) -> None:
    sport_override(sedan_master, 'front_spring.rate: -10 N/mm')
    assert refused(sample_root, sedan_master) == [
        f"{sedan_master}: configurations.sport.overrides.front_spring.rate: must be positive, "
        "found '-10 N/mm'"]


def test_override_of_a_text_must_be_a_valid_choice(sample_root: Path, sedan_master: Path) -> None:
    sport_override(sedan_master, 'front_hardpoints.template: swing_axle')
    assert refused(sample_root, sedan_master) == [
        f"{sedan_master}: configurations.sport.overrides.front_hardpoints.template: 'swing_axle' "
        "is not one of: macpherson, double_wishbone, multilink"]


def test_several_bad_overrides_are_all_reported(sample_root: Path, sedan_master: Path) -> None:
    sport_override(sedan_master, 'front_alignment.camber: -1.5\n      front_spring.rate: -10 N/mm')
    assert refused(sample_root, sedan_master) == [
        f"{sedan_master}: configurations.sport.overrides.front_alignment.camber: override -1.5 "
        "needs a unit (e.g. '-1.5 deg')",
        f"{sedan_master}: configurations.sport.overrides.front_spring.rate: must be positive, "
        "found '-10 N/mm'"]


def test_point_coordinate_override_changes_one_coordinate(sedan_master: Path) -> None:
    # sedan.yaml: front_hardpoints.points.lca_outer.z: 171 mm; X.yaml: [18.4, 706.0, 181.0] mm
    study = load_study(sedan_master)
    sport = study.configurations['sport'].group('front_hardpoints').point('points.lca_outer')
    base = study.configurations['baseline'].group('front_hardpoints').point('points.lca_outer')
    assert_allclose(sport, (0.0184, 0.706, 0.171), rtol=RTOL)
    assert_allclose(base, (0.0184, 0.706, 0.181), rtol=RTOL)


def test_point_coordinate_override_in_another_unit(sedan_master: Path) -> None:
    replace_once(sedan_master, 'lca_outer.z: 171 mm', 'lca_outer.y: 0.6 m')
    point = load_study(sedan_master).configurations['sport'].group(
        'front_hardpoints').point('points.lca_outer')
    assert_allclose(point, (0.0184, 0.6, 0.181), rtol=RTOL)


def test_point_coordinate_override_needs_a_length(sample_root: Path, sedan_master: Path) -> None:
    replace_once(sedan_master, 'lca_outer.z: 171 mm', 'lca_outer.z: 171 deg')
    assert refused(sample_root, sedan_master) == [
        f"{sedan_master}: configurations.sport.overrides.front_hardpoints.points.lca_outer.z: "
        "unit 'deg' is not a length unit (expected e.g. 'm')"]


def test_a_whole_point_cannot_be_overridden(sample_root: Path, sedan_master: Path) -> None:
    replace_once(sedan_master, 'lca_outer.z: 171 mm', 'lca_outer: [18.4, 620.6, 171]')
    assert refused(sample_root, sedan_master) == [
        f"{sedan_master}: configurations.sport.overrides.front_hardpoints.points.lca_outer: a "
        "point cannot be overridden as a whole; override a single value (e.g. a coordinate "
        "'.x', '.y' or '.z' of a point)"]


def test_a_coordinate_of_a_scalar_is_refused(sample_root: Path, sedan_master: Path) -> None:
    sport_override(sedan_master, 'front_alignment.camber.z: 1 mm')
    assert refused(sample_root, sedan_master) == [
        f"{sedan_master}: configurations.sport.overrides.front_alignment.camber.z: 'camber' is a "
        "scalar, not a point"]


# --- data files and the data-root boundary ----------------------------------------------------

def test_every_broken_data_file_of_a_configuration_is_reported(sample_root: Path) -> None:
    master = sample_root / 'studies' / 'hmmwv.yaml'
    replace_once(sample_root / 'hmmwv/front_spring/X.yaml', 'preload: 11975', 'preload: -1')
    replace_once(sample_root / 'hmmwv/rear_damper/X.yaml', 'kind: damper', 'kind: spring')
    front = sample_root / 'hmmwv/front_spring/X.yaml'
    assert refused(sample_root, master) == [
        f"hmmwv/front_spring/X.yaml: preload: must be >= 0 N, found -1 "
        f"(line {line_no(front, '  preload:')})",
        "hmmwv/rear_damper/X.yaml: kind: file is of kind 'spring' but group 'rear_damper' needs "
        "kind 'damper' (line 1)"]


@pytest.mark.parametrize('target', ['../../etc/passwd', '/etc/passwd', '../outside.tir'])
def test_tire_file_outside_the_data_root_is_refused_unread(
        tmp_path: Path, sample_root: Path, sedan_master: Path, monkeypatch: pytest.MonkeyPatch,
        target: str) -> None:
    # a valid tire file just outside the root: had it been read, the study would load
    shutil.copy(sample_root / 'tires/Sedan_Pac02Tire.tir', tmp_path / 'outside.tir')
    replace_once(sample_root / 'sedan/front_tire/X.yaml', 'tires/Sedan_Pac02Tire.tir', target)
    before = tree_snapshot(tmp_path)
    reads: list[Path] = []
    for method in ('read_bytes', 'read_text'):
        real = getattr(Path, method)

        def spy(self: Path, *args: object, _real=real, **kwargs: object) -> object:
            reads.append(self)
            return _real(self, *args, **kwargs)

        monkeypatch.setattr(Path, method, spy)
    with pytest.raises(DataError) as info:
        load_study(sedan_master)
    monkeypatch.undo()
    assert tree_snapshot(tmp_path) == before
    assert str(info.value) == (f"sedan/front_tire/X.yaml: file: '{target}' is outside the data "
                               f"root {os.path.normpath(sample_root)}")
    assert reads
    assert all(os.path.commonpath([sample_root, os.path.abspath(p)]) == str(sample_root)
               for p in reads)


def test_tire_file_with_a_missing_block_names_file_and_block(sample_root: Path,
                                                             sedan_master: Path) -> None:
    tire = sample_root / 'tires' / 'Sedan_Pac02Tire.tir'
    text, count = re.subn(r'(?ms)^\[VERTICAL\].*?(?=^\[)', '', tire.read_text(encoding='ascii'))
    assert count == 1
    tire.write_text(text, encoding='ascii')
    # front and rear use the same file: reported once
    assert refused(sample_root, sedan_master) == [f'{tire}: missing block [VERTICAL]']


def test_data_file_with_malformed_yaml_is_named_relative_to_the_root(sample_root: Path,
                                                                     sedan_master: Path) -> None:
    replace_once(sample_root / 'sedan/rear_spring/X.yaml', 'rate: 55.0', 'rate: [55.0')
    lines = refused(sample_root, sedan_master)
    assert len(lines) == 1
    assert lines[0].startswith('sedan/rear_spring/X.yaml: malformed YAML: ')


def test_geometry_must_agree_with_the_wheel_centre_hard_points(sedan_master):
    """
    Refuse a wheelbase that disagrees with the wheel-centre hard points.

    A wheelbase edited in the master file without moving the hard points describes two
    different cars: refused, naming configuration, key and the values.
    """
    from vdtest import tree_snapshot

    text = sedan_master.read_text().replace(
        '  baseline:\n    description: Reference car, all shared data unchanged.\n',
        '  baseline:\n    description: Reference car.\n    overrides:\n'
        '      geometry.wheelbase: 2700 mm\n')
    sedan_master.write_text(text)
    before = tree_snapshot(sedan_master.parents[1])
    with pytest.raises(DataError) as err:
        load_study(sedan_master)
    assert str(err.value) == (
        f'{sedan_master}: configurations.baseline: geometry.wheelbase: wheelbase = 2700.0 mm '
        'but the x distance of the front and rear wheel centres is 2776.0 mm (hard points '
        'sedan/front_hardpoints/X.yaml, sedan/rear_hardpoints/X.yaml); keep them within 1 mm')
    assert tree_snapshot(sedan_master.parents[1]) == before


def test_set_override_of_a_track_is_checked_against_the_hard_points(sedan_master):
    from vd_data_server.master import with_overrides

    study = load_study(sedan_master)
    with pytest.raises(DataError) as err:
        with_overrides(study.configurations['sport'], {'geometry.track_rear': '1600 mm'})
    assert str(err.value) == (
        '--set: configurations.sport: geometry.track_rear: track_rear = 1600.0 mm but twice '
        'the rear wheel-centre y is 1580.0 mm (hard points sedan/front_hardpoints/X.yaml, '
        'sedan/rear_hardpoints/X.yaml); keep them within 1 mm')
    moved = with_overrides(study.configurations['sport'],
                           {'geometry.track_rear': '1600 mm',
                            'rear_hardpoints.points.wheel_centre.y': '800 mm'})
    assert moved.group('geometry').scalar('track_rear') == pytest.approx(1.6)


def test_overrides_must_be_a_mapping(sample_root: Path, sedan_master: Path) -> None:
    replace_once(sedan_master, '    overrides:\n', '    overrides: [camber]\n    unused:\n')
    line = line_no(sedan_master, '    overrides:')
    assert refused(sample_root, sedan_master)[-1] == (
        f"{sedan_master}: configurations.sport.overrides: expected a mapping of group.key: "
        f"value, found list ['camber'] (line {line})")


def test_a_data_root_that_is_no_folder_is_refused(sample_root: Path, sedan_master: Path) -> None:
    text = sedan_master.read_text()
    sedan_master.write_text(re.sub(r'(?m)^  data_root: .*$', '  data_root: nowhere', text))
    root = Path(os.path.realpath(sedan_master.parent / 'nowhere'))
    assert refused(sample_root, sedan_master) == [
        f'{sedan_master}: study.data_root: the data root {root} is not a folder '
        f"(line {line_no(sedan_master, '  data_root:')})"]


def test_flexible_components_must_be_a_list(sample_root: Path, sedan_master: Path) -> None:
    replace_once(sedan_master, '    flexible_components: [lca, strut, upright]\n',
                 '    flexible_components: 3\n')
    assert refused(sample_root, sedan_master) == [
        f'{sedan_master}: configurations.sport.flexible_components: expected a non-empty list '
        f"of component names, found 3 (line {line_no(sedan_master, '    flexible_components:')})"]
