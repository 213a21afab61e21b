# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Edits of master files (the workbench, vd import xlsx): validated, atomic, comments kept.

Every refused edit checks the exact message and that nothing under the data root changed.
"""
from __future__ import annotations

import os
from pathlib import Path

import pytest

from vd_data_server.errors import DataError
from vd_data_server.masteredit import Edit, edit_master
from vd_data_server.service import DataService
from vd_data_server.study import load_study
from vdtest import tree_snapshot


def refused(root: Path, master: Path, edit: Edit) -> str:
    before = tree_snapshot(root)
    with pytest.raises(DataError) as info:
        edit_master(master, [edit])
    assert tree_snapshot(root) == before
    return str(info.value)


def test_an_override_is_written_with_comments_order_and_a_backup(sedan_master: Path) -> None:
    before = sedan_master.read_text()
    assert edit_master(sedan_master, [Edit('override', 'baseline', key='front_alignment.camber',
                                           value='-1.2 deg')])
    after = sedan_master.read_text()
    # only the new lines differ: every comment, key order and folded text is kept
    assert after == before.replace(
        '    description: Reference car, all shared data unchanged.\n',
        '    description: Reference car, all shared data unchanged.\n'
        '    overrides:\n      front_alignment.camber: -1.2 deg\n')
    assert (sedan_master.parent / 'sedan.yaml.bak').read_text() == before
    status = load_study(sedan_master).status_of('baseline', 'front_alignment')
    assert status.state == 'MODIFIED'
    assert [(m.key, m.data_value, m.master_value, m.unit) for m in status.modified_keys] == [
        ('camber', '-0.5', '-1.2', 'deg')]
    # cleared again: the file is the original
    assert edit_master(sedan_master, [Edit('override', 'baseline', key='front_alignment.camber')])
    assert sedan_master.read_text() == before


def test_variant_flexible_and_copy(sedan_master: Path) -> None:
    edit_master(sedan_master, [
        Edit('variant', 'baseline', group='front_spring', value='Y'),
        Edit('flexible', 'stiff_rear', value='lca, strut'),
        Edit('add', 'sport_copy', source='sport', value='Sport with a softer front'),
        Edit('variant', 'sport_copy', group='front_spring', value='X'),
    ])
    study = load_study(sedan_master)
    assert study.configuration_names == ['baseline', 'stiff_rear', 'sport', 'sport_copy']
    assert study.status_of('baseline', 'front_spring').variant == 'Y'
    assert study.configurations['stiff_rear'].flexible_components == ('lca', 'strut')
    copy, sport = study.master.configurations['sport_copy'], study.master.configurations['sport']
    assert copy.description == 'Sport with a softer front'
    assert copy.overrides == sport.overrides
    assert copy.variants == {**sport.variants, 'front_spring': 'X'}
    text = sedan_master.read_text()
    assert '    flexible_components: [lca, strut]\n' in text
    edit_master(sedan_master, [Edit('flexible', 'stiff_rear', value='off')])
    assert not load_study(sedan_master).configurations['stiff_rear'].flexible


def test_a_bad_value_is_refused_with_the_loader_message(sample_root: Path,
                                                        sedan_master: Path) -> None:
    assert refused(sample_root, sedan_master, Edit(
        'override', 'baseline', key='front_alignment.camber', value='-1.2 kg')) == (
        f'{sedan_master}: configurations.baseline.overrides.front_alignment.camber: unit '
        "'kg' is not an angle unit (expected e.g. 'rad')")
    # the same message as loading a master file that holds the value (vd data check)
    message = refused(sample_root, sedan_master, Edit(
        'override', 'sport', key='front_alignment.camber', value='-1.2'))
    by_hand = sedan_master.read_text().replace('camber: -1.5 deg', "camber: '-1.2'")
    hand = sample_root / 'studies' / 'hand.yaml'
    hand.write_text(by_hand)
    with pytest.raises(DataError) as info:
        load_study(hand)
    assert message == str(info.value).replace(str(hand), str(sedan_master))
    assert message.startswith(f'{sedan_master}: configurations.sport.overrides.'
                              "front_alignment.camber: value '-1.2' needs a unit")
    assert refused(sample_root, sedan_master, Edit(
        'override', 'baseline', key='front_spring.colour', value='red')).startswith(
        f"{sedan_master}: configurations.baseline.overrides.front_spring.colour: key 'colour' "
        "does not exist in group 'front_spring' (sedan/front_spring/X.yaml); keys: ")


def test_an_unknown_variant_or_configuration_is_refused(sample_root: Path,
                                                        sedan_master: Path) -> None:
    assert refused(sample_root, sedan_master, Edit(
        'variant', 'baseline', group='front_spring', value='Z')) == (
        f"{sedan_master}: variant 'Z' of group 'front_spring' does not exist (no file "
        'sedan/front_spring/Z.yaml; available: X, Y)')
    assert refused(sample_root, sedan_master, Edit(
        'variant', 'baseline', group='front_spring', value='../../etc/passwd')) == (
        f"{sedan_master}: configurations.baseline.variants.front_spring: variant must be a "
        "plain name, found '../../etc/passwd'")
    assert refused(sample_root, sedan_master, Edit(
        'override', 'nosuch', key='front_alignment.camber', value='1 deg')) == (
        f"{sedan_master}: configuration 'nosuch' does not exist (available: baseline, "
        'stiff_rear, sport)')
    assert refused(sample_root, sedan_master, Edit('add', 'sport')) == (
        f"{sedan_master}: configurations.sport: configuration 'sport' exists already")
    assert refused(sample_root, sedan_master, Edit('add', 'a b')) == (
        f"{sedan_master}: configurations: configuration name 'a b': names may hold letters, "
        "digits, '_', '-' and '.'")
    assert refused(sample_root, sedan_master, Edit('rename', 'sport')) == (
        f"{sedan_master}: unknown edit 'rename' (expected one of: variant, override, flexible, "
        'add)')
    assert refused(sample_root, sedan_master, Edit('flexible', 'baseline', value='spring')) == (
        f"{sedan_master}: configurations.baseline.flexible_components: flexible component "
        "'spring' is not defined in the configuration's flex data (defined: anti_roll_bar, "
        'lateral_link, lca, strut, subframe, tierod, trailing_link, upper_arm, upright)')


def test_a_linked_master_file_is_edited_where_it_really_is(sample_root: Path,
                                                           sedan_master: Path,
                                                           tmp_path: Path) -> None:
    link = tmp_path / 'linked.yaml'
    link.symlink_to(sedan_master)
    edit_master(link, [Edit('override', 'sport', key='front_damper.scale', value='110 %')])
    assert link.is_symlink()
    assert 'front_damper.scale: 110 %' in sedan_master.read_text()


def test_the_data_server_core_follows_an_edit(sedan_master: Path) -> None:
    service = DataService(sedan_master)
    assert service.load().changed
    assert service.poll() is None
    edit_master(sedan_master, [Edit('override', 'baseline', key='front_alignment.camber',
                                    value='-1.2 deg')])
    os.utime(sedan_master, ns=(1, 1))  # a new mtime even on a coarse file-system clock
    outcome = service.poll()
    assert outcome is not None and outcome.changed and not outcome.errors
    assert service.study.status_of('baseline', 'front_alignment').state == 'MODIFIED'
