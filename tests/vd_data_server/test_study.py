# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Resolution and feedback of a study, and the --json contract.

UNCHANGED/MODIFIED against the shared file, SAME/DIFFERS across configurations (the
thesis' overview tab, §2.3).
"""
from __future__ import annotations

import json
import math
from pathlib import Path
import shutil

from numpy.testing import assert_allclose

from vd_data_server.study import ModifiedKey, Study, load_study
from vdtest import replace_once

RTOL = 1e-12
#: groups whose data differ between the sedan study's configurations: sport and stiff_rear
#: pick other variants of front_spring, front_bushings, rear_stabilizer and targets, and sport
#: overrides values of front_alignment, front_hardpoints and front_damper (studies/sedan.yaml)
SEDAN_DIFFERS = {'targets', 'front_spring', 'front_bushings', 'rear_stabilizer',
                 'front_alignment', 'front_hardpoints', 'front_damper'}


def states(study: Study, configuration: str) -> dict[str, str]:
    return {s.group: s.state for s in study.status if s.configuration == configuration}


def consistency(study: Study) -> dict[str, set[str]]:
    out: dict[str, set[str]] = {}
    for s in study.status:
        out.setdefault(s.group, set()).add(s.consistency)
    return out


def test_baseline_is_unchanged_everywhere(sedan_master: Path) -> None:
    study = load_study(sedan_master)
    assert set(states(study, 'baseline').values()) == {'UNCHANGED'}
    assert all(not s.modified_keys for s in study.status if s.configuration == 'baseline')


def test_variants_alone_do_not_modify_the_shared_data(sedan_master: Path) -> None:
    study = load_study(sedan_master)
    assert set(states(study, 'stiff_rear').values()) == {'UNCHANGED'}
    assert study.status_of('stiff_rear', 'rear_stabilizer').variant == 'Y'
    assert study.status_of('stiff_rear', 'targets').variant == 'stiff_rear'


def test_sport_is_modified_exactly_where_the_master_overrides(sedan_master: Path) -> None:
    study = load_study(sedan_master)
    modified = {g for g, s in states(study, 'sport').items() if s == 'MODIFIED'}
    assert modified == {'front_hardpoints', 'front_damper', 'front_alignment'}


def test_modified_keys_give_data_value_master_value_and_file_unit(sedan_master: Path) -> None:
    # front_alignment/X.yaml: camber -0.5 (deg); sedan.yaml: front_alignment.camber: -1.5 deg
    study = load_study(sedan_master)
    assert study.status_of('sport', 'front_alignment').modified_keys == (
        ModifiedKey('camber', '-0.5', '-1.5', 'deg'),)
    assert study.status_of('sport', 'front_hardpoints').modified_keys == (
        ModifiedKey('points.lca_outer', '[18.4, 706, 181]', '[18.4, 706, 171]', 'mm'),)
    assert study.status_of('sport', 'front_damper').modified_keys == (
        ModifiedKey('scale', '1', '1.2', ''),)


def test_groups_with_different_data_differ_and_the_rest_are_the_same(sedan_master: Path) -> None:
    study = load_study(sedan_master)
    per_group = consistency(study)
    assert {g for g, c in per_group.items() if c == {'DIFFERS'}} == SEDAN_DIFFERS
    assert {g for g, c in per_group.items() if c == {'SAME'}} == set(study.groups) - SEDAN_DIFFERS


def test_different_variants_with_identical_content_are_the_same(sample_root: Path,
                                                                sedan_master: Path) -> None:
    folder = sample_root / 'sedan' / 'rear_spring'
    shutil.copy(folder / 'X.yaml', folder / 'Z.yaml')
    replace_once(sedan_master, '      targets: stiff_rear\n', '      targets: stiff_rear\n'
                 '      rear_spring: Z\n')
    study = load_study(sedan_master)
    assert study.status_of('stiff_rear', 'rear_spring').variant == 'Z'
    assert {study.status_of(c, 'rear_spring').consistency for c in study.configurations} == {
        'SAME'
    }
    assert {study.status_of(c, 'rear_spring').state for c in study.configurations} == {'UNCHANGED'}


def test_an_override_equal_to_the_data_value_stays_unchanged(sedan_master: Path) -> None:
    # rear_alignment/X.yaml: camber -1.2 (deg); rear_hardpoints/X.yaml wheel_centre z 332 (mm)
    replace_once(
        sedan_master,
        '      front_damper.scale: 120 %\n',
        '      front_damper.scale: 120 %\n'
        '      rear_alignment.camber: -1.2 deg\n'
        '      rear_hardpoints.points.wheel_centre.z: 0.332 m\n',
    )
    study = load_study(sedan_master)
    for group in ('rear_alignment', 'rear_hardpoints'):
        entry = study.status_of('sport', group)
        assert (entry.state, entry.consistency, entry.modified_keys) == ('UNCHANGED', 'SAME', ())


def test_editing_a_data_file_changes_value_and_hash_of_its_users_only(sample_root: Path,
                                                                      sedan_master: Path) -> None:
    before = load_study(sedan_master)
    replace_once(sample_root / 'sedan/front_spring/X.yaml', 'rate: 30.0', 'rate: 32.5')
    after = load_study(sedan_master)
    assert_allclose(after.configurations['baseline'].group('front_spring').scalar('rate'),
                    32.5e3, rtol=RTOL)
    for name in ('baseline', 'stiff_rear'):  # front_spring X
        assert after.configurations[name].data_hash != before.configurations[name].data_hash
    # sport uses front_spring Y and is untouched
    assert after.configurations['sport'].data_hash == before.configurations['sport'].data_hash
    # the feedback follows the file: the new data are the shared data
    assert after.status_of('baseline', 'front_spring').state == 'UNCHANGED'


def test_editing_the_tire_file_changes_the_hash(sample_root: Path, sedan_master: Path) -> None:
    before = load_study(sedan_master)
    tire = sample_root / 'tires' / 'Sedan_Pac02Tire.tir'
    text = tire.read_text(encoding='ascii')
    assert text.count('= 16.6 ') == 1  # LONGVL, the measurement speed
    tire.write_text(text.replace('= 16.6 ', '= 16.7 '), encoding='ascii')
    after = load_study(sedan_master)
    for name in before.configurations:
        assert after.configurations[name].data_hash != before.configurations[name].data_hash


def test_the_hash_does_not_depend_on_loading_twice(sedan_master: Path) -> None:
    first, second = load_study(sedan_master), load_study(sedan_master)
    assert {n: c.data_hash for n, c in first.configurations.items()} == \
        {n: c.data_hash for n, c in second.configurations.items()}
    assert len({c.data_hash for c in first.configurations.values()}) == 3


def test_optional_group_used_by_one_configuration_differs(sample_root: Path) -> None:
    study = load_study(sample_root / 'studies' / 'hmmwv.yaml')
    unused = study.status_of('baseline', 'front_bushings')
    used = study.status_of('bushings', 'front_bushings')
    assert (unused.variant, unused.state, unused.consistency) == ('', 'UNCHANGED', 'DIFFERS')
    assert (used.variant, used.state, used.consistency) == ('X', 'UNCHANGED', 'DIFFERS')
    assert 'front_bushings' not in study.configurations['baseline'].groups
    others = {g for g, c in consistency(study).items() if c == {'SAME'}}
    assert others == set(study.groups) - {'front_bushings'}


def test_status_json_has_exactly_the_contract_keys(sedan_master: Path) -> None:
    study = load_study(sedan_master)
    data = json.loads(json.dumps(study.to_json()))
    # the ARCHITECTURE contract, extended by the flexible-components switch
    assert set(data) == {'master', 'configurations', 'groups', 'status', 'flexible'}
    assert data['master'] == str(sedan_master)
    assert data['configurations'] == ['baseline', 'stiff_rear', 'sport']
    assert data['groups'] == list(study.groups)
    assert len(data['status']) == len(data['configurations']) * len(data['groups'])
    for entry in data['status']:
        assert set(entry) == {'configuration', 'group', 'variant', 'state', 'consistency',
                              'modified_keys'}
        assert entry['state'] in ('UNCHANGED', 'MODIFIED')
        assert entry['consistency'] in ('SAME', 'DIFFERS')
        for key in entry['modified_keys']:
            assert set(key) == {'key', 'data_value', 'master_value', 'unit'}
    camber = next(e for e in data['status']
                  if (e['configuration'], e['group']) == ('sport', 'front_alignment'))
    assert camber['modified_keys'] == [{'key': 'camber', 'data_value': '-0.5',
                                        'master_value': '-1.5', 'unit': 'deg'}]


def test_resolved_values_are_si_with_their_source(sedan_master: Path) -> None:
    study = load_study(sedan_master)
    sport = study.configurations['sport'].group('front_alignment')
    base = study.configurations['baseline'].group('front_alignment')
    assert_allclose(sport.scalar('camber'), math.radians(-1.5), rtol=RTOL)
    assert_allclose(base.scalar('camber'), math.radians(-0.5), rtol=RTOL)
    assert sport.values['camber'].unit == 'rad'
    assert sport.values['camber'].source == (
        'master override configurations.sport.overrides.front_alignment.camber')
    assert sport.values['toe'].source == 'sedan/front_alignment/X.yaml (variant X)'


def test_extra_overrides_count_as_modifications(sedan_master: Path) -> None:
    study = load_study(sedan_master, extra_overrides={'baseline': {'rear_spring.rate': '60 N/mm'}})
    entry = study.status_of('baseline', 'rear_spring')
    # rear_spring/X.yaml: rate 55.0 in N/mm
    assert entry.state == 'MODIFIED'
    assert [(k.key, k.data_value, k.master_value) for k in entry.modified_keys] == [
        ('rate', '55', '60')]
    value = study.configurations['baseline'].group('rear_spring').values['rate']
    assert value.source == '--set rear_spring.rate'
    assert_allclose(value.si, 60e3, rtol=RTOL)


def test_flexible_switch_is_part_of_the_feedback(sedan_master):
    """
    Check that the overview shows each configuration's flexible-components switch.

    The switch is the one of thesis Fig. 2.3.2; the overview also shows whether the
    configurations agree on it.
    """
    from vd_data_server.study import load_study

    status = load_study(sedan_master).to_json()['flexible']
    assert status == [
        {
            'configuration': 'baseline',
            'flexible': False,
            'components': [],
            'consistency': 'DIFFERS',
        },
        {
            'configuration': 'stiff_rear',
            'flexible': False,
            'components': [],
            'consistency': 'DIFFERS',
        },
        {
            'configuration': 'sport',
            'flexible': True,
            'components': ['lca', 'strut', 'upright'],
            'consistency': 'DIFFERS',
        },
    ]
